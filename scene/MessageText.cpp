#include "scene/MessageText.h"

#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <sstream>

namespace inkgraph::detail {

std::string excerptForMessage(std::string_view text) {
    if (text.size() <= kMessageExcerptChars) {
        return std::string(text);
    }
    return std::string(text.substr(0, kMessageExcerptChars)) + "... (" + std::to_string(text.size()) + " bytes)";
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
