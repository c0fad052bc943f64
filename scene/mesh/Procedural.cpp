#include "scene/mesh/Procedural.h"

#include "scene/mesh/MeshOps.h"

#include <glm/gtc/constants.hpp>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace inkgraph {

namespace {

void require(bool condition, const char* function, const std::string& problem) {
    if (!condition) {
        throw std::invalid_argument(std::string(function) + ": " + problem);
    }
}

} // namespace

Mesh makeUvSphere(glm::vec3 center, float radius, int segments, int rings) {
    require(std::isfinite(radius) && radius > 0.0f, "makeUvSphere()", "radius must be positive and finite");
    require(segments >= 3 && rings >= 2, "makeUvSphere()", "needs segments >= 3 and rings >= 2");
    require(std::isfinite(center.x) && std::isfinite(center.y) && std::isfinite(center.z), "makeUvSphere()",
            "center must be finite");

    // Poles on the z axis, one vertex each; rings - 1 latitude circles of `segments` vertices in between, the seam
    // shared through wrap-around indices. Normals are computed first, in double, so positions follow from them.
    Mesh mesh;
    mesh.name = "uv-sphere";
    const auto addVertex = [&](const glm::dvec3& normal) {
        mesh.normals.emplace_back(normal);
        mesh.positions.emplace_back(glm::dvec3(center) + double(radius) * normal);
    };
    const auto circles = std::uint32_t(rings - 1);
    const auto around = std::uint32_t(segments);
    addVertex({0.0, 0.0, 1.0});
    for (std::uint32_t circle = 0; circle < circles; ++circle) {
        const double polar = glm::pi<double>() * double(circle + 1) / double(rings);
        for (std::uint32_t segment = 0; segment < around; ++segment) {
            const double azimuth = 2.0 * glm::pi<double>() * double(segment) / double(segments);
            addVertex({std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth), std::cos(polar)});
        }
    }
    addVertex({0.0, 0.0, -1.0});
    const std::uint32_t northPole = 0;
    const auto southPole = std::uint32_t(mesh.positions.size() - 1);
    const auto vertexAt = [&](std::uint32_t circle, std::uint32_t segment) {
        return 1 + circle * around + segment % around;
    };

    // Counter-clockwise from outside: going down (increasing polar angle) then around (increasing azimuth).
    for (std::uint32_t segment = 0; segment < around; ++segment) {
        mesh.triangles.emplace_back(northPole, vertexAt(0, segment), vertexAt(0, segment + 1));
    }
    for (std::uint32_t circle = 0; circle + 1 < circles; ++circle) {
        for (std::uint32_t segment = 0; segment < around; ++segment) {
            const std::uint32_t upperLeft = vertexAt(circle, segment);
            const std::uint32_t upperRight = vertexAt(circle, segment + 1);
            const std::uint32_t lowerLeft = vertexAt(circle + 1, segment);
            const std::uint32_t lowerRight = vertexAt(circle + 1, segment + 1);
            mesh.triangles.emplace_back(upperLeft, lowerLeft, lowerRight);
            mesh.triangles.emplace_back(upperLeft, lowerRight, upperRight);
        }
    }
    for (std::uint32_t segment = 0; segment < around; ++segment) {
        mesh.triangles.emplace_back(southPole, vertexAt(circles - 1, segment + 1), vertexAt(circles - 1, segment));
    }
    return mesh;
}

Mesh makeTorus(float majorRadius, float minorRadius, int majorSegments, int minorSegments) {
    require(std::isfinite(majorRadius) && std::isfinite(minorRadius) && minorRadius > 0.0f && majorRadius > minorRadius,
            "makeTorus()", "needs finite radii with majorRadius > minorRadius > 0");
    require(majorSegments >= 3 && minorSegments >= 3, "makeTorus()", "needs at least 3 segments each way");

    Mesh mesh;
    mesh.name = "torus";
    const auto aroundMajor = std::uint32_t(majorSegments);
    const auto aroundMinor = std::uint32_t(minorSegments);
    for (std::uint32_t i = 0; i < aroundMajor; ++i) {
        const double u = 2.0 * glm::pi<double>() * double(i) / double(majorSegments);
        for (std::uint32_t j = 0; j < aroundMinor; ++j) {
            const double v = 2.0 * glm::pi<double>() * double(j) / double(minorSegments);
            const double ring = double(majorRadius) + double(minorRadius) * std::cos(v);
            mesh.positions.emplace_back(ring * std::cos(u), ring * std::sin(u), double(minorRadius) * std::sin(v));
            mesh.normals.emplace_back(std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v));
        }
    }
    const auto vertexAt = [&](std::uint32_t i, std::uint32_t j) {
        return (i % aroundMajor) * aroundMinor + j % aroundMinor;
    };
    // dP/du x dP/dv points outward, so (u, v) -> (u+1, v) -> (u+1, v+1) is counter-clockwise from outside.
    for (std::uint32_t i = 0; i < aroundMajor; ++i) {
        for (std::uint32_t j = 0; j < aroundMinor; ++j) {
            const std::uint32_t a = vertexAt(i, j);
            const std::uint32_t b = vertexAt(i + 1, j);
            const std::uint32_t c = vertexAt(i + 1, j + 1);
            const std::uint32_t d = vertexAt(i, j + 1);
            mesh.triangles.emplace_back(a, b, c);
            mesh.triangles.emplace_back(a, c, d);
        }
    }
    return mesh;
}

Mesh makeCube(glm::vec3 center, float halfSize) {
    require(std::isfinite(halfSize) && halfSize > 0.0f, "makeCube()", "halfSize must be positive and finite");
    require(std::isfinite(center.x) && std::isfinite(center.y) && std::isfinite(center.z), "makeCube()",
            "center must be finite");
    Mesh mesh;
    mesh.name = "cube";
    // Per face: the outward normal and two in-plane axes with u x v = normal, so corners taken counter-clockwise in
    // (u, v) are counter-clockwise seen from outside.
    const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const glm::vec3& normal : normals) {
        const glm::vec3 u = glm::vec3(normal.z, normal.x, normal.y); // a cyclic shift: perpendicular to the normal
        const glm::vec3 v = glm::cross(normal, u);
        const auto first = std::uint32_t(mesh.positions.size());
        for (const glm::vec2 corner : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
            mesh.positions.push_back(center + halfSize * (normal + corner.x * u + corner.y * v));
            mesh.normals.push_back(normal);
        }
        mesh.triangles.emplace_back(first, first + 1, first + 2);
        mesh.triangles.emplace_back(first, first + 2, first + 3);
    }
    return mesh;
}

Scene makeScene(Mesh mesh) {
    Scene scene;
    scene.report.format = "procedural";
    scene.report.trianglesRead = mesh.triangles.size();
    scene.report.verticesBeforeWeld = mesh.positions.size();
    scene.report.verticesAfterWeld = mesh.positions.size();
    // Keep the loader's invariant of one normal per position for meshes built by hand without normals.
    if (mesh.normals.size() != mesh.positions.size()) {
        mesh.normals = computeSmoothNormals(mesh.positions, mesh.triangles);
        scene.report.normalsComputed = true;
    }
    scene.meshes.push_back(std::move(mesh));
    return scene;
}

} // namespace inkgraph
