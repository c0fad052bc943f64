/** @file What the readers share (FormatReaders.h): the load's memory budget, the placement of coordinates read in
 *  double, and the messages that name the file. */

#include "scene/formats/FormatReaders.h"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <new>
#include <stdexcept>
#include <iterator>

namespace inkgraph {

namespace detail {

std::string memoryText(std::size_t bytes) {
    if (bytes >= (std::size_t(1) << 20)) return std::to_string(bytes >> 20) + " MiB";
    if (bytes >= 1024) return std::to_string(bytes >> 10) + " KiB";
    return std::to_string(bytes) + (bytes == 1 ? " byte" : " bytes");
}

void checkModelExtent(const std::string& path, double extent, std::string_view function) {
    if (!(extent <= kMaxModelExtent)) {
        throwLoadError(path,
                       "the model is " + formatExtent(extent) + " units across (bounding-box diagonal), above the " +
                           formatExtent(kMaxModelExtent) +
                           " the renderer can hold (float relative to the model's centre); "
                           "check the units or the node scales",
                       function);
    }
    if (extent > 0.0 && extent < kMinModelExtent) {
        throwLoadError(path,
                       "the model is " + formatExtent(extent) + " units across (bounding-box diagonal), below the " +
                           formatExtent(kMinModelExtent) +
                           " the renderer can resolve; check the units or the node scales",
                       function);
    }
}

glm::dvec3 storeNearModel(const std::string& path, std::span<const glm::dvec3> world, std::vector<glm::vec3>& stored,
                          std::string_view function) {
    BoundingBox box;
    for (const glm::dvec3& p : world) {
        box.add(p);
    }
    const double extent = box.diagonal();
    checkModelExtent(path, extent, function);
    const glm::dvec3 centre = box.empty() ? glm::dvec3(0.0) : box.center();
    const glm::dvec3 distance = glm::abs(centre);
    const glm::dvec3 origin = std::max({distance.x, distance.y, distance.z}) <= extent ? glm::dvec3(0.0) : centre;
    stored.resize(world.size());
    for (std::size_t i = 0; i < world.size(); ++i) {
        stored[i] = glm::vec3(world[i] - origin);
    }
    return origin;
}

std::string noTrianglesInTheFile(const std::vector<Warning>& warnings) {
    constexpr std::size_t kNamed = 3;
    std::string message = "no triangles in the file";
    for (std::size_t i = 0; i < std::min(warnings.size(), kNamed); ++i)
        message += (i == 0 ? "; what the load said: " : "; ") + warnings[i].message;
    if (warnings.size() > kNamed) message += "; and " + std::to_string(warnings.size() - kNamed) + " more warnings";
    return message;
}

void throwLoadError(const std::string& path, std::string_view problem, std::string_view function) {
    throw SceneError(std::string(function) + ": " + quotedFileName(path) + ": " + std::string(problem));
}

void throwLoadErrorAtLine(const std::string& path, std::size_t line, std::string_view problem) {
    throw SceneError("loadScene(): " + quotedFileName(path) + " line " + std::to_string(line) + ": " +
                     std::string(problem));
}

std::size_t MeshBudget::estimate(std::size_t vertices, std::size_t triangles) const {
    // Saturating: declared counts may be anything up to 2^64.
    const auto product = [](std::size_t count, std::size_t bytes) {
        return count > SIZE_MAX / bytes ? SIZE_MAX : count * bytes;
    };
    const auto sum = [](std::size_t a, std::size_t b) { return a > SIZE_MAX - b ? SIZE_MAX : a + b; };
    const std::size_t allVertices = sum(mVertices, vertices);
    const std::size_t allTriangles = sum(mTriangles, triangles);
    return sum(sum(mFileBytes, mOtherBytes),
               sum(product(allVertices, kBytesPerVertex), product(allTriangles, kBytesPerTriangle)));
}

void MeshBudget::chargeFile(std::size_t bytes) {
    mFileBytes = mFileBytes > SIZE_MAX - bytes ? SIZE_MAX : mFileBytes + bytes;
    if (estimate(0, 0) > mLimitBytes)
        throwLoadError(mPath,
                       "the file is " + memoryText(bytes) + "; the load would hold about " +
                           memoryText(estimate(0, 0)) + ", above the memory limit of " + memoryText(mLimitBytes) +
                           " (" + mLimitName + ")",
                       mFunction);
}

void MeshBudget::chargeBytes(std::size_t bytes, std::string_view what) {
    mOtherBytes = mOtherBytes > SIZE_MAX - bytes ? SIZE_MAX : mOtherBytes + bytes;
    if (estimate(0, 0) > mLimitBytes)
        throwLoadError(mPath,
                       "the load would hold about " + memoryText(estimate(0, 0)) + " (with " + std::string(what) +
                           "), above the memory limit of " + memoryText(mLimitBytes) + " (" + mLimitName + ")",
                       mFunction);
}

void MeshBudget::checkBytes(std::size_t bytes, std::string_view what) const {
    const std::size_t held = estimate(0, 0);
    const std::size_t total = held > SIZE_MAX - bytes ? SIZE_MAX : held + bytes;
    if (total > mLimitBytes)
        throwLoadError(mPath,
                       std::string(what) + " would need about " + memoryText(bytes) + "; the load would hold about " +
                           memoryText(total) + ", above the memory limit of " + memoryText(mLimitBytes) + " (" +
                           mLimitName + ")",
                       mFunction);
}

void MeshBudget::check(std::size_t vertices, std::size_t triangles) const {
    const std::size_t bytes = estimate(vertices, triangles);
    if (bytes > mLimitBytes)
        throwLoadError(mPath,
                       "the mesh would need about " + memoryText(bytes) + " (" + std::to_string(mVertices + vertices) +
                           " vertices, " + std::to_string(mTriangles + triangles) +
                           " triangles), above the memory limit of " + memoryText(mLimitBytes) + " (" + mLimitName +
                           ")",
                       mFunction);
}

void MeshBudget::charge(std::size_t vertices, std::size_t triangles) {
    check(vertices, triangles);
    mVertices += vertices;
    mTriangles += triangles;
}

std::string wholeFileBestEffort(const std::string& path) {
    // One read of the size the file reports (a character iterator took 5-10 ms over a 3 MB OBJ); a file that
    // shrank meanwhile gives what was there, one that grew its first bytes.
    std::ifstream file(path, std::ios::binary | std::ios::ate);
    const std::streamoff size = file ? std::streamoff(file.tellg()) : std::streamoff(-1);
    if (size <= 0) return {};
    try {
        std::string content(std::size_t(size), '\0');
        file.seekg(0);
        file.read(content.data(), size);
        content.resize(std::size_t(file.gcount()));
        return content;
    } catch (const std::bad_alloc&) {
        return {}; // nothing thrown: the load that follows reports what it cannot read
    } catch (const std::length_error&) {
        return {};
    }
}

Warning polygonsFannedWarning(const PolygonTriangulator& triangulator) {
    const std::size_t beyondWork = triangulator.polygonsBeyondWork();
    const std::size_t crossing = triangulator.unresolvedPolygons() - beyondWork;
    std::string message;
    if (crossing > 0) {
        message = crossing == 1 ? "1 polygon crosses itself" : std::to_string(crossing) + " polygons cross themselves";
    }
    if (beyondWork > 0) {
        message += (message.empty() ? "" : ", and ") + std::to_string(beyondWork) + " concave polygon" +
                   (beyondWork == 1 ? " was" : "s were") + " beyond the work one file may take to cut (" +
                   std::to_string(PolygonTriangulator::kWorkBudget) + " corner tests)";
    }
    const bool one = triangulator.unresolvedPolygons() == 1;
    return makeWarning(WarningKind::PolygonsFanned,
                       message + "; fanned from " + (one ? "its" : "their") + " first corner, so " +
                           (one ? "its outline" : "their outlines") + " may be drawn wrong");
}

} // namespace detail

} // namespace inkgraph
