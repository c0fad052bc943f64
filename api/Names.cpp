#include "api/Internal.h"

#include "passes/gbuffer/GBufferPrecision.h"
#include "passes/lines/LineTypes.h"
#include "passes/shade/ShadingModel.h"

#include <iterator>

namespace inkgraph::api {
inline namespace INKGRAPH_ABI_NAMESPACE {
namespace {

/** The line types' names in LineType's order, which is the registry's (tests/api/ApiTest.cpp checks the two agree). */
const char* const kLineTypeNames[] = {"hidden-mesh-silhouette",
                                      "hidden-crease",
                                      "hidden-border",
                                      "hidden-intersection",
                                      "hidden-suggestive-object",
                                      "outline",
                                      "silhouette",
                                      "normal-edge",
                                      "depth-edge",
                                      "crease",
                                      "border",
                                      "intersection",
                                      "material-boundary",
                                      "object-boundary",
                                      "suggestive",
                                      "suggestive-object",
                                      "contour",
                                      "mesh-silhouette"};
static_assert(std::size(kLineTypeNames) == std::size_t(LineType::MeshSilhouette) + 1);

/** Error(Usage) for an enum value outside its enumerators (a cast from a number): it names nothing. */
template <class Enum>
Error noSuch(const char* enumName, Enum value) {
    return Error(Error::Kind::Usage, std::string("nameOf(): no ") + enumName + " has the value " +
                                         std::to_string(static_cast<long long>(value)));
}

} // namespace

std::string nameOf(Shading shading) {
    if (static_cast<int>(shading) < 0 || shading > Shading::Auto) throw noSuch("Shading", shading);
    return traitsOf(static_cast<ShadingModel>(shading)).name;
}

std::string nameOf(LineType type) {
    if (static_cast<std::size_t>(type) >= std::size(kLineTypeNames)) throw noSuch("LineType", type);
    return kLineTypeNames[static_cast<std::size_t>(type)];
}

std::string nameOf(ViewVector mode) {
    switch (mode) {
    case ViewVector::Exact: return "exact";
    case ViewVector::Constant: return "constant";
    }
    throw noSuch("ViewVector", mode);
}

std::string nameOf(FaceOrientation method) {
    switch (method) {
    case FaceOrientation::Standard: return "standard";
    case FaceOrientation::DuringTriangles: return "during-triangles";
    case FaceOrientation::DuringVertices: return "during-vertices";
    case FaceOrientation::AfterVertices: return "after-vertices";
    }
    throw noSuch("FaceOrientation", method);
}

std::string nameOf(Precision precision) {
    switch (precision) {
    case Precision::Float32: return "float";
    case Precision::Float16: return "half";
    }
    throw noSuch("Precision", precision);
}

LineType lineTypeNamed(const std::string& name) {
    std::string names;
    for (std::size_t index = 0; index < std::size(kLineTypeNames); ++index) {
        if (name == kLineTypeNames[index]) return static_cast<LineType>(index);
        names += (names.empty() ? "" : ", ") + std::string(kLineTypeNames[index]);
    }
    throw Error(Error::Kind::Usage, "lineTypeNamed(): no line type '" + name + "' (there are: " + names + ")");
}

std::string vectorText(const Vec3& vector) {
    return exactText(vector.x) + "," + exactText(vector.y) + "," + exactText(vector.z);
}

std::string colorText(const Color& color) {
    return exactText(color.r) + "," + exactText(color.g) + "," + exactText(color.b) + "," + exactText(color.a);
}

} // namespace INKGRAPH_ABI_NAMESPACE
} // namespace inkgraph::api
