#include "scene/MessageText.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <sstream>

namespace inkgraph::detail {

std::string escapedControlCharacters(std::string_view text, ControlsKept kept) {
    // A NUL byte is written "\x00" too: a message is read back through what(), a C string, which ended at it (a pose
    // file's bone name "he\u0000ad" was told as "unknown humanoid bone 'he" and nothing after).
    static constexpr char kDigits[] = "0123456789abcdef";
    std::string line;
    line.reserve(text.size());
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        const bool keptHere = kept == ControlsKept::LineBreaksAndTabs && (c == '\n' || c == '\t');
        if ((byte < 0x20 || byte == 0x7f) && !keptHere) {
            line += "\\x";
            line += kDigits[byte >> 4];
            line += kDigits[byte & 15];
        } else {
            line += c;
        }
    }
    return line;
}

std::string oneLineText(std::string_view text) { return escapedControlCharacters(text, ControlsKept::None); }

std::string excerptForMessage(std::string_view text) {
    std::string excerpt = oneLineText(text.substr(0, std::min(text.size(), kMessageExcerptChars)));
    if (text.size() > kMessageExcerptChars) excerpt += "... (" + std::to_string(text.size()) + " bytes)";
    return excerpt;
}

std::string quotedFileName(std::string_view path) {
    std::string result = "'";
    result += oneLineText(path);
    result += "'";
    return result;
}

std::string quotedExcerpt(std::string_view text) {
    // Appended rather than "'" + text: GCC 12 warns (-Wrestrict, a false positive) on a literal prepended to a
    // temporary string.
    std::string result = "'";
    result += excerptForMessage(text);
    result += "'";
    return result;
}

std::string formatNumber(double value) {
    std::string text;
    for (int precision = 6; precision <= 17; ++precision) {
        std::ostringstream candidate;
        candidate << std::setprecision(precision) << value;
        text = candidate.str();
        if (!std::isfinite(value) || std::strtod(text.c_str(), nullptr) == value) {
            break;
        }
    }
    return text;
}

std::string_view withoutByteOrderMark(std::string_view content) {
    constexpr std::string_view kUtf8ByteOrderMark = "\xEF\xBB\xBF";
    if (content.substr(0, kUtf8ByteOrderMark.size()) == kUtf8ByteOrderMark) {
        content.remove_prefix(kUtf8ByteOrderMark.size());
    }
    return content;
}

std::string formatExtent(double value) {
    std::ostringstream text;
    text << std::setprecision(3) << value;
    return text.str();
}

} // namespace inkgraph::detail
