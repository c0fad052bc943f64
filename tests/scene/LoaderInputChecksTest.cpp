// Bad or unusual input must be refused with a clear message or rendered right, never turned silently into a wrong
// picture (issue 16): byte-order marks, out-of-range scene and material indices, required extensions, extreme
// extents, STL told apart by content, long names and URIs in messages, the files a load reads, and textures that
// are named but never decoded.

#include "scene/Scene.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/types.h>

#include <algorithm>
#include <fstream>
#include <string>

namespace inkgraph {
namespace {

using test::GltfWriter;
using test::TempFile;

const std::string kByteOrderMark = "\xEF\xBB\xBF";
const std::string kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

bool anyWarningContains(const Scene& scene, const std::string& part) {
    return std::ranges::any_of(scene.report.warnings, [&](const Warning& w) { return contains(w.message, part); });
}

/** One unit right triangle in one mesh on one node, with `primitiveExtra` and `nodeExtra` spliced into the mesh's
 *  primitive and the node, and `top` into the top level. */
std::string triangleGltf(const std::string& primitiveExtra = "", const std::string& nodeExtra = "",
                         const std::string& top = "") {
    GltfWriter writer;
    const int positions = writer.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    return writer.gltf("\"meshes\": [{\"name\": \"plate\", \"primitives\": [{\"attributes\": {\"POSITION\": " +
                       std::to_string(positions) + "}" + primitiveExtra +
                       "}]}], \"nodes\": [{\"name\": \"holder\", \"mesh\": 0" + nodeExtra +
                       "}], \"scenes\": [{\"nodes\": [0]}]" + top);
}

/** The body of a one-triangle glTF (mesh, node, scene) with its positions added to `writer`: for tests that choose
 *  how the writer puts its buffer in the file. */
std::string triangleBody(GltfWriter& writer) {
    const int positions = writer.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    return "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
           "}}]}], \"nodes\": [{\"mesh\": 0}], \"scenes\": [{\"nodes\": [0]}]";
}

/** A folder under the temp directory, removed with everything in it on destruction. */
class TempFolder {
public:
    TempFolder() {
        mPath = std::filesystem::temp_directory_path() /
                ("inkgraph_inputs_" + std::to_string(::getpid()) + "_" + std::to_string(sCounter++));
        std::filesystem::create_directories(mPath);
    }
    ~TempFolder() {
        std::error_code ignored;
        std::filesystem::remove_all(mPath, ignored);
    }
    std::string write(const std::string& name, const std::string& content) const {
        const std::string path = (mPath / name).string();
        std::ofstream(path, std::ios::binary) << content;
        return path;
    }
    std::string path(const std::string& name) const { return (mPath / name).string(); }

private:
    static inline int sCounter = 0;
    std::filesystem::path mPath;
};

// --- 1. byte-order marks ---

TEST(LoaderInputChecks, ObjWithByteOrderMarkKeepsItsFirstVertex) {
    // Read as a keyword, "\xEF\xBB\xBFv" was skipped: two vertices were left and face index 3 was out of range.
    const TempFile file("bom.obj", kByteOrderMark + kTriangleObj);
    const Scene scene = loadScene(file.path());
    const Mesh& mesh = scene.meshes.at(0);
    ASSERT_EQ(mesh.positions.size(), 3u);
    EXPECT_EQ(test::worldPosition(scene, mesh.positions[mesh.triangles[0].x]), glm::dvec3(0, 0, 0));
    EXPECT_EQ(test::worldPosition(scene, mesh.positions[mesh.triangles[0].y]), glm::dvec3(1, 0, 0));
    EXPECT_EQ(test::worldPosition(scene, mesh.positions[mesh.triangles[0].z]), glm::dvec3(0, 1, 0));
}

TEST(LoaderInputChecks, AsciiStlWithByteOrderMarkIsAscii) {
    const TempFile file("bom.stl", kByteOrderMark + "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
                                                    "vertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n");
    const Scene scene = loadScene(file.path());
    EXPECT_EQ(scene.report.format, "stl-ascii");
    EXPECT_EQ(scene.triangleCount(), 1u);
}

TEST(LoaderInputChecks, GltfJsonWithByteOrderMarkLoads) {
    // tinygltf's JSON parser skips the mark itself; this keeps it that way (and the reader's own JSON passes).
    const TempFile file("bom.gltf", kByteOrderMark + triangleGltf());
    EXPECT_EQ(loadScene(file.path()).triangleCount(), 1u);
}

// --- 3. the default scene ---

TEST(LoaderInputChecks, GltfSceneIndexOutOfRangeIsRefused) {
    // It used to draw scene 0 instead.
    const TempFile file("scene7.gltf", triangleGltf("", "", ", \"scene\": 7"));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_TRUE(contains(message, "loadScene(): '" + file.path() + "'")) << message;
    EXPECT_TRUE(contains(message, "\"scene\": 7 is out of range (file has 1 scenes)")) << message;
}

// --- 4. materials ---

TEST(LoaderInputChecks, GltfMaterialIndexOutOfRangeIsRefused) {
    // It used to render in the default grey.
    const TempFile file("material.gltf", triangleGltf(", \"material\": 3"));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_TRUE(contains(message, "mesh 0 'plate' primitive 0: material index 3 out of range (file has 0 materials)"))
        << message;
}

TEST(LoaderInputChecks, ObjMissingMaterialLibraryIsAWarningNamingIt) {
    const TempFile file("nolib.obj", "mtllib absent.mtl\nusemtl Steel\n" + kTriangleObj);
    const Scene scene = loadScene(file.path());
    EXPECT_EQ(scene.triangleCount(), 1u);
    EXPECT_TRUE(anyWarningContains(scene, "mtllib 'absent.mtl' (line 1)"))
        << ::testing::PrintToString(scene.report.warnings);
    EXPECT_EQ(scene.report.inputFiles, std::vector<std::string>{file.path()});
}

TEST(LoaderInputChecks, ReferencedFilesTakeEveryMtllibLineOnceWhereverItStands) {
    // Only lines whose first word is mtllib name libraries: not a comment or an object that mentions it; a line that
    // says it twice counts once; indented, CRLF and unterminated last lines count.
    const TempFolder folder;
    const std::string model = folder.write("many.obj", "# mtllib commented.mtl\n" + kTriangleObj +
                                                           "o mtllib_object\n  mtllib mtllib.mtl\r\n" +
                                                           "v 0 0 0 # mtllib trailing.mtl\nmtllib\nmtllib last.mtl");
    EXPECT_EQ(referencedFiles(model), (std::vector<std::string>{folder.path("mtllib.mtl"), folder.path("last.mtl")}));
}

TEST(LoaderInputChecks, ReferencedFilesSeeAMaterialLibraryAfterAByteOrderMark) {
    const TempFolder folder;
    const std::string model = folder.write("bom.obj", kByteOrderMark + "mtllib parts.mtl\n" + kTriangleObj);
    EXPECT_EQ(referencedFiles(model), std::vector<std::string>{folder.path("parts.mtl")});
}

TEST(LoaderInputChecks, ObjUndefinedMaterialIsAWarningNamingIt) {
    const TempFolder folder;
    const std::string library = folder.write("parts.mtl", "newmtl Steel\nKd 0.5 0.5 0.5\n");
    const std::string model = folder.write("part.obj", "mtllib parts.mtl\nusemtl Steel\nusemtl Brass\n" + kTriangleObj);
    const Scene scene = loadScene(model);
    EXPECT_TRUE(anyWarningContains(scene, "'Brass' (line 3)")) << ::testing::PrintToString(scene.report.warnings);
    EXPECT_FALSE(anyWarningContains(scene, "'Steel'"));
    EXPECT_EQ(scene.report.inputFiles, (std::vector<std::string>{model, library}));
}

// --- 5. required extensions ---

TEST(LoaderInputChecks, UnknownRequiredExtensionIsRefusedNamingIt) {
    const std::string top = ", \"extensionsUsed\": [\"EXT_future\", \"KHR_lights_punctual\", \"KHR_texture_basisu\"], "
                            "\"extensionsRequired\": [\"EXT_future\", \"KHR_lights_punctual\", \"KHR_texture_basisu\"]";
    const TempFile file("required.gltf", triangleGltf("", "", top));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_TRUE(contains(message, "requires the unsupported extensions 'EXT_future', 'KHR_texture_basisu'")) << message;
}

TEST(LoaderInputChecks, SupportedRequiredExtensionLoads) {
    const std::string top = ", \"extensionsUsed\": [\"KHR_lights_punctual\"], "
                            "\"extensionsRequired\": [\"KHR_lights_punctual\"]";
    const TempFile file("lights.gltf", triangleGltf("", "", top));
    EXPECT_EQ(loadScene(file.path()).triangleCount(), 1u);
    // The whole list, as the refusal names it (GltfMaterialsTest and VrmMaterialsTest load each one's files).
    EXPECT_EQ(supportedGltfExtensions(),
              (std::vector<std::string>{"KHR_lights_punctual", "KHR_mesh_quantization", "KHR_draco_mesh_compression",
                                        "EXT_meshopt_compression", "KHR_texture_transform", "KHR_materials_unlit",
                                        "KHR_materials_emissive_strength", "KHR_materials_pbrSpecularGlossiness",
                                        "EXT_texture_webp", "VRM", "VRMC_materials_mtoon", "VRMC_vrm"}));
}

// --- 6. extreme extents ---

TEST(LoaderInputChecks, NodeScaleBeyondTheRenderableExtentIsRefusedNamingTheNode) {
    const TempFile file("huge.gltf", triangleGltf("", ", \"scale\": [1e38, 1e38, 1e38]"));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_TRUE(contains(message, "loadScene(): '" + file.path() + "': node 0 'holder'")) << message;
    EXPECT_TRUE(contains(message, "more than the 1e+15 the renderer can hold")) << message;
}

TEST(LoaderInputChecks, NonFiniteAfterTheTransformIsRefusedNamingTheNode) {
    // 1e200 x 1e200 overflows double.
    GltfWriter writer;
    const int positions = writer.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const TempFile file(
        "overflow.gltf",
        writer.gltf("\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
                    "}}]}], \"nodes\": [{\"name\": \"outer\", \"scale\": [1e200, 1e200, 1e200], "
                    "\"children\": [1]}, {\"name\": \"inner\", \"mesh\": 0, \"scale\": [1e200, "
                    "1e200, 1e200]}], \"scenes\": [{\"nodes\": [0]}]"));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_TRUE(contains(message, "node 1 'inner'")) << message;
    EXPECT_TRUE(contains(message, "non-finite")) << message;
}

TEST(LoaderInputChecks, ModelExtentIsCheckedAtBothEnds) {
    // Three corners (0,0,0), (s,0,0), (0,s,0): the bounding-box diagonal is s sqrt(2).
    const auto triangleOfSize = [](const std::string& s) {
        return "v 0 0 0\nv " + s + " 0 0\nv 0 " + s + " 0\nf 1 2 3\n";
    };
    const TempFile large("large.obj", triangleOfSize("7e14"));
    EXPECT_EQ(loadScene(large.path()).triangleCount(), 1u); // 9.9e14 across
    const TempFile tooLarge("toolarge.obj", triangleOfSize("8e14"));
    const std::string largeMessage = test::sceneErrorMessage([&] { loadScene(tooLarge.path()); });
    EXPECT_TRUE(contains(largeMessage, "the model is 1.13e+15 units across (bounding-box diagonal), above the 1e+15"))
        << largeMessage;

    const TempFile small("small.obj", triangleOfSize("1e-12"));
    EXPECT_EQ(loadScene(small.path()).triangleCount(), 1u); // 1.4e-12 across
    const TempFile tooSmall("toosmall.obj", triangleOfSize("5e-13"));
    const std::string smallMessage = test::sceneErrorMessage([&] { loadScene(tooSmall.path()); });
    EXPECT_TRUE(contains(smallMessage, "the model is 7.07e-13 units across (bounding-box diagonal), below the 1e-12"))
        << smallMessage;
}

TEST(LoaderInputChecks, ObjCoordinateBeyondFloatIsRefusedAtItsLine) {
    // Read in double, 1e39 is finite; no renderable model has such a coordinate (float ends at 3.4e38).
    const TempFile file("far.obj", "v 0 0 0\nv 1 0 0\nv 1e39 1 0\nf 1 2 3\n");
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_TRUE(contains(message, "line 3: non-finite vertex coordinate in float (1e+39 is beyond float's range)"))
        << message;
}

// --- 7. messages ---

TEST(LoaderInputChecks, AsciiStlWithoutSolidIsReadAsAscii) {
    // Its bytes 80-83 as a binary count read 959328288 triangles: "truncated binary STL".
    std::string text;
    for (int i = 0; i < 3; ++i) {
        text += "facet normal 0 0 1\n outer loop\n  vertex 0 0 " + std::to_string(i) + "\n  vertex 1 0 " +
                std::to_string(i) + "\n  vertex 0 1 " + std::to_string(i) + "\n endloop\nendfacet\n";
    }
    const TempFile file("nosolid.stl", text);
    const Scene scene = loadScene(file.path());
    EXPECT_EQ(scene.report.format, "stl-ascii");
    EXPECT_EQ(scene.triangleCount(), 3u);
    // Without 'solid' there is no 'endsolid' to miss: one warning, not two.
    ASSERT_EQ(scene.report.warnings.size(), 1u) << ::testing::PrintToString(scene.report.warnings);
    EXPECT_EQ(scene.report.warnings[0].message, "ASCII STL without a 'solid' line");
    EXPECT_EQ(scene.report.warnings[0].code, "stl-solid-incomplete");
}

TEST(LoaderInputChecks, TextThatIsNotStlSaysSo) {
    const TempFile file("notes.stl", "These are my notes about the part, which is not attached here after all.\n"
                                     "Second line of the notes.\n");
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_TRUE(contains(message, "not an STL file: it looks like text, but ASCII STL starts with 'solid' (or 'facet') "
                                  "and this starts with 'These are my notes"))
        << message;
    EXPECT_FALSE(contains(message, "triangles")) << message;
}

TEST(LoaderInputChecks, TruncatedBinaryStlGivesTheCountAndTheSize) {
    std::string binary(80, '\0');
    const std::uint32_t count = 10;
    binary.append(reinterpret_cast<const char*>(&count), 4);
    binary.append(50 * 3, '\0'); // 3 of the 10 triangles
    const TempFile file("short.stl", binary);
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_TRUE(contains(message, "truncated binary STL: its binary header declares 10 triangles (584 bytes) but the "
                                  "file has 234 bytes"))
        << message;
}

TEST(LoaderInputChecks, BinaryStlWithATextHeaderAndAHugeCountIsStillBinary) {
    // 80 spaces, then 0xFFFFFFFF: the header is text, the count is not.
    const TempFile file("huge.stl", std::string(80, ' ') + std::string(4, '\xFF') + std::string(50, '\0'));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_TRUE(contains(message, "truncated binary STL: its binary header declares 4294967295 triangles")) << message;
}

TEST(LoaderInputChecks, LongDataUriIsShortenedInMessages) {
    // A buffer whose data: URI does not decode: tinygltf quotes the URI whole; the message says why instead.
    const std::string uri = "data:application/octet-stream;base64," + std::string(1 << 20, '!');
    const std::string gltf =
        "{\"asset\": {\"version\": \"2.0\"}, \"buffers\": [{\"uri\": \"" + uri + "\", \"byteLength\": 12}]}";
    const TempFile glbFile("longuri.glb", [&] {
        // GLB: the binary reader's message quotes the URI ("Failed to decode 'uri' : <uri> in Buffer").
        std::string json = gltf;
        while (json.size() % 4 != 0) json += ' ';
        std::string file = "glTF";
        const auto append = [&](std::uint32_t value) { file.append(reinterpret_cast<const char*>(&value), 4); };
        append(2);
        append(std::uint32_t(12 + 8 + json.size()));
        append(std::uint32_t(json.size()));
        file += "JSON" + json;
        return file;
    }());
    const std::string message = test::sceneErrorMessage([&] { loadScene(glbFile.path()); });
    EXPECT_LT(message.size(), 1000u) << message.substr(0, 2000);
    EXPECT_TRUE(contains(message, "longuri.glb': invalid GLB: buffers[0].uri's data: URI is not valid base64"))
        << message.substr(0, 2000);
}

TEST(LoaderInputChecks, LongNameWithSpacesIsShortenedInMessages) {
    // tinygltf quotes an invalid image's name whole; short words must not add up to a long message either.
    std::string name;
    for (int i = 0; i < 100000; ++i) name += "word ";
    const TempFile file("longname.gltf", triangleGltf("", "",
                                                      ", \"images\": [{\"name\": \"" + name +
                                                          "\", \"uri\": \"a.png\", "
                                                          "\"bufferView\": 0}]"));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_LT(message.size(), 1000u) << message.substr(0, 2000);
    EXPECT_TRUE(contains(message, "Only one of")) << message.substr(0, 2000);
}

TEST(LoaderInputChecks, ManyUnsupportedRequiredExtensionsAreCounted) {
    std::string list;
    for (int i = 0; i < 1000; ++i) list += (list.empty() ? "\"EXT_" : ", \"EXT_") + std::to_string(i) + "\"";
    const TempFile file(
        "many.gltf",
        triangleGltf("", "", ", \"extensionsUsed\": [" + list + "], \"extensionsRequired\": [" + list + "]"));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_TRUE(contains(message, "'EXT_8', 'EXT_9' and 990 more (extensionsRequired;")) << message.substr(0, 2000);
}

TEST(LoaderInputChecks, LongObjTokenIsShortenedInMessages) {
    const TempFile file("token.obj", "v 0 0 " + std::string(100000, '7') + "x\n");
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_LT(message.size(), 400u);
    EXPECT_TRUE(contains(message, "... (100001 bytes)'")) << message;
}

// --- 8. the files a load reads ---

TEST(LoaderInputChecks, InputFilesListTheModelBuffersAndImages) {
    const TempFolder folder;
    GltfWriter writer;
    const int positions = writer.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const std::string body =
        "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
        "}}]}], \"nodes\": [{\"mesh\": 0}], \"scenes\": [{\"nodes\": [0]}], "
        "\"images\": [{\"uri\": \"textures/wood%20grain.png\"}, {\"uri\": \"missing.png\"}]";
    const std::string buffer = folder.write("geometry.bin", writer.binary());
    std::filesystem::create_directories(folder.path("textures"));
    const std::string texture = folder.write("textures/wood grain.png", "not read");
    const std::string model = folder.write("model.gltf", writer.gltfWithExternalBuffer(body, "geometry.bin"));
    const Scene scene = loadScene(model);
    EXPECT_EQ(scene.report.inputFiles, (std::vector<std::string>{model, buffer, texture, folder.path("missing.png")}));
    // The missing image is unused: no failure and nothing to warn about.
    EXPECT_TRUE(scene.report.warnings.empty()) << ::testing::PrintToString(scene.report.warnings);
}

TEST(LoaderInputChecks, UrisNameTheFilesTheySpellAndPathsOfTheExportingMachineAreFoundBesideTheModel) {
    // A '+' and a lone '%' are themselves in a URI (RFC 3986; tinygltf read '+' as a space and "%.p" as a byte, so
    // the buffer was missing and the images untextured); a Windows path, '\' separators and a file:// URI as
    // exporters write them take the file of that name beside the model, and a name whose case differs from the
    // file's (Windows ignores case) takes that file.
    const TempFolder folder;
    GltfWriter writer;
    const int positions = writer.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const std::string body =
        "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
        "}}]}], \"nodes\": [{\"mesh\": 0}], \"scenes\": [{\"nodes\": [0]}], \"images\": ["
        "{\"uri\": \"my+skin.png\"}, {\"uri\": \"100%.png\"}, {\"uri\": \"100%25%20done.png\"}, "
        "{\"uri\": \"C:\\\\Users\\\\me\\\\tex\\\\face.png\"}, {\"uri\": \"textures\\\\wood.png\"}, "
        "{\"uri\": \"file:///home/artist/eyes.png\"}, {\"uri\": \"Textures/Hair.PNG\"}]";
    const std::string buffer = folder.write("model+lod0.bin", writer.binary());
    std::filesystem::create_directories(folder.path("textures"));
    const std::vector<std::string> images{
        folder.write("my+skin.png", "not read"),       folder.write("100%.png", "not read"),
        folder.write("100% done.png", "not read"),     folder.write("face.png", "not read"),
        folder.write("textures/wood.png", "not read"), folder.write("eyes.png", "not read"),
        folder.write("textures/hair.png", "not read")};
    const std::string model = folder.write("model.gltf", writer.gltfWithExternalBuffer(body, "model+lod0.bin"));
    const Scene scene = loadScene(model);
    ASSERT_EQ(scene.images.size(), images.size());
    for (std::size_t i = 0; i < images.size(); ++i) {
        EXPECT_EQ(scene.images[i].path, images[i]) << i;
    }
    std::vector<std::string> expected{model, buffer};
    expected.insert(expected.end(), images.begin(), images.end());
    EXPECT_EQ(scene.report.inputFiles, expected);
    EXPECT_EQ(referencedFiles(model), std::vector<std::string>(expected.begin() + 1, expected.end()));
}

TEST(LoaderInputChecks, AUriIsNeverReadWhereAnAbsolutePathPointsAndTwoBuffersTinygltfConfusesAreRefused) {
    // A glTF names its files relative to itself: "/elsewhere/secret.bin", "file:///elsewhere/eyes.png" and a Windows
    // share are looked for by their last name beside the model, not read where they point (a hostile file read any
    // file it named). "%00" is no NUL: "t.png%00.jpg" read t.png.
    const TempFolder folder;
    std::filesystem::create_directories(folder.path("model"));
    std::filesystem::create_directories(folder.path("elsewhere"));
    GltfWriter writer;
    const int positions = writer.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    folder.write("elsewhere/eyes.png", "not read");
    folder.write("elsewhere/share.png", "not read");
    folder.write("model/t.png", "not read");
    std::string windowsShare = folder.path("elsewhere/share.png");
    std::replace(windowsShare.begin(), windowsShare.end(), '/', '\\');
    std::string escapedShare; // in JSON
    for (const char c : "\\" + windowsShare) escapedShare += c == '\\' ? std::string("\\\\") : std::string(1, c);
    const std::string body =
        "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
        "}}]}], \"nodes\": [{\"mesh\": 0}], \"scenes\": [{\"nodes\": [0]}], \"images\": ["
        "{\"uri\": \"file://" +
        folder.path("elsewhere/eyes.png") + "\"}, {\"uri\": \"" + escapedShare + "\"}, {\"uri\": \"t.png%00.jpg\"}]";
    folder.write("model/geometry.bin", writer.binary());
    const std::string model = folder.write("model/m.gltf", writer.gltfWithExternalBuffer(body, "geometry.bin"));
    const Scene scene = loadScene(model);
    ASSERT_EQ(scene.images.size(), 3u);
    EXPECT_EQ(scene.images[0].path, folder.path("model/eyes.png"));
    EXPECT_EQ(scene.images[1].path, folder.path("model/share.png"));
    EXPECT_EQ(scene.images[2].path, folder.path("model/t.png%00.jpg"));

    const std::string secret = folder.write("elsewhere/secret.bin", writer.binary());
    const std::string absolute = folder.write("model/abs.gltf", writer.gltfWithExternalBuffer(body, secret));
    const std::string notRead = test::sceneErrorMessage([&] { loadScene(absolute); });
    EXPECT_NE(notRead.find("not found"), std::string::npos) << notRead;
    EXPECT_NE(notRead.find("secret.bin"), std::string::npos) << notRead;

    // "a+b.bin" and "a%20b.bin" both reach tinygltf as "a b.bin": one file would be read for both, silently.
    folder.write("model/a+b.bin", writer.binary());
    folder.write("model/a b.bin", writer.binary());
    std::string twoBuffers = writer.gltfWithExternalBuffer(body, "a+b.bin");
    const std::size_t buffers = twoBuffers.find("\"buffers\"");
    ASSERT_NE(buffers, std::string::npos);
    const std::size_t firstBuffer = twoBuffers.find('{', buffers);
    const std::size_t firstEnd = twoBuffers.find('}', firstBuffer);
    std::string second = twoBuffers.substr(firstBuffer, firstEnd + 1 - firstBuffer);
    second.replace(second.find("a+b.bin"), 7, "a%20b.bin");
    twoBuffers.insert(firstEnd + 1, ", " + second);
    const std::string collide = folder.write("model/collide.gltf", twoBuffers);
    const std::string message = test::sceneErrorMessage([&] { loadScene(collide); });
    EXPECT_NE(message.find("buffers 'a+b.bin' and 'a%20b.bin' name different files that tinygltf reads by one name "
                           "('a b.bin'), so it cannot read both"),
              std::string::npos)
        << message;
    // An image is never read at load time, so an image URI that tinygltf reads by a buffer's name is no clash: the
    // buffer reads its own file, and the image keeps its own path for when it is decoded.
    std::string imageFirst = writer.gltfWithExternalBuffer(body, "a+b.bin");
    const std::string lastImage = "{\"uri\": \"t.png%00.jpg\"}";
    imageFirst.replace(imageFirst.find(lastImage), lastImage.size(), "{\"uri\": \"a%20b.bin\"}");
    const Scene shared = loadScene(folder.write("model/shared.gltf", imageFirst));
    ASSERT_EQ(shared.images.size(), 3u);
    EXPECT_EQ(shared.images[2].path, folder.path("model/a b.bin"));
    EXPECT_NE(std::ranges::find(shared.report.inputFiles, folder.path("model/a+b.bin")),
              shared.report.inputFiles.end());
}

TEST(LoaderInputChecks, AMissingBufferIsNamedAsTheFileWritesIt) {
    // tinygltf said "File not found : model lod0.bin" for the URI "model+lod0.bin": its own decoding, without a folder.
    const TempFolder folder;
    GltfWriter writer;
    const std::string body = triangleBody(writer);
    const std::string model = folder.write("m.gltf", writer.gltfWithExternalBuffer(body, "model+lod0.bin"));
    const std::string message = test::sceneErrorMessage([&] { loadScene(model); });
    EXPECT_NE(message.find("buffer 'model+lod0.bin': file not found: '" + folder.path("model+lod0.bin") + "'"),
              std::string::npos)
        << message;
    folder.write("model+lod0.bin", writer.binary());
    EXPECT_EQ(loadScene(model).triangleCount(), 1u);
    // A GLB may write its BIN chunk's buffer as "uri": "": no file is named, from any folder.
    const std::string glb = test::glb(writer.gltfWithExternalBuffer(body, ""), writer.binary());
    EXPECT_EQ(loadSceneFromMemory("bare.glb", glb).triangleCount(), 1u);
}

TEST(LoaderInputChecks, ABufferThatTwoFilesMatchInCaseAloneIsRefusedNamingThem) {
    // "Model.bin" beside model.bin and MODEL.bin: neither is taken, and the refusal said "file not found".
    const TempFolder folder;
    GltfWriter writer;
    const std::string body = triangleBody(writer);
    folder.write("model.bin", writer.binary());
    folder.write("MODEL.bin", writer.binary());
    const std::string model = folder.write("m.gltf", writer.gltfWithExternalBuffer(body, "Model.bin"));
    const std::string message = test::sceneErrorMessage([&] { loadScene(model); });
    EXPECT_NE(message.find("buffer 'Model.bin': '" + folder.path("Model.bin") + "' cannot be found: the folder '" +
                           std::filesystem::path(model).parent_path().string() +
                           "' holds 'MODEL.bin' and 'model.bin', which differ from its name in case alone: rename "
                           "the one meant to 'Model.bin'"),
              std::string::npos)
        << message;
}

TEST(LoaderInputChecks, InputFilesOfStl) {
    const TempFile file("one.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                   "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n");
    EXPECT_EQ(loadScene(file.path()).report.inputFiles, std::vector<std::string>{file.path()});
}

// --- 9. images are never read ---

/** Peak resident memory since the last resetPeakResident(), in bytes; 0 where Linux does not offer it. */
std::size_t peakResidentBytes() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line)) {
        if (line.rfind("VmHWM:", 0) == 0) return std::stoull(line.substr(6)) * 1024;
    }
    return 0;
}

std::size_t residentBytes() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line)) {
        if (line.rfind("VmRSS:", 0) == 0) return std::stoull(line.substr(6)) * 1024;
    }
    return 0;
}

/** Resets VmHWM to the current resident size (Linux 4.0+: "5" to clear_refs); false where that is not possible. */
bool resetPeakResident() {
    std::ofstream clear("/proc/self/clear_refs");
    clear << "5";
    clear.flush();
    return bool(clear);
}

TEST(LoaderInputChecks, LargeImageIsNeitherReadNorCharged) {
    // A 256 MiB (sparse) texture: read, it would be resident (the old loader read every image whole) and charged to
    // the memory budget; with a 64 MiB limit the read failed, leaving a tinygltf warning.
    const TempFolder folder;
    const std::string image = folder.path("huge.png");
    std::filesystem::resize_file(folder.write("huge.png", ""), std::uintmax_t(256) << 20);
    GltfWriter writer;
    const int positions = writer.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const std::string model = folder.write(
        "model.gltf",
        writer.gltf("\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
                    "}}]}], \"nodes\": [{\"mesh\": 0}], \"scenes\": [{\"nodes\": [0]}], "
                    "\"images\": [{\"uri\": \"huge.png\"}]"));
    LoadOptions options;
    options.memoryLimitBytes = std::size_t(64) << 20;
    const bool peakMeasured = resetPeakResident();
    const std::size_t residentBefore = residentBytes();
    const Scene scene = loadScene(model, options);
    EXPECT_TRUE(scene.report.warnings.empty()) << ::testing::PrintToString(scene.report.warnings);
    EXPECT_EQ(scene.report.inputFiles, (std::vector<std::string>{model, image}));
    if (peakMeasured && peakResidentBytes() > 0) {
        EXPECT_LT(peakResidentBytes() - std::min(residentBefore, peakResidentBytes()), std::size_t(32) << 20);
    }
}

TEST(LoaderInputChecks, ImageNamingAFifoLoadsWithoutBlocking) {
    const TempFolder folder;
    ASSERT_EQ(::mkfifo(folder.path("pipe.png").c_str(), 0600), 0);
    const std::string model =
        folder.write("model.gltf", triangleGltf("", "", ", \"images\": [{\"uri\": \"pipe.png\"}]"));
    const Scene scene = loadScene(model);
    EXPECT_EQ(scene.triangleCount(), 1u);
    EXPECT_TRUE(scene.report.warnings.empty()) << ::testing::PrintToString(scene.report.warnings);
}

} // namespace
} // namespace inkgraph
