#include "render/Messages.h"

#include "scene/MessageText.h"

namespace inkgraph {
namespace {

constexpr std::size_t kLongQuote = 200;
constexpr std::size_t kQuoteEnds = 80;

bool continuesCharacter(unsigned char byte) { return (byte & 0xC0) == 0x80; }

/** The largest cut at or before `position` that does not split a UTF-8 character. */
std::size_t characterStartAtOrBefore(const std::string& text, std::size_t position) {
    while (position > 0 && position < text.size() && continuesCharacter(static_cast<unsigned char>(text[position])))
        --position;
    return position;
}

/** The smallest cut at or after `position` that does not split a UTF-8 character. */
std::size_t characterStartAtOrAfter(const std::string& text, std::size_t position) {
    while (position < text.size() && continuesCharacter(static_cast<unsigned char>(text[position]))) ++position;
    return position;
}

std::string shortened(const std::string& quoted) {
    const std::size_t headEnd = characterStartAtOrBefore(quoted, kQuoteEnds);
    const std::size_t tailStart = characterStartAtOrAfter(quoted, quoted.size() - kQuoteEnds);
    return quoted.substr(0, headEnd) + "..." + quoted.substr(tailStart) + " (" + std::to_string(quoted.size()) +
           " bytes)";
}

} // namespace

std::string printableText(const std::string& text) {
    return detail::escapedControlCharacters(text, detail::ControlsKept::LineBreaksAndTabs);
}

std::string boundedMessage(const std::string& text) {
    const std::string message = printableText(text);
    if (message.size() <= kMessageByteLimit) return message;
    std::string bounded;
    std::size_t position = 0;
    while (position < message.size()) {
        const std::size_t open = message.find('\'', position);
        const std::size_t close = open == std::string::npos ? std::string::npos : message.find('\'', open + 1);
        if (close == std::string::npos) {
            bounded += message.substr(position);
            break;
        }
        const std::string quoted = message.substr(open + 1, close - open - 1);
        bounded += message.substr(position, open + 1 - position);
        bounded += quoted.size() > kLongQuote ? shortened(quoted) : quoted;
        bounded += '\'';
        position = close + 1;
    }
    if (bounded.size() <= kMessageByteLimit) return bounded;
    const std::string cut = " ... (cut; the message had " + std::to_string(message.size()) + " bytes)";
    return bounded.substr(0, characterStartAtOrBefore(bounded, kMessageByteLimit - cut.size())) + cut;
}

} // namespace inkgraph
