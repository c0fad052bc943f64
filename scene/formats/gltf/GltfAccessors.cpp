/** @file glTF accessor reading (GltfAccessors.h): one bounds-checked path for plain, strided, quantized, normalized
 *  and sparse accessors, so a file's declared counts and offsets can never make a read leave its buffer. */

#include "scene/formats/gltf/GltfAccessors.h"

#include "scene/formats/FormatReaders.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <span>

namespace inkgraph::detail {

namespace {

static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian; add byte swapping");

const char* typeName(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "unknown";
    }
}

/** The component sizes glTF 2.0 allows (tinygltf also knows double, which glTF does not). */
std::size_t componentBytes(int componentType) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
    }
}

/** Reports failures of one accessor as "<role> accessor <n>: <problem>". */
struct AccessorContext {
    const std::string& path;
    const tinygltf::Model& model;
    int index;
    const std::string& role;

    [[noreturn]] void fail(const std::string& problem) const {
        throwLoadError(path, role + " accessor " + std::to_string(index) + ": " + problem);
    }
};

/** The accessor, its index, type and component type checked. */
constexpr std::size_t kMaxAccessorElements = std::size_t(1) << 32;

const tinygltf::Accessor& checkedAccessor(const AccessorContext& context, int expectedType) {
    if (context.index < 0 || std::size_t(context.index) >= context.model.accessors.size()) {
        throwLoadError(context.path, context.role + " accessor index " + std::to_string(context.index) +
                                         " out of range (file has " + std::to_string(context.model.accessors.size()) +
                                         " accessors)");
    }
    const tinygltf::Accessor& accessor = context.model.accessors[std::size_t(context.index)];
    if (accessor.type != expectedType) {
        context.fail(std::string("unexpected element type ") + typeName(accessor.type) + " (expected " +
                     typeName(expectedType) + ")");
    }
    if (componentBytes(accessor.componentType) == 0) {
        context.fail("invalid component type " + std::to_string(accessor.componentType));
    }
    // glTF indexes elements with 32 bits. Without a buffer view (sparse or zeros) nothing else bounds a count, and
    // count x components x bytes must not wrap in the reads and the memory charges that multiply it.
    if (accessor.count > kMaxAccessorElements) {
        context.fail("declares " + std::to_string(accessor.count) + " elements, more than the " +
                     std::to_string(kMaxAccessorElements) + " a glTF accessor can index");
    }
    return accessor;
}

/** `count` elements of `elementBytes` bytes, `stride` apart, starting `byteOffset` into buffer view `viewIndex`: the
 *  first byte, after checking (without overflow) that the last element ends inside the view and the view inside its
 *  buffer. */
const unsigned char* checkedWindow(const AccessorContext& context, int viewIndex, std::size_t byteOffset,
                                   std::size_t count, std::size_t elementBytes, std::size_t stride,
                                   const std::string& what) {
    const tinygltf::Model& model = context.model;
    if (viewIndex < 0 || std::size_t(viewIndex) >= model.bufferViews.size()) {
        context.fail(what + "buffer view " + std::to_string(viewIndex) + " out of range (file has " +
                     std::to_string(model.bufferViews.size()) + " buffer views)");
    }
    const tinygltf::BufferView& view = model.bufferViews[std::size_t(viewIndex)];
    if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size()) {
        context.fail("buffer view " + std::to_string(viewIndex) + " has an out-of-range buffer");
    }
    const std::vector<unsigned char>& buffer = model.buffers[std::size_t(view.buffer)].data;
    if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset) {
        context.fail("buffer view " + std::to_string(viewIndex) + " (offset " + std::to_string(view.byteOffset) +
                     ", length " + std::to_string(view.byteLength) + ") exceeds its buffer of " +
                     std::to_string(buffer.size()) + " bytes");
    }
    if (count == 0) {
        return nullptr;
    }
    // Last byte read: byteOffset + stride * (count - 1) + elementBytes.
    const std::size_t available = view.byteLength;
    const bool fits = byteOffset <= available && elementBytes <= available - byteOffset &&
                      (count - 1) <= (available - byteOffset - elementBytes) / stride;
    if (!fits) {
        context.fail(what + std::to_string(count) + " elements from offset " + std::to_string(byteOffset) +
                     ": the last reads past the end of buffer view " + std::to_string(viewIndex) + " (" +
                     std::to_string(available) + " bytes)");
    }
    return buffer.data() + view.byteOffset + byteOffset;
}

/** glTF 2.0 ("Data Alignment") requires the data of an accessor (and of its sparse indices and values) to start at a
 *  multiple of its component size, in its buffer view and in its buffer (a stride that is not a multiple of 4
 *  tinygltf refuses itself). A file that breaks it was written wrong, and readers that map the buffer as typed arrays
 *  (three.js) cannot load it; read as written, such data was as often garbage (a model "3.22e-41 units across"), so
 *  it is refused naming the offset. `what` names the part ("", "sparse indices: "); called after checkedWindow(),
 *  which checked the view. */
void checkAlignment(const AccessorContext& context, int viewIndex, std::size_t byteOffset, std::size_t component,
                    const std::string& what) {
    const tinygltf::BufferView& view = context.model.bufferViews[std::size_t(viewIndex)];
    const std::string sizeText = "a multiple of its component size (" + std::to_string(component) + " bytes)";
    const std::string rule = ", as glTF requires (readers that map buffers as typed arrays, three.js, refuse it too)";
    if (byteOffset % component != 0) {
        context.fail(what + "byteOffset " + std::to_string(byteOffset) + " is not " + sizeText + rule);
    }
    if ((view.byteOffset + byteOffset) % component != 0) {
        context.fail(what + "starts at byte " + std::to_string(view.byteOffset + byteOffset) +
                     " of its buffer (buffer view " + std::to_string(viewIndex) + "'s byteOffset " +
                     std::to_string(view.byteOffset) + " plus its own " + std::to_string(byteOffset) +
                     "), which is not " + sizeText + rule);
    }
}

/** Where an accessor's own elements lie (not its sparse part): checked as checkedWindow() checks. */
struct BaseWindow {
    const unsigned char* first = nullptr;
    std::size_t stride = 0;
};

BaseWindow baseWindow(const AccessorContext& context, const tinygltf::Accessor& accessor, int components) {
    const std::size_t elementBytes = componentBytes(accessor.componentType) * std::size_t(components);
    std::size_t stride = elementBytes;
    if (accessor.bufferView >= 0 && std::size_t(accessor.bufferView) < context.model.bufferViews.size()) {
        const std::size_t declared = context.model.bufferViews[std::size_t(accessor.bufferView)].byteStride;
        if (declared != 0) {
            if (declared < elementBytes) {
                context.fail("byte stride " + std::to_string(declared) + " is smaller than an element (" +
                             std::to_string(elementBytes) + " bytes)");
            }
            stride = declared;
        }
    }
    const unsigned char* first =
        checkedWindow(context, accessor.bufferView, accessor.byteOffset, accessor.count, elementBytes, stride, "");
    checkAlignment(context, accessor.bufferView, accessor.byteOffset, componentBytes(accessor.componentType), "");
    return {first, stride};
}

template <typename T>
T loadLittle(const unsigned char* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof value);
    return value;
}

/** One component as glTF defines its value: normalized integers map to [0, 1] or [-1, 1] (the signed ones clamped,
 *  since -128 / 127 would pass -1), other integers keep their value. */
float componentValue(const unsigned char* bytes, int componentType, bool normalized) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return loadLittle<float>(bytes);
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const float value = float(loadLittle<std::int8_t>(bytes));
        return normalized ? std::max(value / 127.0f, -1.0f) : value;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
        const float value = float(loadLittle<std::uint8_t>(bytes));
        return normalized ? value / 255.0f : value;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        const float value = float(loadLittle<std::int16_t>(bytes));
        return normalized ? std::max(value / 32767.0f, -1.0f) : value;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        const float value = float(loadLittle<std::uint16_t>(bytes));
        return normalized ? value / 65535.0f : value;
    }
    default: { // UNSIGNED_INT (checkedAccessor() let nothing else through)
        const double value = double(loadLittle<std::uint32_t>(bytes));
        return float(normalized ? value / 4294967295.0 : value);
    }
    }
}

std::uint32_t unsignedValue(const unsigned char* bytes, int componentType) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return loadLittle<std::uint8_t>(bytes);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return loadLittle<std::uint16_t>(bytes);
    default: return loadLittle<std::uint32_t>(bytes);
    }
}

/** Reads every component of `accessor` through `convert(bytes, componentType)` into `values` (count x components),
 *  then applies the sparse substitutions. */
template <typename Value, typename Convert>
std::vector<Value> readComponents(const AccessorContext& context, const tinygltf::Accessor& accessor, int components,
                                  Convert convert) {
    const std::size_t perComponent = componentBytes(accessor.componentType);
    const std::size_t elementBytes = perComponent * std::size_t(components);
    const std::size_t count = accessor.count;
    std::vector<Value> values;
    // glTF: an accessor without a buffer view holds zeros (the sparse part, if any, overrides some).
    if (accessor.bufferView < 0) {
        values.assign(count * std::size_t(components), Value(0));
    } else {
        const BaseWindow window = baseWindow(context, accessor, components);
        const unsigned char* first = window.first;
        const std::size_t stride = window.stride;
        values.resize(count * std::size_t(components));
        for (std::size_t i = 0; i < count; ++i) {
            const unsigned char* element = first + i * stride;
            for (int c = 0; c < components; ++c) {
                values[i * std::size_t(components) + std::size_t(c)] =
                    convert(element + std::size_t(c) * perComponent, accessor.componentType);
            }
        }
    }
    if (!accessor.sparse.isSparse) {
        return values;
    }

    const auto& sparse = accessor.sparse;
    if (sparse.count < 1 || std::size_t(sparse.count) > count) {
        context.fail("sparse count " + std::to_string(sparse.count) + " is outside [1, " + std::to_string(count) +
                     "] (the accessor's count)");
    }
    if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0) {
        context.fail("sparse byte offsets must not be negative");
    }
    const int indexType = sparse.indices.componentType;
    if (indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
        context.fail("sparse indices must be unsigned byte, short or int (component type " + std::to_string(indexType) +
                     ")");
    }
    const std::size_t substitutions = std::size_t(sparse.count);
    const std::size_t indexBytes = componentBytes(indexType);
    const unsigned char* indices =
        checkedWindow(context, sparse.indices.bufferView, std::size_t(sparse.indices.byteOffset), substitutions,
                      indexBytes, indexBytes, "sparse indices: ");
    checkAlignment(context, sparse.indices.bufferView, std::size_t(sparse.indices.byteOffset), indexBytes,
                   "sparse indices: ");
    const unsigned char* substituted =
        checkedWindow(context, sparse.values.bufferView, std::size_t(sparse.values.byteOffset), substitutions,
                      elementBytes, elementBytes, "sparse values: ");
    checkAlignment(context, sparse.values.bufferView, std::size_t(sparse.values.byteOffset), perComponent,
                   "sparse values: ");
    std::size_t previous = 0;
    for (std::size_t s = 0; s < substitutions; ++s) {
        const std::size_t target = unsignedValue(indices + s * indexBytes, indexType);
        // The specification requires strictly increasing indices; a repeat would make the result order-dependent.
        if (target >= count || (s > 0 && target <= previous)) {
            context.fail("sparse index " + std::to_string(target) + " (substitution " + std::to_string(s) +
                         ") is out of range or not increasing (accessor has " + std::to_string(count) + " elements)");
        }
        previous = target;
        for (int c = 0; c < components; ++c) {
            values[target * std::size_t(components) + std::size_t(c)] =
                convert(substituted + s * elementBytes + std::size_t(c) * perComponent, accessor.componentType);
        }
    }
    return values;
}

} // namespace

int componentsOf(int accessorType) {
    switch (accessorType) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
    }
}

std::size_t accessorCount(const std::string& path, const tinygltf::Model& model, int index, int expectedType,
                          const std::string& role) {
    const AccessorContext context{path, model, index, role};
    const tinygltf::Accessor& accessor = checkedAccessor(context, expectedType);
    // A count its buffer view cannot hold is refused here, before a caller charges or allocates for it.
    if (accessor.bufferView >= 0) baseWindow(context, accessor, componentsOf(expectedType));
    return accessor.count;
}

std::vector<float> readAccessorFloats(const std::string& path, const tinygltf::Model& model, int index,
                                      int expectedType, const std::string& role) {
    const AccessorContext context{path, model, index, role};
    const tinygltf::Accessor& accessor = checkedAccessor(context, expectedType);
    const int components = componentsOf(expectedType);
    const bool normalized = accessor.normalized;
    std::vector<float> values =
        readComponents<float>(context, accessor, components, [normalized](const unsigned char* bytes, int type) {
            return componentValue(bytes, type, normalized);
        });
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (!std::isfinite(values[i])) {
            context.fail("element " + std::to_string(i / std::size_t(components)) + ": non-finite value " +
                         formatNumber(values[i]));
        }
    }
    return values;
}

std::vector<std::uint32_t> readAccessorIntegers(const std::string& path, const tinygltf::Model& model, int index,
                                                int expectedType, const std::string& role) {
    const AccessorContext context{path, model, index, role};
    const tinygltf::Accessor& accessor = checkedAccessor(context, expectedType);
    const int type = accessor.componentType;
    if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
        context.fail("component type must be unsigned byte, short or int (got " + std::to_string(type) + ")");
    }
    return readComponents<std::uint32_t>(context, accessor, componentsOf(expectedType), &unsignedValue);
}

} // namespace inkgraph::detail
