#pragma once
/** @file How text from a file and numbers appear in the scene layer's messages: every reader and every scene check
 *  that quotes a file-given name or prints a value uses these. Internal to the scene layer (and the app's style-file
 *  reader, for the byte-order mark). */

#include <cstddef>
#include <string>
#include <string_view>

namespace inkgraph::detail {

/** Text taken from a file (a name, a URI, a token) as it may appear in a message: at most kMessageExcerptChars
 *  characters, longer text cut with "..." and its byte count, so a 64 MB data: URI or name never fills a terminal
 *  or a log. Every reader quotes file-given text through this one function. */
std::string excerptForMessage(std::string_view text);

/** excerptForMessage(text) in single quotes: how a file-given name appears in a warning or an error. */
std::string quotedExcerpt(std::string_view text);

/** Characters of file-given text that excerptForMessage() keeps. */
inline constexpr std::size_t kMessageExcerptChars = 60;

/** The shortest text that reads back as `value` (e.g. 0.5, 1e+15, 3.1415926535897936, inf), for messages. */
std::string formatNumber(double value);

/** Three significant digits ("1.73e+16"), for sizes and distances in messages. */
std::string formatExtent(double value);

/** `content` without a leading UTF-8 byte-order mark (EF BB BF), which some Windows tools write before text. */
std::string_view withoutByteOrderMark(std::string_view content);

} // namespace inkgraph::detail
