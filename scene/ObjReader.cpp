/** @file Wavefront OBJ: v, vn and f (v, v/vt, v//vn, v/vt/vn; negative = relative), polygons fan-triangulated.
 *  Parses the whole file from memory with std::from_chars; everything else (vt, o/g names, materials, groups,
 *  smoothing) is skipped, except that the first `o` name names the mesh. */

#include "scene/FormatReaders.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <unordered_map>

namespace inkgraph::detail {

namespace {

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

const char* plural(bool isNormal) { return isNormal ? "normals" : "vertices"; }

/** One corner of a face as written in the file, already made 0-based; `normal` is kNoNormal when absent. */
struct Corner {
    std::uint32_t position = 0;
    std::uint32_t normal = 0;
};

/** Lines between memory-budget checks: a line adds at most a few hundred bytes per byte of text. */
constexpr std::size_t kBudgetCheckInterval = 1 << 14;

constexpr std::uint32_t kNoNormal = std::numeric_limits<std::uint32_t>::max();

/** A positive index that pointed past the vertices defined so far; legal only if the vertex appears later. */
struct ForwardReference {
    std::size_t line = 0;
    long long index = 0; ///< 1-based, as written
    bool isNormal = false;
};

class ObjParser {
public:
    ObjParser(const std::string& path, std::string_view text, MeshBudget& budget)
        : mPath(path), mText(text), mBudget(budget) {}

    RawScene parse() {
        // Text never holds NUL bytes; a GLB or binary STL saved as .obj would otherwise read as "no faces".
        if (const std::size_t nul = mText.find('\0'); nul != std::string_view::npos) {
            mLine = std::size_t(std::count(mText.begin(), mText.begin() + std::ptrdiff_t(nul), '\n')) + 1;
            fail("binary data (NUL byte); an OBJ file is text (is this a .glb or binary .stl?)");
        }
        const char* cursor = mText.data();
        const char* const end = cursor + mText.size();
        while (cursor < end) {
            ++mLine;
            const char* lineEnd = static_cast<const char*>(std::memchr(cursor, '\n', std::size_t(end - cursor)));
            if (lineEnd == nullptr) {
                lineEnd = end;
            }
            parseLine(cursor, lineEnd);
            cursor = lineEnd + 1;
            if (mLine % kBudgetCheckInterval == 0) {
                mBudget.check(mPositions.size() + mNormals.size(), mPositionTriangles.size() + mNormalTriangles.size());
            }
        }
        checkForwardReferences();
        if (mPositionTriangles.empty()) {
            throwLoadError(mPath, "no triangles: the file has no faces");
        }
        return buildScene();
    }

private:
    [[noreturn]] void fail(std::string_view problem) const { throwLoadErrorAtLine(mPath, mLine, problem); }

    void parseLine(const char* p, const char* end) {
        while (p < end && isBlank(*p)) {
            ++p;
        }
        if (p == end || *p == '#') {
            return;
        }
        const char* keyword = p;
        while (p < end && !isBlank(*p)) {
            ++p;
        }
        const std::string_view command(keyword, std::size_t(p - keyword));
        if (command == "v") {
            mPositions.push_back(parseVector(p, end, "vertex"));
        } else if (command == "vn") {
            mNormals.push_back(parseVector(p, end, "normal"));
        } else if (command == "f") {
            parseFace(p, end);
        } else if (command == "o" && mMeshName.empty()) {
            while (p < end && isBlank(*p)) {
                ++p;
            }
            const char* nameEnd = end;
            while (nameEnd > p && isBlank(nameEnd[-1])) {
                --nameEnd;
            }
            mMeshName.assign(p, nameEnd);
        } else if (command == "l" || command == "p") {
            ++mSkippedNonFaces;
        }
        // vt, g, s, usemtl, mtllib and unknown statements carry nothing this renderer uses.
    }

    /** Three finite coordinates; a fourth (w, or vertex colours after them) is ignored. */
    glm::vec3 parseVector(const char*& p, const char* end, const char* what) {
        glm::vec3 value;
        for (int axis = 0; axis < 3; ++axis) {
            const double number = parseNumber(p, end, what);
            value[axis] = float(number);
            if (!std::isfinite(value[axis])) {
                fail(std::string("non-finite ") + what + " coordinate (" + std::to_string(number) + ")");
            }
        }
        return value;
    }

    double parseNumber(const char*& p, const char* end, const char* what) {
        while (p < end && isBlank(*p)) {
            ++p;
        }
        if (p == end) {
            fail(std::string(what) + " has fewer than 3 coordinates");
        }
        const char* start = p;
        if (*p == '+') {
            ++p; // from_chars rejects an explicit plus sign
        }
        double number = 0.0;
        const auto [next, error] = std::from_chars(p, end, number);
        const bool endsCleanly = next == end || isBlank(*next);
        if (error == std::errc::result_out_of_range && endsCleanly) {
            // Underflow gives 0, overflow infinity (then rejected as non-finite); strtod tells which.
            number = std::strtod(std::string(start, next).c_str(), nullptr);
        } else if (error != std::errc() || !endsCleanly) {
            const char* tokenEnd = start;
            while (tokenEnd < end && !isBlank(*tokenEnd)) {
                ++tokenEnd;
            }
            fail(std::string("cannot read ") + what + " coordinate '" + std::string(start, tokenEnd) + "'");
        }
        p = next;
        return number;
    }

    long long parseIndex(const char*& p, const char* end) {
        long long index = 0;
        const auto [next, error] = std::from_chars(p, end, index);
        if (error != std::errc()) {
            const char* tokenEnd = p;
            while (tokenEnd < end && !isBlank(*tokenEnd)) {
                ++tokenEnd;
            }
            fail("cannot read face index in '" + std::string(p, tokenEnd) + "'");
        }
        p = next;
        return index;
    }

    /** 1-based or negative (relative) index to 0-based; positive indices past the current count are checked once the
     *  whole file is read. */
    std::uint32_t resolveIndex(long long index, std::size_t definedSoFar, bool isNormal) {
        const char* what = isNormal ? "normal" : "vertex";
        if (index == 0) {
            fail(std::string(what) + " index 0 is invalid (OBJ indices start at 1)");
        }
        if (index > 0) {
            if (index > std::numeric_limits<std::uint32_t>::max() - 1) {
                fail(std::string(what) + " index " + std::to_string(index) + " out of range");
            }
            if (std::size_t(index) > definedSoFar) {
                mForwardReferences.push_back({mLine, index, isNormal});
            }
            return std::uint32_t(index - 1);
        }
        if (index < -std::int64_t(std::numeric_limits<std::uint32_t>::max()) || std::size_t(-index) > definedSoFar) {
            fail("relative " + std::string(what) + " index " + std::to_string(index) + " out of range (" +
                 std::to_string(definedSoFar) + " " + plural(isNormal) + " defined so far)");
        }
        return std::uint32_t(definedSoFar - std::size_t(-index));
    }

    void parseFace(const char* p, const char* end) {
        mCorners.clear();
        bool faceHasNormals = true;
        while (true) {
            while (p < end && isBlank(*p)) {
                ++p;
            }
            if (p == end) {
                break;
            }
            Corner corner;
            corner.position = resolveIndex(parseIndex(p, end), mPositions.size(), false);
            corner.normal = kNoNormal;
            if (p < end && *p == '/') {
                ++p;
                if (p < end && *p != '/' && !isBlank(*p)) {
                    parseIndex(p, end); // texture coordinate: syntax checked, value unused
                }
                if (p < end && *p == '/') {
                    ++p;
                    corner.normal = resolveIndex(parseIndex(p, end), mNormals.size(), true);
                }
            }
            if (p < end && !isBlank(*p)) {
                fail("unexpected character '" + std::string(1, *p) + "' in face");
            }
            faceHasNormals = faceHasNormals && corner.normal != kNoNormal;
            mCorners.push_back(corner);
        }
        if (mCorners.size() < 3) {
            fail("face has " + std::to_string(mCorners.size()) + " vertices (needs at least 3)");
        }
        if (faceHasNormals) {
            ++mFacesWithNormals;
        } else {
            ++mFacesWithoutNormals;
        }
        // Fan triangulation keeps the polygon's winding; OBJ polygons are planar and convex in practice.
        for (std::size_t i = 1; i + 1 < mCorners.size(); ++i) {
            mPositionTriangles.emplace_back(mCorners[0].position, mCorners[i].position, mCorners[i + 1].position);
            if (faceHasNormals) {
                mNormalTriangles.emplace_back(mCorners[0].normal, mCorners[i].normal, mCorners[i + 1].normal);
            }
        }
    }

    void checkForwardReferences() {
        for (const ForwardReference& reference : mForwardReferences) {
            const std::size_t available = reference.isNormal ? mNormals.size() : mPositions.size();
            if (std::size_t(reference.index) > available) {
                const char* what = reference.isNormal ? "normal" : "vertex";
                throwLoadErrorAtLine(mPath, reference.line,
                                     std::string(what) + " index " + std::to_string(reference.index) +
                                         " out of range (file has " + std::to_string(available) + " " +
                                         plural(reference.isNormal) + ")");
            }
        }
    }

    RawScene buildScene() {
        RawScene scene;
        scene.format = "obj";
        RawMesh mesh;
        mesh.name = mMeshName.empty() ? std::filesystem::path(mPath).stem().string() : mMeshName;

        if (mFacesWithNormals > 0 && mFacesWithoutNormals == 0) {
            // A vertex is a (position, normal) pair; hard edges reference one position with several normals.
            std::unordered_map<std::uint64_t, std::uint32_t> vertexOfPair;
            vertexOfPair.reserve(mPositions.size() * 2);
            mesh.triangles.resize(mPositionTriangles.size());
            for (std::size_t t = 0; t < mPositionTriangles.size(); ++t) {
                for (int corner = 0; corner < 3; ++corner) {
                    const std::uint32_t position = mPositionTriangles[t][corner];
                    const std::uint32_t normal = mNormalTriangles[t][corner];
                    const std::uint64_t key = (std::uint64_t(position) << 32) | normal;
                    const auto [it, inserted] = vertexOfPair.try_emplace(key, std::uint32_t(mesh.positions.size()));
                    if (inserted) {
                        mesh.positions.push_back(mPositions[position]);
                        mesh.normals.push_back(mNormals[normal]);
                    }
                    mesh.triangles[t][corner] = it->second;
                }
            }
        } else {
            if (mFacesWithNormals > 0) {
                scene.warnings.push_back(std::to_string(mFacesWithoutNormals) +
                                         " faces have no normals; all normals recomputed");
            }
            mesh.positions = std::move(mPositions);
            mesh.triangles = std::move(mPositionTriangles);
        }
        if (mSkippedNonFaces > 0) {
            scene.warnings.push_back(std::to_string(mSkippedNonFaces) + " line/point elements (l, p) skipped");
        }
        scene.meshes.push_back(std::move(mesh));
        return scene;
    }

    const std::string& mPath;
    std::string_view mText;
    MeshBudget& mBudget;
    std::size_t mLine = 0;
    std::string mMeshName;
    std::vector<glm::vec3> mPositions;
    std::vector<glm::vec3> mNormals;
    std::vector<glm::uvec3> mPositionTriangles;
    std::vector<glm::uvec3> mNormalTriangles; ///< parallel to mPositionTriangles while every face has normals
    std::vector<Corner> mCorners;             ///< scratch for the current face
    std::vector<ForwardReference> mForwardReferences;
    std::size_t mFacesWithNormals = 0;
    std::size_t mFacesWithoutNormals = 0;
    std::size_t mSkippedNonFaces = 0;
};

} // namespace

RawScene readObj(const std::string& path, std::string_view content, MeshBudget& budget) {
    return ObjParser(path, content, budget).parse();
}

} // namespace inkgraph::detail
