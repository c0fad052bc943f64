#include "graph/Resource.h"

#include <cassert>
#include <stdexcept>
#include <string>

namespace inkgraph {

int bytesPerPixel(Format format) {
    switch (format) {
    case Format::RGBA32F: return 16;
    case Format::R32F: return 4;
    case Format::RGBA8: return 4;
    case Format::R8: return 1;
    case Format::RGBA16F: return 8;
    case Format::R16F: return 2;
    case Format::Depth32F: return 4;
    }
    assert(false && "bytesPerPixel(): unknown Format");
    return 0;
}

std::string_view formatName(Format format) {
    switch (format) {
    case Format::RGBA32F: return "rgba32f";
    case Format::R32F: return "r32f";
    case Format::RGBA8: return "rgba8";
    case Format::R8: return "r8";
    case Format::RGBA16F: return "rgba16f";
    case Format::R16F: return "r16f";
    case Format::Depth32F: return "depth32f";
    }
    assert(false && "formatName(): unknown Format");
    return "unknown";
}

int scaledSide(int frameSide, int scale, int divisor) {
    if (scale < 1 || divisor < 1)
        throw std::invalid_argument("scaledSide(): 'scale' and 'divisor' must be at least 1, got " +
                                    std::to_string(scale) + " and " + std::to_string(divisor));
    const long long side = static_cast<long long>(frameSide) * scale;
    if (side % divisor != 0)
        throw std::invalid_argument("scaledSide(): a side of " + std::to_string(side) + " pixels is not a whole " +
                                    "multiple of the divisor " + std::to_string(divisor));
    return static_cast<int>(side / divisor);
}

bool isFloatFormat(Format format) {
    return format == Format::RGBA32F || format == Format::R32F || format == Format::RGBA16F || format == Format::R16F ||
           format == Format::Depth32F;
}

ResourceName ResourceName::split(std::string_view resource) {
    const std::size_t dot = resource.find('.');
    if (dot == std::string_view::npos || resource.find('.', dot + 1) != std::string_view::npos) return {};
    return {std::string(resource.substr(0, dot)), std::string(resource.substr(dot + 1))};
}

} // namespace inkgraph
