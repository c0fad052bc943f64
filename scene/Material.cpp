#include "scene/Material.h"

#include <sstream>

namespace inkgraph {
namespace {

/** A float the file gave, to the 6 significant digits a float holds: 0.2f, whose double is 0.20000000298..., is 0.2. */
std::string formatFloat(float value) {
    std::ostringstream text;
    text << value;
    return text.str();
}

} // namespace

std::string whyMaterialDrawsNothing(const Material& material) {
    const float alpha = material.baseColorFactor.a;
    if (material.alphaMode == AlphaMode::Mask && alpha < material.alphaCutoff)
        return "alphaMode MASK with a base colour alpha of " + formatFloat(alpha) + ", under its alphaCutoff " +
               formatFloat(material.alphaCutoff) + ", cuts out every fragment";
    if (material.alphaMode == AlphaMode::Blend && alpha < kLeastVisibleAlpha)
        return "alphaMode BLEND with a base colour alpha of " + formatFloat(alpha) +
               ", under half a level of 8-bit colour (1/510), changes no pixel";
    return "";
}

} // namespace inkgraph
