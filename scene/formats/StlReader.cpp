/** @file STL, binary and ASCII. Facet normals are ignored (often wrong or zero in the wild); loadScene() computes
 *  smooth normals after welding the three separate corners each facet carries. */

#include "scene/formats/FormatTable.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>

namespace inkgraph::detail {

namespace {

constexpr std::size_t kBinaryHeaderBytes = 80;
constexpr std::size_t kBinaryPreambleBytes = kBinaryHeaderBytes + 4; // header + uint32 triangle count
constexpr std::size_t kBinaryTriangleBytes = 50;                     // normal, 3 corners, uint16 attribute
constexpr std::size_t kVerticesBetweenBudgetChecks = 1 << 16;        // ASCII vertices between memory checks

template <typename T>
T readLittleEndian(const char* bytes) {
    static_assert(sizeof(T) == 4);
    std::uint32_t raw = 0;
    std::memcpy(&raw, bytes, sizeof raw);
    if constexpr (std::endian::native == std::endian::big) {
        raw = ((raw & 0xFFu) << 24) | ((raw & 0xFF00u) << 8) | ((raw >> 8) & 0xFF00u) | (raw >> 24);
    }
    return std::bit_cast<T>(raw);
}

std::string meshNameFor(const std::string& path) { return std::filesystem::path(path).stem().string(); }

RawScene readBinary(const std::string& path, std::string_view content, std::uint32_t triangleCount,
                    MeshBudget& budget) {
    budget.charge(std::size_t(triangleCount) * 3, triangleCount);
    RawScene scene;
    scene.format = "stl-binary";
    RawMesh mesh;
    mesh.name = meshNameFor(path);
    // The caller checked the file holds every declared triangle, so this reservation is bounded by the file size.
    mesh.positions.reserve(std::size_t(triangleCount) * 3);
    mesh.triangles.reserve(triangleCount);
    const char* record = content.data() + kBinaryPreambleBytes;
    for (std::uint32_t triangle = 0; triangle < triangleCount; ++triangle, record += kBinaryTriangleBytes) {
        const char* corners = record + 12; // skip the facet normal
        for (int corner = 0; corner < 3; ++corner) {
            glm::vec3 position;
            for (int axis = 0; axis < 3; ++axis) {
                position[axis] = readLittleEndian<float>(corners + 12 * corner + 4 * axis);
            }
            if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z)) {
                throwLoadError(path, "triangle " + std::to_string(triangle) + ": non-finite vertex coordinate");
            }
            mesh.positions.push_back(position);
        }
        const auto first = std::uint32_t(3 * triangle);
        mesh.triangles.emplace_back(first, first + 1, first + 2);
    }
    scene.meshes.push_back(std::move(mesh));
    return scene;
}

/** Where the ASCII parser gave up; kept separate so the caller can still report a binary interpretation. */
struct AsciiFailure {
    std::size_t line = 0;
    std::string problem;
    bool binaryData = false; ///< the content holds bytes text never does (NUL), so it is no text at all
};

/** Whitespace tokenizer that tracks line numbers. */
class Tokenizer {
public:
    explicit Tokenizer(std::string_view text) : mText(text) {}

    /** The next token, or an empty view at the end. */
    std::string_view next() {
        skipWhitespace();
        const std::size_t start = mPosition;
        while (mPosition < mText.size() && !std::isspace(static_cast<unsigned char>(mText[mPosition]))) {
            ++mPosition;
        }
        return mText.substr(start, mPosition - start);
    }

    void skipRestOfLine() {
        while (mPosition < mText.size() && mText[mPosition] != '\n') {
            ++mPosition;
        }
    }

    std::size_t line() const { return mLine; }

private:
    void skipWhitespace() {
        while (mPosition < mText.size() && std::isspace(static_cast<unsigned char>(mText[mPosition]))) {
            if (mText[mPosition] == '\n') {
                ++mLine;
            }
            ++mPosition;
        }
    }

    std::string_view mText;
    std::size_t mPosition = 0;
    std::size_t mLine = 1;
};

bool equalsIgnoringCase(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) {
        return false;
    }
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) {
            return false;
        }
    }
    return true;
}

/** Whether `token` is a whole number as an ASCII STL writes one (a leading '+' allowed), read into `value`. */
bool isNumber(std::string_view token, double& value) {
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
    return error == std::errc() && end == token.data() + token.size();
}

/** Whether `token` is how the Microsoft C runtime printed a NaN or an infinity: "1.#IND00", "-1.#QNAN0",
 * "1.#INF00e+000", "1.#SNAN0". */
bool isWindowsNonNumber(std::string_view token) {
    const std::size_t hash = token.find('#');
    if (hash == std::string_view::npos || hash == 0) return false;
    std::string_view word = token.substr(hash + 1);
    for (const std::string_view name : {"IND", "QNAN", "SNAN", "INF"})
        if (word.size() >= name.size() && equalsIgnoringCase(word.substr(0, name.size()), name)) {
            return std::isdigit(static_cast<unsigned char>(token[hash - 1])) != 0 || token[hash - 1] == '.';
        }
    return false;
}

/** Parses `solid ... facet normal n n n / outer loop / vertex x y z (3+) / endloop / endfacet ... endsolid`, several
 *  solids allowed. Loops with more than three vertices are fan-triangulated. `withoutSolid`: the text starts at its
 *  first `facet` (some exporters drop the `solid` line). Positions are read in double into `positions` (one per loop
 *  corner); `mesh` gets the triangles. */
std::optional<AsciiFailure> parseAscii(std::string_view content, bool withoutSolid, RawMesh& mesh,
                                       std::vector<glm::dvec3>& positions, std::vector<Warning>& warnings,
                                       const MeshBudget& budget) {
    // Text never holds NUL bytes while binary STL nearly always does (zero floats, zero attribute words): this
    // catches a binary file whose header starts with "solid" before its bytes are misread as tokens.
    if (const std::size_t nul = content.find('\0'); nul != std::string_view::npos) {
        const auto line = std::size_t(std::count(content.begin(), content.begin() + std::ptrdiff_t(nul), '\n')) + 1;
        return AsciiFailure{line, "binary data (NUL byte) in text", true};
    }
    Tokenizer tokens(content);
    enum class State { OutsideSolid, InSolid, InFacet, InLoop, AfterLoop };
    State state = withoutSolid ? State::InSolid : State::OutsideSolid;
    std::size_t loopStart = 0; // index in positions of the current loop's first vertex

    auto failure = [&](std::string problem) { return AsciiFailure{tokens.line(), std::move(problem)}; };
    auto readNumber = [&](double& value) -> bool { return isNumber(tokens.next(), value); };

    for (std::string_view token = tokens.next(); !token.empty(); token = tokens.next()) {
        if (equalsIgnoringCase(token, "solid") && state == State::OutsideSolid) {
            tokens.skipRestOfLine(); // the solid's name
            state = State::InSolid;
        } else if (equalsIgnoringCase(token, "endsolid") && state == State::InSolid) {
            tokens.skipRestOfLine();
            state = State::OutsideSolid;
        } else if (equalsIgnoringCase(token, "facet") && state == State::InSolid) {
            if (!equalsIgnoringCase(tokens.next(), "normal")) {
                return failure("expected 'normal' after 'facet'");
            }
            // The normal is not used (the winding is); old Windows exporters write a degenerate facet's as the C
            // runtime spells a NaN or infinity: -1.#IND00e+000, 1.#QNAN0, 1.#INF00.
            for (int axis = 0; axis < 3; ++axis) {
                const std::string_view component = tokens.next();
                double ignored = 0.0;
                if (!isNumber(component, ignored) && !isWindowsNonNumber(component)) {
                    return failure("cannot read facet normal");
                }
            }
            state = State::InFacet;
        } else if (equalsIgnoringCase(token, "outer") && state == State::InFacet) {
            if (!equalsIgnoringCase(tokens.next(), "loop")) {
                return failure("expected 'loop' after 'outer'");
            }
            loopStart = positions.size();
            state = State::InLoop;
        } else if (equalsIgnoringCase(token, "vertex") && state == State::InLoop) {
            glm::dvec3 position;
            for (int axis = 0; axis < 3; ++axis) {
                if (!readNumber(position[axis])) {
                    return failure("cannot read vertex coordinate");
                }
            }
            if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z)) {
                return failure("non-finite vertex coordinate");
            }
            // As before positions were read in double: a coordinate beyond float's range is no renderable model's.
            if (std::max({std::abs(position.x), std::abs(position.y), std::abs(position.z)}) >
                std::numeric_limits<float>::max()) {
                return failure("cannot read vertex coordinate (beyond float's range)");
            }
            positions.push_back(position);
            if (positions.size() % kVerticesBetweenBudgetChecks == 0)
                budget.check(positions.size(), mesh.triangles.size());
        } else if (equalsIgnoringCase(token, "endloop") && state == State::InLoop) {
            const std::size_t loopSize = positions.size() - loopStart;
            if (loopSize < 3) {
                return failure("facet loop has " + std::to_string(loopSize) + " vertices (needs 3)");
            }
            for (std::size_t i = 1; i + 1 < loopSize; ++i) {
                mesh.triangles.emplace_back(loopStart, loopStart + i, loopStart + i + 1);
            }
            state = State::AfterLoop;
        } else if (equalsIgnoringCase(token, "endfacet") && state == State::AfterLoop) {
            state = State::InSolid;
        } else {
            return failure("unexpected '" + excerptForMessage(token) + "'");
        }
    }
    if (state == State::InSolid) {
        if (!withoutSolid) {
            warnings.push_back(
                makeWarning(WarningKind::StlSolidIncomplete, "ASCII STL ends without 'endsolid' (truncated?)"));
        }
    } else if (state != State::OutsideSolid) {
        return failure("unexpected end of file inside a facet");
    }
    return std::nullopt;
}

/** Whether the text starts, after whitespace, with `keyword` in any case; `wholeWord`: followed by whitespace or the
 *  end. "solid" is a prefix test as it always was ("solidname" lines exist); "facet" must be the whole word. */
bool startsWithKeyword(std::string_view text, std::string_view keyword, bool wholeWord) {
    std::size_t start = 0;
    while (start < text.size() && std::isspace(static_cast<unsigned char>(text[start]))) {
        ++start;
    }
    const std::size_t end = start + keyword.size();
    if (text.size() < end || !equalsIgnoringCase(text.substr(start, keyword.size()), keyword)) {
        return false;
    }
    return !wholeWord || end == text.size() || std::isspace(static_cast<unsigned char>(text[end]));
}

/** Whether the bytes a binary STL's preamble would occupy are all printable ASCII (or whitespace): a binary header is
 *  free-form text, but its triangle count is not (any count below 2^24 has a zero byte; a huge one like 0xFFFFFFFF
 *  has bytes above 0x7F), so printable ASCII there means the file was written as text. */
bool preambleLooksLikeText(std::string_view content) {
    const std::string_view preamble = content.substr(0, kBinaryPreambleBytes);
    return std::ranges::all_of(preamble, [](char c) {
        const auto byte = static_cast<unsigned char>(c);
        return byte < 0x80 && (std::isprint(byte) || std::isspace(byte));
    });
}

RawScene readStl(const std::string& path, std::string_view content, MeshBudget& budget) {
    const bool hasBinaryPreamble = content.size() >= kBinaryPreambleBytes;
    const std::uint32_t declaredTriangles =
        hasBinaryPreamble ? readLittleEndian<std::uint32_t>(content.data() + kBinaryHeaderBytes) : 0;
    const std::uint64_t binarySize = kBinaryPreambleBytes + std::uint64_t(declaredTriangles) * kBinaryTriangleBytes;
    // Every declared triangle is present; extra bytes after them are tolerated (some exporters pad).
    const bool binaryFits = hasBinaryPreamble && binarySize <= content.size();
    const std::string binaryClaim = "its binary header declares " + std::to_string(declaredTriangles) + " triangles (" +
                                    std::to_string(binarySize) + " bytes) but the file has " +
                                    std::to_string(content.size()) + " bytes";
    const auto readBinaryWithTrailingBytes = [&](const std::string& what) {
        RawScene scene = readBinary(path, content, declaredTriangles, budget);
        scene.warnings.push_back(
            makeWarning(WarningKind::TrailingDataIgnored, what + ": " + std::to_string(content.size() - binarySize) +
                                                              " bytes after the last triangle ignored"));
        return scene;
    };

    // The size test comes first: binary exporters often start the free-form header with "solid" too.
    if (hasBinaryPreamble && binarySize == content.size()) {
        return readBinary(path, content, declaredTriangles, budget);
    }
    // A byte-order mark (Windows editors) before "solid" would otherwise make the text unrecognisable.
    const std::string_view text = withoutByteOrderMark(content);
    const auto parseAsText = [&](bool withoutSolid, RawScene& scene) {
        scene.format = "stl-ascii";
        RawMesh mesh;
        mesh.name = meshNameFor(path);
        std::vector<glm::dvec3> positions;
        std::optional<AsciiFailure> failure = parseAscii(text, withoutSolid, mesh, positions, scene.warnings, budget);
        if (!failure) {
            scene.origin = storeNearModel(path, positions, mesh.positions);
            scene.meshes.push_back(std::move(mesh));
        }
        return failure;
    };
    if (startsWithKeyword(text, "facet", true)) {
        RawScene scene;
        scene.warnings.push_back(makeWarning(WarningKind::StlSolidIncomplete, "ASCII STL without a 'solid' line"));
        if (const std::optional<AsciiFailure> failure = parseAsText(true, scene)) {
            throwLoadErrorAtLine(path, failure->line,
                                 "invalid ASCII STL (it has no 'solid' line): " + failure->problem);
        }
        return scene;
    }
    if (startsWithKeyword(text, "solid", false)) {
        RawScene scene;
        const std::optional<AsciiFailure> failure = parseAsText(false, scene);
        if (!failure) {
            return scene;
        }
        // Real text that fails past its 'solid' line is broken ASCII: its bytes 80-83 read as a triangle count mean
        // nothing (text bytes make that count over 150 million). Binary data (NUL bytes), or a failure on the first
        // line, is taken for a binary file whose header happens to start with "solid".
        const bool looksLikeText = !failure->binaryData && failure->line > 1;
        if (!hasBinaryPreamble || looksLikeText) {
            throwLoadErrorAtLine(path, failure->line, "invalid ASCII STL: " + failure->problem);
        }
        // Complete as binary: the same reading as a binary file whose header does not start with "solid".
        if (binaryFits) {
            return readBinaryWithTrailingBytes("binary STL (its header starts with 'solid' but it is not ASCII STL)");
        }
        throwLoadError(path, "neither ASCII STL (line " + std::to_string(failure->line) + ": " + failure->problem +
                                 ") nor binary STL (" + binaryClaim + ")");
    }
    if (!hasBinaryPreamble) {
        throwLoadError(path, "not an STL file: " + std::to_string(content.size()) +
                                 " bytes are too few for a binary STL (84-byte preamble) and there is no 'solid' line");
    }
    if (!binaryFits && preambleLooksLikeText(content)) {
        // Read as binary, text makes a count in the hundreds of millions; saying "truncated" would mislead.
        throwLoadError(path, "not an STL file: it looks like text, but ASCII STL starts with 'solid' (or 'facet') and "
                             "this starts with '" +
                                 excerptForMessage(text.substr(0, text.find_first_of("\r\n"))) + "'");
    }
    if (!binaryFits) {
        throwLoadError(path, "truncated binary STL: " + binaryClaim);
    }
    return readBinaryWithTrailingBytes("binary STL");
}

} // namespace

FormatReader stlFormat() {
    return {
        "STL", {".stl"}, [](const std::string& path, std::string_view content, MeshBudget& budget, const LoadOptions&) {
            return readStl(path, content, budget);
        }};
}

} // namespace inkgraph::detail
