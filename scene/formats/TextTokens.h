#pragma once
// The blanks and tokens of the text formats' lines (OBJ, MTL, ASCII PLY), shared by their readers.

#include <cstddef>
#include <string_view>
#include <vector>

namespace inkgraph::detail {

/** A blank between a line's tokens: space and tab, and the \r, \f and \v that exporters leave in lines. */
inline bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

/** `text` without its leading and trailing blanks. */
inline std::string_view trimmed(std::string_view text) {
    while (!text.empty() && isBlank(text.front())) text.remove_prefix(1);
    while (!text.empty() && isBlank(text.back())) text.remove_suffix(1);
    return text;
}

/** The runs of non-blank characters of `text`, in order. */
inline std::vector<std::string_view> tokensOf(std::string_view text) {
    std::vector<std::string_view> tokens;
    std::size_t at = 0;
    while (at < text.size()) {
        while (at < text.size() && isBlank(text[at])) ++at;
        const std::size_t start = at;
        while (at < text.size() && !isBlank(text[at])) ++at;
        if (at > start) tokens.push_back(text.substr(start, at - start));
    }
    return tokens;
}

} // namespace inkgraph::detail
