/** @file PLY, the polygon file format of the Stanford 3D Scanning Repository (Turk, "The PLY Polygon File Format",
 *  1994): `format ascii 1.0`, `binary_little_endian 1.0` and `binary_big_endian 1.0`. The header declares elements
 *  and their counts, each with scalar properties (char/int8, uchar/uint8, short/int16, ushort/uint16, int/int32,
 *  uint/uint32, float/float32, double/float64) and list properties (a count, then that many items). Read: `vertex`
 *  x y z (any numeric type, in double until the model is known, storeNearModel()), optional nx ny nz and red green
 *  blue [alpha] (integers scaled by their type's maximum, uchar 255 -> 1, floats as written; as written means linear,
 *  as OBJ's vertex colours are taken); `face` with a list `vertex_indices` (or `vertex_index`), each polygon cut into
 *  n - 2 triangles inside its outline (scene/mesh/PolygonTriangulation.h). Every other element and property, lists
 *  included, is skipped. Counts come from the header, so they are charged to the budget and checked against the
 *  file's bytes before anything is reserved. */

#include "scene/formats/FormatTable.h"
#include "scene/formats/TextTokens.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <type_traits>

namespace inkgraph::detail {

namespace {

enum class Encoding { Ascii, BinaryLittleEndian, BinaryBigEndian };

enum class Type : std::uint8_t { Int8, Uint8, Int16, Uint16, Int32, Uint32, Float32, Float64 };

struct TypeName {
    std::string_view name;
    Type type;
};

/** The specification's names and the sized aliases later writers use (VTK, Open3D, MeshLab). */
constexpr std::array<TypeName, 16> kTypeNames{{{"char", Type::Int8},
                                               {"int8", Type::Int8},
                                               {"uchar", Type::Uint8},
                                               {"uint8", Type::Uint8},
                                               {"short", Type::Int16},
                                               {"int16", Type::Int16},
                                               {"ushort", Type::Uint16},
                                               {"uint16", Type::Uint16},
                                               {"int", Type::Int32},
                                               {"int32", Type::Int32},
                                               {"uint", Type::Uint32},
                                               {"uint32", Type::Uint32},
                                               {"float", Type::Float32},
                                               {"float32", Type::Float32},
                                               {"double", Type::Float64},
                                               {"float64", Type::Float64}}};

std::size_t sizeOf(Type type) {
    switch (type) {
    case Type::Int8:
    case Type::Uint8: return 1;
    case Type::Int16:
    case Type::Uint16: return 2;
    case Type::Int32:
    case Type::Uint32:
    case Type::Float32: return 4;
    case Type::Float64: return 8;
    }
    return 1;
}

bool isInteger(Type type) { return type != Type::Float32 && type != Type::Float64; }

/** The largest value of an integer type: what a full-intensity colour component is written as. */
double maximumOf(Type type) {
    switch (type) {
    case Type::Int8: return 127.0;
    case Type::Uint8: return 255.0;
    case Type::Int16: return 32767.0;
    case Type::Uint16: return 65535.0;
    case Type::Int32: return 2147483647.0;
    case Type::Uint32: return 4294967295.0;
    default: return 1.0;
    }
}

/** What the reader takes a property for. */
enum class Role : std::uint8_t { Other, X, Y, Z, NormalX, NormalY, NormalZ, Red, Green, Blue, Alpha, Indices };

struct Property {
    std::string name;
    Type type = Type::Float32; ///< the scalar's, or a list's items'
    bool list = false;
    Type countType = Type::Uint8; ///< a list's count
    Role role = Role::Other;
};

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> properties;

    bool has(Role role) const {
        return std::ranges::any_of(properties, [role](const Property& p) { return p.role == role; });
    }
    /** The fewest bytes (binary) or tokens (ASCII) one instance can take: a list may be empty, except the face list,
     *  which needs three indices to be read at all. */
    std::size_t minimumSize(bool binary) const {
        std::size_t size = 0;
        for (const Property& p : properties) {
            size += binary ? sizeOf(p.list ? p.countType : p.type) : 1;
            if (p.role == Role::Indices) size += 3 * (binary ? sizeOf(p.type) : 1);
        }
        return size;
    }
    bool fixedSize() const {
        return std::ranges::none_of(properties, [](const Property& p) { return p.list; });
    }
};

struct Header {
    Encoding encoding = Encoding::Ascii;
    std::vector<Element> elements;
    std::size_t bodyOffset = 0; ///< the first byte after the `end_header` line
    std::size_t bodyLine = 1;   ///< its line number, for ASCII messages
    const Element* vertices = nullptr;
    const Element* faces = nullptr;
    std::string textureFile; ///< a `comment TextureFile NAME` line's NAME (MeshLab's convention), or ""
};

/** What of a texture the file gives and the reader leaves out (it draws a PLY untextured): texture coordinates in
 *  the vertex element (s t, u v, texture_u texture_v, texture_s texture_t) or a face's texcoord list, and a
 *  `comment TextureFile` image; "" when none. */
std::string ignoredTexture(const Header& header) {
    std::vector<std::string> given;
    const auto named = [](const Element* element, std::initializer_list<std::string_view> names) -> std::string {
        if (element == nullptr) return {};
        for (const Property& property : element->properties)
            if (std::ranges::find(names, std::string_view(property.name)) != names.end()) return property.name;
        return {};
    };
    if (const std::string name = named(header.vertices, {"s", "u", "texture_u", "texture_s"}); !name.empty())
        given.push_back("vertex property '" + name + "'");
    if (const std::string name = named(header.faces, {"texcoord", "texcoords"}); !name.empty())
        given.push_back("face property '" + name + "'");
    if (!header.textureFile.empty())
        given.push_back("the image '" + excerptForMessage(header.textureFile) + "' (comment TextureFile)");
    if (given.empty()) return {};
    std::string list;
    for (std::size_t i = 0; i < given.size(); ++i)
        list += (i == 0 ? "" : i + 1 == given.size() ? " and " : ", ") + given[i];
    return "texture coordinates and images are not read from PLY (" + list +
           "): drawn untextured, in its vertex colours or grey (OBJ with MTL or glTF carry a texture)";
}

std::string typeNames() {
    std::string names;
    for (const TypeName& entry : kTypeNames) names += (names.empty() ? "" : ", ") + std::string(entry.name);
    return names;
}

std::optional<Type> typeNamed(std::string_view name) {
    for (const TypeName& entry : kTypeNames) {
        if (entry.name == name) return entry.type;
    }
    return std::nullopt;
}

std::string_view nameOf(Type type) {
    for (const TypeName& entry : kTypeNames) {
        if (entry.type == type) return entry.name;
    }
    return "?";
}

Role vertexRole(std::string_view name) {
    if (name == "x") return Role::X;
    if (name == "y") return Role::Y;
    if (name == "z") return Role::Z;
    if (name == "nx") return Role::NormalX;
    if (name == "ny") return Role::NormalY;
    if (name == "nz") return Role::NormalZ;
    if (name == "red" || name == "diffuse_red") return Role::Red;
    if (name == "green" || name == "diffuse_green") return Role::Green;
    if (name == "blue" || name == "diffuse_blue") return Role::Blue;
    if (name == "alpha" || name == "diffuse_alpha") return Role::Alpha;
    return Role::Other;
}

/** The header, from the `ply` line to `end_header`; every problem refused with its line. */
Header readHeader(const std::string& path, std::string_view content) {
    const std::size_t firstEnd = content.find('\n');
    std::string_view firstLine = content.substr(0, firstEnd);
    // Blanks after the magic word (a writer's "ply \r\n") leave it the magic word.
    while (!firstLine.empty() && (firstLine.back() == '\r' || firstLine.back() == ' ' || firstLine.back() == '\t'))
        firstLine.remove_suffix(1);
    if (firstLine != "ply") {
        throwLoadError(path,
                       "not a PLY file: it starts with '" + excerptForMessage(firstLine) + "', not the line 'ply'");
    }
    Header header;
    bool hasFormat = false;
    std::size_t line = 1;
    std::size_t position = firstEnd == std::string_view::npos ? content.size() : firstEnd + 1;
    const auto fail = [&](std::string_view problem) { throwLoadErrorAtLine(path, line, problem); };
    while (true) {
        if (position >= content.size()) {
            throwLoadError(path, "the header ends without an 'end_header' line (truncated?)");
        }
        ++line;
        const std::size_t end = std::min(content.find('\n', position), content.size());
        const std::string_view text = content.substr(position, end - position);
        position = end + 1;
        const std::vector<std::string_view> tokens = tokensOf(text);
        if (tokens.size() >= 3 && tokens[0] == "comment" && tokens[1] == "TextureFile")
            header.textureFile = std::string(tokens[2]);
        if (tokens.empty() || tokens[0] == "comment" || tokens[0] == "obj_info") continue;
        const std::string_view keyword = tokens[0];
        if (keyword == "end_header") {
            if (tokens.size() != 1) fail("'end_header' followed by '" + excerptForMessage(tokens[1]) + "'");
            break;
        }
        if (keyword == "format") {
            if (hasFormat) fail("a second 'format' line");
            if (tokens.size() != 3) fail("expected 'format <encoding> 1.0'");
            if (tokens[1] == "ascii") {
                header.encoding = Encoding::Ascii;
            } else if (tokens[1] == "binary_little_endian") {
                header.encoding = Encoding::BinaryLittleEndian;
            } else if (tokens[1] == "binary_big_endian") {
                header.encoding = Encoding::BinaryBigEndian;
            } else {
                fail("unknown format '" + excerptForMessage(tokens[1]) +
                     "' (ascii, binary_little_endian or binary_big_endian)");
            }
            if (tokens[2] != "1.0" && tokens[2] != "1") {
                fail("PLY version '" + excerptForMessage(tokens[2]) + "' (only 1.0 is read)");
            }
            hasFormat = true;
        } else if (keyword == "element") {
            if (tokens.size() != 3) fail("expected 'element <name> <count>'");
            Element element;
            element.name = std::string(tokens[1]);
            const std::string_view count = tokens[2];
            if (count.front() == '-') {
                fail("element '" + excerptForMessage(element.name) + "' has a negative count " +
                     excerptForMessage(count));
            }
            const auto [next, error] = std::from_chars(count.data(), count.data() + count.size(), element.count);
            if (error == std::errc::result_out_of_range) {
                fail("element '" + excerptForMessage(element.name) + "' count " + excerptForMessage(count) +
                     " overflows 64 bits");
            }
            if (error != std::errc() || next != count.data() + count.size()) {
                fail("cannot read element '" + excerptForMessage(element.name) + "' count '" +
                     excerptForMessage(count) + "'");
            }
            for (const Element& other : header.elements) {
                if ((element.name == "vertex" || element.name == "face") && other.name == element.name) {
                    fail("a second '" + element.name + "' element");
                }
            }
            header.elements.push_back(std::move(element));
        } else if (keyword == "property") {
            if (header.elements.empty()) fail("'property' before any 'element'");
            Element& element = header.elements.back();
            Property property;
            const auto typeOf = [&](std::string_view name) {
                const std::optional<Type> type = typeNamed(name);
                if (!type) fail("unknown property type '" + excerptForMessage(name) + "' (" + typeNames() + ")");
                return *type;
            };
            if (tokens.size() >= 2 && tokens[1] == "list") {
                if (tokens.size() != 5) fail("expected 'property list <count type> <item type> <name>'");
                property.list = true;
                property.countType = typeOf(tokens[2]);
                property.type = typeOf(tokens[3]);
                property.name = std::string(tokens[4]);
                if (!isInteger(property.countType)) {
                    fail("list '" + excerptForMessage(property.name) + "' has a count of type '" +
                         std::string(tokens[2]) + "', not an integer type");
                }
            } else {
                if (tokens.size() != 3) fail("expected 'property <type> <name>'");
                property.type = typeOf(tokens[1]);
                property.name = std::string(tokens[2]);
            }
            const bool isIndexList = property.name == "vertex_indices" || property.name == "vertex_index";
            Role role = Role::Other;
            if (element.name == "vertex" && !property.list) {
                role = vertexRole(property.name);
            } else if (element.name == "face" && isIndexList) {
                if (!property.list) fail("face property '" + property.name + "' is not a list");
                if (!isInteger(property.type)) {
                    fail("face list '" + property.name + "' has items of type '" + std::string(nameOf(property.type)) +
                         "', not an integer type");
                }
                role = Role::Indices;
            }
            if (role != Role::Other && !element.has(role)) property.role = role; // a repeated name is skipped
            element.properties.push_back(std::move(property));
        } else {
            fail("unknown header line '" + excerptForMessage(text) + "'");
        }
    }
    if (!hasFormat) throwLoadError(path, "the header has no 'format' line");
    header.bodyOffset = std::min(position, content.size());
    header.bodyLine = line + 1;
    for (const Element& element : header.elements) {
        if (element.name == "vertex") header.vertices = &element;
        if (element.name == "face") header.faces = &element;
    }
    return header;
}

/** Values in the binary encodings, in the file's byte order. Every read is checked against the end. */
class BinarySource {
public:
    BinarySource(std::string_view body, bool bigEndian) : mBody(body), mSwap(bigEndian != kNativeBigEndian) {}

    /** False (nothing read) when fewer than `bytes` bytes remain. */
    bool has(std::uint64_t bytes) const { return bytes <= mBody.size() - mPosition; }
    std::size_t remaining() const { return mBody.size() - mPosition; }
    void skip(std::uint64_t bytes) { mPosition += std::size_t(bytes); } // the caller checked has(bytes)

    /** One value (the caller checked has(sizeOf(type))), as double: exact for every integer type. */
    double value(Type type) {
        switch (type) {
        case Type::Int8: return double(read<std::int8_t>());
        case Type::Uint8: return double(read<std::uint8_t>());
        case Type::Int16: return double(read<std::int16_t>());
        case Type::Uint16: return double(read<std::uint16_t>());
        case Type::Int32: return double(read<std::int32_t>());
        case Type::Uint32: return double(read<std::uint32_t>());
        case Type::Float32: return double(read<float>());
        case Type::Float64: return read<double>();
        }
        return 0.0;
    }

private:
    static constexpr bool kNativeBigEndian = std::endian::native == std::endian::big;

    template <typename T>
    T read() {
        std::array<char, sizeof(T)> bytes;
        std::memcpy(bytes.data(), mBody.data() + mPosition, sizeof(T));
        mPosition += sizeof(T);
        if (mSwap) std::ranges::reverse(bytes);
        return std::bit_cast<T>(bytes);
    }

    std::string_view mBody;
    std::size_t mPosition = 0;
    bool mSwap;
};

/** Values in the ASCII encoding: whitespace-separated tokens, lines counted for messages. */
class AsciiSource {
public:
    AsciiSource(std::string_view body, std::size_t firstLine) : mBody(body), mLine(firstLine) {}

    /** The next token, empty at the end of the text. */
    std::string_view token() {
        while (mPosition < mBody.size() && std::isspace(static_cast<unsigned char>(mBody[mPosition]))) {
            if (mBody[mPosition] == '\n') ++mLine;
            ++mPosition;
        }
        const std::size_t start = mPosition;
        while (mPosition < mBody.size() && !std::isspace(static_cast<unsigned char>(mBody[mPosition]))) ++mPosition;
        return mBody.substr(start, mPosition - start);
    }

    std::size_t line() const { return mLine; }

private:
    std::string_view mBody;
    std::size_t mPosition = 0;
    std::size_t mLine;
};

/** What the vertex and face elements give, before the mesh is built. */
struct Model {
    std::vector<glm::dvec3> positions;
    std::vector<glm::vec3> normals; ///< empty, or one per position
    std::vector<glm::vec4> colors;  ///< empty, or one per position
    std::vector<glm::uvec3> triangles;
    std::size_t nonFiniteColours = 0;
    /** The vertices whose normal is not finite in float, with their line (ASCII; 0 for binary): refused only when a
     *  face uses one (refuseNonFiniteNormalsInUse()), since a vertex no face uses is dropped. */
    std::vector<std::pair<std::uint64_t, std::size_t>> nonFiniteNormals;
    std::size_t coloursOutOfRange = 0; ///< float colour components outside [0, 1], clamped
    double colourFarthestOut = 0.0;    ///< the one farthest outside
    PolygonTriangulator triangulator;
    /** Polygons of more than three corners read before the vertices (a file that puts `face` first): fanned as read,
     *  from their first triangle on, and cut properly once the positions are known. */
    std::vector<std::pair<std::size_t, std::vector<std::uint32_t>>> polygonsBeforeVertices;

    /** `polygonTriangles`: the triangles of the polygon whose vertices are `corners`, as indices into `corners`, cut
     *  from the corner of the lowest vertex on, as OBJ's (lowestCornerFirst(): a double-faced card's two sides are
     *  fanned along the same diagonals). */
    void triangulate(std::span<const std::uint32_t> corners, std::vector<glm::uvec3>& polygonTriangles) {
        const std::size_t first = lowestCornerFirst(corners, [](std::uint32_t vertex) { return vertex; });
        polygonPositions.clear();
        for (std::size_t i = 0; i < corners.size(); ++i) {
            polygonPositions.push_back(positions[corners[(first + i) % corners.size()]]);
        }
        triangulator.triangulate(polygonPositions, polygonTriangles);
        rotateTriangles(polygonTriangles, first, corners.size());
    }

    void triangulatePolygonsBeforeVertices() {
        std::vector<glm::uvec3> polygonTriangles;
        for (const auto& [firstTriangle, corners] : polygonsBeforeVertices) {
            triangulate(corners, polygonTriangles);
            for (std::size_t t = 0; t < polygonTriangles.size(); ++t) {
                const glm::uvec3& local = polygonTriangles[t];
                triangles[firstTriangle + t] = glm::uvec3(corners[local.x], corners[local.y], corners[local.z]);
            }
        }
        polygonsBeforeVertices = {};
    }

private:
    std::vector<glm::dvec3> polygonPositions; ///< scratch
};

/** Refuses the file where a face uses a vertex whose normal is not finite, naming the first such vertex (and its
 *  line); the normals of vertices no face uses are set aside (finalizeMesh() drops those vertices). */
void refuseNonFiniteNormalsInUse(const std::string& path, Model& model) {
    if (model.nonFiniteNormals.empty()) return;
    std::vector<std::uint8_t> used(model.normals.size(), 0);
    for (const glm::uvec3& triangle : model.triangles)
        for (int corner = 0; corner < 3; ++corner) used[triangle[corner]] = 1;
    for (const auto& [vertex, line] : model.nonFiniteNormals) {
        const glm::vec3& normal = model.normals[vertex];
        if (!used[vertex]) {
            model.normals[vertex] = glm::vec3(0.0f, 0.0f, 1.0f);
            continue;
        }
        const std::string problem = "vertex " + std::to_string(vertex) + ", which a face uses: non-finite normal (" +
                                    formatNumber(normal.x) + ", " + formatNumber(normal.y) + ", " +
                                    formatNumber(normal.z) + ")";
        if (line > 0) throwLoadErrorAtLine(path, line, problem);
        throwLoadError(path, problem);
    }
}

/** Triangles beyond the faces' count (polygons of more than three corners) are charged in steps of this many. */
constexpr std::size_t kTriangleChargeStep = std::size_t(1) << 16;

/** Reads the body in either encoding: `Binary` selects BinarySource, else AsciiSource. Every message names the
 *  element instance ("vertex 12", "face 3", "element 'material' 0"), and for ASCII its line. */
template <bool Binary>
class BodyReader {
public:
    using Source = std::conditional_t<Binary, BinarySource, AsciiSource>;

    BodyReader(const std::string& path, Source& source, std::size_t bodyBytes, MeshBudget& budget)
        : mPath(path), mSource(source), mBodyBytes(bodyBytes), mBudget(budget) {}

    /** Refuses, before the caller charges the budget, a count the whole body cannot hold even at its smallest: a
     *  short file that declares a billion vertices is truncated, not too large for --memory-limit. */
    void checkCountsFit(const Header& header) const {
        for (const Element& element : header.elements)
            if (!element.properties.empty() && element.count > 0) checkFits(element);
    }

    void read(const Header& header, Model& model) {
        for (const Element& element : header.elements) {
            if (element.properties.empty() || element.count == 0) continue; // nothing to read, whatever the count
            checkFits(element);
            if (&element == header.vertices) {
                readVertices(element, model);
            } else if (&element == header.faces) {
                readFaces(element, header.vertices ? header.vertices->count : 0, model);
            } else {
                skipElement(element);
            }
        }
    }

private:
    [[noreturn]] void fail(std::string_view problem) const {
        if constexpr (Binary) {
            throwLoadError(mPath, problem);
        } else {
            throwLoadErrorAtLine(mPath, mSource.line(), problem);
        }
    }

    std::string instance(const Element& element, std::uint64_t index) const {
        const std::string name = element.name == "vertex" || element.name == "face"
                                     ? element.name
                                     : "element '" + excerptForMessage(element.name) + "'";
        return name + " " + std::to_string(index);
    }

    [[noreturn]] void truncated(const Element& element, std::uint64_t index) const {
        fail("truncated: the file ends in " + instance(element, index) + " of " + std::to_string(element.count));
    }

    /** Refuses, before anything is reserved, a count the remaining bytes cannot hold even at its smallest. */
    void checkFits(const Element& element) const {
        if (element.count <= mostInstances(element)) return;
        if constexpr (Binary) {
            truncated(element, mostInstances(element));
        } else {
            fail("truncated: element '" + excerptForMessage(element.name) + "' declares " +
                 std::to_string(element.count) + " instances of " + std::to_string(element.minimumSize(false)) +
                 " values or more, more than the " + std::to_string(mBodyBytes) + " bytes after the header hold");
        }
    }

    /** The most instances of `element` the rest of the file can hold: binary, its bytes over the smallest
     * instance's; ASCII, its bytes over two per value (a digit and a separator), the last value's separator aside.
     */
    std::uint64_t mostInstances(const Element& element) const {
        const std::size_t smallest = element.minimumSize(Binary);
        if (smallest == 0) return std::numeric_limits<std::uint64_t>::max();
        if constexpr (Binary) {
            return mSource.remaining() / smallest;
        } else {
            return (mBodyBytes + 1) / (2 * smallest);
        }
    }

    /** Reserves for the element's instances, no more than the rest of the file can hold. */
    std::size_t reservation(const Element& element) const {
        return std::size_t(std::min(element.count, mostInstances(element)));
    }

    double scalar(const Element& element, std::uint64_t index, Type type) {
        if constexpr (Binary) {
            if (!mSource.has(sizeOf(type))) truncated(element, index);
            return mSource.value(type);
        } else {
            std::string_view token = mSource.token();
            if (token.empty()) truncated(element, index);
            if (token.front() == '+') token.remove_prefix(1);
            double value = 0.0;
            const auto [next, error] = std::from_chars(token.data(), token.data() + token.size(), value);
            // Out of range, from_chars leaves the value; strtod says which way: underflow is 0, overflow infinity (a
            // coordinate then refused as non-finite, as "inf" is).
            if (error == std::errc::result_out_of_range) return std::strtod(std::string(token).c_str(), nullptr);
            if (error != std::errc() || next != token.data() + token.size()) {
                fail(instance(element, index) + ": cannot read '" + excerptForMessage(token) + "' as a number");
            }
            return value;
        }
    }

    std::int64_t integer(const Element& element, std::uint64_t index, Type type) {
        if constexpr (Binary) {
            return std::int64_t(scalar(element, index, type)); // every integer type fits, exactly
        } else {
            std::string_view token = mSource.token();
            if (token.empty()) truncated(element, index);
            if (token.front() == '+') token.remove_prefix(1);
            std::int64_t value = 0;
            const auto [next, error] = std::from_chars(token.data(), token.data() + token.size(), value);
            if (error != std::errc() || next != token.data() + token.size()) {
                fail(instance(element, index) + ": cannot read '" + excerptForMessage(token) + "' as an integer");
            }
            return value;
        }
    }

    std::uint64_t listCount(const Element& element, std::uint64_t index, const Property& property) {
        const std::int64_t count = integer(element, index, property.countType);
        if (count < 0) {
            fail(instance(element, index) + ": list '" + excerptForMessage(property.name) + "' has a negative count " +
                 std::to_string(count));
        }
        return std::uint64_t(count);
    }

    void skipList(const Element& element, std::uint64_t index, const Property& property) {
        const std::uint64_t count = listCount(element, index, property);
        if constexpr (Binary) {
            const std::uint64_t size = sizeOf(property.type);
            if (count > mSource.remaining() / size) truncated(element, index);
            mSource.skip(count * size);
        } else {
            for (std::uint64_t item = 0; item < count; ++item) { // each item a token: bounded by the file
                if (mSource.token().empty()) truncated(element, index);
            }
        }
    }

    void skip(const Element& element, std::uint64_t index, const Property& property) {
        if (property.list) {
            skipList(element, index, property);
        } else if constexpr (Binary) {
            if (!mSource.has(sizeOf(property.type))) truncated(element, index);
            mSource.skip(sizeOf(property.type));
        } else {
            if (mSource.token().empty()) truncated(element, index);
        }
    }

    void skipElement(const Element& element) {
        if (Binary && element.fixedSize()) {
            if constexpr (Binary) { // checkFits() saw every instance fit
                mSource.skip(element.count * element.minimumSize(true));
            }
            return;
        }
        for (std::uint64_t index = 0; index < element.count; ++index) {
            for (const Property& property : element.properties) skip(element, index, property);
        }
    }

    void readVertices(const Element& element, Model& model) {
        const bool hasNormals = element.has(Role::NormalX) && element.has(Role::NormalY) && element.has(Role::NormalZ);
        const bool hasColours = element.has(Role::Red) && element.has(Role::Green) && element.has(Role::Blue);
        const std::size_t reserve = reservation(element);
        model.positions.reserve(reserve);
        if (hasNormals) model.normals.reserve(reserve);
        if (hasColours) model.colors.reserve(reserve);
        for (std::uint64_t index = 0; index < element.count; ++index) {
            glm::dvec3 position(0.0);
            glm::dvec3 normal(0.0);
            glm::vec4 colour(1.0f);
            for (const Property& property : element.properties) {
                if (property.role == Role::Other) {
                    skip(element, index, property);
                    continue;
                }
                const double value = scalar(element, index, property.type);
                switch (property.role) {
                case Role::X:
                case Role::Y:
                case Role::Z: position[int(property.role) - int(Role::X)] = value; break;
                case Role::NormalX:
                case Role::NormalY:
                case Role::NormalZ: normal[int(property.role) - int(Role::NormalX)] = value; break;
                case Role::Red:
                case Role::Green:
                case Role::Blue:
                case Role::Alpha: {
                    double component = isInteger(property.type) ? value / maximumOf(property.type) : value;
                    if (!std::isfinite(component)) {
                        ++model.nonFiniteColours;
                        component = 1.0;
                    } else if (component < 0.0 || component > 1.0) {
                        ++model.coloursOutOfRange;
                        if (std::abs(component - 0.5) > std::abs(model.colourFarthestOut - 0.5))
                            model.colourFarthestOut = component;
                    }
                    colour[int(property.role) - int(Role::Red)] = float(std::clamp(component, 0.0, 1.0));
                    break;
                }
                default: break;
                }
            }
            for (int axis = 0; axis < 3; ++axis) {
                if (!std::isfinite(position[axis])) {
                    fail(instance(element, index) + ": non-finite vertex coordinate (" + formatNumber(position[axis]) +
                         ")");
                }
                if (std::abs(position[axis]) > std::numeric_limits<float>::max()) {
                    fail(instance(element, index) + ": non-finite vertex coordinate in float (" +
                         formatNumber(position[axis]) + " is beyond float's range)");
                }
            }
            model.positions.push_back(position);
            if (hasNormals) {
                const glm::vec3 stored(normal);
                if (!std::isfinite(stored.x) || !std::isfinite(stored.y) || !std::isfinite(stored.z)) {
                    std::size_t line = 0;
                    if constexpr (!Binary) line = mSource.line();
                    model.nonFiniteNormals.emplace_back(index, line);
                }
                model.normals.push_back(stored);
            }
            if (hasColours) model.colors.push_back(colour);
        }
    }

    void readFaces(const Element& element, std::uint64_t vertexCount, Model& model) {
        std::size_t charged = std::size_t(element.count); // loadPly() charged one triangle per face
        model.triangles.reserve(reservation(element));
        for (std::uint64_t index = 0; index < element.count; ++index) {
            bool seen = false; // a repeated vertex_indices was made Other by the header
            for (const Property& property : element.properties) {
                if (property.role != Role::Indices || seen) {
                    skip(element, index, property);
                    continue;
                }
                seen = true;
                const std::uint64_t corners = listCount(element, index, property);
                if (corners < 3) {
                    fail(instance(element, index) + " has " + std::to_string(corners) + " vertices (needs 3)");
                }
                mCorners.clear();
                for (std::uint64_t corner = 0; corner < corners; ++corner) {
                    const std::int64_t vertex = integer(element, index, property.type);
                    if (vertex < 0 || std::uint64_t(vertex) >= vertexCount) {
                        fail(instance(element, index) + ": vertex index " + std::to_string(vertex) +
                             " out of range (file has " + std::to_string(vertexCount) + " vertices)");
                    }
                    mCorners.push_back(std::uint32_t(vertex)); // the header's count fits 32 bits
                }
                while (model.triangles.size() + mCorners.size() - 2 > charged) {
                    mBudget.charge(0, kTriangleChargeStep);
                    charged += kTriangleChargeStep;
                }
                addPolygon(model);
            }
        }
    }

    /** The triangles of the polygon in mCorners, cut inside its outline (scene/mesh/PolygonTriangulation.h). */
    void addPolygon(Model& model) {
        const bool positionsKnown = !model.positions.empty();
        if (mCorners.size() > 3 && positionsKnown) {
            model.triangulate(mCorners, mPolygonTriangles);
            for (const glm::uvec3& local : mPolygonTriangles) {
                model.triangles.emplace_back(mCorners[local.x], mCorners[local.y], mCorners[local.z]);
            }
            return;
        }
        if (mCorners.size() > 3) {
            model.polygonsBeforeVertices.emplace_back(model.triangles.size(), mCorners);
        }
        for (std::size_t i = 1; i + 1 < mCorners.size(); ++i) {
            model.triangles.emplace_back(mCorners[0], mCorners[i], mCorners[i + 1]);
        }
    }

    std::vector<std::uint32_t> mCorners;       ///< scratch: the current face's vertices
    std::vector<glm::uvec3> mPolygonTriangles; ///< scratch: its triangles, as indices into mCorners
    const std::string& mPath;
    Source& mSource;
    std::size_t mBodyBytes;
    MeshBudget& mBudget;
};

RawScene readPly(const std::string& path, std::string_view content, MeshBudget& budget, const LoadOptions&) {
    const Header header = readHeader(path, content);
    const std::uint64_t vertexCount = header.vertices ? header.vertices->count : 0;
    const std::uint64_t faceCount = header.faces ? header.faces->count : 0;
    if (faceCount == 0) {
        throwLoadError(path, "no triangles: the file has no faces" +
                                 (vertexCount > 0 ? " (a point cloud of " + std::to_string(vertexCount) + " vertices)"
                                                  : std::string()));
    }
    if (vertexCount > std::numeric_limits<std::uint32_t>::max()) {
        throwLoadError(path, "element 'vertex' declares " + std::to_string(vertexCount) +
                                 " vertices, more than the 4294967295 a mesh can index");
    }
    if (vertexCount > 0) {
        for (const Role role : {Role::X, Role::Y, Role::Z}) {
            if (!header.vertices->has(role)) {
                throwLoadError(path, std::string("element 'vertex' has no property '") + "xyz"[int(role) - 1] + "'");
            }
        }
    }
    if (!header.faces->has(Role::Indices)) {
        throwLoadError(path, "element 'face' has no list property 'vertex_indices' (or 'vertex_index')");
    }
    // Before anything is reserved, once the counts fit the file: each face is a triangle at least; polygons charge the
    // rest as they are read.
    const auto charge = [&] {
        budget.charge(std::size_t(vertexCount), std::size_t(std::min<std::uint64_t>(faceCount, SIZE_MAX)));
    };

    RawScene scene;
    Model model;
    const std::string_view body = content.substr(header.bodyOffset);
    if (header.encoding == Encoding::Ascii) {
        scene.format = "ply-ascii";
        // Text never holds NUL bytes; a binary body under an "ascii" header would otherwise read as garbled
        // numbers.
        if (const std::size_t nul = body.find('\0'); nul != std::string_view::npos) {
            throwLoadErrorAtLine(path,
                                 header.bodyLine + std::size_t(std::count(body.begin(), body.begin() + nul, '\n')),
                                 "binary data (NUL byte) in an ASCII PLY body (is the file binary?)");
        }
        AsciiSource source(body, header.bodyLine);
        BodyReader<false> reader(path, source, body.size(), budget);
        reader.checkCountsFit(header);
        charge();
        reader.read(header, model);
        if (const std::string_view rest = source.token(); !rest.empty()) {
            scene.warnings.push_back(
                makeWarning(WarningKind::TrailingDataIgnored, "text after the last element ignored (line " +
                                                                  std::to_string(source.line()) + ": '" +
                                                                  excerptForMessage(rest) + "')"));
        }
    } else {
        scene.format = "ply-binary";
        BinarySource source(body, header.encoding == Encoding::BinaryBigEndian);
        BodyReader<true> reader(path, source, body.size(), budget);
        reader.checkCountsFit(header);
        charge();
        reader.read(header, model);
        if (source.remaining() > 0) {
            scene.warnings.push_back(
                makeWarning(WarningKind::TrailingDataIgnored,
                            std::to_string(source.remaining()) + " bytes after the last element ignored"));
        }
    }
    model.triangulatePolygonsBeforeVertices();
    refuseNonFiniteNormalsInUse(path, model);
    if (model.triangulator.unresolvedPolygons() > 0) {
        scene.warnings.push_back(polygonsFannedWarning(model.triangulator));
    }
    if (const std::string texture = ignoredTexture(header); !texture.empty())
        scene.warnings.push_back(makeWarning(WarningKind::TextureIgnored, texture));
    if (model.coloursOutOfRange > 0) {
        // A float colour holds [0, 1]; 0 to 255 there is an integer colour written as float.
        scene.warnings.push_back(
            makeWarning(WarningKind::ValueOutOfRange,
                        std::to_string(model.coloursOutOfRange) + " vertex colour component" +
                            (model.coloursOutOfRange == 1 ? " lies" : "s lie") + " outside [0, 1] (as far out as " +
                            formatNumber(model.colourFarthestOut) +
                            (model.colourFarthestOut > 1.5 ? "; colours of 0 to 255 in a float property?" : "") +
                            "); clamped into [0, 1]"));
    }
    if (model.nonFiniteColours > 0) {
        scene.warnings.push_back(
            makeWarning(WarningKind::ColoursNonFinite, std::to_string(model.nonFiniteColours) +
                                                           " vertex colour components are not finite; read as 1"));
    }

    RawMesh mesh;
    mesh.name = std::filesystem::path(path).stem().string();
    scene.origin = storeNearModel(path, model.positions, mesh.positions);
    model.positions = {};
    mesh.normals = std::move(model.normals);
    mesh.triangles = std::move(model.triangles);
    if (!model.colors.empty()) {
        mesh.colors = std::move(model.colors);
        // The base colour multiplies the vertex colours (glTF's rule); white shows them as the file wrote them.
        mesh.material.baseColorFactor = glm::vec4(1.0f);
    }
    scene.meshes.push_back(std::move(mesh));
    return scene;
}

} // namespace

FormatReader plyFormat() { return {"PLY", {".ply"}, readPly, nullptr, false}; }

} // namespace inkgraph::detail
