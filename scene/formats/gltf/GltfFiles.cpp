/** @file A glTF file and the files it names (GltfFiles.h). */

#include "scene/formats/gltf/GltfFiles.h"

#include "scene/formats/FormatReaders.h"
#include "scene/formats/gltf/GltfDraco.h"
#include "scene/formats/gltf/GltfMeshopt.h"
#include "scene/formats/gltf/GltfValueShapes.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace inkgraph::detail {

namespace {

/** Deepest nesting of arrays and objects in JSON text, outside strings. */
std::size_t jsonNestingDepth(std::string_view text) {
    std::size_t depth = 0;
    std::size_t deepest = 0;
    bool inString = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            if (c == '\\')
                ++i;
            else if (c == '"')
                inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            deepest = std::max(deepest, ++depth);
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return deepest;
}

/** The external (non-data:) URIs of the top-level "buffers" and "images" arrays, collected by a SAX pass over the
 *  JSON before tinygltf reads it, so the file callbacks can tell an image (not read at load time) from a buffer (read).
 */
class ExternalUriCollector : public nlohmann::json_sax<nlohmann::json> {
public:
    std::vector<std::string> bufferUris;
    std::vector<std::string> imageUris;
    std::vector<std::string> imageDataUris; ///< ExternalUris::imageDataUris

    bool null() override { return leaveValue(); }
    bool boolean(bool) override { return leaveValue(); }
    bool number_integer(number_integer_t) override { return leaveValue(); }
    bool number_unsigned(number_unsigned_t) override { return leaveValue(); }
    bool number_float(number_float_t, const string_t&) override { return leaveValue(); }
    bool binary(binary_t&) override { return leaveValue(); }
    bool string(string_t& value) override {
        // Depth 3: the root object, the "buffers"/"images" array, one element object; the member is "uri".
        if (mKeys.size() == 3 && mKeys[2] == "uri" && value.rfind("data:", 0) != 0) {
            if (mKeys[0] == "buffers") bufferUris.push_back(value);
            if (mKeys[0] == "images") imageUris.push_back(value);
        } else if (mKeys.size() == 3 && mKeys[2] == "uri" && mKeys[0] == "images" && !tinygltf::IsDataURI(value)) {
            imageDataUris.push_back(value);
        }
        return leaveValue();
    }
    bool start_object(std::size_t) override {
        mKeys.emplace_back();
        return true;
    }
    bool key(string_t& name) override {
        mKeys.back() = name.size() <= 8 ? name : std::string(); // only "buffers", "images" and "uri" matter
        return true;
    }
    bool end_object() override {
        mKeys.pop_back();
        return leaveValue();
    }
    bool start_array(std::size_t) override {
        mKeys.emplace_back(); // arrays have no keys; the placeholder keeps depths aligned with objects
        return true;
    }
    bool end_array() override {
        mKeys.pop_back();
        return leaveValue();
    }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
        return false; // tinygltf reports the error in its own words
    }

private:
    bool leaveValue() { return true; }

    std::vector<std::string> mKeys; ///< per open container: the member being read ("" in arrays)
};

int hexDigitValue(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

/** A URI as tinygltf turns it into a file name: '+' becomes a space and '%' with the next two characters the byte
 *  they spell (a non-hex digit counts as 0), so the names match the ones its file callbacks receive. */
std::string tinygltfDecodedUri(std::string_view uri) {
    std::string decoded;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '+') {
            decoded += ' ';
        } else if (uri[i] == '%' && i + 2 < uri.size()) {
            decoded += char((std::max(hexDigitValue(uri[i + 1]), 0) << 4) | std::max(hexDigitValue(uri[i + 2]), 0));
            i += 2;
        } else {
            decoded += uri[i];
        }
    }
    return decoded;
}

/** The file name a relative URI reference spells (RFC 3986): "%XX" is the byte XX; a '+', and a '%' not followed by
 *  two hex digits ("100%.png"), are themselves, as every file system and glTF viewer takes them. A "file://" URI,
 *  which some exporters write, is its path. */
std::string fileNameOfUri(std::string_view uri) {
    if (uri.rfind("file://", 0) == 0) uri.remove_prefix(7);
    std::string decoded;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        // "%00" stays as written: the system would read the name up to the NUL, another file.
        if (uri[i] == '%' && i + 2 < uri.size() && hexDigitValue(uri[i + 1]) >= 0 && hexDigitValue(uri[i + 2]) >= 0 &&
            (uri[i + 1] != '0' || uri[i + 2] != '0')) {
            decoded += char(hexDigitValue(uri[i + 1]) << 4 | hexDigitValue(uri[i + 2]));
            i += 2;
        } else {
            decoded += uri[i];
        }
    }
    return decoded;
}

/** The JSON text with every data: URI longer than 4 KiB cut to its first printable ASCII bytes, at most 64 (its media
 *  type and encoding): as good as the whole for judging the file's numbers, and parsed in a fraction of the time (a 16
 *  MB .gltf's data URI took nlohmann 0.2 s). Other strings stay whole, however long: a message quotes them as written
 *  (an asset.version of 5000 escaped characters was told as '' when every long string was cut). */
std::string withLongStringsCut(std::string_view text) {
    constexpr std::size_t kLongString = 4096;
    constexpr std::size_t kKept = 64;
    std::string cut;
    cut.reserve(std::min(text.size(), std::size_t(1) << 20));
    std::size_t i = 0;
    while (i < text.size()) {
        const std::size_t quote = text.find('"', i);
        if (quote == std::string_view::npos) break;
        cut.append(text.substr(i, quote + 1 - i));
        std::size_t end = quote + 1; // past the closing quote, escapes skipped
        while (end < text.size() && text[end] != '"') end += text[end] == '\\' ? 2 : 1;
        const std::string_view inside = text.substr(quote + 1, std::min(end, text.size()) - quote - 1);
        if (inside.size() <= kLongString || inside.substr(0, 5) != "data:") {
            cut.append(inside);
        } else {
            std::size_t kept = 0;
            while (kept < kKept && inside[kept] >= ' ' && inside[kept] <= '~' && inside[kept] != '\\') ++kept;
            cut.append(inside.substr(0, kept));
        }
        if (end >= text.size()) return cut; // an unterminated string: the parse fails, as it would on the whole
        cut += '"';
        i = end + 1;
    }
    cut.append(text.substr(std::min(i, text.size())));
    return cut;
}

/** Where glTF's schema puts integers (indices into the file's arrays, offsets, counts, enums): the members of these
 *  names whose value is a number, the number elements of these arrays, and every member of an `attributes` object and
 *  of a morph target. */
constexpr std::array<std::string_view, 29> kIntegerMembers = {
    "buffer",        "bufferView", "byteLength", "byteOffset", "byteStride", "camera",
    "componentType", "count",      "index",      "indices",    "input",      "inverseBindMatrices",
    "light",         "magFilter",  "material",   "mesh",       "minFilter",  "mode",
    "node",          "output",     "sampler",    "scene",      "skeleton",   "skin",
    "source",        "target",     "texCoord",   "wrapS",      "wrapT"};
constexpr std::array<std::string_view, 3> kIntegerArrays = {"children", "joints", "nodes"};
/** Of them, the sizes (64 bits in tinygltf); the rest are indices and enums, which tinygltf keeps in an int and would
 *  wrap (4294967299 read as 3). */
constexpr std::array<std::string_view, 4> kSizeMembers = {"byteLength", "byteOffset", "byteStride", "count"};

/** What `value` becomes where glTF wants an integer: itself when it is one, the integer when it is a number with a
 *  zero fraction (3.0, which JSON Schema counts as an integer and numpy-based writers write), none otherwise. */
std::optional<nlohmann::json> asInteger(const nlohmann::json& value) {
    if (value.is_number_integer()) return value;
    if (!value.is_number_float()) return std::nullopt;
    const double number = value.get<double>();
    // 2^53: every whole number below it is exact in a double, and far beyond any index or length a file can hold.
    if (number != std::floor(number) || std::abs(number) > 9007199254740992.0) return std::nullopt;
    return number < 0.0 ? nlohmann::json(std::int64_t(number)) : nlohmann::json(std::uint64_t(number));
}

/** Writes glTF's integers given as whole numbers (3.0) as integers; tinygltf reads only an integer token there and
 *  takes 3.0 for an absent member (a primitive's indices dropped: a triangle soup; its material dropped: grey).
 *  Outside extensions and extras, a value there that is not a whole number from 0 up (3.5, "3", true, -1; null is
 *  taken as absent, as tinygltf takes it), or an index beyond an int, is refused naming where it is, for the same
 *  reason; an extension's reader judges its own values, and extras are left as written.
 *  `where` is the value's place ("meshes[0].primitives[0]"). Returns whether anything changed. */
bool integersAsWritten(const std::string& path, nlohmann::json& value, const std::string& where, bool core) {
    const auto integer = [&](nlohmann::json& member, const std::string& at, bool size) {
        if (member.is_object() || member.is_array()) return integersAsWritten(path, member, at, core);
        const std::optional<nlohmann::json> whole = asInteger(member);
        if (whole) {
            // Every glTF integer is 0 or more (tinygltf takes -1 for absent: "indices": -1 drew a soup of vertices).
            const double limit = size ? 9007199254740992.0 : 2147483647.0;
            const double number = whole->get<double>();
            if (core && number < 0.0) {
                throwLoadError(path, at + " is " + member.dump() + ", negative: glTF's " +
                                         (size ? "offsets, lengths, strides and counts" : "indices and enums") +
                                         " are 0 or more");
            }
            if (core && number > limit) {
                throwLoadError(path, at + " is " + member.dump() + ", over " + formatNumber(limit) +
                                         (size ? "" : ", the largest index glTF's reader can hold"));
            }
            const bool changed = !member.is_number_integer();
            member = *whole;
            return changed;
        }
        // null is taken as absent, as tinygltf takes it.
        if (core && !member.is_null()) {
            const std::string text = member.is_string()
                                         ? "the string " + quotedExcerpt(member.get<std::string>())
                                         : member.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
            throwLoadError(path, at + " is " + text +
                                     ", not an integer (glTF writes indices, offsets and counts as "
                                     "whole numbers)");
        }
        return false;
    };
    bool changed = false;
    if (value.is_array()) {
        for (std::size_t i = 0; i < value.size(); ++i)
            changed |= integersAsWritten(path, value[i], where + "[" + std::to_string(i) + "]", core);
        return changed;
    }
    if (!value.is_object()) return false;
    for (auto& [key, member] : value.items()) {
        const std::string at = where.empty() ? key : where + "." + key;
        if (key == "extras") continue;
        if (key == "extensions") {
            changed |= integersAsWritten(path, member, at, false);
        } else if (key == "attributes" && member.is_object()) {
            for (auto& [name, attribute] : member.items()) changed |= integer(attribute, at + "." + name, false);
        } else if (key == "targets" && member.is_array()) {
            for (std::size_t t = 0; t < member.size(); ++t) {
                if (!member[t].is_object()) continue;
                for (auto& [name, attribute] : member[t].items())
                    changed |= integer(attribute, at + "[" + std::to_string(t) + "]." + name, false);
            }
        } else if (std::ranges::find(kIntegerArrays, key) != kIntegerArrays.end() && member.is_array()) {
            for (std::size_t i = 0; i < member.size(); ++i) {
                nlohmann::json& element = member[i];
                const std::string elementAt = at + "[" + std::to_string(i) + "]";
                // The top-level "nodes" holds node objects; a scene's holds indices.
                changed |= element.is_object() ? integersAsWritten(path, element, elementAt, core)
                                               : integer(element, elementAt, false);
            }
        } else if (std::ranges::find(kIntegerMembers, key) != kIntegerMembers.end()) {
            changed |= integer(member, at, std::ranges::find(kSizeMembers, key) != kSizeMembers.end());
        } else {
            changed |= integersAsWritten(path, member, at, core);
        }
    }
    return changed;
}

} // namespace

/** A material's shade map path: relative to the glTF file, like its buffer URIs, so a scene folder can be moved or
 *  rendered from anywhere; lexically normalised. */
std::string shadeMapBesideModel(const std::string& modelPath, const std::string& named) {
    const std::filesystem::path path(named);
    const std::filesystem::path resolved =
        path.is_absolute() ? path : std::filesystem::path(modelPath).parent_path() / path;
    return resolved.lexically_normal().string();
}

/** The JSON text of a .gltf file or of a GLB's JSON chunk (empty when the GLB is too short to have one). */
std::string_view jsonOf(std::string_view content, bool binary) {
    if (!binary) return content;
    if (content.size() < 20) return {};
    std::uint32_t chunkLength = 0;
    std::memcpy(&chunkLength, content.data() + 12, sizeof chunkLength);
    return content.substr(20, chunkLength);
}

/** The file as tinygltf can take it (TinygltfInput), or nothing rewritten when the JSON names neither extension or
 *  does not parse (tinygltf then says why). The decoded Draco faces replace the dropped indices
 *  (decodeDracoPrimitive()), the decoded meshopt views the placeholders (decodeMeshoptBufferViews()). A GLB is rebuilt
 *  around the new JSON chunk with its other chunks as they were. */
TinygltfInput forTinygltf(const std::string& path, std::string_view content, bool binary) {
    TinygltfInput input;
    if (binary) judgeGlbHeader(path, content);
    const std::string_view json = jsonOf(content, binary);
    const bool draco = json.find(kDracoExtension) != std::string_view::npos;
    const bool meshopt = json.find(kMeshoptExtension) != std::string_view::npos;
    ValueShapes shapes;
    if (!draco && !meshopt) {
        // Judged without the long strings first: the whole document is parsed only when something is rewritten.
        nlohmann::json shortened = nlohmann::json::parse(withLongStringsCut(json), nullptr, false);
        if (!shortened.is_object()) return input;
        const bool rewrite = integersAsWritten(path, shortened, "", true);
        shapes = judgeValueShapes(path, shortened);
        input.warnings = shapes.warnings;
        if (!rewrite && shapes.dropped.empty()) return input;
    }
    nlohmann::json document = nlohmann::json::parse(json, nullptr, false);
    if (!document.is_object()) return input;
    bool changed = integersAsWritten(path, document, "", true);
    if (draco || meshopt) {
        shapes = judgeValueShapes(path, document);
        input.warnings = shapes.warnings;
    }
    dropValues(document, shapes.dropped);
    changed = changed || !shapes.dropped.empty();
    if (draco && document.contains("meshes") && document["meshes"].is_array()) {
        for (nlohmann::json& mesh : document["meshes"]) {
            if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
            for (nlohmann::json& primitive : mesh["primitives"]) {
                if (primitive.is_object() && primitive.contains("indices") && primitive.contains("extensions") &&
                    primitive["extensions"].is_object() && primitive["extensions"].contains(kDracoExtension)) {
                    primitive.erase("indices");
                    changed = true;
                }
            }
        }
    }
    if (meshopt) {
        input.meshoptPlaceholders = stubMeshoptPlaceholders(document, binary);
        changed = changed || !input.meshoptPlaceholders.empty();
    }
    if (!changed) return input;
    std::string text = document.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    if (!binary) {
        input.rewritten = std::move(text);
        return input;
    }
    const std::size_t restOffset = 20 + json.size();
    if (content.size() < restOffset) return TinygltfInput{};
    while (text.size() % 4 != 0) text += ' '; // GLB chunks are 4-byte aligned; JSON pads with spaces
    const auto u32 = [](std::size_t value) {
        const std::uint32_t little = std::uint32_t(value);
        return std::string(reinterpret_cast<const char*>(&little), 4);
    };
    const std::string_view rest = content.substr(restOffset);
    input.rewritten = std::string(content.substr(0, 8)) + u32(12 + 8 + text.size() + rest.size()) + u32(text.size()) +
                      "JSON" + text + std::string(rest);
    return input;
}

/** tinygltf parses JSON recursively, so absurd nesting would overflow the stack: glTF itself nests a few levels, and
 *  extras rarely more than a dozen. Checked before tinygltf sees the file. */
void rejectDeepJson(const std::string& path, std::string_view content, bool binary) {
    constexpr std::size_t kMaxJsonDepth = 256;
    // GLB: 12-byte header, then the JSON chunk's length, type, and text.
    const std::string_view json = binary && content.size() < 20 ? content : jsonOf(content, binary);
    if (jsonNestingDepth(json) > kMaxJsonDepth)
        throwLoadError(path, "JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
}

std::string tinygltfPathBesideModel(const std::string& baseDirectory, std::string_view uri) {
    const std::string decoded = tinygltfDecodedUri(uri);
    if (baseDirectory.empty()) return decoded;
    return baseDirectory + (baseDirectory.back() == '/' ? "" : "/") + decoded;
}

std::string pathBesideModel(const std::string& baseDirectory, std::string_view uri) {
    std::string name = fileNameOfUri(uri);
    std::string slashed = name;
    std::replace(slashed.begin(), slashed.end(), '\\', '/');
    // A glTF names its files relative to itself: an absolute path, a file:// URI or a Windows share is a path of the
    // exporting machine, looked for by its last name beside the model, never read where it points.
    if (uri.rfind("file://", 0) == 0 || (!slashed.empty() && slashed.front() == '/')) {
        name = slashed.substr(slashed.rfind('/') + 1);
    }
    return fileBeside(baseDirectory, name);
}

std::optional<std::string> ExternalFiles::name(const std::string& baseDirectory, std::string_view uri, bool image) {
    const std::string asked = tinygltfPathBesideModel(baseDirectory, uri);
    (image ? imagePaths : bufferPaths).insert(asked);
    // An image is answered by a placeholder, never read here (its file is found when it is decoded), so only a
    // buffer needs its file, and only buffers can clash.
    if (image || uri.rfind("data:", 0) == 0) return std::nullopt;
    const std::string file = pathBesideModel(baseDirectory, uri);
    const auto [known, added] = fileOf.try_emplace(asked, file);
    const auto [firstUri, uriAdded] = uriOf.try_emplace(asked, std::string(uri));
    if (!added && known->second != file) return firstUri->second;
    return std::nullopt;
}

const std::string& ExternalFiles::fileAskedAs(const std::string& path) const {
    const auto it = fileOf.find(path);
    return it == fileOf.end() ? path : it->second;
}

/** Only the files the JSON names, beside the model: tinygltf would otherwise fall back to the current folder and read a
 *  file of the same name there. Asks the file system rather than opening (tinygltf's own test blocks on a FIFO). An
 *  image counts as present even when missing: it is not read at load time (only when a pass decodes it, which reports a
 *  missing one then), so loading must not fail or warn for it. */
bool externalFileExists(const std::string& path, void* user) {
    const auto& files = *static_cast<const ExternalFiles*>(user);
    if (files.imagePaths.count(path) > 0) {
        return true;
    }
    std::error_code error;
    return files.bufferPaths.count(path) > 0 && std::filesystem::exists(files.fileAskedAs(path), error);
}

/** tinygltf's file reading. An image gets a one-byte placeholder without being opened (SceneImage keeps its path, read
 *  when decoded, so a 1 GiB texture is not held by every load); a buffer must be a regular file, and its size is
 * charged to the load's memory budget before it is read. A refusal comes back to tinygltf as a read error with the
 * reason. */
bool readExternalFile(std::vector<unsigned char>* out, std::string* error, const std::string& asked, void* user) {
    auto& files = *static_cast<ExternalFiles*>(user);
    if (files.bufferPaths.count(asked) == 0 && files.imagePaths.count(asked) > 0) {
        out->assign(1, 0); // tinygltf refuses an empty image; keepEncodedImage() ignores the byte
        return true;
    }
    const std::string& path = files.fileAskedAs(asked);
    // A FIFO or device ("/dev/stdin", "/dev/zero") as a buffer URI would block or never end: files only.
    std::error_code typeError;
    if (!std::filesystem::is_regular_file(path, typeError)) {
        if (error) *error += "external file '" + excerptForMessage(path) + "' is not a regular file\n";
        return false;
    }
    std::error_code sizeError;
    const std::uintmax_t size = std::filesystem::file_size(path, sizeError);
    if (sizeError) {
        if (error) *error += "cannot read '" + excerptForMessage(path) + "': " + sizeError.message() + "\n";
        return false;
    }
    try {
        files.budget.chargeFile(std::size_t(size));
    } catch (const SceneError&) {
        if (error)
            *error += "external file '" + excerptForMessage(path) + "' is " + memoryText(size) +
                      ", above the memory limit of " + memoryText(files.budget.limitBytes()) + "\n";
        return false;
    }
    files.opened.push_back(path);
    return tinygltf::ReadWholeFile(out, error, path, nullptr);
}

namespace {

/** The bytes of RFC 4648 base64 `text` (padding optional), or nothing when a character is not of its alphabet. */
std::optional<std::vector<unsigned char>> strictBase64(std::string_view text) {
    while (!text.empty() && text.back() == '=') text.remove_suffix(1);
    std::vector<unsigned char> bytes;
    bytes.reserve(text.size() / 4 * 3 + 2);
    std::uint32_t bits = 0;
    int bitCount = 0;
    for (const char c : text) {
        int value = -1;
        if (c >= 'A' && c <= 'Z') value = c - 'A';
        if (c >= 'a' && c <= 'z') value = c - 'a' + 26;
        if (c >= '0' && c <= '9') value = c - '0' + 52;
        if (c == '+') value = 62;
        if (c == '/') value = 63;
        if (value < 0) return std::nullopt;
        bits = bits << 6 | std::uint32_t(value);
        bitCount += 6;
        if (bitCount >= 8) {
            bitCount -= 8;
            bytes.push_back(static_cast<unsigned char>((bits >> bitCount) & 0xFF));
        }
    }
    return bytes;
}

/** An image given as a data: URI of a media type tinygltf does not decode (image/webp: ExternalUris::imageDataUris),
 *  decoded here and charged to the budget. Anything but base64 is refused. */
std::shared_ptr<const std::vector<unsigned char>> dataUriImageBytes(const std::string& path, std::size_t index,
                                                                    std::string_view uri, MeshBudget& budget) {
    const std::size_t comma = uri.find(',');
    const std::string_view header = uri.substr(0, comma);
    constexpr std::string_view kBase64 = ";base64";
    if (comma == std::string_view::npos || header.size() < kBase64.size() ||
        header.substr(header.size() - kBase64.size()) != kBase64)
        throwLoadError(path, "image " + std::to_string(index) + ": its data: URI '" +
                                 excerptForMessage(std::string(header)) + "' is not base64");
    const std::string_view payload = uri.substr(comma + 1);
    budget.chargeFile(payload.size() / 4 * 3 + 3);
    std::optional<std::vector<unsigned char>> bytes = strictBase64(payload);
    if (!bytes)
        throwLoadError(path, "image " + std::to_string(index) + ": its data: URI '" +
                                 excerptForMessage(std::string(header)) + "' holds characters that are not base64");
    return std::make_shared<const std::vector<unsigned char>>(std::move(*bytes));
}

} // namespace

/** The file's images in its order (a texture's `source` indexes them): embedded ones with their encoded bytes, external
 *  ones with their path beside the model, not read here. */
std::vector<SceneImage> sceneImages(const std::string& path, const tinygltf::Model& model,
                                    const std::string& baseDirectory, const DataUriImages& dataUriImages,
                                    MeshBudget& budget) {
    std::vector<SceneImage> images;
    images.reserve(model.images.size());
    for (std::size_t i = 0; i < model.images.size(); ++i) {
        const tinygltf::Image& image = model.images[i];
        SceneImage result;
        result.name = image.name.empty() ? excerptForMessage(image.uri) : image.name;
        result.mimeType = image.mimeType;
        if (image.bufferView >= 0) {
            // tinygltf checked only that the view and its buffer exist.
            const tinygltf::BufferView& view = model.bufferViews[std::size_t(image.bufferView)];
            const std::vector<unsigned char>& buffer = model.buffers[std::size_t(view.buffer)].data;
            if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset) {
                throwLoadError(path, "image " + std::to_string(i) + ": buffer view " +
                                         std::to_string(image.bufferView) + " (offset " +
                                         std::to_string(view.byteOffset) + ", length " +
                                         std::to_string(view.byteLength) + ") exceeds its buffer of " +
                                         std::to_string(buffer.size()) + " bytes");
            }
            budget.chargeFile(view.byteLength);
            const auto first = buffer.begin() + std::ptrdiff_t(view.byteOffset);
            result.encoded =
                std::make_shared<const std::vector<unsigned char>>(first, first + std::ptrdiff_t(view.byteLength));
        } else if (image.uri.rfind("data:", 0) == 0) {
            result.name = image.name;
            result.encoded = dataUriImageBytes(path, i, image.uri, budget);
        } else if (!image.uri.empty()) {
            result.path = pathBesideModel(baseDirectory, image.uri);
        } else if (i < dataUriImages.bytes.size()) {
            result.encoded = dataUriImages.bytes[i];
        }
        images.push_back(std::move(result));
    }
    return images;
}

ExternalUris externalUris(std::string_view json) {
    ExternalUriCollector collector; // whatever it collected before a syntax error still counts
    nlohmann::json::sax_parse(json.begin(), json.end(), &collector, nlohmann::json::input_format_t::json, false);
    return {std::move(collector.bufferUris), std::move(collector.imageUris), std::move(collector.imageDataUris)};
}

/** tinygltf's image decoder, replaced: images stay encoded until a pass samples them (scene/Material.h). tinygltf
 *  calls it for data: URIs (bytes it decoded itself, the size exact), for external files (our one-byte placeholder:
 *  readExternalFile()) and for buffer-view images, whose window it does not bounds-check: those are copied later by
 *  sceneImages() after checking, so only data: URIs are kept here. */
bool keepEncodedImage(tinygltf::Image* image, const int imageIndex, std::string* error, std::string*, int, int,
                      const unsigned char* bytes, int size, void* user) {
    auto& images = *static_cast<DataUriImages*>(user);
    if (image->bufferView != -1 || !image->uri.empty() || imageIndex < 0 || size < 0) {
        return true;
    }
    try {
        images.budget.chargeFile(std::size_t(size));
    } catch (const SceneError&) {
        if (error) *error += "image " + std::to_string(imageIndex) + " is above the memory limit\n";
        return false;
    }
    if (images.bytes.size() <= std::size_t(imageIndex)) images.bytes.resize(std::size_t(imageIndex) + 1);
    images.bytes[std::size_t(imageIndex)] = std::make_shared<const std::vector<unsigned char>>(bytes, bytes + size);
    return true;
}

std::optional<std::string> dataUriBufferProblem(std::string_view json) {
    const nlohmann::json document = nlohmann::json::parse(json, nullptr, false);
    if (!document.is_object() || !document.contains("buffers") || !document["buffers"].is_array()) return std::nullopt;
    const nlohmann::json& buffers = document["buffers"];
    for (std::size_t i = 0; i < buffers.size(); ++i) {
        const nlohmann::json& buffer = buffers[i];
        if (!buffer.is_object() || !buffer.contains("uri") || !buffer["uri"].is_string()) continue;
        const std::string& uri = buffer["uri"].get_ref<const std::string&>();
        if (uri.rfind("data:", 0) != 0) continue;
        const std::string at = "buffers[" + std::to_string(i) + "]";
        const std::size_t comma = uri.find(',');
        if (comma == std::string::npos || uri.substr(0, comma).find(";base64") == std::string::npos)
            return at + ".uri is a data: URI without ';base64,' (glTF's data: URIs are base64)";
        const std::string mediaType = uri.substr(5, uri.find(';') - 5);
        if (mediaType != "application/octet-stream" && mediaType != "application/gltf-buffer")
            return at + ".uri's data: URI has the media type " + quotedExcerpt(mediaType) +
                   ", where a glTF buffer's is 'application/octet-stream' or 'application/gltf-buffer'";
        const std::optional<std::vector<unsigned char>> bytes = strictBase64(std::string_view(uri).substr(comma + 1));
        if (!bytes) return at + ".uri's data: URI is not valid base64";
        if (buffer.contains("byteLength") && buffer["byteLength"].is_number_unsigned() &&
            buffer["byteLength"].get<std::uint64_t>() != bytes->size()) {
            return at + ".byteLength is " + std::to_string(buffer["byteLength"].get<std::uint64_t>()) +
                   ", but its data: URI holds " + std::to_string(bytes->size()) + " bytes";
        }
    }
    return std::nullopt;
}

/** The files a glTF (or GLB: `content` may stop after the JSON chunk) names: external buffers and images, and the
 *  shade maps of its materials, resolved as readGltf() resolves them. Best effort, nothing thrown. */
std::vector<std::string> gltfReferencedFiles(const std::string& path, std::string_view content) {
    const bool binary = content.size() >= 4 && content.substr(0, 4) == "glTF";
    const std::string_view json = jsonOf(content, binary);
    const std::string baseDirectory = std::filesystem::path(path).parent_path().string();
    std::vector<std::string> files;
    ExternalUriCollector uris; // whatever it collected before a syntax error still counts
    nlohmann::json::sax_parse(json.begin(), json.end(), &uris, nlohmann::json::input_format_t::json, false);
    for (const auto* list : {&uris.bufferUris, &uris.imageUris})
        for (const std::string& uri : *list) files.push_back(pathBesideModel(baseDirectory, uri));
    constexpr std::size_t kMaxJsonDepth = 256; // as rejectDeepJson()
    if (jsonNestingDepth(json) > kMaxJsonDepth) return files;
    const nlohmann::json document = nlohmann::json::parse(json, nullptr, false);
    if (!document.is_object() || !document.contains("materials") || !document["materials"].is_array()) return files;
    for (const nlohmann::json& material : document["materials"]) {
        const nlohmann::json::json_pointer where("/extras/inkgraph/shademap");
        if (material.is_object() && material.contains(where) && material[where].is_string() &&
            !material[where].get_ref<const std::string&>().empty())
            files.push_back(shadeMapBesideModel(path, material[where].get_ref<const std::string&>()));
    }
    return files;
}

/** A GLB's (or VRM's) header and JSON chunk, without the binary chunk after it, which can be large and names no file;
 *  empty when they cannot be read. */
namespace {

std::string glbJsonChunk(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    std::string content(20, '\0');
    if (!file.read(content.data(), 20)) return {};
    std::uint32_t chunkLength = 0;
    std::memcpy(&chunkLength, content.data() + 12, sizeof chunkLength);
    std::error_code error;
    const std::uintmax_t size = std::filesystem::file_size(path, error);
    if (error || chunkLength > size - 20) return {};
    content.resize(20 + std::size_t(chunkLength));
    if (!file.read(content.data() + 20, chunkLength)) return {};
    return content;
}

} // namespace

std::vector<std::string> glbReferencedFiles(const std::string& path) {
    const std::string content = glbJsonChunk(path);
    return content.empty() ? std::vector<std::string>{} : gltfReferencedFiles(path, content);
}

} // namespace inkgraph::detail
