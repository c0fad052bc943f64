#pragma once
/** @file A warning as a record: what went wrong (a stable code), the text the command line prints, and the file and
 *  the thing inside the model it concerns. The scene layer is the lowest that warns (the readers); the passes
 *  (texture decoding) and the app (shade maps, the camera) use the same record. Every code is a row of warningCodes(),
 *  the one table; docs/robustness.md's "Warning codes" section is generated from it (`inkgraph help --docs
 *  warning-codes`). */

#include <cstddef>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace inkgraph {

/** Every kind of warning, in the order of warningCodes(): a new kind is a value here and its row there. */
enum class WarningKind {
    TextureMissing,
    TextureUndecodable,
    TextureWithoutCoreImage,
    TextureCoordinateSetUnsupported,
    TextureCoordinatesMissing,
    TextureTransformDropped,
    TextureDownscaled,
    MaskIgnored,
    ValueOutOfRange,
    MaterialValueInvalid,
    ExtrasKeyIgnored,
    VrmPropertyInvalid,
    MToonFeatureNotDrawn,
    MToonOutlineWidth,
    MaterialLibraryMissing,
    MaterialStatementIgnored,
    MaterialRedefined,
    MaterialUndefined,
    MaterialInvisible,
    WhiteEmissionIgnored,
    PrimitiveSkipped,
    IndicesIncomplete,
    MeshDegenerate,
    DetailsMerged,
    MeshInsideOut,
    WindingMixed,
    NormalsInward,
    TextureIgnored,
    VertexValuesIgnored,
    NormalsMissing,
    TexcoordsMissing,
    TexcoordsNonFinite,
    ColoursNonFinite,
    ElementsSkipped,
    PolygonsFanned,
    TrailingDataIgnored,
    StlSolidIncomplete,
    CameraIgnored,
    CameraAspectIgnored,
    LightIgnored,
    AnimationIgnored,
    AnimationChannelIgnored,
    PoseBoneMissing,
    MorphAttributeIgnored,
    MorphWeightsMismatched,
    SkinWeightsUnnormalised,
    TimeUnused,
    GltfParserMessage,
    ShadeMapUnused,
    LookSettingUnused,
    ModelOutsideView,
    WidthMapUnread,
    TriangleIdInexact,
    LinesSkipped,
    LinesEmpty,
    Count ///< not a kind: the number of them
};

/** A row of the table: the kind, its stable kebab-case code and what it means, in one line. */
struct WarningCode {
    WarningKind kind;
    std::string_view code;
    std::string_view meaning;
};

/** Every warning code, in WarningKind's order, each once (tests/scene/WarningTest.cpp checks). */
const std::vector<WarningCode>& warningCodes();

/** The code of `kind` ("texture-missing"). */
std::string_view warningCode(WarningKind kind);

struct Warning {
    std::string code;    ///< a code of warningCodes(): what went wrong, stable across releases
    std::string message; ///< what the command line prints after "inkgraph: warning: "
    std::string file;    ///< the file it concerns (the texture's, the shade map's, the model's), or ""
    std::string item;    ///< the thing inside the model (material, mesh, texture, node, primitive) as the message
                         ///< names it, or ""

    bool operator==(const Warning&) const = default;
};

/** A warning of `kind`: its code from the table, so no site spells one. */
Warning makeWarning(WarningKind kind, std::string message, std::string file = {}, std::string item = {});

/** "[code] message (file, item)", for test failures. */
std::ostream& operator<<(std::ostream& out, const Warning& warning);

} // namespace inkgraph
