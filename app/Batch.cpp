#include "app/Batch.h"

#include "render/ImageFiles.h"
#include "app/OutputFiles.h"
#include "app/Render.h"                // memoryLimitOf()
#include "passes/shade/ShadingModel.h" // traitsOf()
#include "render/StillRenderer.h"      // readShadeMapFile()
#include "scene/MessageText.h"         // withoutByteOrderMark(), quotedFileName()
#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <istream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>

namespace inkgraph {
namespace {

/** A list is text, one path a line: 16 MiB is some 100 000 models, far more than one process should take. */
constexpr std::size_t kMaxListBytes = std::size_t(16) << 20;

/** A list read from a stream to its end: at most kMaxListBytes. `shownName`: "standard input" or the quoted path. */
std::string streamText(std::istream& stream, const std::string& shownName) {
    std::string text;
    char buffer[65536];
    while (stream.read(buffer, sizeof buffer) || stream.gcount() > 0) {
        text.append(buffer, std::size_t(stream.gcount()));
        if (text.size() > kMaxListBytes)
            throw UsageError("--list: " + shownName + " holds more than " + std::to_string(kMaxListBytes >> 20) +
                             " MiB; split the list");
    }
    return text;
}

std::string listText(const std::string& listPath, std::istream& standardInput) {
    if (listPath == "-") return streamText(standardInput, "standard input");
    // A pipe is read as standard input is: the shell's `--list <(find models -name '*.obj')` names one.
    std::error_code statusError;
    if (std::filesystem::status(listPath, statusError).type() == std::filesystem::file_type::fifo) {
        std::ifstream pipe(listPath, std::ios::binary);
        if (!pipe)
            throw UsageError("--list: " + detail::quotedFileName(listPath) + ": cannot open the pipe for reading");
        return streamText(pipe, detail::quotedFileName(listPath));
    }
    try {
        return readInputBytes(listPath, kMaxListBytes, "--list");
    } catch (const FileError& error) {
        throw UsageError(error.what());
    }
}

std::string trimmed(const std::string& text) {
    const auto first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos) return "";
    return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

bool hasModelPlaceholder(const std::string& pattern) {
    return pattern.find("{name}") != std::string::npos || pattern.find("{index}") != std::string::npos;
}

bool hasViewPlaceholder(const std::string& pattern) { return pattern.find("{view}") != std::string::npos; }

/** Views per model: N with --views N, else 1. */
std::size_t viewCountOf(const RenderOptions& options) { return options.viewsGiven ? options.viewSampling.count : 1; }

/** `number` in decimal with leading zeros to the width of `widest`. */
std::string zeroPadded(std::size_t number, std::size_t widest) {
    std::string text = std::to_string(number);
    const std::size_t width = std::to_string(widest).size();
    if (text.size() < width) text.insert(0, width - text.size(), '0');
    return text;
}

/** The example of a batch's output path for `flag`, with the placeholders it lacks. */
std::string examplePath(const std::string& flag, const std::string& pattern, bool views) {
    const std::string stem = views ? "out/{name}-{view}" : "out/{name}";
    return flag == "--dump" ? stem + "-dump" : stem + std::filesystem::path(pattern).extension().string();
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
        const std::string listName =
            options.listPath == "-" ? "standard input" : detail::quotedFileName(options.listPath);
        std::istringstream lines(text);
        std::string line;
        for (std::size_t number = 1; std::getline(lines, line); ++number) {
            if (line.find('\0') != std::string::npos)
                throw UsageError("--list " + listName + " line " + std::to_string(number) +
                                 ": binary data (NUL byte); a list holds one model path per line");
            // Windows editors (Notepad's "UTF-8") write a byte-order mark first, and lists joined with cat keep each
            // one's: it was glued to the model's name, told as "file not found" with the mark invisible in the name.
            const std::string path = trimmed(std::string(detail::withoutByteOrderMark(line)));
            if (path.empty() || path[0] == '#') continue;
            paths.push_back(path);
        }
        if (paths.empty()) throw UsageError("--list " + listName + ": no models in it (one path per line)");
    }
    BatchList list;
    list.total = paths.size();
    list.isBatch = paths.size() > 1 || !options.listPath.empty() || viewCountOf(options) > 1;
    for (std::size_t position = 0; position < paths.size(); ++position) {
        if (options.shard && int(position % std::size_t(options.shard->count)) != options.shard->index) continue;
        list.models.push_back({paths[position], position});
    }
    const std::size_t views = viewCountOf(options);
    if (list.models.size() > kMaxStillsPerProcess / views)
        throw UsageError(std::to_string(list.models.size()) + " models x " + std::to_string(views) +
                         " views (--views) are more than the " + std::to_string(kMaxStillsPerProcess) +
                         " stills one process renders; split the list with --shard K/N (e.g. --shard 0/" +
                         std::to_string((list.models.size() * views) / kMaxStillsPerProcess + 1) + ")");
    if (options.shard) list.everyPath = std::move(paths);
    return list;
}

std::vector<BatchStill> batchStills(const RenderOptions& options, const BatchList& list) {
    const ViewSampling sampling = viewSamplingOf(options);
    std::vector<BatchStill> stills;
    for (const BatchModel& model : list.models) {
        if (!options.viewsGiven) {
            stills.push_back({model, 0, std::nullopt});
            continue;
        }
        // Keyed by the model path as listed: the same list gives the same views in any shard split.
        for (ViewSample& view : sampleViews(sampling, model.path))
            stills.push_back({model, view.index, std::move(view)});
    }
    return stills;
}

std::string expandOutputPattern(const std::string& pattern, const BatchModel& model, std::size_t total,
                                std::size_t viewIndex, std::size_t viewCount) {
    const std::string index = zeroPadded(model.position + 1, std::max<std::size_t>(total, 1));
    const std::string view = zeroPadded(viewIndex, std::max<std::size_t>(viewCount, 1) - 1);
    const std::string name = std::filesystem::path(model.path).stem().string();
    std::string expanded;
    for (std::size_t i = 0; i < pattern.size();) {
        if (pattern.compare(i, 6, "{name}") == 0) {
            expanded += name;
            i += 6;
        } else if (pattern.compare(i, 7, "{index}") == 0) {
            expanded += index;
            i += 7;
        } else if (pattern.compare(i, 6, "{view}") == 0) {
            expanded += view;
            i += 6;
        } else {
            expanded += pattern[i++];
        }
    }
    return expanded;
}

RenderOptions stillOptions(const RenderOptions& options, const BatchStill& still, std::size_t total) {
    RenderOptions result = options;
    result.modelPath = still.model.path;
    for (const auto& [flag, field] : outputPathFlags())
        result.*field = expandOutputPattern(result.*field, still.model, total, still.viewIndex, viewCountOf(options));
    if (!still.view) return result;
    const ViewSample& view = *still.view;
    Orbit orbit;
    orbit.azimuthDegrees = view.azimuthDegrees;
    orbit.elevationDegrees = view.elevationDegrees;
    orbit.distanceScale = view.distanceScale;
    result.orbit = orbit;
    // As --light makes the recorded direction unit length, so --light with the recorded numbers gives this light.
    if (view.towardLight) {
        const glm::dvec3 light = *view.towardLight;
        result.look.towardLight =
            glm::normalize(light / std::max({std::abs(light.x), std::abs(light.y), std::abs(light.z)}));
    }
    if (view.expressions) result.expressions = *view.expressions;
    if (view.pose) result.pose = *view.pose == kRestPoseChoice ? "" : *view.pose;
    result.view = view;
    return result;
}

namespace {

/** An output path as absolute and normal text: what two shares compare (no file system access, so a list of a
 *  million models is checked in seconds; links are not followed). */
std::string normalPlace(const std::string& path) {
    return std::filesystem::absolute(std::filesystem::path(path)).lexically_normal().string();
}

/** With --shard, the other shares write into the same folders (an array job): every still of the whole list is
 *  expanded, and one of this share that writes what a still of another share writes is refused. Hashes first, the
 *  paths themselves only for equal hashes. */
void checkOutputsAcrossShards(const RenderOptions& options, const BatchList& list) {
    if (!options.shard || list.everyPath.empty()) return;
    const std::size_t viewCount = viewCountOf(options);
    if (list.everyPath.size() > kMaxStillsCheckedAcrossShards / viewCount) return;
    const auto flags = outputFlags(options);
    struct Written {
        std::size_t hash, position, view, flag;
    };
    std::vector<Written> written;
    written.reserve(list.everyPath.size() * viewCount * flags.size());
    const auto placeOf = [&](const Written& one) {
        return normalPlace(expandOutputPattern(flags[one.flag].second, {list.everyPath[one.position], one.position},
                                               list.total, one.view, viewCount));
    };
    for (std::size_t position = 0; position < list.everyPath.size(); ++position)
        for (std::size_t view = 0; view < viewCount; ++view)
            for (std::size_t flag = 0; flag < flags.size(); ++flag) {
                Written one{0, position, view, flag};
                one.hash = std::hash<std::string>{}(placeOf(one));
                written.push_back(one);
            }
    std::sort(written.begin(), written.end(), [](const Written& a, const Written& b) {
        return std::tie(a.hash, a.position, a.view) < std::tie(b.hash, b.position, b.view);
    });
    const auto shardOf = [&](std::size_t position) { return int(position % std::size_t(options.shard->count)); };
    for (std::size_t i = 1; i < written.size(); ++i) {
        const Written &a = written[i - 1], &b = written[i];
        if (a.hash != b.hash || shardOf(a.position) == shardOf(b.position)) continue;
        if (shardOf(a.position) != options.shard->index && shardOf(b.position) != options.shard->index) continue;
        const std::string place = placeOf(a);
        if (place != placeOf(b)) continue;
        throw UsageError(flags[a.flag].first + " " + detail::quotedFileName(place) + " is written for both " +
                         detail::quotedFileName(list.everyPath[a.position]) + " (list position " +
                         std::to_string(a.position + 1) + ", shard " + std::to_string(shardOf(a.position)) + "/" +
                         std::to_string(options.shard->count) + ") and " +
                         detail::quotedFileName(list.everyPath[b.position]) + " (position " +
                         std::to_string(b.position + 1) + ", shard " + std::to_string(shardOf(b.position)) + "/" +
                         std::to_string(options.shard->count) + "); models of one name need {index}");
    }
}

} // namespace

void checkBatchInputs(const RenderOptions& options) {
    if (!options.look.shadeMapPath.empty()) {
        try {
            (void)readShadeMapFile(options.look.shadeMapPath, traitsOf(options.look.shading).oneDimensionalMap);
        } catch (const InputFileError& error) {
            // A style file's map is named by its line, as the style's other settings are.
            if (options.shadeMapOrigin.empty()) throw;
            throw InputFileError(options.shadeMapOrigin + ": " + error.what());
        }
    }
    const std::size_t memoryLimit = memoryLimitOf(options);
    checkPoseFile(options.pose, memoryLimit, "--pose");
    for (const std::string& choice : options.viewSampling.poseChoices)
        if (choice != kRestPoseChoice) checkPoseFile(choice, memoryLimit, "--poses");
}

void checkBatchOutputs(const RenderOptions& options, const BatchList& list) {
    const std::size_t viewCount = viewCountOf(options);
    for (const auto& [flag, pattern] : outputFlags(options)) {
        if (list.total > 1 && !hasModelPlaceholder(pattern))
            throw UsageError(flag + " " + detail::quotedFileName(pattern) + " would be the same file for all " +
                             std::to_string(list.total) + " models; put {name} or {index} in it, e.g. " +
                             detail::quotedFileName(examplePath(flag, pattern, viewCount > 1)));
        if (viewCount > 1 && !hasViewPlaceholder(pattern))
            throw UsageError(flag + " " + detail::quotedFileName(pattern) + " would be the same file for all " +
                             std::to_string(viewCount) + " views of --views; put {view} in it, e.g. " +
                             detail::quotedFileName(examplePath(flag, pattern, true)));
    }
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
            std::set<std::string> modelsRead; // a model listed many times is read once
            for (const BatchModel& model : list.models)
                if (modelsRead.insert(model.path).second)
                    for (const std::string& file : referencedFiles(model.path))
                        if (const auto named = fileIdentity(file))
                            namedFiles->emplace(*named, std::make_pair(&model, file));
        }
        const auto found = namedFiles->find(identity);
        return found == namedFiles->end() ? nullptr : &found->second;
    };
    // The files every still reads besides its model (--list, --style, --shademap, the width map's image): each known
    // by place and identity once, so a list of a million stills compares against them without asking the file system.
    struct RunInputFile {
        std::filesystem::path place;
        std::optional<FileIdentity> identity;
        std::string what;
    };
    std::vector<RunInputFile> runInputs;
    for (const RunInput& input : inputsNamedBesidesModel(options))
        runInputs.push_back({resolvedPath(input.path), fileIdentity(input.path), input.what});
    // Place -> the first still writing there (a model listed twice is two stills, each view one).
    std::map<std::filesystem::path, const BatchStill*> writers;
    // Every still by its model and view index: the outputs do not depend on the view drawn, so none is sampled here.
    std::vector<BatchStill> stills;
    stills.reserve(list.models.size() * viewCount);
    for (const BatchModel& model : list.models)
        for (std::size_t view = 0; view < viewCount; ++view) stills.push_back({model, view, std::nullopt});
    for (const BatchStill& still : stills) {
        const BatchModel& model = still.model;
        for (const auto& [flag, pattern] : outputFlags(options)) {
            const std::string output = expandOutputPattern(pattern, model, list.total, still.viewIndex, viewCount);
            const std::filesystem::path place = resolvedPath(output);
            // Worded as OutputSet words the same clash for one still, which would find it only at this still's turn,
            // after the stills before it are written.
            const auto identity = fileIdentity(output);
            for (const RunInputFile& input : runInputs)
                if (place == input.place || (identity && input.identity && *identity == *input.identity))
                    throw UsageError(flag + " " + detail::quotedFileName(output) + " is " + input.what +
                                     "; choose another file");
            const BatchModel* overwritten = nullptr;
            if (auto input = modelsByPlace.find(place); input != modelsByPlace.end()) overwritten = input->second;
            if (identity)
                if (auto input = modelsByIdentity.find(*identity); input != modelsByIdentity.end())
                    overwritten = input->second;
            if (overwritten != nullptr && overwritten->path == model.path)
                throw UsageError(flag + " " + detail::quotedFileName(output) +
                                 " is the model itself; choose another file");
            if (overwritten != nullptr)
                throw UsageError(flag + " " + detail::quotedFileName(output) + " (for " +
                                 detail::quotedFileName(model.path) + ") would overwrite the model " +
                                 detail::quotedFileName(overwritten->path));
            if (identity)
                if (const auto* named = modelNaming(*identity))
                    throw UsageError(flag + " " + detail::quotedFileName(output) + " (for " +
                                     detail::quotedFileName(model.path) + ") would overwrite " +
                                     detail::quotedFileName(named->second) + ", which the model " +
                                     detail::quotedFileName(named->first->path) + " reads");
            // One still's own outputs colliding with each other are OutputSet's to report.
            const auto [earlier, inserted] = writers.emplace(place, &still);
            const BatchStill& other = *earlier->second;
            if (!inserted && (other.model.position != model.position || other.viewIndex != still.viewIndex)) {
                const auto described = [viewCount](const BatchStill& one) {
                    return detail::quotedFileName(one.model.path) + " (list position " +
                           std::to_string(one.model.position + 1) +
                           (viewCount > 1 ? ", view " + zeroPadded(one.viewIndex, viewCount - 1) : std::string()) + ")";
                };
                throw UsageError(flag + " " + detail::quotedFileName(output) + " is written for both " +
                                 described(other) + " and " + described(still) +
                                 (other.model.position != model.position ? "; models of one name need {index}"
                                                                         : "; views need {view}"));
            }
        }
    }
    checkOutputsAcrossShards(options, list);
}

} // namespace inkgraph
