/** @file A mesh given as arrays (sceneFromArrays(), scene/MeshArrays.h) renders byte for byte like the same mesh read
 *  from its OBJ file: the still renderer draws the file by path and the arrays' Scene as StillRequest::loadedScene,
 *  with the same flags and the auto-framed camera. */

#include "flags/Options.h"
#include "app/Render.h"
#include "render/StillRenderer.h"
#include "scene/MeshArrays.h"
#include "tests/support/MeshArraysFixtures.h"
#include "scene/mesh/Procedural.h"
#include "tests/support/TestFolder.h"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

using test::exact;

class SceneFromArraysGL : public test::TestFolder {};

/** The final picture of a still of the model at `path`, or of `loaded` (then `path` only names it), with `flags`. */
cv::Mat renderPicture(StillRenderer& renderer, const std::string& path, std::shared_ptr<const Scene> loaded,
                      const std::vector<std::string>& flags) {
    StillRequest request = stillRequestOf(parseRenderFlags(flags));
    request.modelPath = path;
    request.loadedScene = std::move(loaded);
    std::ostringstream log;
    const StillLog stillLog{log, false, true};
    const std::unique_ptr<PreparedStill> still = renderer.prepare(std::move(request), stillLog);
    StillResult result = renderer.execute(*still, stillLog);
    // A copy: the store's textures go back to the renderer's pool with the result.
    return result.store().image(still->graph.finalResource).clone();
}

/** Equal bytes, and a picture with something drawn in it (not one colour throughout). */
void expectSamePicture(const cv::Mat& fromFile, const cv::Mat& fromArrays) {
    ASSERT_EQ(fromFile.size(), fromArrays.size());
    ASSERT_EQ(fromFile.type(), fromArrays.type());
    ASSERT_TRUE(fromFile.isContinuous() && fromArrays.isContinuous());
    const std::size_t bytes = fromFile.total() * fromFile.elemSize();
    std::size_t differing = 0;
    for (std::size_t i = 0; i < bytes; ++i) differing += fromFile.data[i] != fromArrays.data[i] ? 1 : 0;
    EXPECT_EQ(differing, 0u) << "of " << bytes << " bytes";
    std::size_t drawn = 0;
    const std::size_t pixel = fromFile.elemSize();
    for (std::size_t i = 0; i < fromFile.total(); ++i) {
        drawn += std::memcmp(fromFile.data + i * pixel, fromFile.data, pixel) != 0 ? 1 : 0;
    }
    EXPECT_GT(drawn, fromFile.total() / 20) << "the picture is almost one colour: nothing was drawn";
}

TEST_F(SceneFromArraysGL, AModelFileAndItsArraysRenderTheSamePicture) {
    const std::string path = INKGRAPH_SOURCE_ROOT "/models/torusknot_open3d.obj";
    test::OwnedArrays owned = test::readObjTriangles(path);
    owned.name = "torusknot_open3d";
    const MeshArrays arrays = owned.view();
    ASSERT_EQ(arrays.faceCount, 2880u);
    const auto scene = std::make_shared<const Scene>(sceneFromArrays(arrays));

    const std::vector<std::string> flags = {"--size", "160x120"};
    StillRenderer renderer;
    expectSamePicture(renderPicture(renderer, path, nullptr, flags), renderPicture(renderer, path, scene, flags));
}

TEST_F(SceneFromArraysGL, NormalsUvsAndColoursRenderTheSamePictureAsTheirObj) {
    // A sphere with its exact normals, uvs from its angles and a colour per vertex, written as an OBJ file.
    const Mesh sphere = makeUvSphere(glm::vec3(0.5f, 0.0f, -0.25f), 2.0f, 32, 16);
    std::vector<float> positions, normals, uvs, colors;
    std::vector<std::uint32_t> triangles;
    std::ostringstream obj;
    obj << "o sphere\n";
    for (std::size_t v = 0; v < sphere.positions.size(); ++v) {
        const glm::vec3 p = sphere.positions[v];
        const glm::vec3 n = sphere.normals[v];
        const glm::vec2 uv(float(std::atan2(n.y, n.x) / (2.0 * M_PI) + 0.5),
                           float(std::acos(std::clamp(n.z, -1.0f, 1.0f)) / M_PI));
        const glm::vec3 colour(0.5f + 0.5f * n.x, 0.5f + 0.5f * n.y, float(v % 7) / 6.0f);
        positions.insert(positions.end(), {p.x, p.y, p.z});
        normals.insert(normals.end(), {n.x, n.y, n.z});
        uvs.insert(uvs.end(), {uv.x, uv.y});
        colors.insert(colors.end(), {colour.r, colour.g, colour.b});
        obj << "v " << exact(p.x) << ' ' << exact(p.y) << ' ' << exact(p.z) << ' ' << exact(colour.r) << ' '
            << exact(colour.g) << ' ' << exact(colour.b) << "\nvn " << exact(n.x) << ' ' << exact(n.y) << ' '
            << exact(n.z) << "\nvt " << exact(uv.x) << ' ' << exact(uv.y) << '\n';
    }
    for (const glm::uvec3& t : sphere.triangles) {
        triangles.insert(triangles.end(), {t.x, t.y, t.z});
        obj << 'f';
        for (int c = 0; c < 3; ++c) {
            const std::string index = std::to_string(t[c] + 1);
            obj << ' ' << index << '/' << index << '/' << index;
        }
        obj << '\n';
    }
    const std::string path = (directory / "sphere.obj").string();
    std::ofstream(path) << obj.str();

    MeshArrays arrays;
    arrays.vertices = positions.data();
    arrays.vertexCount = positions.size() / 3;
    arrays.faces = triangles.data();
    arrays.faceCount = triangles.size() / 3;
    arrays.normals = normals.data();
    arrays.uvs = uvs.data();
    arrays.colors = colors.data();
    arrays.colorChannels = 3;
    arrays.name = "sphere";
    const auto scene = std::make_shared<const Scene>(sceneFromArrays(arrays));

    const std::vector<std::string> flags = {"--size", "160x120"};
    StillRenderer renderer;
    expectSamePicture(renderPicture(renderer, path, nullptr, flags), renderPicture(renderer, path, scene, flags));
}

} // namespace
} // namespace inkgraph
