// The loader's memory bound (LoadOptions::memoryLimitBytes, detail::MeshBudget): refused before allocating, with
// the file and the numbers in the message; and loadSceneFromMemory(), the fuzz targets' entry.
#include "scene/formats/FormatReaders.h"
#include "scene/Scene.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cstdint>
#include <limits>
#include <sstream>

namespace inkgraph {
namespace {

using test::GltfWriter;
using test::TempFile;

const std::vector<glm::vec3> kTriangle = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};

/** One triangle mesh placed by `instances` sibling nodes, each moved along x so no two coincide. */
std::string instancedTriangle(GltfWriter& writer, int instances) {
    const int positions = writer.addVec3(kTriangle);
    std::string nodes, roots;
    for (int i = 0; i < instances; ++i) {
        nodes += std::string(i ? ", " : "") + "{\"mesh\": 0, \"translation\": [" + std::to_string(2 * i) + ", 0, 0]}";
        roots += std::string(i ? ", " : "") + std::to_string(i);
    }
    return "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
           "}}]}], \"nodes\": [" + nodes + "], \"scenes\": [{\"nodes\": [" + roots + "]}], \"scene\": 0";
}

std::string binaryStlHeader(std::uint32_t triangles) {
    std::string bytes(80, 'x');
    for (int shift = 0; shift < 32; shift += 8) bytes.push_back(char((triangles >> shift) & 0xFF));
    return bytes;
}

TEST(LoadLimits, EveryInstanceOfAGltfMeshIsChargedBeforeItIsCopied) {
    GltfWriter writer;
    const std::string body = instancedTriangle(writer, 3000);
    const TempFile file("instanced.glb", writer.glb(body));
    EXPECT_EQ(loadScene(file.path()).triangleCount(), 3000u) << "within the default limit every instance loads";

    // 3000 instances x (3 vertices x 96 + 1 triangle x 64 bytes) = 1,056,000 bytes, plus the file: above 1 MiB,
    // though the file holds one triangle.
    LoadOptions tight;
    tight.memoryLimitBytes = 1u << 20;
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path(), tight); });
    EXPECT_EQ(message.rfind("loadScene(): '" + file.path() + "': the mesh would need about", 0), 0u) << message;
    EXPECT_NE(message.find("above the memory limit of 1 MiB (--memory-limit)"), std::string::npos) << message;
}

/** `gltf` (GltfWriter::gltf()) with `accessors` (JSON objects) put before the writer's, which move up by as many. */
std::string withAccessorsFirst(std::string gltf, const std::string& accessors) {
    const std::string list = "\"accessors\": [";
    gltf.insert(gltf.find(list) + list.size(), accessors + ", ");
    return gltf;
}

TEST(LoadLimits, ASkinsOrAnAnimationsAccessorAboveTheLimitIsToldAsItself) {
    // Accessors without a buffer view hold zeros and may declare any count: a million matrices (122 MiB as doubles),
    // two million keyframes (30 MiB as floats). Their refusals spoke of "the mesh" and its vertices.
    const std::string zeros = "{\"componentType\": 5126, \"count\": 1000000, \"type\": ";
    LoadOptions options;
    options.memoryLimitBytes = 16u << 20;

    GltfWriter writer; // its accessors are 1, 2 and 3 once the zeros come first
    writer.addVec3(kTriangle);
    writer.addJoints({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
    writer.addFloats({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4", 4);
    const std::string skinned = withAccessorsFirst(
        writer.gltf("\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 1, \"JOINTS_0\": 2, "
                    "\"WEIGHTS_0\": 3}}]}], \"nodes\": [{\"mesh\": 0, \"skin\": 0}, {\"name\": \"bone\"}], "
                    "\"scenes\": [{\"nodes\": [0, 1]}], \"skins\": [{\"joints\": [1], \"inverseBindMatrices\": 0}]"),
        zeros + "\"MAT4\"}");
    const std::string skinMessage =
        test::sceneErrorMessage([&] { loadScene(TempFile("skin.gltf", skinned).path(), options); });
    EXPECT_NE(skinMessage.find("skin.gltf': skin 0 inverseBindMatrices would need about 122 MiB; the load would hold "
                               "about"),
              std::string::npos)
        << skinMessage;
    EXPECT_EQ(skinMessage.find("the mesh"), std::string::npos) << skinMessage;

    const std::string twiceAsMany = "{\"componentType\": 5126, \"count\": 2000000, \"type\": ";
    GltfWriter animated; // its triangle is accessor 2
    animated.addVec3(kTriangle);
    const std::string moving = withAccessorsFirst(
        animated.gltf("\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 2}}]}], \"nodes\": "
                      "[{\"mesh\": 0}], \"scenes\": [{\"nodes\": [0]}], \"animations\": [{\"name\": \"walk\", "
                      "\"channels\": [{\"sampler\": 0, \"target\": {\"node\": 0, \"path\": \"translation\"}}], "
                      "\"samplers\": [{\"input\": 0, \"output\": 1}]}]"),
        twiceAsMany + "\"SCALAR\"}, " + twiceAsMany + "\"VEC3\"}");
    options.animation = "walk";
    const std::string animationMessage =
        test::sceneErrorMessage([&] { loadScene(TempFile("walk.gltf", moving).path(), options); });
    EXPECT_NE(animationMessage.find("walk.gltf': animation 0 'walk' sampler 0's keyframes would need about "
                                    "30 MiB; the load would hold about"),
              std::string::npos)
        << animationMessage;
    EXPECT_EQ(animationMessage.find("the mesh"), std::string::npos) << animationMessage;
}

TEST(LoadLimits, BinaryStlDeclaringMoreThanTheLimitIsRefusedFromItsHeader) {
    // 200,000 triangles of zeros, all present: the size check passes, the memory bound does not.
    std::string bytes = binaryStlHeader(200'000);
    bytes.resize(84 + 200'000 * 50, '\0');
    const TempFile file("big.stl", bytes);
    LoadOptions options;
    options.memoryLimitBytes = 64u << 20;
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path(), options); });
    // 10 MB file + 600,000 vertices x 96 + 200,000 triangles x 64 = 80 MB > 64 MiB.
    EXPECT_NE(message.find("(600000 vertices, 200000 triangles)"), std::string::npos) << message;
    EXPECT_NE(message.find("memory limit of 64 MiB"), std::string::npos) << message;
}

TEST(LoadLimits, GrowingObjIsStoppedAtTheLimit) {
    std::ostringstream obj;
    for (int i = 0; i < 40'000; ++i) obj << "v " << i << " 0 0\nv " << i << " 1 0\nv " << i << " 0 1\nf -3 -2 -1\n";
    const TempFile file("grow.obj", obj.str());
    LoadOptions options;
    options.memoryLimitBytes = 4u << 20; // the file alone is about 1.3 MB; its mesh needs about 14 MB
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path(), options); });
    EXPECT_NE(message.find(file.fileName() + "': the mesh would need about"), std::string::npos) << message;
    options.memoryLimitBytes = 64u << 20;
    EXPECT_EQ(loadScene(file.path(), options).triangleCount(), 40'000u);
}

TEST(LoadLimits, ContinuedLinesAreStoppedAtTheLimitToo) {
    // The limit is checked every 16,384 lines; a face over two lines ended on odd lines only, so the check never ran
    // and 6 million faces loaded past --memory-limit 256.
    std::ostringstream obj;
    obj << "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (int i = 0; i < 100'000; ++i) obj << "f 1 2 \\\n3\n";
    const TempFile file("continued.obj", obj.str());
    LoadOptions options;
    options.memoryLimitBytes = 4u << 20;
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path(), options); });
    EXPECT_NE(message.find(file.fileName() + "': the mesh would need about"), std::string::npos) << message;
}

TEST(LoadLimits, FileLargerThanTheLimitIsRefusedBeforeItIsRead) {
    const TempFile file("large.obj", std::string(3u << 20, '#'));
    LoadOptions options;
    options.memoryLimitBytes = 2u << 20;
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path(), options); });
    EXPECT_NE(message.find("the file is 3 MiB; the load would hold about 3 MiB, above the memory limit of 2 MiB"),
              std::string::npos)
        << message;
}

TEST(LoadLimits, LimitsUnderAMebibyteAreToldInKibibytesOrBytes) {
    // The library takes any limit in bytes: one of a few bytes read "the memory limit of 0 MiB".
    const TempFile file("small.obj", std::string(3000, '#'));
    LoadOptions options;
    options.memoryLimitBytes = 1;
    EXPECT_NE(test::sceneErrorMessage([&] {
                  loadScene(file.path(), options);
              }).find("the file is 2 KiB; the load would hold about 2 KiB, above the memory limit of 1 byte"),
              std::string::npos);
    options.memoryLimitBytes = 1000;
    EXPECT_NE(test::sceneErrorMessage([&] { loadScene(file.path(), options); }).find("memory limit of 1000 bytes"),
              std::string::npos);
}

TEST(LoadLimits, GlbIsChargedTwiceForTinygltfsCopyOfItsBuffers) {
    GltfWriter writer;
    const std::string body = instancedTriangle(writer, 1);
    const std::string bytes = writer.glb(body);
    LoadOptions options;
    // The file twice, one triangle and its mesh's node path (one unnamed node): just enough.
    options.memoryLimitBytes = 2 * bytes.size() + 3 * 96 + 64 + sizeof(std::vector<std::string>) + sizeof(std::string);
    EXPECT_EQ(loadSceneFromMemory("one.glb", bytes, options).triangleCount(), 1u);
    options.memoryLimitBytes -= 1;
    const std::string message = test::sceneErrorMessage([&] { loadSceneFromMemory("one.glb", bytes, options); });
    EXPECT_NE(message.find("(3 vertices, 1 triangles), above the memory limit"), std::string::npos) << message;
}

TEST(LoadLimits, DeclaredCountsNearTwoToTheSixtyFourSaturateInsteadOfWrapping) {
    detail::MeshBudget budget("huge.glb", std::size_t(8) << 30);
    const std::size_t huge = std::numeric_limits<std::size_t>::max() / 64 + 1; // x 64 wraps to 0 without saturation
    EXPECT_THROW(budget.check(0, huge), SceneError);
    EXPECT_THROW(budget.check(huge, huge), SceneError);
    EXPECT_NO_THROW(budget.check(1000, 1000));
}

TEST(LoadLimits, GltfBufferThatIsNotARegularFileIsRefusedWithoutReadingIt) {
    // A FIFO would block tinygltf's read forever (so would /dev/stdin); a device would never end.
    const std::filesystem::path fifo =
        std::filesystem::temp_directory_path() / ("inkgraph_fifo_" + std::to_string(::getpid()) + ".bin");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    GltfWriter writer;
    const int positions = writer.addVec3(kTriangle);
    const TempFile file(
        "fifo.gltf", writer.gltfWithExternalBuffer(
                         "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
                             "}}]}], \"nodes\": [{\"mesh\": 0}], \"scenes\": [{\"nodes\": "
                             "[0]}], \"scene\": 0",
                         fifo.filename().string()));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    std::filesystem::remove(fifo);
    EXPECT_NE(message.find("is not a regular file"), std::string::npos) << message;
    EXPECT_NE(message.find(file.fileName()), std::string::npos) << message;
}

TEST(LoadFromMemory, GivesTheSameSceneAsTheFileAndNamesThePath) {
    const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    const TempFile file("tetra.obj", obj);
    const Scene fromFile = loadScene(file.path());
    const Scene fromMemory = loadSceneFromMemory(file.path(), obj);
    ASSERT_EQ(fromMemory.meshes.size(), 1u);
    EXPECT_EQ(fromMemory.meshes[0].positions, fromFile.meshes[0].positions);
    EXPECT_EQ(fromMemory.meshes[0].triangles, fromFile.meshes[0].triangles);
    const std::string message = test::sceneErrorMessage([&] { loadSceneFromMemory("in/memory.stl", "solid x\nfoo"); });
    EXPECT_EQ(message.rfind("loadScene(): 'in/memory.stl'", 0), 0u) << message;
}

} // namespace
} // namespace inkgraph
