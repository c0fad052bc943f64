#include "scene/MessageText.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <sstream>

namespace inkgraph::detail {

std::string excerptForMessage(std::string_view text) {
    // A NUL byte is written "\x00": a message is read back through what(), a C string, which ended at it (a pose
    // file's bone name "he\u0000ad" was told as "unknown humanoid bone 'he" and nothing after).
    const std::string_view kept = text.substr(0, std::min(text.size(), kMessageExcerptChars));
    std::string excerpt;
    excerpt.reserve(kept.size());
    for (const char c : kept) {
        if (c == '\0')
            excerpt += "\\x00";
        else
            excerpt += c;
    }
    if (text.size() > kMessageExcerptChars) excerpt += "... (" + std::to_string(text.size()) + " bytes)";
    return excerpt;
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
