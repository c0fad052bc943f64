// libFuzzer target: style files (flags/StyleFile) and, through them, the parser of every look flag they may set.
#include "flags/Options.h"
#include "flags/StyleFile.h"

#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        inkgraph::SourcedArguments style = inkgraph::styleArguments(text, "fuzz.style", "styles");
        for (const char* argument : {"model.obj", "-o", "out.png"}) {
            style.arguments.push_back(argument);
            style.origins.emplace_back();
        }
        inkgraph::parseRenderOptions(style.arguments, style.origins);
    } catch (const inkgraph::UsageError&) {
    }
    return 0;
}
