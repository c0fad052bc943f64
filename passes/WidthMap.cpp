#include "passes/WidthMap.h"

#include <stdexcept>

namespace inkgraph {
namespace {

constexpr const char* kChannels = "RGBA";

[[noreturn]] void refuse(const std::string& text, const std::string& why) {
    throw std::invalid_argument("--outline-width-map: " + why + ", got '" + text + "'");
}

int parseChannel(const std::string& text, const std::string& channel) {
    if (channel.size() == 1)
        for (int index = 0; index < 4; ++index)
            if (channel[0] == kChannels[index] || channel[0] == kChannels[index] + ('a' - 'A')) return index;
    refuse(text, "unknown channel '" + channel + "' (expected R, G, B or A)");
}

} // namespace

std::string WidthMap::text() const {
    switch (source) {
    case Source::None: return "none";
    case Source::VertexColor: return std::string("color:") + kChannels[channel];
    case Source::Texture: return "texture:" + texture + ":" + kChannels[channel];
    }
    return "none";
}

WidthMap parseWidthMap(const std::string& text) {
    WidthMap map;
    if (text == "none") return map;
    const std::string expected = "expected none, color:R|G|B|A or texture:FILE:R|G|B|A";
    if (text.rfind("color:", 0) == 0) {
        map.source = WidthMap::Source::VertexColor;
        map.channel = parseChannel(text, text.substr(6));
        return map;
    }
    if (text.rfind("texture:", 0) == 0) {
        const std::string rest = text.substr(8);
        const std::size_t colon = rest.rfind(':');
        if (colon == std::string::npos) refuse(text, expected + " (the channel is missing)");
        map.source = WidthMap::Source::Texture;
        map.texture = rest.substr(0, colon);
        if (map.texture.empty()) refuse(text, expected + " (the image's name is empty)");
        map.channel = parseChannel(text, rest.substr(colon + 1));
        return map;
    }
    refuse(text, expected);
}

} // namespace inkgraph
