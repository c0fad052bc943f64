/** @file Wavefront OBJ: v, vn and f (v, v/vt, v//vn, v/vt/vn; negative = relative), polygons fan-triangulated.
 *  Parses the whole file from memory with std::from_chars; everything else (vt, o/g names, groups, smoothing) is
 *  skipped, except that the first `o` name names the mesh. Materials are not drawn (an OBJ mesh takes the default
 *  colour), but the `mtllib` files are read for their `newmtl` names so that a missing library or an undefined
 *  `usemtl` material is reported as a warning: exports often travel without their .mtl, and refusing them would
 *  help nobody. */

#include "scene/FormatReaders.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <system_error>
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

/** Undefined `usemtl` materials named one by one in the warnings; the rest are counted. */
constexpr std::size_t kMaxNamedMaterials = 10;

std::string_view trimmed(const char* begin, const char* end) {
    while (begin < end && isBlank(*begin)) {
        ++begin;
    }
    while (end > begin && isBlank(end[-1])) {
        --end;
    }
    return std::string_view(begin, std::size_t(end - begin));
}

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
        // Windows tools may write a byte-order mark; left in, it would glue itself to the first keyword
        // ("\xEF\xBB\xBFv") and that vertex would be skipped, shifting every index after it.
        mText = withoutByteOrderMark(mText);
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
        checkMaterials();
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
            mPositions.push_back(parsePosition(p, end));
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
        } else if (command == "mtllib") {
            readMaterialLibraries(trimmed(p, end));
        } else if (command == "usemtl") {
            mUsedMaterials.try_emplace(std::string(trimmed(p, end)), mLine);
        }
        // vt, g, s and unknown statements carry nothing this renderer uses.
    }

    /** A `v` line, kept in double until the whole model is known (storeNearModel()), so a model far from the world
     *  origin keeps its detail. A coordinate beyond float's range is refused as it always was: no renderable model
     *  has one. */
    glm::dvec3 parsePosition(const char*& p, const char* end) {
        glm::dvec3 value;
        for (int axis = 0; axis < 3; ++axis) {
            value[axis] = parseNumber(p, end, "vertex");
            if (!std::isfinite(value[axis])) {
                fail("non-finite vertex coordinate (" + formatNumber(value[axis]) + ")");
            }
            if (std::abs(value[axis]) > std::numeric_limits<float>::max()) {
                fail("non-finite vertex coordinate in float (" + formatNumber(value[axis]) +
                     " is beyond float's range)");
            }
        }
        return value;
    }

    /** `mtllib a.mtl [b.mtl ...]`: each library next to the OBJ is read for its `newmtl` names. A name with spaces
     *  is tried whole first, since exporters write such names unquoted. */
    void readMaterialLibraries(std::string_view names) {
        if (names.empty()) {
            return;
        }
        if (readMaterialLibrary(names, false)) {
            return;
        }
        const char* p = names.data();
        const char* const end = p + names.size();
        while (p < end) {
            while (p < end && isBlank(*p)) {
                ++p;
            }
            const char* nameStart = p;
            while (p < end && !isBlank(*p)) {
                ++p;
            }
            if (p > nameStart) {
                readMaterialLibrary(std::string_view(nameStart, std::size_t(p - nameStart)), true);
            }
        }
    }

    /** Reads one library's `newmtl` names; false (and, when `warnIfMissing`, a warning) when it cannot be read. */
    bool readMaterialLibrary(std::string_view name, bool warnIfMissing) {
        const std::filesystem::path named{std::string(name)};
        const std::filesystem::path resolved =
            named.is_absolute() ? named : std::filesystem::path(mPath).parent_path() / named;
        const std::string shown = "mtllib '" + excerptForMessage(name) + "' (line " + std::to_string(mLine) + ")";
        std::error_code error;
        // A FIFO or device would block or never end: only regular files are opened.
        if (!std::filesystem::is_regular_file(resolved, error)) {
            if (warnIfMissing) {
                mWarnings.push_back(shown + ": '" + excerptForMessage(resolved.string()) +
                                    "' is missing or not a regular file; materials are not drawn for OBJ, so the "
                                    "render is the same");
                mMissingLibrary = true;
            }
            return false;
        }
        const std::uintmax_t size = std::filesystem::file_size(resolved, error);
        std::ifstream file(resolved, std::ios::binary);
        if (error || !file) {
            if (warnIfMissing) {
                mWarnings.push_back(shown + ": cannot read '" + excerptForMessage(resolved.string()) + "'");
                mMissingLibrary = true;
            }
            return false;
        }
        mBudget.chargeFile(std::size_t(size));
        mInputFiles.push_back(resolved.string());
        // At most the size the file system reports: some "regular" files (/proc/self/pagemap) report 0 and then
        // stream gigabytes.
        std::string text(std::size_t(size), '\0');
        file.read(text.data(), std::streamsize(size));
        text.resize(std::size_t(file.gcount()));
        std::size_t start = 0;
        while (start < text.size()) {
            std::size_t lineEnd = text.find('\n', start);
            if (lineEnd == std::string::npos) {
                lineEnd = text.size();
            }
            const std::string_view line = trimmed(text.data() + start, text.data() + lineEnd);
            constexpr std::string_view kNewMaterial = "newmtl";
            if (line.size() > kNewMaterial.size() && line.substr(0, kNewMaterial.size()) == kNewMaterial &&
                isBlank(line[kNewMaterial.size()])) {
                const std::string_view defined = line.substr(kNewMaterial.size());
                mDefinedMaterials.insert(std::string(trimmed(defined.data(), defined.data() + defined.size())));
            }
            start = lineEnd + 1;
        }
        return true;
    }

    /** Warns about `usemtl` names that no library read defines (unless a library was missing: that was said). */
    void checkMaterials() {
        if (mUsedMaterials.empty()) {
            return;
        }
        std::vector<std::string> undefined;
        std::size_t undefinedCount = 0;
        for (const auto& [name, line] : mUsedMaterials) {
            if (mDefinedMaterials.count(name) == 0) {
                if (++undefinedCount <= kMaxNamedMaterials) {
                    std::string entry = "'";
                    entry += excerptForMessage(name);
                    entry += "' (line " + std::to_string(line) + ")";
                    undefined.push_back(std::move(entry));
                }
            }
        }
        if (undefinedCount == 0 || mMissingLibrary) {
            return;
        }
        std::string list;
        for (const std::string& entry : undefined) {
            list += (list.empty() ? "" : ", ") + entry;
        }
        if (undefinedCount > undefined.size()) {
            list += " and " + std::to_string(undefinedCount - undefined.size()) + " more";
        }
        const std::string where = !mInputFiles.empty() ? "in its mtllib files" : "(the file has no mtllib)";
        mWarnings.push_back("usemtl names materials not defined " + where + ": " + list +
                            "; materials are not drawn for OBJ, so the render is the same");
    }

    /** Three finite coordinates; a fourth (w, or vertex colours after them) is ignored. */
    glm::vec3 parseVector(const char*& p, const char* end, const char* what) {
        glm::vec3 value(0.0f);
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
            fail(std::string("cannot read ") + what + " coordinate '" +
                 excerptForMessage(std::string_view(start, std::size_t(tokenEnd - start))) + "'");
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
            fail("cannot read face index in '" + excerptForMessage(std::string_view(p, std::size_t(tokenEnd - p))) +
                 "'");
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
        std::vector<glm::vec3> positions;
        scene.origin = storeNearModel(mPath, mPositions, positions);
        mPositions = {}; // its memory back before the mesh is built
        scene.inputFiles = std::move(mInputFiles);
        scene.warnings = std::move(mWarnings);
        RawMesh mesh;
        mesh.name = mMeshName.empty() ? std::filesystem::path(mPath).stem().string() : mMeshName;
        if (!mMeshName.empty()) mesh.nodePath = {mMeshName}; // the first `o` name: what --frame selects

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
                        mesh.positions.push_back(positions[position]);
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
            mesh.positions = std::move(positions);
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
    std::vector<std::string> mInputFiles; ///< the mtllib files read
    std::vector<std::string> mWarnings;
    std::map<std::string, std::size_t> mUsedMaterials; ///< usemtl name -> first line using it
    std::set<std::string> mDefinedMaterials;           ///< newmtl names of every library read
    bool mMissingLibrary = false;
    std::vector<glm::dvec3> mPositions; ///< as read; rounded to float once the model's extent is known
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

std::vector<std::string> objReferencedFiles(const std::string& path, std::string_view content) {
    const std::filesystem::path folder = std::filesystem::path(path).parent_path();
    const auto beside = [&](std::string_view name) {
        const std::filesystem::path named{std::string(name)};
        return (named.is_absolute() ? named : folder / named).string();
    };
    std::vector<std::string> files;
    content = withoutByteOrderMark(content); // as readObj(): a mark must not hide a first-line mtllib
    for (std::size_t start = 0; start < content.size();) {
        std::size_t end = content.find('\n', start);
        if (end == std::string_view::npos) end = content.size();
        std::string_view line = content.substr(start, end - start);
        start = end + 1;
        while (!line.empty() && isBlank(line.front())) line.remove_prefix(1);
        while (!line.empty() && (isBlank(line.back()) || line.back() == '\r')) line.remove_suffix(1);
        if (line.substr(0, 6) != "mtllib" || line.size() < 8 || !isBlank(line[6])) continue;
        std::string_view names = line.substr(7);
        while (!names.empty() && isBlank(names.front())) names.remove_prefix(1);
        files.push_back(beside(names)); // a name with spaces, whole
        for (std::size_t at = 0; at < names.size();) {
            const std::size_t from = names.find_first_not_of(" \t", at);
            if (from == std::string_view::npos) break;
            const std::size_t to = std::min(names.find_first_of(" \t", from), names.size());
            if (from != 0 || to != names.size()) files.push_back(beside(names.substr(from, to - from)));
            at = to;
        }
    }
    return files;
}

} // namespace inkgraph::detail
