#pragma once
/** @file How text from a file and numbers appear in the scene layer's messages: every reader and every scene check
 *  that quotes a file-given name or prints a value uses these. Internal to the scene layer (and the layers above, for
 *  the byte-order mark and the names of files on progress lines). */

#include <cstddef>
#include <string>
#include <string_view>

namespace inkgraph::detail {

/** Which control characters escapedControlCharacters() leaves as they are. */
enum class ControlsKept { None, LineBreaksAndTabs };

/** `text` with its control characters (bytes 0-31 and 127) but those `kept` written as "\xNN": a file name or a
 *  name inside a model may hold a terminal's escape sequences, which a message must show, not send. */
std::string escapedControlCharacters(std::string_view text, ControlsKept kept);

/** `text` with every control character, line breaks and tabs included, written as "\xNN": a name shown on one line
 *  of a message or a progress report, where a line break in a file's name split the line. */
std::string oneLineText(std::string_view text);

/** Text taken from a file (a name, a URI, a token) as it may appear in a message: oneLineText() of at most
 *  kMessageExcerptChars characters, longer text cut with "..." and its byte count, so a 64 MB data: URI or name never
 *  fills a terminal or a log. Every reader quotes file-given text through this one function. */
std::string excerptForMessage(std::string_view text);

/** A file's name as the user gave it (a model, an output), in single quotes and on one line (oneLineText()), whole:
 *  how messages and progress lines name it. */
std::string quotedFileName(std::string_view path);

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
