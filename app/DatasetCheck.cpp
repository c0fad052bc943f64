#include "app/DatasetCheck.h"
#include "app/FileLock.h"

#include "app/Dataset.h"
#include "render/ErrorReport.h"
#include "render/ImageFiles.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <optional>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string_view>

namespace inkgraph {
namespace fs = std::filesystem;

namespace {

std::string readAll(const fs::path& path) {
    std::ifstream file(path, std::ios::binary);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

/** `text` in single quotes (appended: GCC 12 warns falsely, -Wrestrict bug 105329, on "'" + text inlined). */
std::string quoted(const std::string& text) {
    std::string result = "'";
    result += text;
    result += "'";
    return result;
}

bool endsWith(const std::string& text, const std::string& tail) {
    return text.size() >= tail.size() && text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

/** Why `bytes` are not a whole file of `path`'s format, or "" when they are (or the format has no check). */
std::string formatProblem(const fs::path& path, const std::string& bytes) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (extension == ".png") {
        if (bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0) return "not a PNG (no signature)";
        // The IEND chunk: length 0, type, CRC 0xAE426082. A file cut short ends before it.
        if (!endsWith(bytes, std::string("\0\0\0\0IEND\xae\x42\x60\x82", 12))) return "a PNG cut short (no IEND last)";
    } else if (extension == ".exr") {
        if (bytes.compare(0, 4, "\x76\x2f\x31\x01") != 0) return "not an OpenEXR file (no magic number)";
    } else if (extension == ".tif" || extension == ".tiff") {
        if (bytes.compare(0, 4, std::string("II*\0", 4)) != 0 && bytes.compare(0, 4, std::string("MM\0*", 4)) != 0)
            return "not a TIFF file (no byte-order mark)";
    } else if (extension == ".jpg" || extension == ".jpeg") {
        if (bytes.compare(0, 2, "\xff\xd8") != 0 || !endsWith(bytes, "\xff\xd9"))
            return "a JPEG without its start or end";
    } else if (extension == ".json") {
        if (nlohmann::json::parse(bytes, nullptr, false).is_discarded()) return "JSON that does not parse";
    } else if (extension == ".svg") {
        if (bytes.rfind("</svg>") == std::string::npos || bytes.size() - bytes.rfind("</svg>") > 16)
            return "an SVG cut short (no closing </svg>)";
    }
    return "";
}

/** The "| name | number |" rows of a card's counts table. */
std::map<std::string, std::size_t> cardCounts(const std::string& card) {
    std::map<std::string, std::size_t> counts;
    static const std::regex kRow(R"(^\| ([a-z ]+) \| ([0-9]+) \|$)");
    std::istringstream lines(card);
    std::string line;
    std::smatch match;
    while (std::getline(lines, line))
        if (std::regex_match(line, match, kRow)) {
            // A number too large for size_t (a hand-edited card) is a count no index matches, not a crash.
            std::size_t count = std::numeric_limits<std::size_t>::max();
            const std::string digits = match[2].str();
            if (std::from_chars(digits.data(), digits.data() + digits.size(), count).ec != std::errc())
                count = std::numeric_limits<std::size_t>::max();
            counts[match[1]] = count;
        }
    return counts;
}

/** One line of an index (checkIndex()): its record's fields and files, counted into `positions`, `stills` and
 *  `failed`. Throws nlohmann::json::exception for a field of the wrong type. */
void checkIndexLine(const fs::path& folder, const std::string& line, const std::string& where, DatasetReport& report,
                    std::set<std::string>& listed, std::set<std::size_t>& positions, std::size_t& stills,
                    std::size_t& failed) {
    const nlohmann::json record = nlohmann::json::parse(line, nullptr, false);
    if (record.is_discarded() || !record.is_object()) {
        report.errors.push_back(where + ": not a JSON object");
        return;
    }
    if (!record.contains("model") || !record["model"].is_string() || !record.contains("position") ||
        !record["position"].is_number_unsigned() || !record.contains("status") || !record["status"].is_string()) {
        report.errors.push_back(where + ": lacks its model, position or status");
        return;
    }
    positions.insert(record["position"].get<std::size_t>());
    const std::string model = record["model"];
    if (record["status"] == "failed") {
        ++failed;
        report.warnings.push_back(where + ": '" + model + "' failed: " + record.value("error", std::string("?")));
        return;
    }
    if (record["status"] != "ok") {
        report.errors.push_back(where + ": status '" + record["status"].get<std::string>() + "'");
        return;
    }
    ++stills;
    if (!record.contains("checksums") || !record["checksums"].is_object() || !record.contains("files") ||
        !record["files"].is_object()) {
        report.errors.push_back(where + ": '" + model + "' lists no files");
        return;
    }
    for (const auto& [flag, path] : record["files"].items())
        if (!path.is_string() || !fs::exists(folder / path.get<std::string>()))
            report.errors.push_back(where + ": " + flag + " '" + path.dump() + "' is missing");
    for (const auto& [relative, expected] : record["checksums"].items()) {
        listed.insert(relative);
        const fs::path path = folder / relative;
        std::error_code error;
        const fs::file_status status = fs::symlink_status(path, error);
        if (!fs::exists(status)) {
            report.errors.push_back("'" + relative + "' is missing (" + where + ")");
            continue;
        }
        if (!fs::is_regular_file(status)) { // a FIFO would block the read, a link lead out of the set
            report.errors.push_back("'" + relative + "' is not a plain file (a link, a FIFO, a device or a folder; " +
                                    where + ")");
            continue;
        }
        const std::string bytes = readAll(path);
        if (bytes.empty()) {
            report.errors.push_back("'" + relative + "' is empty");
            continue;
        }
        if (const std::string problem = formatProblem(path, bytes); !problem.empty()) {
            report.errors.push_back("'" + relative + "' is " + problem);
            continue;
        }
        const std::string checksum = hexDigits(fnv1a64(bytes.data(), bytes.size()));
        if (!expected.is_object() || expected.value("size", std::uint64_t(0)) != bytes.size() ||
            expected.value("fnv1a64", std::string()) != checksum) {
            report.errors.push_back("'" + relative + "' is not the file the index recorded (size " +
                                    std::to_string(bytes.size()) + ", checksum " + checksum + "; " + where + ")");
            continue;
        }
        ++report.files; // only what passed: a missing or changed file was counted as verified
    }
}

/** One of the set's own files (an index, a card), whole ("" when there is none); nullopt, with the error reported,
 *  when it is not a plain file (readDatasetFile()). */
std::optional<std::string> readOwnFile(const fs::path& path, DatasetReport& report) {
    try {
        return readDatasetFile(path, "check-dataset").value_or(std::string());
    } catch (const FileError& error) {
        report.errors.push_back(error.what());
        return std::nullopt;
    }
}

/** One index (and its card): its lines, their files, the counts. */
void checkIndex(const fs::path& folder, const fs::path& index, const fs::path& card, DatasetReport& report,
                std::set<std::string>& listed) {
    const std::string indexName = index.filename().string();
    const std::optional<std::string> text = readOwnFile(index, report);
    if (!text) return;
    std::istringstream file(*text);
    std::string line;
    std::size_t number = 0, stills = 0, failed = 0;
    std::set<std::size_t> positions;
    while (std::getline(file, line)) {
        ++number;
        const std::string where = indexName + " line " + std::to_string(number);
        try {
            checkIndexLine(folder, line, where, report, listed, positions, stills, failed);
        } catch (const nlohmann::json::exception& error) {
            // A field of the wrong type (a size as a string, a number where text belongs): an error of the set.
            report.errors.push_back(where + ": a field of the wrong type (" + std::string(error.what()) + ")");
        }
    }
    report.stills += stills;
    report.failed += failed;
    const std::string cardName = card.filename().string();
    if (!fs::is_regular_file(card)) {
        report.errors.push_back("the card '" + cardName + "' is missing");
        return;
    }
    const std::optional<std::string> cardText = readOwnFile(card, report);
    if (!cardText) return;
    const auto counts = cardCounts(*cardText);
    const std::vector<std::pair<std::string, std::size_t>> expected = {
        {"models", positions.size()}, {"stills in the set", stills}, {"failed", failed}};
    // Every model with each of its views: the index holds models x views lines.
    if (const auto views = counts.find("views per model");
        views != counts.end() && positions.size() * views->second != stills + failed)
        report.errors.push_back(cardName + " says " + std::to_string(positions.size()) + " models x " +
                                std::to_string(views->second) + " views, " + indexName + " holds " +
                                std::to_string(stills + failed) + " stills");
    for (const auto& [name, count] : expected) {
        const auto found = counts.find(name);
        if (found == counts.end())
            report.errors.push_back(cardName + " does not state the count of " + name);
        else if (found->second != count)
            report.errors.push_back(cardName + " says " + std::to_string(found->second) + " " + name + ", " +
                                    indexName + " holds " + std::to_string(count));
    }
}

/** --shard's largest N (flags/FlagTable.cpp parseShard): an index name with a larger one is no run's. */
constexpr int kMaxShardCount = 1000000;

/** K or N of a shard index's name: decimal digits as inkgraph writes them (no leading zero but for 0 itself), or
 *  nothing for a number out of range or of another spelling. */
std::optional<int> shardNumber(const std::string& digits) {
    if (digits.empty() || digits.size() > 9 || (digits.size() > 1 && digits[0] == '0')) return std::nullopt;
    int value = 0;
    const auto [end, failure] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (failure != std::errc() || end != digits.data() + digits.size()) return std::nullopt;
    return value;
}

} // namespace

DatasetReport checkDataset(const fs::path& folder) {
    DatasetReport report;
    // The indexes: index.jsonl, or index-K-of-N.jsonl for every K of one N.
    static const std::regex kShardIndex(R"(index-([0-9]+)-of-([0-9]+)\.jsonl)");
    std::vector<std::pair<fs::path, fs::path>> indexes; // index, card
    std::set<std::string> own = {".inkgraph"};
    std::map<int, std::set<int>> shardsByCount;
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(folder, error)) {
        const std::string name = entry.path().filename().string();
        std::smatch match;
        if (name == "index.jsonl") {
            indexes.emplace_back(entry.path(), folder / "README.md");
        } else if (std::regex_match(name, match, kShardIndex)) {
            const auto index = shardNumber(match[1].str()), count = shardNumber(match[2].str());
            if (!index || !count || *count < 1 || *count > kMaxShardCount || *index >= *count) {
                report.errors.push_back(quoted(name) +
                                        ": not an index inkgraph writes (index-K-of-N.jsonl with 0 <= K "
                                        "< N <= " +
                                        std::to_string(kMaxShardCount) + ", as --shard takes them)");
                own.insert(name);
                continue;
            }
            indexes.emplace_back(entry.path(), folder / ("README-" + match[1].str() + "-of-" + match[2].str() + ".md"));
            shardsByCount[*count].insert(*index);
        }
    }
    std::sort(indexes.begin(), indexes.end());
    if (indexes.empty()) report.errors.push_back("no index.jsonl (or index-K-of-N.jsonl): not a finished data set");
    const bool plainIndex = std::any_of(indexes.begin(), indexes.end(),
                                        [](const auto& index) { return index.first.filename() == "index.jsonl"; });
    if (shardsByCount.size() > 1 || (plainIndex && !shardsByCount.empty()))
        report.errors.push_back("indexes of two layouts (index.jsonl and index-K-of-N.jsonl, or two N)");
    for (const auto& [count, shards] : shardsByCount) {
        // Each missing shard by name, the first few of them: N is at most a million, and one line says the rest.
        constexpr int kNamed = 20;
        const int missing = count - int(shards.size());
        int named = 0;
        for (int shard = 0; shard < count && named < kNamed; ++shard)
            if (shards.count(shard) == 0) {
                report.errors.push_back("shard " + std::to_string(shard) + " of " + std::to_string(count) +
                                        " is missing (index-" + std::to_string(shard) + "-of-" + std::to_string(count) +
                                        ".jsonl): that task has not finished");
                ++named;
            }
        if (missing > named)
            report.errors.push_back("and " + std::to_string(missing - named) + " more shards of " +
                                    std::to_string(count) + " are missing");
    }
    std::set<std::string> listed;
    for (const auto& [index, card] : indexes) {
        own.insert(index.filename().string());
        own.insert(card.filename().string());
        checkIndex(folder, index, card, report, listed);
    }
    // A split's lock held: its run is writing the set now (its journal is that run's). A journal with no run holding
    // its lock: a run that did not finish (killed, or failed); --resume finishes it. A lock file no run holds is what a
    // killed run leaves, and nothing to report.
    for (const auto& entry : fs::directory_iterator(folder / ".inkgraph", error)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("lock", 0) == 0 && !fs::is_regular_file(fs::symlink_status(entry.path(), error))) {
            report.errors.push_back("'.inkgraph/" + name +
                                    "': not a plain file (a link, a FIFO, a device or a folder); every run of the set "
                                    "refuses it: remove it");
        } else if (name.rfind("lock", 0) == 0 && isLockHeld(entry.path())) {
            report.errors.push_back("'.inkgraph/" + name +
                                    "': an inkgraph run is writing this data set now; check it when it has finished");
        } else if (name.rfind("journal", 0) == 0) {
            // journal[-K-of-N].jsonl -> lock[-K-of-N]
            constexpr std::string_view kPrefix = "journal", kExtension = ".jsonl";
            const std::size_t affixes = kPrefix.size() + kExtension.size();
            const std::string suffix = name.size() >= affixes ? name.substr(kPrefix.size(), name.size() - affixes) : "";
            if (!isLockHeld(folder / ".inkgraph" / ("lock" + suffix)))
                report.errors.push_back("'.inkgraph/" + name +
                                        "': a run that did not finish; run it again with --resume");
        }
    }
    // Leftovers of killed runs, and files no index lists.
    for (auto it = fs::recursive_directory_iterator(folder, error); !error && it != fs::recursive_directory_iterator();
         it.increment(error)) {
        const fs::path relative = it->path().lexically_relative(folder);
        const std::string name = it->path().filename().string();
        if (it.depth() == 0 && own.count(name) != 0) {
            if (it->is_directory()) it.disable_recursion_pending();
            continue;
        }
        if (name.rfind(".inkgraph-", 0) == 0) {
            report.errors.push_back(quoted(relative.generic_string()) + ": a temporary " +
                                    (it->is_directory() ? "folder" : "file") +
                                    " of a run that was killed or is running");
            if (it->is_directory()) it.disable_recursion_pending();
            continue;
        }
        if (it->is_regular_file() && listed.count(relative.generic_string()) == 0)
            report.warnings.push_back(quoted(relative.generic_string()) + " is not in the index");
    }
    return report;
}

std::string checkDatasetHelp() {
    return "Usage: inkgraph check-dataset DIR\n\n"
           "Verifies a data set made with inkgraph render --dataset DIR (docs/datasets.md): the index and the card\n"
           "(README.md; with --shard, index-K-of-N.jsonl and README-K-of-N.md for every K) exist and parse, every\n"
           "file the index lists is there, non-empty, whole for its format (PNG: signature and IEND; JPEG: its\n"
           "start and end markers; EXR, TIFF: signature; JSON: parses; SVG: closing tag) and has its recorded\n"
           "size and checksum, no journal is left (a run that did not finish: resume it with --resume), no\n"
           "temporary file of a killed run is left, and the card's counts match the index. Files the index does\n"
           "not list and failed stills are warnings.\n\n"
           "Prints one line per problem (at most " +
           std::to_string(kShownProblems) +
           ", then how many more) and a summary.\n\n"
           "Exit codes: 0 the data set is whole, 1 it is not, 2 bad command line.\n";
}

int runCheckDatasetCommand(const std::vector<std::string>& arguments, std::ostream& out, std::ostream& err) {
    if (arguments.size() == 1 && (arguments[0] == "--help" || arguments[0] == "-h")) {
        out << checkDatasetHelp();
        return kExitOk;
    }
    if (arguments.size() != 1 || arguments[0].empty() || arguments[0][0] == '-') {
        err << "inkgraph: check-dataset takes one folder, the data set (see: inkgraph check-dataset --help)\n";
        return kExitUsage;
    }
    const fs::path folder = arguments[0];
    std::error_code error;
    if (!fs::is_directory(folder, error)) {
        err << "inkgraph: check-dataset: '" << arguments[0] << "' is not a folder\n";
        return kExitUsage;
    }
    const DatasetReport report = checkDataset(folder);
    std::size_t shown = 0;
    const std::size_t problems = report.errors.size() + report.warnings.size();
    for (const auto& [kind, lines] : {std::pair{"error", &report.errors}, std::pair{"warning", &report.warnings}})
        for (const std::string& line : *lines)
            if (shown++ < kShownProblems) out << kind << ": " << line << "\n";
    if (problems > kShownProblems) out << "and " << problems - kShownProblems << " more\n";
    out << "check-dataset '" << arguments[0] << "': " << report.stills << " stills, " << report.failed << " failed, "
        << report.files << " files verified; " << report.errors.size() << " errors, " << report.warnings.size()
        << " warnings: " << (report.errors.empty() ? "whole" : "NOT whole") << "\n";
    return report.errors.empty() ? kExitOk : 1;
}

} // namespace inkgraph
