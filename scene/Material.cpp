#include "scene/Material.h"

#include "scene/MessageText.h"

namespace inkgraph {

std::string whyMaterialDrawsNothing(const Material& material) {
    const float alpha = material.baseColorFactor.a;
    if (material.alphaMode == AlphaMode::Mask && alpha < material.alphaCutoff)
        return "alphaMode MASK with a base colour alpha of " + formatNumber(alpha) + ", under its alphaCutoff " +
               formatNumber(material.alphaCutoff) + ", cuts out every fragment";
    if (material.alphaMode == AlphaMode::Blend && alpha < kLeastVisibleAlpha)
        return "alphaMode BLEND with a base colour alpha of " + formatNumber(alpha) +
               ", under half a level of 8-bit colour (1/510), changes no pixel";
    return "";
}

} // namespace inkgraph
