#pragma once
/** @file A strict reader of the SVG documents postfx/SvgLines.h writes, for tests (no GL): the size, the title, the
 *  background rect, and each <g> layer's stroke and paths. It reads exactly that subset of XML and SVG and throws
 *  std::runtime_error on anything else or anything malformed (unbalanced or mismatched tags, an unknown element,
 *  entity or attribute syntax, text outside <title>, a path outside a group, a path command other than an initial
 *  M, then L, then an optional final Z), so parsing a document is itself a check of it. Coordinates are returned as
 *  written: SVG user units (output pixels, origin top-left). Header-only: std and OpenCV core only. */

#include <opencv2/core.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

namespace inkgraph::test {

/** One <g> layer. */
struct SvgPathGroup {
    std::string id;                              ///< e.g. "lines-contour"
    std::string label;                           ///< inkscape:label, empty when absent
    std::string stroke;                          ///< as written, e.g. "#000000"
    double opacity = 1.0;                        ///< the group's opacity (the colour's alpha); 1 when absent
    double strokeWidth = 0.0;                    ///< user units
    std::vector<std::vector<cv::Point2d>> paths; ///< each <path>'s M and L points, in order
    std::vector<bool> closed;                    ///< per path: whether it ended with Z
    std::vector<double> pathOpacities;           ///< per path: its stroke-opacity, 1 when absent (a faded line's)
};

/** The whole document. */
struct SvgPathDocument {
    int width = 0;                         ///< the <svg> width attribute (plain pixels)
    int height = 0;                        ///< the <svg> height attribute
    std::string title;                     ///< <title>, entities resolved
    std::optional<std::string> background; ///< fill of <rect id="background">, when there is one
    std::vector<SvgPathGroup> groups;      ///< in document order
};

namespace svg_paths_detail {

[[noreturn]] inline void fail(const std::string& message, std::size_t at) {
    throw std::runtime_error("parseSvgPathDocument(): " + message + " at byte " + std::to_string(at));
}

inline bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

inline bool isNameCharacter(char c, bool first) {
    const bool letter = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == ':';
    return letter || (!first && ((c >= '0' && c <= '9') || c == '-' || c == '.'));
}

/** Resolves the five predefined entities; a raw '<' or any other '&' is an error. */
inline std::string unescape(std::string_view text, std::size_t at) {
    static const std::pair<std::string_view, char> kEntities[] = {
        {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}};
    std::string out;
    for (std::size_t index = 0; index < text.size();) {
        if (text[index] == '<') fail("raw '<' in text or attribute", at + index);
        if (text[index] != '&') {
            out += text[index++];
            continue;
        }
        bool known = false;
        for (const auto& [entity, character] : kEntities)
            if (text.substr(index, entity.size()) == entity) {
                out += character;
                index += entity.size();
                known = true;
                break;
            }
        if (!known) fail("unknown entity or bare '&'", at + index);
    }
    return out;
}

inline double parseNumber(std::string_view text, const std::string& what, std::size_t at) {
    double value = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || error != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
        fail(what + ": '" + std::string(text) + "' is not a finite number", at);
    return value;
}

inline int parseInteger(std::string_view text, const std::string& what, std::size_t at) {
    int value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || error != std::errc() || end != text.data() + text.size() || value < 1)
        fail(what + ": '" + std::string(text) + "' is not a whole number >= 1", at);
    return value;
}

/** Path data as SvgLines writes it: "M x y" then " L x y" any number of times, then optionally " Z". */
inline std::pair<std::vector<cv::Point2d>, bool> parsePathData(std::string_view data, std::size_t at) {
    std::vector<std::string_view> tokens;
    for (std::size_t index = 0; index < data.size();) {
        if (isSpace(data[index])) {
            ++index;
            continue;
        }
        std::size_t end = index;
        while (end < data.size() && !isSpace(data[end])) ++end;
        tokens.push_back(data.substr(index, end - index));
        index = end;
    }
    std::vector<cv::Point2d> points;
    bool closed = false;
    for (std::size_t index = 0; index < tokens.size();) {
        const std::string_view command = tokens[index];
        if (command == "Z") {
            if (index + 1 != tokens.size() || points.size() < 2)
                fail("path 'Z' must end a path of 2 points or more", at);
            closed = true;
            break;
        }
        if (command != (points.empty() ? "M" : "L"))
            fail("path command '" + std::string(command) + "' where " + (points.empty() ? "M" : "L or Z") +
                     " was expected",
                 at);
        if (index + 2 >= tokens.size()) fail("path command '" + std::string(command) + "' lacks its x and y", at);
        points.emplace_back(parseNumber(tokens[index + 1], "path x", at), parseNumber(tokens[index + 2], "path y", at));
        index += 3;
    }
    if (points.empty()) fail("empty path data", at);
    return {std::move(points), closed};
}

struct Element {
    std::string name;
    std::map<std::string, std::string> attributes;
    bool selfClosing = false;
    bool closing = false;
    std::size_t at = 0;

    const std::string& required(const std::string& attribute) const {
        const auto found = attributes.find(attribute);
        if (found == attributes.end()) fail("<" + name + "> lacks attribute '" + attribute + "'", at);
        return found->second;
    }
    std::optional<std::string> optional(const std::string& attribute) const {
        const auto found = attributes.find(attribute);
        return found == attributes.end() ? std::nullopt : std::optional<std::string>(found->second);
    }
};

/** Reads one tag starting at text[at] == '<'; leaves `at` after its '>'. */
inline Element readTag(const std::string& text, std::size_t& at) {
    Element element;
    element.at = at;
    std::size_t index = at + 1;
    if (index < text.size() && text[index] == '/') {
        element.closing = true;
        ++index;
    }
    const std::size_t nameStart = index;
    while (index < text.size() && isNameCharacter(text[index], index == nameStart)) ++index;
    if (index == nameStart) fail("a tag without a name", at);
    element.name = text.substr(nameStart, index - nameStart);
    for (;;) {
        const std::size_t beforeSpace = index;
        while (index < text.size() && isSpace(text[index])) ++index;
        if (index >= text.size()) fail("unterminated tag <" + element.name + ">", at);
        if (text[index] == '>') {
            ++index;
            break;
        }
        if (text.compare(index, 2, "/>") == 0 && !element.closing) {
            element.selfClosing = true;
            index += 2;
            break;
        }
        if (element.closing) fail("attributes in a closing tag </" + element.name + ">", at);
        if (index == beforeSpace) fail("no space before an attribute in <" + element.name + ">", index);
        const std::size_t attributeStart = index;
        while (index < text.size() && isNameCharacter(text[index], index == attributeStart)) ++index;
        if (index == attributeStart) fail("bad attribute name in <" + element.name + ">", index);
        const std::string attribute = text.substr(attributeStart, index - attributeStart);
        if (text.compare(index, 2, "=\"") != 0) fail("attribute '" + attribute + "' needs =\"...\"", index);
        index += 2;
        const std::size_t valueEnd = text.find('"', index);
        if (valueEnd == std::string::npos) fail("unterminated value of '" + attribute + "'", index);
        const std::string value = unescape(std::string_view(text).substr(index, valueEnd - index), index);
        if (!element.attributes.emplace(attribute, value).second)
            fail("attribute '" + attribute + "' repeated in <" + element.name + ">", attributeStart);
        index = valueEnd + 1;
    }
    at = index;
    return element;
}

} // namespace svg_paths_detail

/** Parses a document of postfx/SvgLines.h's svgDocument(); throws std::runtime_error naming the byte offset on
 *  anything it does not expect (see the file comment). */
inline SvgPathDocument parseSvgPathDocument(const std::string& svgText) {
    using namespace svg_paths_detail;
    SvgPathDocument document;
    std::size_t at = 0;
    static const std::string kDeclaration = "<?xml version=\"1.0\" encoding=\"UTF-8\"";
    if (svgText.compare(0, kDeclaration.size(), kDeclaration) != 0) fail("no XML declaration first", 0);
    at = svgText.find("?>");
    if (at == std::string::npos) fail("unterminated XML declaration", 0);
    at += 2;

    std::vector<std::string> open; // element names from the root down
    bool rootSeen = false, titleSeen = false;
    SvgPathGroup* group = nullptr;
    while (at < svgText.size()) {
        if (svgText[at] != '<') {
            const std::size_t textEnd = std::min(svgText.find('<', at), svgText.size());
            const std::string_view raw = std::string_view(svgText).substr(at, textEnd - at);
            const bool blank = raw.find_first_not_of(" \t\n\r") == std::string_view::npos;
            if (!open.empty() && open.back() == "title") {
                document.title += unescape(raw, at);
            } else if (!blank) {
                fail("text outside <title>", at);
            }
            at = textEnd;
            continue;
        }
        if (svgText.compare(at, 2, "<?") == 0 || svgText.compare(at, 2, "<!") == 0)
            fail("a processing instruction, comment, CDATA or DOCTYPE (not written by svgDocument())", at);
        const Element element = readTag(svgText, at);
        if (element.closing) {
            if (open.empty() || open.back() != element.name)
                fail("</" + element.name + "> does not close " + (open.empty() ? "anything" : "<" + open.back() + ">"),
                     element.at);
            if (element.name == "g") group = nullptr;
            open.pop_back();
            continue;
        }
        const std::string parent = open.empty() ? std::string() : open.back();
        if (element.name == "svg") {
            if (rootSeen || !open.empty() || element.selfClosing)
                fail("a second, nested or self-closing <svg>", element.at);
            rootSeen = true;
            if (element.required("xmlns") != "http://www.w3.org/2000/svg")
                fail("<svg> has the wrong xmlns", element.at);
            if (element.required("xmlns:inkscape") != "http://www.inkscape.org/namespaces/inkscape")
                fail("<svg> has the wrong xmlns:inkscape", element.at);
            document.width = parseInteger(element.required("width"), "<svg> width", element.at);
            document.height = parseInteger(element.required("height"), "<svg> height", element.at);
            const std::string expectedViewBox =
                "0 0 " + std::to_string(document.width) + " " + std::to_string(document.height);
            if (element.required("viewBox") != expectedViewBox)
                fail("<svg> viewBox '" + element.required("viewBox") + "' is not '" + expectedViewBox + "'",
                     element.at);
        } else if (element.name == "title") {
            if (parent != "svg" || titleSeen || element.selfClosing) fail("<title> misplaced or repeated", element.at);
            titleSeen = true;
        } else if (element.name == "rect") {
            if (parent != "svg" || !element.selfClosing || element.required("id") != "background" ||
                document.background)
                fail("only one self-closing <rect id=\"background\"> in <svg> is expected", element.at);
            if (element.required("width") != std::to_string(document.width) ||
                element.required("height") != std::to_string(document.height))
                fail("the background rect does not cover the image", element.at);
            document.background = element.required("fill");
        } else if (element.name == "g") {
            if (parent != "svg" || element.selfClosing) fail("<g> must be an open tag directly in <svg>", element.at);
            SvgPathGroup parsed;
            parsed.id = element.required("id");
            parsed.label = element.optional("inkscape:label").value_or("");
            parsed.stroke = element.required("stroke");
            parsed.strokeWidth = parseNumber(element.required("stroke-width"), "<g> stroke-width", element.at);
            if (element.optional("stroke-opacity"))
                fail("<g> has stroke-opacity (its opacity is the group's)", element.at);
            if (const auto opacity = element.optional("opacity"))
                parsed.opacity = parseNumber(*opacity, "<g> opacity", element.at);
            for (const SvgPathGroup& earlier : document.groups)
                if (earlier.id == parsed.id) fail("repeated group id '" + parsed.id + "'", element.at);
            document.groups.push_back(std::move(parsed));
            group = &document.groups.back();
        } else if (element.name == "path") {
            if (parent != "g" || group == nullptr || !element.selfClosing)
                fail("<path/> must be self-closing inside a <g>", element.at);
            auto [points, closed] = parsePathData(element.required("d"), element.at);
            group->paths.push_back(std::move(points));
            group->closed.push_back(closed);
            const auto opacity = element.optional("stroke-opacity");
            group->pathOpacities.push_back(opacity ? parseNumber(*opacity, "<path> stroke-opacity", element.at) : 1.0);
        } else {
            fail("unexpected element <" + element.name + ">", element.at);
        }
        if (!rootSeen) fail("<" + element.name + "> before <svg>", element.at);
        if (!element.selfClosing) open.push_back(element.name);
    }
    if (!rootSeen) fail("no <svg> element", at);
    if (!open.empty()) fail("<" + open.back() + "> is never closed", at);
    if (!titleSeen) fail("no <title>", at);
    return document;
}

/** The <g> layers of a document of svgDocument(), in order; throws as parseSvgPathDocument() does. */
inline std::vector<SvgPathGroup> parseSvgPathGroups(const std::string& svgText) {
    return parseSvgPathDocument(svgText).groups;
}

} // namespace inkgraph::test
