/** @file EXT_meshopt_compression decoding (GltfMeshopt.h), after the extension's specification: a buffer view's
 *  extension object names the compressed bytes (buffer, byteOffset, byteLength) and their layout once decoded (count
 *  elements of byteStride bytes, the view's byteLength in all), the codec (mode) and the transform applied after it
 *  (filter). The view's own buffer holds the uncompressed data, or nothing when it is a placeholder. */

#include "scene/formats/gltf/GltfMeshopt.h"

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace inkgraph::detail {

namespace {

enum class Mode { Attributes, Triangles, Indices };
enum class Filter { None, Octahedral, Quaternion, Exponential };

constexpr std::array<std::string_view, 3> kModeNames = {"ATTRIBUTES", "TRIANGLES", "INDICES"};
constexpr std::array<std::string_view, 4> kFilterNames = {"NONE", "OCTAHEDRAL", "QUATERNION", "EXPONENTIAL"};

/** One view's extension object, read and checked against the specification's rules. */
struct CompressedView {
    std::size_t buffer = 0;
    std::size_t byteOffset = 0;
    std::size_t byteLength = 0;
    std::size_t byteStride = 0;
    std::size_t count = 0;
    Mode mode = Mode::Attributes;
    Filter filter = Filter::None;
};

/** "'A', 'B' or 'C'" */
template <std::size_t N>
std::string quotedChoices(const std::array<std::string_view, N>& names) {
    std::string text;
    for (std::size_t i = 0; i < N; ++i) {
        text += (i == 0 ? "'" : i + 1 == N ? " or '" : ", '") + std::string(names[i]) + "'";
    }
    return text;
}

class ViewDecoder {
public:
    ViewDecoder(const std::string& path, std::size_t viewIndex) : mPath(path), mViewIndex(viewIndex) {}

    [[noreturn]] void fail(const std::string& problem) const {
        throwLoadError(mPath, "buffer view " + std::to_string(mViewIndex) + ": " + kMeshoptExtension + ": " + problem);
    }

    /** The extension object as the file wrote it (tinygltf's own copy narrows large integers to int). */
    nlohmann::json extensionObject(const tinygltf::BufferView& view) const {
        const nlohmann::json extensions = nlohmann::json::parse(view.extensions_json_string, nullptr, false);
        if (!extensions.is_object() || !extensions.contains(kMeshoptExtension) ||
            !extensions[kMeshoptExtension].is_object()) {
            fail("must be an object");
        }
        return extensions[kMeshoptExtension];
    }

    std::optional<std::size_t> unsignedMember(const nlohmann::json& object, const char* name) const {
        if (!object.contains(name)) return std::nullopt;
        const nlohmann::json& value = object[name];
        if (!value.is_number_unsigned()) {
            fail(std::string("'") + name + "' must be a non-negative integer (it is " +
                 excerptForMessage(value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)) + ")");
        }
        return std::size_t(value.get<std::uint64_t>());
    }

    std::size_t requiredUnsigned(const nlohmann::json& object, const char* name) const {
        const std::optional<std::size_t> value = unsignedMember(object, name);
        if (!value) fail(std::string("needs '") + name + "'");
        return *value;
    }

    template <typename Enum, std::size_t N>
    Enum choice(const nlohmann::json& object, const char* name, const std::array<std::string_view, N>& names,
                std::optional<Enum> fallback) const {
        if (!object.contains(name)) {
            if (!fallback) fail(std::string("needs '") + name + "' (" + quotedChoices(names) + ")");
            return *fallback;
        }
        const nlohmann::json& value = object[name];
        const std::string text = value.is_string()
                                     ? value.get<std::string>()
                                     : value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
        const auto found = std::ranges::find(names, std::string_view(text));
        if (!value.is_string() || found == names.end()) {
            fail(std::string(name) + " '" + excerptForMessage(text) + "' is not " + quotedChoices(names));
        }
        return Enum(found - names.begin());
    }

    /** The extension object's members, every rule of the specification checked, and its sizes against the view and
     *  the buffers the file has (`fileBuffers`, of which `placeholders` hold no data). */
    CompressedView read(const tinygltf::BufferView& view, const tinygltf::Model& model, std::size_t fileBuffers,
                        const std::vector<std::size_t>& placeholders) const {
        const nlohmann::json object = extensionObject(view);
        CompressedView compressed;
        compressed.buffer = requiredUnsigned(object, "buffer");
        compressed.byteOffset = unsignedMember(object, "byteOffset").value_or(0);
        compressed.byteLength = requiredUnsigned(object, "byteLength");
        compressed.byteStride = requiredUnsigned(object, "byteStride");
        compressed.count = requiredUnsigned(object, "count");
        compressed.mode = choice<Mode>(object, "mode", kModeNames, std::nullopt);
        compressed.filter = choice<Filter>(object, "filter", kFilterNames, Filter::None);

        if (compressed.buffer >= fileBuffers) {
            fail("buffer " + std::to_string(compressed.buffer) + " out of range (file has " +
                 std::to_string(fileBuffers) + " buffers)");
        }
        if (std::ranges::find(placeholders, compressed.buffer) != placeholders.end()) {
            fail("buffer " + std::to_string(compressed.buffer) +
                 " is a placeholder for uncompressed data and holds no compressed bytes");
        }
        const std::size_t available = model.buffers[compressed.buffer].data.size();
        if (compressed.byteOffset > available || compressed.byteLength > available - compressed.byteOffset) {
            fail("the compressed bytes (offset " + std::to_string(compressed.byteOffset) + ", length " +
                 std::to_string(compressed.byteLength) + ") exceed buffer " + std::to_string(compressed.buffer) +
                 " of " + std::to_string(available) + " bytes");
        }
        checkLayout(compressed, view);
        return compressed;
    }

    /** The specification's rules for byteStride, count, mode and filter, and the decoded size against the view's. */
    void checkLayout(const CompressedView& compressed, const tinygltf::BufferView& view) const {
        const std::size_t stride = compressed.byteStride;
        const std::string strideText = "byteStride " + std::to_string(stride);
        const std::string_view modeName = kModeNames[std::size_t(compressed.mode)];
        const std::string_view filterName = kFilterNames[std::size_t(compressed.filter)];
        if (compressed.mode == Mode::Attributes) {
            if (stride == 0 || stride % 4 != 0 || stride > 256) {
                fail(strideText + " must be a multiple of 4 from 4 to 256 in mode ATTRIBUTES");
            }
        } else {
            if (stride != 2 && stride != 4) fail(strideText + " must be 2 or 4 in mode " + std::string(modeName));
            if (compressed.filter != Filter::None) {
                fail("filter " + std::string(filterName) + " applies only to mode ATTRIBUTES, not " +
                     std::string(modeName));
            }
            if (compressed.mode == Mode::Triangles && compressed.count % 3 != 0) {
                fail("count " + std::to_string(compressed.count) + " is not a multiple of 3 in mode TRIANGLES");
            }
        }
        if ((compressed.filter == Filter::Octahedral && stride != 4 && stride != 8) ||
            (compressed.filter == Filter::Quaternion && stride != 8)) {
            fail(strideText + " does not suit filter " + std::string(filterName) +
                 (compressed.filter == Filter::Octahedral ? " (4 or 8)" : " (8)"));
        }
        if (view.byteStride != 0 && view.byteStride != stride) {
            fail(strideText + " differs from the buffer view's byteStride " + std::to_string(view.byteStride));
        }
        if (compressed.count > SIZE_MAX / stride || compressed.count * stride != view.byteLength) {
            fail("count " + std::to_string(compressed.count) + " x " + strideText +
                 " does not equal the buffer view's byteLength " + std::to_string(view.byteLength));
        }
    }

    /** The view's bytes decoded (and filtered) from `compressed`. */
    std::vector<unsigned char> decode(const CompressedView& compressed, const tinygltf::Model& model) const {
        std::vector<unsigned char> decoded(compressed.count * compressed.byteStride);
        const unsigned char* source = model.buffers[compressed.buffer].data.data() + compressed.byteOffset;
        int result = 0;
        switch (compressed.mode) {
        case Mode::Attributes:
            result = meshopt_decodeVertexBuffer(decoded.data(), compressed.count, compressed.byteStride, source,
                                                compressed.byteLength);
            break;
        case Mode::Triangles:
            result = meshopt_decodeIndexBuffer(decoded.data(), compressed.count, compressed.byteStride, source,
                                               compressed.byteLength);
            break;
        case Mode::Indices:
            result = meshopt_decodeIndexSequence(decoded.data(), compressed.count, compressed.byteStride, source,
                                                 compressed.byteLength);
            break;
        }
        if (result != 0) {
            fail("meshoptimizer cannot decode its " + std::to_string(compressed.byteLength) + " bytes as " +
                 std::to_string(compressed.count) + " elements of mode " +
                 std::string(kModeNames[std::size_t(compressed.mode)]) + " (error " + std::to_string(result) +
                 ": malformed or cut short)");
        }
        // Each filter transforms the decoded elements in place; a garbage element decodes to a garbage number, which
        // the accessor reads refuse when it is not finite.
        switch (compressed.filter) {
        case Filter::None: break;
        case Filter::Octahedral:
            meshopt_decodeFilterOct(decoded.data(), compressed.count, compressed.byteStride);
            break;
        case Filter::Quaternion:
            meshopt_decodeFilterQuat(decoded.data(), compressed.count, compressed.byteStride);
            break;
        case Filter::Exponential:
            meshopt_decodeFilterExp(decoded.data(), compressed.count, compressed.byteStride);
            break;
        }
        return decoded;
    }

private:
    const std::string& mPath;
    std::size_t mViewIndex;
};

} // namespace

std::vector<std::size_t> stubMeshoptPlaceholders(nlohmann::json& document, bool binary) {
    std::vector<std::size_t> placeholders;
    if (!document.contains("buffers") || !document["buffers"].is_array()) return placeholders;
    nlohmann::json& buffers = document["buffers"];
    for (std::size_t i = 0; i < buffers.size(); ++i) {
        nlohmann::json& buffer = buffers[i];
        if (!buffer.is_object()) continue;
        const nlohmann::json::json_pointer fallback(std::string("/extensions/") + kMeshoptExtension + "/fallback");
        const bool markedFallback =
            buffer.contains(fallback) && buffer[fallback].is_boolean() && buffer[fallback].get<bool>();
        const bool withoutData = !buffer.contains("uri") && !(binary && i == 0);
        if (!markedFallback && !withoutData) continue;
        // tinygltf refuses an empty data: URI, so the stub is one zero byte.
        buffer["uri"] = "data:application/octet-stream;base64,AA==";
        buffer["byteLength"] = 1;
        placeholders.push_back(i);
    }
    return placeholders;
}

void decodeMeshoptBufferViews(const std::string& path, tinygltf::Model& model,
                              const std::vector<std::size_t>& placeholders, MeshBudget& budget) {
    const std::size_t fileBuffers = model.buffers.size();
    for (std::size_t viewIndex = 0; viewIndex < model.bufferViews.size(); ++viewIndex) {
        tinygltf::BufferView& view = model.bufferViews[viewIndex];
        const ViewDecoder decoder(path, viewIndex);
        if (view.extensions.count(kMeshoptExtension) == 0) {
            if (view.buffer >= 0 && std::ranges::find(placeholders, std::size_t(view.buffer)) != placeholders.end()) {
                throwLoadError(path, "buffer view " + std::to_string(viewIndex) +
                                         " is not compressed, but its buffer " + std::to_string(view.buffer) + " is " +
                                         kMeshoptExtension + "'s placeholder, which holds no data");
            }
            continue;
        }
        const CompressedView compressed = decoder.read(view, model, fileBuffers, placeholders);
        budget.chargeBytes(view.byteLength, "EXT_meshopt_compression's decoded buffer views");
        tinygltf::Buffer decoded;
        decoded.data = decoder.decode(compressed, model);
        model.buffers.push_back(std::move(decoded));
        view.buffer = int(model.buffers.size() - 1);
        view.byteOffset = 0;
    }
}

} // namespace inkgraph::detail
