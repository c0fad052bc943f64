#pragma once
/** @file What the tests of meshes from arrays share (tests/scene/SceneFromArraysTest.cpp, tests/app/
 *  SceneFromArraysGLTest.cpp): arrays that own their rows, the exact text of a float for the OBJ that should equal
 *  them, and an OBJ file of triangles read as arrays. */

#include "scene/MeshArrays.h"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace inkgraph::test {

/** A mesh's arrays, owned, for building a MeshArrays. */
struct OwnedArrays {
    std::vector<float> positions;
    std::vector<std::uint32_t> triangles;
    std::vector<float> normals;
    std::vector<float> uvs;
    std::vector<float> colors;
    int colorChannels = 0;
    std::string name = "arrays";

    MeshArrays view() const {
        MeshArrays arrays;
        arrays.vertices = positions.data();
        arrays.vertexCount = positions.size() / 3;
        arrays.faces = triangles.data();
        arrays.faceCount = triangles.size() / 3;
        arrays.normals = normals.empty() ? nullptr : normals.data();
        arrays.uvs = uvs.empty() ? nullptr : uvs.data();
        arrays.colors = colors.empty() ? nullptr : colors.data();
        arrays.colorChannels = colorChannels;
        arrays.name = name;
        return arrays;
    }
    std::size_t vertexCount() const { return positions.size() / 3; }
};

/** `%.17g` of the float's value: the OBJ reader computes in double (1 - v for `vt`, a far model's offset), so the text
 *  must give back the float's value as a double, not only the float (`%.9g` gives 0.333333343 for 1/3 in float, and
 *  1 - 0.333333343 rounds to another float than 1 - 0.3333333432674408). */
inline std::string exact(float value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", double(value));
    return text;
}

/** The `v` and `f` lines of an OBJ file of triangles (what the models/ files hold), as arrays. */
inline OwnedArrays readObjTriangles(const std::string& path) {
    std::ifstream file(path);
    OwnedArrays owned;
    for (std::string line; std::getline(file, line);) {
        std::istringstream words(line);
        std::string keyword;
        words >> keyword;
        if (keyword == "v") {
            float x = 0, y = 0, z = 0;
            words >> x >> y >> z;
            owned.positions.insert(owned.positions.end(), {x, y, z});
        } else if (keyword == "f") {
            std::uint32_t a = 0, b = 0, c = 0;
            words >> a >> b >> c;
            owned.triangles.insert(owned.triangles.end(), {a - 1, b - 1, c - 1});
        }
    }
    return owned;
}

} // namespace inkgraph::test
