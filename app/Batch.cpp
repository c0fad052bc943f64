#include "app/Batch.h"

#include "render/ImageFiles.h"
#include "app/OutputFiles.h"
#include "scene/Scene.h"

#include <algorithm>
#include <filesystem>
#include <istream>
#include <map>
#include <optional>
#include <sstream>

namespace inkgraph {
namespace {

/** A list is text, one path a line: 16 MiB is some 100 000 models, far more than one process should take. */
constexpr std::size_t kMaxListBytes = std::size_t(16) << 20;

std::string listText(const std::string& listPath, std::istream& standardInput) {
    if (listPath != "-") {
        try {
            return readInputBytes(listPath, kMaxListBytes, "--list");
        } catch (const FileError& error) {
            throw UsageError(error.what());
        }
    }
    std::string text;
    char buffer[65536];
    while (standardInput.read(buffer, sizeof buffer) || standardInput.gcount() > 0) {
        text.append(buffer, std::size_t(standardInput.gcount()));
        if (text.size() > kMaxListBytes)
            throw UsageError("--list: standard input holds more than " + std::to_string(kMaxListBytes >> 20) +
                             " MiB; split the list");
    }
    return text;
}

std::string trimmed(const std::string& text) {
    const auto first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos) return "";
    return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

bool hasPlaceholder(const std::string& pattern) {
    return pattern.find("{name}") != std::string::npos || pattern.find("{index}") != std::string::npos;
}

/** Each output flag given and its value, in --help's order. */
std::vector<std::pair<std::string, std::string>> outputFlags(const RenderOptions& options) {
    std::vector<std::pair<std::string, std::string>> flags;
    for (const auto& [flag, field] : outputPathFlags())
        if (!(options.*field).empty()) flags.emplace_back(flag, options.*field);
    return flags;
}

} // namespace

BatchList batchList(const RenderOptions& options, std::istream& standardInput) {
    std::vector<std::string> paths = options.modelPaths;
    if (!options.listPath.empty()) {
        const std::string text = listText(options.listPath, standardInput);
        const std::string listName = options.listPath == "-" ? "standard input" : "'" + options.listPath + "'";
        std::istringstream lines(text);
        std::string line;
        for (std::size_t number = 1; std::getline(lines, line); ++number) {
            if (line.find('\0') != std::string::npos)
                throw UsageError("--list " + listName + " line " + std::to_string(number) +
                                 ": binary data (NUL byte); a list holds one model path per line");
            const std::string path = trimmed(line);
            if (path.empty() || path[0] == '#') continue;
            paths.push_back(path);
        }
        if (paths.empty()) throw UsageError("--list " + listName + ": no models in it (one path per line)");
    }
    BatchList list;
    list.total = paths.size();
    list.isBatch = paths.size() > 1 || !options.listPath.empty();
    for (std::size_t position = 0; position < paths.size(); ++position) {
        if (options.shard && int(position % std::size_t(options.shard->count)) != options.shard->index) continue;
        list.models.push_back({paths[position], position});
    }
    return list;
}

std::string expandOutputPattern(const std::string& pattern, const BatchModel& model, std::size_t total) {
    std::string index = std::to_string(model.position + 1);
    const std::size_t width = std::to_string(std::max<std::size_t>(total, 1)).size();
    if (index.size() < width) index.insert(0, width - index.size(), '0');
    const std::string name = std::filesystem::path(model.path).stem().string();
    std::string expanded;
    for (std::size_t i = 0; i < pattern.size();) {
        if (pattern.compare(i, 6, "{name}") == 0) {
            expanded += name;
            i += 6;
        } else if (pattern.compare(i, 7, "{index}") == 0) {
            expanded += index;
            i += 7;
        } else {
            expanded += pattern[i++];
        }
    }
    return expanded;
}

RenderOptions stillOptions(const RenderOptions& options, const BatchModel& model, std::size_t total) {
    RenderOptions still = options;
    still.modelPath = model.path;
    for (const auto& [flag, field] : outputPathFlags()) still.*field = expandOutputPattern(still.*field, model, total);
    return still;
}

void checkBatchOutputs(const RenderOptions& options, const BatchList& list) {
    if (list.total > 1)
        for (const auto& [flag, pattern] : outputFlags(options))
            if (!hasPlaceholder(pattern))
                throw UsageError(flag + " '" + pattern + "' would be the same file for all " +
                                 std::to_string(list.total) + " models; put {name} or {index} in it, e.g. '" +
                                 (flag == "--dump"
                                      ? "out/{name}-dump"
                                      : "out/{name}" + std::filesystem::path(pattern).extension().string()) +
                                 "'");
    // By place and by device and inode: a hard link of a model is that model under another name.
    std::map<std::filesystem::path, const BatchModel*> modelsByPlace;
    std::map<FileIdentity, const BatchModel*> modelsByIdentity;
    for (const BatchModel& model : list.models) {
        modelsByPlace.emplace(resolvedPath(model.path), &model);
        if (const auto identity = fileIdentity(model.path)) modelsByIdentity.emplace(*identity, &model);
    }
    // The files each model names (glTF buffers, images, material shade maps; OBJ material libraries): no still may
    // replace one, whichever model reads it. Only an output that exists can replace anything, so the models are read
    // for them only then (a first run into new names reads none), and only with several models: one still checks its
    // own inputs (OutputSet).
    std::optional<std::map<FileIdentity, std::pair<const BatchModel*, std::string>>> namedFiles;
    const auto modelNaming = [&](const FileIdentity& identity) -> const std::pair<const BatchModel*, std::string>* {
        if (list.models.size() < 2) return nullptr;
        if (!namedFiles) {
            namedFiles.emplace();
            for (const BatchModel& model : list.models)
                for (const std::string& file : referencedFiles(model.path))
                    if (const auto named = fileIdentity(file))
                        namedFiles->emplace(*named, std::make_pair(&model, file));
        }
        const auto found = namedFiles->find(identity);
        return found == namedFiles->end() ? nullptr : &found->second;
    };
    // Place -> the first still writing there (a model listed twice is two stills).
    std::map<std::filesystem::path, const BatchModel*> writers;
    for (const BatchModel& model : list.models) {
        for (const auto& [flag, pattern] : outputFlags(options)) {
            const std::string output = expandOutputPattern(pattern, model, list.total);
            const std::filesystem::path place = resolvedPath(output);
            // A still writing over its own model is OutputSet's to report, as for a single model.
            const auto identity = fileIdentity(output);
            const BatchModel* overwritten = nullptr;
            if (auto input = modelsByPlace.find(place); input != modelsByPlace.end()) overwritten = input->second;
            if (identity)
                if (auto input = modelsByIdentity.find(*identity); input != modelsByIdentity.end())
                    overwritten = input->second;
            if (overwritten != nullptr && overwritten->path != model.path)
                throw UsageError(flag + " '" + output + "' (for '" + model.path + "') would overwrite the model '" +
                                 overwritten->path + "'");
            if (identity)
                if (const auto* named = modelNaming(*identity))
                    throw UsageError(flag + " '" + output + "' (for '" + model.path + "') would overwrite '" +
                                     named->second + "', which the model '" + named->first->path + "' reads");
            // One still's own outputs colliding with each other are OutputSet's to report.
            const auto [earlier, inserted] = writers.emplace(place, &model);
            if (!inserted && earlier->second->position != model.position)
                throw UsageError(flag + " '" + output + "' is written for both '" + earlier->second->path +
                                 "' (list position " + std::to_string(earlier->second->position + 1) + ") and '" +
                                 model.path + "' (position " + std::to_string(model.position + 1) +
                                 "); models of one name need {index}");
        }
    }
}

} // namespace inkgraph
