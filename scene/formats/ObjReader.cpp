/** @file Wavefront OBJ: v (with an optional vertex colour), vt, vn and f (v, v/vt, v//vn, v/vt/vn; negative =
 *  relative), polygons cut into triangles inside their outline (scene/mesh/PolygonTriangulation.h), and the materials
 *  of its `mtllib` libraries (scene/formats/ObjMaterials.cpp) that `usemtl` picks: one mesh per material of each `o`
 *  object, named by the first `o` name (or the file stem) when the file has faces in one object only. Parses the
 *  whole file from memory with std::from_chars; `g` groups and smoothing groups are skipped. A missing library or an
 *  undefined `usemtl` material is a warning, and those faces take the default grey: exports often travel without
 *  their .mtl, and refusing them would help nobody. */

#include "scene/formats/FormatTable.h"
#include "scene/formats/TextTokens.h"

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
#include <optional>
#include <system_error>
#include <unordered_map>

namespace inkgraph::detail {

namespace {

/** What a face index refers to. */
enum class IndexKind { Vertex, Texcoord, Normal };

const char* singular(IndexKind kind) {
    return kind == IndexKind::Vertex ? "vertex" : kind == IndexKind::Texcoord ? "texture coordinate" : "normal";
}
const char* plural(IndexKind kind) {
    return kind == IndexKind::Vertex ? "vertices" : kind == IndexKind::Texcoord ? "texture coordinates" : "normals";
}

constexpr std::uint32_t kAbsent = std::numeric_limits<std::uint32_t>::max();

/** One corner of a face as written in the file, already made 0-based; `texcoord` and `normal` are kAbsent when the
 *  corner has none. */
struct Corner {
    std::uint32_t position = 0;
    std::uint32_t texcoord = kAbsent;
    std::uint32_t normal = kAbsent;
    bool operator==(const Corner&) const = default;
};

struct CornerHash {
    std::size_t operator()(const Corner& corner) const {
        std::uint64_t hash = corner.position;
        hash = hash * 0x9E3779B97F4A7C15ull ^ corner.texcoord;
        hash = hash * 0x9E3779B97F4A7C15ull ^ corner.normal;
        return std::size_t(hash ^ (hash >> 29));
    }
};

/** The faces of one `o` object that one `usemtl` material (or none, before the first `usemtl`) covers: one mesh. */
struct FaceGroup {
    std::uint32_t object = 0;    ///< index into ObjParser::mObjectNames
    std::string materialName;    ///< as `usemtl` wrote it; empty for the faces before any
    std::vector<Corner> corners; ///< three per triangle
    std::size_t facesWithNormals = 0;
    std::size_t facesWithoutNormals = 0;
    std::size_t facesWithTexcoords = 0;
    std::size_t facesWithoutTexcoords = 0;
};

/** Undefined `usemtl` materials named one by one in the warnings; the rest are counted. */
constexpr std::size_t kMaxNamedMaterials = 10;

/** A finite number filling the whole token (an explicit '+' allowed), else nothing. */
std::optional<double> finiteNumber(std::string_view token) {
    if (!token.empty() && token.front() == '+') {
        token.remove_prefix(1);
    }
    double value = 0.0;
    const auto [next, error] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (token.empty() || error != std::errc() || next != token.data() + token.size() || !std::isfinite(value)) {
        return std::nullopt;
    }
    return value;
}

/** Lines between memory-budget checks: a line adds at most a few hundred bytes per byte of text. */
constexpr std::size_t kLinesBetweenBudgetChecks = 1 << 14;

/** A positive index that pointed past the vertices defined so far; legal only if the vertex appears later. */
struct ForwardReference {
    std::size_t line = 0;
    long long index = 0; ///< 1-based, as written
    IndexKind kind = IndexKind::Vertex;
};

/** A polygon of more than three corners read before one of its vertices was defined (legal, if rare): fanned as it
 *  was read, its corners from `firstCorner` on in its group, and cut properly once the file is read. */
struct PolygonNamingLaterVertices {
    std::uint32_t group = 0;
    std::size_t firstCorner = 0;
    std::vector<Corner> corners;
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
            if (continuesOnNextLine(cursor, lineEnd)) {
                cursor = parseContinuedStatement(cursor, lineEnd, end);
            } else {
                parseLine(cursor, lineEnd);
                cursor = lineEnd + 1;
            }
            if (mLine >= mNextBudgetCheck) { // >=: a continued statement steps over several lines
                mBudget.check(mPositions.size() + mNormals.size() + mTexcoords.size(), mCornerCount / 3);
                mNextBudgetCheck = mLine + kLinesBetweenBudgetChecks;
            }
        }
        checkForwardReferences();
        triangulatePolygonsNamingLaterVertices();
        if (mCornerCount == 0) {
            throwLoadError(mPath, "no triangles: the file has no faces");
        }
        checkMaterials();
        return buildScene();
    }

private:
    [[noreturn]] void fail(std::string_view problem) const { throwLoadErrorAtLine(mPath, mLine, problem); }

    /** Where a data statement's values end: at a comment (`f 1 2 3 # quad`, as some exporters write). Names (`o`,
     *  `g`, `usemtl`, `mtllib`) may hold '#', so only the statements of numbers are cut. */
    static const char* valuesEnd(const char* p, const char* end) {
        while (p < end && isBlank(*p)) ++p;
        const char* keyword = p;
        while (p < end && !isBlank(*p)) ++p;
        if (!isDataStatement(std::string_view(keyword, std::size_t(p - keyword)))) return end;
        const char* hash = static_cast<const char*>(std::memchr(p, '#', std::size_t(end - p)));
        return hash != nullptr ? hash : end;
    }

    /** The statements of numbers, which the OBJ specification lets go on over lines ending in '\\'. */
    static bool isDataStatement(std::string_view keyword) {
        return keyword == "v" || keyword == "vt" || keyword == "vn" || keyword == "vp" || keyword == "f" ||
               keyword == "fo" || keyword == "l" || keyword == "p";
    }

    /** The OBJ specification's line continuation: a statement of numbers (`v`, `f`, ...) whose line ends in '\\'
     *  goes on on the next line (long `f` lines of some exporters). Names and paths never do: a '\\' ends Windows
     *  folders (`g C:\\models\\`, `mtllib`), and a comment ends the values (`f 1 2 3 # C:\\dir\\`). */
    static bool continuesOnNextLine(const char* p, const char* end) {
        const char* last = end;
        while (last > p && isBlank(last[-1])) --last;
        // Most lines: one look at their end. A comment ends the values first (`f 1 2 3 # C:\\dir\\`), on every
        // line of the statement alike.
        if (last == p || (last[-1] != '\\' && std::memchr(p, '#', std::size_t(last - p)) == nullptr)) return false;
        end = valuesEnd(p, end);
        while (end > p && isBlank(end[-1])) --end;
        if (end == p || end[-1] != '\\') return false;
        while (p < end && isBlank(*p)) ++p;
        const char* keyword = p;
        while (p < end && !isBlank(*p)) ++p;
        return isDataStatement(std::string_view(keyword, std::size_t(p - keyword)));
    }

    /** Joins a statement's continued lines (each '\\' and line break read as one blank) and reads it as one line;
     *  errors name its first line. Returns where the next statement starts. */
    const char* parseContinuedStatement(const char* cursor, const char* lineEnd, const char* end) {
        const std::size_t firstLine = mLine;
        std::string statement;
        for (bool first = true;; first = false) {
            // The lines after the first hold values alone: a comment on them ends them too.
            const char* hash =
                first ? nullptr : static_cast<const char*>(std::memchr(cursor, '#', std::size_t(lineEnd - cursor)));
            const char* content = first ? valuesEnd(cursor, lineEnd) : hash != nullptr ? hash : lineEnd;
            while (content > cursor && isBlank(content[-1])) --content;
            const bool continues = content > cursor && content[-1] == '\\';
            statement.append(cursor, continues ? content - 1 : content);
            statement += ' ';
            cursor = lineEnd + 1;
            if (!continues || cursor >= end) break;
            ++mLine;
            lineEnd = static_cast<const char*>(std::memchr(cursor, '\n', std::size_t(end - cursor)));
            if (lineEnd == nullptr) lineEnd = end;
        }
        const std::size_t lastLine = mLine;
        mLine = firstLine;
        parseLine(statement.data(), statement.data() + statement.size());
        mLine = lastLine;
        return cursor;
    }

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
        if (isDataStatement(command)) end = valuesEnd(keyword, end);
        if (command == "v") {
            mPositions.push_back(parsePosition(p, end));
            readVertexColour(p, end);
        } else if (command == "vt") {
            mTexcoords.push_back(parseTexcoord(p, end));
        } else if (command == "vn") {
            mNormals.push_back(parseVector(p, end, "normal"));
        } else if (command == "f") {
            parseFace(p, end);
        } else if (command == "o") {
            while (p < end && isBlank(*p)) {
                ++p;
            }
            const char* nameEnd = end;
            while (nameEnd > p && isBlank(nameEnd[-1])) {
                --nameEnd;
            }
            if (mMeshName.empty()) mMeshName.assign(p, nameEnd);
            // Each `o` line starts an object (ObjectIds.h: the G-buffer's objectId); the material carries over.
            mBudget.chargeBytes(sizeof(std::string) + std::size_t(nameEnd - p));
            mObjectNames.emplace_back(p, nameEnd);
            mCurrentObject = std::uint32_t(mObjectNames.size() - 1);
            mCurrentGroup = kAbsent;
        } else if (command == "l" || command == "p") {
            ++mSkippedNonFaces;
        } else if (command == "mtllib") {
            readMaterialLibraries(trimmed(std::string_view(p, std::size_t(end - p))));
        } else if (command == "usemtl") {
            const std::string name(trimmed(std::string_view(p, std::size_t(end - p))));
            mUsedMaterials.try_emplace(name, mLine);
            mCurrentMaterial = name;
            mCurrentGroup = groupOf(name);
        }
        // g, s and unknown statements carry nothing this renderer uses.
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

    /** What follows a `v` line's x y z: nothing, w (ignored: a renderer draws rational points no differently), or a
     *  colour r g b [a] as many exporters write it (values as written, clamped to [0, 1]). Anything else is skipped as
     *  it always was. The colours exist for every vertex once one vertex has one: the uncoloured ones are white. */
    void readVertexColour(const char* p, const char* end) {
        glm::vec4 colour(1.0f);
        std::size_t count = 0;
        bool allNumbers = true;
        bool outOfRange = false;
        for (const std::string_view token : tokensOf(std::string_view(p, std::size_t(end - p)))) {
            const std::optional<double> value = finiteNumber(token);
            allNumbers = allNumbers && value.has_value();
            if (allNumbers && count < 4) colour[int(count)] = float(std::clamp(*value, 0.0, 1.0));
            if (allNumbers && count < 4 && (*value < 0.0 || *value > 1.0)) {
                const double outside = *value < 0.0 ? -*value : *value - 1.0;
                if (outside > mColourDistanceOut) {
                    mColourDistanceOut = outside;
                    mColourFarthestOut = *value;
                }
                outOfRange = true;
            }
            ++count;
        }
        const bool coloured = allNumbers && (count == 3 || count == 4);
        if (coloured && outOfRange) ++mColoursOutOfRange;
        // Neither w nor a colour (two or five numbers, NaN, a word): counted, and said once for the file.
        if (count > 1 && !coloured) ++mUnreadVertexExtras;
        if (coloured && !mHasColors) {
            mColors.assign(mPositions.size() - 1, glm::vec4(1.0f));
            mHasColors = true;
        }
        if (mHasColors) {
            mColors.push_back(coloured ? colour : glm::vec4(1.0f));
        }
    }

    /** `vt u [v [w]]`, stored as (u, 1 - v): OBJ's v points up from the image's bottom, while the mesh keeps glTF's
     *  convention of (0, 0) at the image's top-left (Mesh::texcoords). */
    glm::vec2 parseTexcoord(const char*& p, const char* end) {
        while (p < end && isBlank(*p)) {
            ++p;
        }
        if (p == end) {
            fail("'vt' without coordinates");
        }
        const double u = parseNumber(p, end, "texture", 1);
        double v = 0.0;
        while (p < end && isBlank(*p)) {
            ++p;
        }
        if (p < end) {
            v = parseNumber(p, end, "texture", 1);
        }
        const glm::vec2 stored(float(u), float(1.0 - v));
        if (!std::isfinite(stored.x) || !std::isfinite(stored.y)) {
            // Not geometry: the shape is still right, only the texture at these corners is not, so a warning, and
            // (0, 0) keeps NaN out of the vertex buffers.
            ++mNonFiniteTexcoords;
            return glm::vec2(0.0f);
        }
        return stored; // a w after u and v is ignored: images are 2D
    }

    /** `mtllib a.mtl [b.mtl ...]`: each library next to the OBJ is read for its materials. A name with spaces
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

    /** Reads one library's materials (readMtl()); false (and, when `warnIfMissing`, a warning) when it cannot be
     *  read. */
    bool readMaterialLibrary(std::string_view name, bool warnIfMissing) {
        const std::filesystem::path resolved =
            fileBeside(std::filesystem::path(mPath).parent_path(), std::string(name));
        const std::string shown = "mtllib '" + excerptForMessage(name) + "' (line " + std::to_string(mLine) + ")";
        std::error_code error;
        // A FIFO or device would block or never end: only regular files are opened.
        if (!std::filesystem::is_regular_file(resolved, error)) {
            if (warnIfMissing) {
                const std::string why =
                    whyFileIsMissing(resolved.string()).value_or("is missing or not a regular file");
                mWarnings.push_back(makeWarning(WarningKind::MaterialLibraryMissing,
                                                shown + ": '" + excerptForMessage(resolved.string()) + "' " + why +
                                                    "; its materials are drawn in the default grey",
                                                resolved.string()));
                mMissingLibrary = true;
            }
            return false;
        }
        const std::uintmax_t size = std::filesystem::file_size(resolved, error);
        std::ifstream file(resolved, std::ios::binary);
        if (error || !file) {
            if (warnIfMissing) {
                mWarnings.push_back(makeWarning(WarningKind::MaterialLibraryMissing,
                                                shown + ": cannot read '" + excerptForMessage(resolved.string()) + "'",
                                                resolved.string()));
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
        readMtl(resolved.string(), text, mMaterials, mWarnings, std::filesystem::path(mPath).parent_path());
        // Its textures too, found or not: inputs the app must never overwrite with an output.
        for (const std::string& texture : mMaterials.namedFiles) {
            if (std::find(mInputFiles.begin(), mInputFiles.end(), texture) == mInputFiles.end()) {
                mInputFiles.push_back(texture);
            }
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
            if (mMaterials.byName.count(name) == 0) {
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
        mWarnings.push_back(
            makeWarning(WarningKind::MaterialUndefined, "usemtl names materials not defined " + where + ": " + list +
                                                            "; their faces are drawn in the default grey"));
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

    double parseNumber(const char*& p, const char* end, const char* what, int needed = 3) {
        while (p < end && isBlank(*p)) {
            ++p;
        }
        if (p == end) {
            fail(std::string(what) + " has fewer than " + std::to_string(needed) + " coordinate" +
                 (needed == 1 ? "" : "s"));
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
    std::uint32_t resolveIndex(long long index, std::size_t definedSoFar, IndexKind kind) {
        const char* what = singular(kind);
        if (index == 0) {
            fail(std::string(what) + " index 0 is invalid (OBJ indices start at 1)");
        }
        if (index > 0) {
            if (index > std::numeric_limits<std::uint32_t>::max() - 1) {
                fail(std::string(what) + " index " + std::to_string(index) + " out of range");
            }
            if (std::size_t(index) > definedSoFar) {
                mForwardReferences.push_back({mLine, index, kind});
            }
            return std::uint32_t(index - 1);
        }
        if (index < -std::int64_t(std::numeric_limits<std::uint32_t>::max()) || std::size_t(-index) > definedSoFar) {
            fail("relative " + std::string(what) + " index " + std::to_string(index) + " out of range (" +
                 std::to_string(definedSoFar) + " " + plural(kind) + " defined so far)");
        }
        return std::uint32_t(definedSoFar - std::size_t(-index));
    }

    void parseFace(const char* p, const char* end) {
        mCorners.clear();
        bool faceHasNormals = true;
        bool faceHasTexcoords = true;
        while (true) {
            while (p < end && isBlank(*p)) {
                ++p;
            }
            if (p == end) {
                break;
            }
            Corner corner;
            corner.position = resolveIndex(parseIndex(p, end), mPositions.size(), IndexKind::Vertex);
            if (p < end && *p == '/') {
                ++p;
                if (p < end && *p != '/' && !isBlank(*p)) {
                    corner.texcoord = resolveIndex(parseIndex(p, end), mTexcoords.size(), IndexKind::Texcoord);
                }
                if (p < end && *p == '/') {
                    ++p;
                    corner.normal = resolveIndex(parseIndex(p, end), mNormals.size(), IndexKind::Normal);
                }
            }
            if (p < end && !isBlank(*p)) {
                fail("unexpected character '" + std::string(1, *p) + "' in face");
            }
            faceHasNormals = faceHasNormals && corner.normal != kAbsent;
            faceHasTexcoords = faceHasTexcoords && corner.texcoord != kAbsent;
            mCorners.push_back(corner);
        }
        if (mCorners.size() < 3) {
            fail("face has " + std::to_string(mCorners.size()) + " vertices (needs at least 3)");
        }
        if (mCurrentGroup == kAbsent) {
            mCurrentGroup = groupOf(mCurrentMaterial);
        }
        FaceGroup& group = mGroups[mCurrentGroup];
        ++(faceHasNormals ? group.facesWithNormals : group.facesWithoutNormals);
        ++(faceHasTexcoords ? group.facesWithTexcoords : group.facesWithoutTexcoords);
        const std::size_t firstCorner = group.corners.size();
        const bool positionsKnown = std::all_of(mCorners.begin(), mCorners.end(), [&](const Corner& corner) {
            return corner.position < mPositions.size();
        });
        if (mCorners.size() > 3 && positionsKnown) {
            triangulatePolygon(mCorners);
        } else {
            // A triangle; or a polygon naming a vertex defined further down, cut once every position is known.
            mPolygonTriangles.clear();
            for (std::uint32_t i = 1; i + 1 < mCorners.size(); ++i) {
                mPolygonTriangles.emplace_back(0u, i, i + 1);
            }
            if (mCorners.size() > 3) {
                mPolygonsNamingLaterVertices.push_back({mCurrentGroup, firstCorner, mCorners});
            }
        }
        for (const glm::uvec3& triangle : mPolygonTriangles) {
            for (int k = 0; k < 3; ++k) {
                group.corners.push_back(mCorners[triangle[k]]);
            }
        }
        mCornerCount += 3 * mPolygonTriangles.size();
    }

    /** mPolygonTriangles: the triangles of the polygon `corners` (scene/mesh/PolygonTriangulation.h), cut from the
     *  corner of the lowest vertex index on (lowestCornerFirst(): a polygon written again in reverse, the back of a
     *  double-faced card, is then fanned along the same diagonals, into twins finalizeMesh() drops for a two-sided
     *  material; from each one's first corner, their diagonals crossed and the card was shaded in black wedges). */
    void triangulatePolygon(std::span<const Corner> corners) {
        const std::size_t first = lowestCornerFirst(corners, [](const Corner& corner) { return corner.position; });
        mPolygonPositions.clear();
        for (std::size_t i = 0; i < corners.size(); ++i) {
            mPolygonPositions.push_back(mPositions[corners[(first + i) % corners.size()].position]);
        }
        mTriangulator.triangulate(mPolygonPositions, mPolygonTriangles);
        rotateTriangles(mPolygonTriangles, first, corners.size());
    }

    /** The polygons that named a vertex defined after them were fanned as they were read; cut them now. */
    void triangulatePolygonsNamingLaterVertices() {
        for (const PolygonNamingLaterVertices& polygon : mPolygonsNamingLaterVertices) {
            triangulatePolygon(polygon.corners);
            std::vector<Corner>& corners = mGroups[polygon.group].corners;
            for (std::size_t t = 0; t < mPolygonTriangles.size(); ++t) {
                for (int k = 0; k < 3; ++k) {
                    corners[polygon.firstCorner + 3 * t + std::size_t(k)] = polygon.corners[mPolygonTriangles[t][k]];
                }
            }
        }
        mPolygonsNamingLaterVertices = {};
    }

    /** The face group of a material name, made on first use. */
    std::uint32_t groupOf(const std::string& materialName) {
        const auto [it, inserted] =
            mGroupOfMaterial.try_emplace({mCurrentObject, materialName}, std::uint32_t(mGroups.size()));
        if (inserted) {
            FaceGroup& group = mGroups.emplace_back();
            group.object = mCurrentObject;
            group.materialName = materialName;
        }
        return it->second;
    }

    void checkForwardReferences() {
        for (const ForwardReference& reference : mForwardReferences) {
            const std::size_t available = reference.kind == IndexKind::Normal     ? mNormals.size()
                                          : reference.kind == IndexKind::Texcoord ? mTexcoords.size()
                                                                                  : mPositions.size();
            if (std::size_t(reference.index) > available) {
                throwLoadErrorAtLine(mPath, reference.line,
                                     std::string(singular(reference.kind)) + " index " +
                                         std::to_string(reference.index) + " out of range (file has " +
                                         std::to_string(available) + " " + plural(reference.kind) + ")");
            }
        }
    }

    RawScene buildScene() {
        RawScene scene;
        scene.format = "obj";
        std::vector<glm::vec3> positions;
        scene.origin = storeNearModel(mPath, mPositions, positions);
        mPositions = {}; // its memory back before the meshes are built
        scene.inputFiles = std::move(mInputFiles);
        scene.warnings = std::move(mWarnings);
        scene.images = std::move(mMaterials.images);
        scene.missingImages = std::move(mMaterials.missingImages);
        const std::string baseName = mMeshName.empty() ? std::filesystem::path(mPath).stem().string() : mMeshName;

        std::size_t groupsWithFaces = 0;
        std::vector<std::size_t> groupsOfObject(mObjectNames.size()); // with faces
        for (const FaceGroup& group : mGroups) {
            groupsWithFaces += group.corners.empty() ? 0 : 1;
            groupsOfObject[group.object] += group.corners.empty() ? 0 : 1;
        }
        const bool severalObjects =
            std::count_if(groupsOfObject.begin(), groupsOfObject.end(), [](std::size_t n) { return n > 0; }) > 1;
        std::size_t facesWithoutNormals = 0;
        std::size_t facesWithoutTexcoords = 0;
        for (FaceGroup& group : mGroups) {
            if (group.corners.empty()) {
                continue;
            }
            RawMesh mesh;
            if (!severalObjects) {
                mesh.name =
                    groupsWithFaces == 1 || group.materialName.empty() ? baseName : baseName + "/" + group.materialName;
                if (!mMeshName.empty()) mesh.nodePath = {mMeshName}; // the first `o` name: what --frame selects
            } else {
                // Each object its own node (--frame selects it by name), told apart by its index where names repeat.
                const std::string& objectName = mObjectNames[group.object];
                const std::string name = objectName.empty() ? std::filesystem::path(mPath).stem().string() : objectName;
                mesh.name = groupsOfObject[group.object] == 1 || group.materialName.empty()
                                ? name
                                : name + "/" + group.materialName;
                if (!objectName.empty()) mesh.nodePath = {objectName};
                mesh.nodeInstance = group.object;
            }
            const auto material = mMaterials.byName.find(group.materialName);
            if (material != mMaterials.byName.end()) {
                mesh.material = material->second;
            } else {
                mesh.material.name = group.materialName; // undefined (warned): the default grey, its name kept
                if (mHasColors) {
                    // The base colour multiplies the vertex colours (glTF's rule); without a material that says
                    // otherwise, white shows them as the file wrote them rather than 80 % darker.
                    mesh.material.baseColorFactor = glm::vec4(1.0f);
                }
            }
            // File normals only when every face of the mesh has them; otherwise all are computed (a warning).
            const bool useNormals = group.facesWithNormals > 0 && group.facesWithoutNormals == 0;
            if (group.facesWithNormals > 0 && group.facesWithoutNormals > 0) {
                facesWithoutNormals += group.facesWithoutNormals;
            }
            const bool useTexcoords = group.facesWithTexcoords > 0;
            if (useTexcoords) {
                facesWithoutTexcoords += group.facesWithoutTexcoords;
            }
            if (groupsWithFaces == 1 && !useNormals && !useTexcoords) {
                // Positions (and colours) alone: the file's vertices as they are, in their order; finalizeMesh()
                // drops the ones no face uses.
                mesh.positions = std::move(positions);
                mesh.colors = std::move(mColors);
                mesh.triangles.resize(group.corners.size() / 3);
                for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
                    mesh.triangles[t] = glm::uvec3(group.corners[3 * t].position, group.corners[3 * t + 1].position,
                                                   group.corners[3 * t + 2].position);
                }
            } else {
                buildVertices(group, positions, useNormals, useTexcoords, mesh);
            }
            group.corners = {};
            scene.meshes.push_back(std::move(mesh));
        }
        if (mColoursOutOfRange > 0) {
            scene.warnings.push_back(makeWarning(
                WarningKind::ValueOutOfRange,
                std::to_string(mColoursOutOfRange) + (mColoursOutOfRange == 1 ? " 'v' line gives" : " 'v' lines give") +
                    " a colour outside [0, 1] (as far out as " + formatNumber(mColourFarthestOut) +
                    (mColourFarthestOut > 1.0 ? "; colours of 0 to 255?" : "") + "); clamped into [0, 1]"));
        }
        if (mUnreadVertexExtras > 0) {
            scene.warnings.push_back(makeWarning(
                WarningKind::VertexValuesIgnored,
                std::to_string(mUnreadVertexExtras) +
                    " 'v' lines have values after x y z that are neither w nor a colour r g b [a] of finite numbers; "
                    "ignored (those vertices are white where others are coloured)"));
        }
        if (facesWithoutNormals > 0) {
            scene.warnings.push_back(
                makeWarning(WarningKind::NormalsMissing, std::to_string(facesWithoutNormals) +
                                                             " faces have no normals; all normals recomputed" +
                                                             (groupsWithFaces > 1 ? " in their meshes" : "")));
        }
        if (facesWithoutTexcoords > 0) {
            scene.warnings.push_back(makeWarning(WarningKind::TexcoordsMissing,
                                                 std::to_string(facesWithoutTexcoords) +
                                                     " faces have no texture coordinates (vt) in a mesh whose other "
                                                     "faces have them; their corners take (0, 0)"));
        }
        if (mNonFiniteTexcoords > 0) {
            scene.warnings.push_back(makeWarning(WarningKind::TexcoordsNonFinite,
                                                 std::to_string(mNonFiniteTexcoords) +
                                                     " texture coordinates (vt) are not finite in float; they read as "
                                                     "(0, 0)"));
        }
        if (mTriangulator.unresolvedPolygons() > 0) {
            scene.warnings.push_back(polygonsFannedWarning(mTriangulator));
        }
        if (mSkippedNonFaces > 0) {
            scene.warnings.push_back(
                makeWarning(WarningKind::ElementsSkipped,
                            std::to_string(mSkippedNonFaces) + " line/point elements (l, p) skipped"));
        }
        return scene;
    }

    /** One vertex per distinct (position, texture coordinate, normal) a face corner names: a hard edge or a texture
     *  seam references one position with several normals or coordinates and stays split; finalizeMesh() welds the
     *  rest. */
    void buildVertices(const FaceGroup& group, const std::vector<glm::vec3>& positions, bool useNormals,
                       bool useTexcoords, RawMesh& mesh) const {
        std::unordered_map<Corner, std::uint32_t, CornerHash> vertexOfCorner;
        mesh.triangles.resize(group.corners.size() / 3);
        for (std::size_t c = 0; c < group.corners.size(); ++c) {
            Corner corner = group.corners[c];
            corner.normal = useNormals ? corner.normal : kAbsent;
            corner.texcoord = useTexcoords ? corner.texcoord : kAbsent;
            const auto [it, inserted] = vertexOfCorner.try_emplace(corner, std::uint32_t(mesh.positions.size()));
            if (inserted) {
                mesh.positions.push_back(positions[corner.position]);
                if (useNormals) {
                    mesh.normals.push_back(mNormals[corner.normal]);
                }
                if (useTexcoords) {
                    mesh.texcoords[0].push_back(corner.texcoord == kAbsent ? glm::vec2(0.0f)
                                                                           : mTexcoords[corner.texcoord]);
                }
                if (!mColors.empty()) {
                    mesh.colors.push_back(mColors[corner.position]);
                }
            }
            mesh.triangles[c / 3][int(c % 3)] = it->second;
        }
    }

    const std::string& mPath;
    std::string_view mText;
    MeshBudget& mBudget;
    std::size_t mLine = 0;
    std::size_t mNextBudgetCheck = kLinesBetweenBudgetChecks; ///< the line at or after which the budget is checked
    std::string mMeshName;
    std::vector<std::string> mInputFiles; ///< the mtllib files read
    std::vector<Warning> mWarnings;
    std::map<std::string, std::size_t> mUsedMaterials; ///< usemtl name -> first line using it
    ObjMaterials mMaterials;                           ///< of every library read
    bool mMissingLibrary = false;
    std::vector<glm::dvec3> mPositions; ///< as read; rounded to float once the model's extent is known
    std::vector<glm::vec4> mColors;     ///< one per position once a `v` line had a colour, else empty
    bool mHasColors = false;
    std::size_t mUnreadVertexExtras = 0; ///< `v` lines whose values after x y z are neither w nor r g b [a]
    std::size_t mColoursOutOfRange = 0;  ///< `v` lines whose colour has a value outside [0, 1], clamped
    double mColourFarthestOut = 0.0;     ///< of those values, the first one farthest outside [0, 1]
    double mColourDistanceOut = 0.0;     ///< how far outside [0, 1] that one is
    std::vector<glm::vec2> mTexcoords;   ///< (u, 1 - v)
    std::vector<glm::vec3> mNormals;
    std::vector<FaceGroup> mGroups; ///< in the order of their first face or usemtl
    /** (object, usemtl name) -> index in mGroups */
    std::map<std::pair<std::uint32_t, std::string>, std::uint32_t> mGroupOfMaterial;
    std::uint32_t mCurrentGroup = kAbsent; ///< kAbsent: none yet for this object and material, made on use
    /** The `o` names in file order; the faces before any `o` belong to the first, unnamed. */
    std::vector<std::string> mObjectNames{std::string()};
    std::uint32_t mCurrentObject = 0;
    std::string mCurrentMaterial; ///< the last `usemtl` name, "" before any
    std::size_t mCornerCount = 0; ///< in all groups
    std::vector<Corner> mCorners; ///< scratch for the current face
    PolygonTriangulator mTriangulator;
    std::vector<glm::dvec3> mPolygonPositions; ///< scratch: the current polygon's corners
    std::vector<glm::uvec3> mPolygonTriangles; ///< scratch: its triangles, as indices into its corners
    std::vector<PolygonNamingLaterVertices> mPolygonsNamingLaterVertices;
    std::vector<ForwardReference> mForwardReferences;
    std::size_t mSkippedNonFaces = 0;
    std::size_t mNonFiniteTexcoords = 0;
};

/** The material libraries an OBJ's `mtllib` lines name, resolved beside it (a name with spaces both whole and split,
 *  as the parser tries it), and the textures those that exist name (mtlReferencedFiles()). */
std::vector<std::string> objReferencedFiles(const std::string& path, std::string_view content) {
    const std::filesystem::path folder = std::filesystem::path(path).parent_path();
    const auto beside = [&](std::string_view name) { return fileBeside(folder, std::string(name)); };
    std::vector<std::string> files;
    content = withoutByteOrderMark(content); // as readObj(): a mark must not hide a first-line mtllib
    // From one occurrence of "mtllib" to the next, not line by line: a batch rerun into existing outputs reads every
    // model for this (Batch.cpp), and a 70,000-triangle OBJ has 100,000 lines and one mtllib at most.
    for (std::size_t hit = content.find("mtllib"); hit != std::string_view::npos;) {
        const std::size_t newlineBefore = hit == 0 ? std::string_view::npos : content.rfind('\n', hit - 1);
        const std::size_t start = newlineBefore == std::string_view::npos ? 0 : newlineBefore + 1;
        std::size_t end = content.find('\n', hit);
        if (end == std::string_view::npos) end = content.size();
        std::string_view line = content.substr(start, end - start);
        hit = content.find("mtllib", end); // each line once, however often it says mtllib
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
    // The textures of the libraries that exist, read as readObj() reads them (regular files, their reported size).
    const std::size_t libraries = files.size();
    for (std::size_t i = 0; i < libraries; ++i) {
        std::error_code error;
        if (!std::filesystem::is_regular_file(files[i], error)) continue;
        const std::uintmax_t size = std::filesystem::file_size(files[i], error);
        std::ifstream file(files[i], std::ios::binary);
        if (error || !file) continue;
        std::string text(std::size_t(size), '\0');
        file.read(text.data(), std::streamsize(size));
        text.resize(std::size_t(file.gcount()));
        for (std::string& texture : mtlReferencedFiles(files[i], text, folder)) {
            if (std::ranges::find(files, texture) == files.end()) files.push_back(std::move(texture));
        }
    }
    return files;
}

} // namespace

FormatReader objFormat() {
    return {"OBJ",
            {".obj"},
            [](const std::string& path, std::string_view content, MeshBudget& budget, const LoadOptions&) {
                return ObjParser(path, content, budget).parse();
            },
            [](const std::string& path) { return objReferencedFiles(path, wholeFileBestEffort(path)); }};
}

} // namespace inkgraph::detail
