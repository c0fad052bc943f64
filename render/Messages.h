#pragma once
/** @file The bound on what a user reads: every error and warning inkgraph prints or raises is at most
 *  kMessageByteLimit bytes, whatever it quotes. Readers already quote file-given text in part
 *  (scene's excerptForMessage()); paths and values the user typed are whole until here. */

#include <cstddef>
#include <string>

namespace inkgraph {

inline constexpr std::size_t kMessageByteLimit = 2000;

/** `text` with every control character but the line break and the tab (bytes 0-31 and 127) written as "\xNN": a
 *  file name or a name inside a model may hold a terminal's escape sequences, which a message must show, not send. */
std::string printableText(const std::string& text);

/** printableText(message) as it is when it fits kMessageByteLimit bytes; else each quoted run ('...') longer than 200
 *  bytes keeps its first and last 80 bytes around "..." and says its length ("(5012 bytes)"), and what is still too
 *  long is cut at the limit. Cuts fall between UTF-8 characters. */
std::string boundedMessage(const std::string& message);

} // namespace inkgraph
