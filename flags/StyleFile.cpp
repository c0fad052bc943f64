#include "flags/StyleFile.h"

#include "render/ImageFiles.h"
#include "flags/FlagTable.h"
#include "flags/Options.h"
#include "scene/MessageText.h" // withoutByteOrderMark(), as the model readers skip one; quotedFileName()

#include <algorithm>
#include <filesystem>
#include <set>

namespace inkgraph {
namespace {

constexpr std::uintmax_t kMaxStyleFileBytes = 64 * 1024;

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

std::string_view trimmed(std::string_view text) {
    while (!text.empty() && isBlank(text.front())) text.remove_prefix(1);
    while (!text.empty() && isBlank(text.back())) text.remove_suffix(1);
    return text;
}

/** "0.1, 0.2, 0.3" -> "0.1,0.2,0.3": lists may be spaced for reading around their commas. Blanks inside an item
 *  stay, so its flag reads what the file holds: "1 5" is refused as a number, not read as 15, and a file name
 *  (--outline-width-map's texture) keeps its spaces. */
std::string withoutBlanksAroundCommas(std::string_view text) {
    std::string compact;
    for (;;) {
        const std::size_t comma = text.find(',');
        compact += trimmed(text.substr(0, comma));
        if (comma == std::string_view::npos) return compact;
        compact += ',';
        text.remove_prefix(comma + 1);
    }
}

} // namespace

const std::vector<std::string>& styleSettingNames() {
    static const std::vector<std::string> kNames = [] {
        std::vector<std::string> names;
        for (const Flag& flag : renderFlags())
            if (flag.inStyle) names.push_back(flag.names.back().substr(2));
        return names;
    }();
    return kNames;
}

SourcedArguments styleArguments(std::string_view text, const std::string& source, const std::string& directory) {
    SourcedArguments result;
    std::set<std::string, std::less<>> seen;
    const std::vector<std::string>& known = styleSettingNames();
    std::size_t lineNumber = 0;
    // Windows editors may write a UTF-8 byte-order mark first; it would glue itself to the first setting's name.
    text = detail::withoutByteOrderMark(text);
    while (!text.empty()) {
        ++lineNumber;
        const std::size_t end = std::min(text.find('\n'), text.size());
        std::string_view line = text.substr(0, end);
        text.remove_prefix(std::min(end + 1, text.size()));
        const std::string where = "--style " + detail::quotedFileName(source) + " line " + std::to_string(lineNumber);
        if (line.find('\0') != std::string_view::npos)
            throw UsageError(where + ": binary data (NUL byte); a style is text");
        if (const std::size_t comment = line.find('#'); comment != std::string_view::npos)
            line = line.substr(0, comment);
        line = trimmed(line);
        if (line.empty()) continue;
        // A CRLF line's CR is trimmed above; one inside joins lines of a file with CR line ends (classic Mac OS),
        // which read as one setting with a value the file does not hold.
        if (line.find('\r') != std::string_view::npos)
            throw UsageError(where + ": a carriage return inside the line (CR line ends?); a style's lines end with "
                                     "LF or CRLF");
        const std::size_t equals = line.find('=');
        if (equals == std::string_view::npos)
            throw UsageError(where + ": expected NAME = VALUE, got '" + std::string(line.substr(0, 80)) + "'");
        const std::string name(trimmed(line.substr(0, equals)));
        const std::string_view value = trimmed(line.substr(equals + 1));
        if (std::find(known.begin(), known.end(), name) == known.end())
            throw UsageError(where + ": '" + name.substr(0, 80) +
                             "' is not a style setting (a style sets the look, lines and size: the render flags "
                             "without their dashes, such as 'shading' or 'contour-width')");
        if (!seen.insert(name).second) throw UsageError(where + ": '" + name + "' is set twice");
        if (value.empty()) throw UsageError(where + ": '" + name + "' has no value");
        std::string argument;
        if (findFlag("--" + name)->pathValue) {
            const std::filesystem::path path{std::string(value)};
            argument = path.is_relative() && !directory.empty() ? (std::filesystem::path(directory) / path).string()
                                                                : path.string();
        } else {
            argument = withoutBlanksAroundCommas(value);
        }
        result.arguments.push_back("--" + name);
        result.arguments.push_back(std::move(argument));
        result.origins.insert(result.origins.end(), 2, where);
    }
    return result;
}

SourcedArguments expandStyleFile(const std::vector<std::string>& arguments) {
    // "--style FILE" stays where it is (the options record the file); its settings go first.
    SourcedArguments rest{arguments, std::vector<std::string>(arguments.size())};
    separateAttachedValues(rest.arguments, rest.origins); // "--style=FILE" is --style too
    std::string stylePath;
    for (std::size_t i = 0; i < rest.arguments.size(); ++i) {
        if (rest.arguments[i] != "--style") continue;
        if (i + 1 >= rest.arguments.size()) throw UsageError("--style: missing FILE");
        if (rest.arguments[i + 1].empty()) throw UsageError("--style: empty value"); // as every flag says it
        if (!stylePath.empty())
            throw UsageError("--style: given twice (" + detail::quotedFileName(stylePath) + ", " +
                             detail::quotedFileName(rest.arguments[i + 1]) + ")");
        stylePath = rest.arguments[++i];
    }
    if (stylePath.empty()) return rest;

    std::string text;
    try {
        text = readInputBytes(stylePath, kMaxStyleFileBytes, "--style");
    } catch (const FileError& error) {
        throw UsageError(error.what()); // the style file is part of the command line (exit 2)
    }

    SourcedArguments expanded =
        styleArguments(text, stylePath, std::filesystem::path(stylePath).parent_path().string());
    expanded.arguments.insert(expanded.arguments.end(), rest.arguments.begin(), rest.arguments.end());
    expanded.origins.insert(expanded.origins.end(), rest.origins.begin(), rest.origins.end());
    return expanded;
}

} // namespace inkgraph
