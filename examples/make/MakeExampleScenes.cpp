// Writes the glTF scenes of examples/ from the bundled models (the .gltf and .bin files there come from this program):
//   inkgraph_make_example_scenes [REPO_ROOT]     (default: the source tree this was built from)
// still-life: four models side by side on an implicit ground (y = 0), each its own node, mesh and material with a
// base colour and a shade map of its own (material extras {"inkgraph": {"shademap": ...}}), a perspective camera
// and a KHR_lights_punctual directional light. Positions and indices only: inkgraph computes the normals.
// The output is a function of the models alone (no time stamps, no hash-map order), so it regenerates byte for byte.
#include "scene/Scene.h"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using Json = nlohmann::ordered_json; // keeps members in the order written: asset first, as people expect to read it
namespace fs = std::filesystem;

/** One object of the still life: a model, how it stands, and its look. */
struct ObjectSpec {
    std::string name;      ///< node, mesh and material name (material: name + " material")
    std::string modelFile; ///< under models/
    glm::dmat3 upright;    ///< baked into the positions, so the model stands with +y up
    double height;         ///< world height after scaling
    double x;              ///< where its footprint's centre stands, on the x axis
    double z;
    double yawDegrees;    ///< turn about +y (the node's rotation)
    glm::dvec3 baseColor; ///< linear
    std::string shadeMap; ///< relative to the .gltf
};

/** A rotation about +x by `degrees`. */
glm::dmat3 aboutX(double degrees) {
    const double c = std::cos(glm::radians(degrees)), s = std::sin(glm::radians(degrees));
    return glm::dmat3(glm::dvec3(1, 0, 0), glm::dvec3(0, c, s), glm::dvec3(0, -s, c)); // columns
}

/** Shortest decimal that reads back as the same float, as a double: min/max then print as 0.472, not
 *  0.47200000286102295, and still bound the float32 data exactly. */
double shortest(float value) {
    char text[64];
    const auto result = std::to_chars(text, text + sizeof text, value);
    return std::strtod(std::string(text, result.ptr).c_str(), nullptr);
}

/** Rounded to `digits` decimals, for readable node transforms (they are authored numbers, not data); + 0.0 turns
 *  -0 into 0. */
double rounded(double value, int digits = 4) {
    const double unit = std::pow(10.0, digits);
    return std::round(value * unit) / unit + 0.0;
}

Json vec(const glm::dvec3& v) { return Json::array({rounded(v.x), rounded(v.y), rounded(v.z)}); }

/** glTF quaternion (x, y, z, w) of a rotation matrix. */
Json quaternion(const glm::dmat3& rotation) {
    const glm::dquat q = glm::normalize(glm::quat_cast(rotation));
    // Six decimals keep it unit to within 1e-6, as glTF validators ask.
    return Json::array({rounded(q.x, 6), rounded(q.y, 6), rounded(q.z, 6), rounded(q.w, 6)});
}

/** A node rotation that turns local -Z toward `forward` with local +Y as near `up` as possible (glTF cameras and
 *  lights look down -Z). */
glm::dmat3 lookRotation(const glm::dvec3& forward, const glm::dvec3& up) {
    const glm::dvec3 back = -glm::normalize(forward);
    const glm::dvec3 right = glm::normalize(glm::cross(up, back));
    return glm::dmat3(right, glm::cross(back, right), back); // columns: local x, y, z in world space
}

class BufferWriter {
public:
    /** Appends a view of `bytes`, 4-byte aligned; returns its index. */
    int addView(const void* data, std::size_t bytes, int target) {
        while (mBytes.size() % 4 != 0) mBytes.push_back(0);
        mViews.push_back({{"buffer", 0}, {"byteOffset", mBytes.size()}, {"byteLength", bytes}, {"target", target}});
        const auto* first = static_cast<const unsigned char*>(data);
        mBytes.insert(mBytes.end(), first, first + bytes);
        return int(mViews.size() - 1);
    }
    const std::vector<unsigned char>& bytes() const { return mBytes; }
    const Json& views() const { return mViews; }

private:
    std::vector<unsigned char> mBytes;
    Json mViews = Json::array();
};

constexpr int kArrayBuffer = 34962;        // GL_ARRAY_BUFFER
constexpr int kElementArrayBuffer = 34963; // GL_ELEMENT_ARRAY_BUFFER
constexpr int kFloat = 5126;
constexpr int kUnsignedInt = 5125;

/** Positions and triangles of every mesh of a model file, in one list, upright, scaled to `height`, standing on
 *  y = 0 and centred on x = z = 0. */
struct Geometry {
    std::vector<glm::vec3> positions;
    std::vector<std::uint32_t> indices;
};

Geometry loadUpright(const fs::path& file, const glm::dmat3& upright, double height) {
    const inkgraph::Scene scene = inkgraph::loadScene(file.string());
    std::vector<glm::dvec3> points;
    Geometry geometry;
    for (const inkgraph::Mesh& mesh : scene.meshes) {
        const auto first = std::uint32_t(points.size());
        for (const glm::vec3& p : mesh.positions) points.push_back(upright * glm::dvec3(p));
        for (const glm::uvec3& t : mesh.triangles)
            for (int corner = 0; corner < 3; ++corner) geometry.indices.push_back(first + t[corner]);
    }
    glm::dvec3 low(std::numeric_limits<double>::max()), high(std::numeric_limits<double>::lowest());
    for (const glm::dvec3& p : points) {
        low = glm::min(low, p);
        high = glm::max(high, p);
    }
    const double scale = height / (high.y - low.y);
    const glm::dvec3 foot(0.5 * (low.x + high.x), low.y, 0.5 * (low.z + high.z));
    for (const glm::dvec3& p : points) geometry.positions.push_back(glm::vec3((p - foot) * scale));
    return geometry;
}

/** Scale baked into the positions, so nodes carry translation and a turn only: the numbers in the file then say
 *  where each object stands. */
void writeStillLife(const fs::path& root) {
    // Left to right: the cow, the teapot in the middle, Suzanne, the knot. Heights and gaps chosen so the outlines
    // do not touch in the camera's view; yaw turns each to a three-quarter view.
    // One object per entry reads as a table.
    // clang-format off
    const std::vector<ObjectSpec> objects = {
        {"Spot", "spot_c3d.obj", glm::dmat3(1.0), 1.3, -2.4, 0.2, -150.0, {1.0, 0.93, 0.86},
         "../../shademaps/duotone-warm.png"},
        {"Teapot", "teapot_c3d.obj", glm::dmat3(1.0), 1.0, -0.6, -0.25, -25.0, {0.92, 0.94, 1.0},
         "../../shademaps/metallic.png"},
        {"Suzanne", "suzanne_npm_4k.obj", glm::dmat3(1.0), 1.0, 1.1, 0.15, -20.0, {0.9, 1.0, 1.0},
         "../../shademaps/duotone-cool.png"},
        // The knot lies in the x-z plane in its file; stood up on its rim it shows its loops to the camera.
        {"Torus knot", "torusknot_open3d.obj", aboutX(90.0), 1.2, 2.65, -0.1, 10.0, {0.95, 0.48, 0.38},
         "../../shademaps/three-bands.png"},
    };
    // clang-format on

    BufferWriter buffer;
    Json accessors = Json::array();
    Json meshes = Json::array();
    Json materials = Json::array();
    Json nodes = Json::array();
    Json sceneNodes = Json::array();
    for (const ObjectSpec& object : objects) {
        const Geometry geometry = loadUpright(root / "models" / object.modelFile, object.upright, object.height);
        glm::vec3 low(std::numeric_limits<float>::max()), high(std::numeric_limits<float>::lowest());
        for (const glm::vec3& p : geometry.positions) {
            low = glm::min(low, p);
            high = glm::max(high, p);
        }
        const int positionView =
            buffer.addView(geometry.positions.data(), geometry.positions.size() * sizeof(glm::vec3), kArrayBuffer);
        const int indexView = buffer.addView(geometry.indices.data(), geometry.indices.size() * sizeof(std::uint32_t),
                                             kElementArrayBuffer);
        std::uint32_t lowIndex = std::numeric_limits<std::uint32_t>::max(), highIndex = 0;
        for (std::uint32_t index : geometry.indices) {
            lowIndex = std::min(lowIndex, index);
            highIndex = std::max(highIndex, index);
        }
        accessors.push_back({{"bufferView", positionView},
                             {"componentType", kFloat},
                             {"count", geometry.positions.size()},
                             {"type", "VEC3"},
                             {"min", {shortest(low.x), shortest(low.y), shortest(low.z)}},
                             {"max", {shortest(high.x), shortest(high.y), shortest(high.z)}}});
        accessors.push_back({{"bufferView", indexView},
                             {"componentType", kUnsignedInt},
                             {"count", geometry.indices.size()},
                             {"type", "SCALAR"},
                             {"min", {lowIndex}},
                             {"max", {highIndex}}});
        const int material = int(materials.size());
        materials.push_back(
            {{"name", object.name + " material"},
             {"pbrMetallicRoughness",
              {{"baseColorFactor",
                {rounded(object.baseColor.r), rounded(object.baseColor.g), rounded(object.baseColor.b), 1.0}},
               {"metallicFactor", 0.0},
               {"roughnessFactor", 0.6}}},
             {"extras", {{"inkgraph", {{"shademap", object.shadeMap}}}}}});
        meshes.push_back({{"name", object.name},
                          {"primitives", Json::array({{{"attributes", {{"POSITION", int(accessors.size()) - 2}}},
                                                       {"indices", int(accessors.size()) - 1},
                                                       {"material", material},
                                                       {"mode", 4}}})}});
        const double yaw = glm::radians(object.yawDegrees);
        const glm::dmat3 turn(glm::dvec3(std::cos(yaw), 0, -std::sin(yaw)), glm::dvec3(0, 1, 0),
                              glm::dvec3(std::sin(yaw), 0, std::cos(yaw)));
        sceneNodes.push_back(nodes.size());
        nodes.push_back({{"name", object.name},
                         {"mesh", int(meshes.size()) - 1},
                         {"translation", vec({object.x, 0.0, object.z})},
                         {"rotation", quaternion(turn)}});
    }

    // The camera: a little above the objects' tops, looking down at the middle of the group.
    const glm::dvec3 eye(0.22, 2.4, 8.4);
    const glm::dvec3 target(0.22, 0.6, 0.0);
    sceneNodes.push_back(nodes.size());
    nodes.push_back({{"name", "Camera"},
                     {"camera", 0},
                     {"translation", vec(eye)},
                     {"rotation", quaternion(lookRotation(target - eye, {0, 1, 0}))}});
    // The key light from the upper left, in front: its node's -Z is the direction the light travels.
    const glm::dvec3 towardLight = glm::normalize(glm::dvec3(-0.55, 0.75, 0.65));
    sceneNodes.push_back(nodes.size());
    nodes.push_back({{"name", "Key light"},
                     {"rotation", quaternion(lookRotation(-towardLight, {0, 1, 0}))},
                     {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});

    const fs::path folder = root / "examples" / "still-life";
    fs::create_directories(folder);
    const std::string binName = "still-life.bin";
    Json gltf = {
        {"asset", {{"version", "2.0"}, {"generator", "inkgraph_make_example_scenes (examples/make)"}}},
        {"extensionsUsed", {"KHR_lights_punctual"}},
        {"extensions",
         {{"KHR_lights_punctual",
           {{"lights", Json::array({{{"name", "Key light"},
                                     {"type", "directional"},
                                     {"color", {1.0, 1.0, 1.0}},
                                     {"intensity", 3.0}}})}}}}},
        {"scene", 0},
        {"scenes", Json::array({{{"name", "Still life"}, {"nodes", sceneNodes}}})},
        {"nodes", nodes},
        {"cameras",
         Json::array(
             {{{"name", "Camera"},
               {"type", "perspective"},
               {"perspective",
                {{"yfov", rounded(glm::radians(27.0))}, {"aspectRatio", 1.6}, {"znear", 0.5}, {"zfar", 50.0}}}}})},
        {"meshes", meshes},
        {"materials", materials},
        {"accessors", accessors},
        {"bufferViews", buffer.views()},
        {"buffers", Json::array({{{"uri", binName}, {"byteLength", buffer.bytes().size()}}})},
    };

    const auto writeFile = [](const fs::path& path, const void* data, std::size_t size) {
        std::ofstream file(path, std::ios::binary | std::ios::trunc);
        file.write(static_cast<const char*>(data), std::streamsize(size));
        file.close();
        if (!file) throw std::runtime_error("writeStillLife(): cannot write '" + path.string() + "'");
    };
    writeFile(folder / binName, buffer.bytes().data(), buffer.bytes().size());
    const std::string text = gltf.dump(2) + "\n";
    writeFile(folder / "still-life.gltf", text.data(), text.size());
    std::printf("%s (%zu bytes), %s\n", (folder / "still-life.gltf").string().c_str(), buffer.bytes().size(),
                (folder / binName).string().c_str());
}

} // namespace

int main(int argc, char** argv) {
    if (argc > 2) {
        std::fprintf(stderr, "usage: %s [REPO_ROOT]   (default: %s)\n", argv[0], INKGRAPH_SOURCE_ROOT);
        return 2;
    }
    try {
        writeStillLife(argc == 2 ? fs::path(argv[1]) : fs::path(INKGRAPH_SOURCE_ROOT));
    } catch (const std::exception& error) {
        std::fprintf(stderr, "%s: %s\n", argv[0], error.what());
        return 1;
    }
    return 0;
}
