#pragma once
/** @file Reading glTF accessors, shared by the glTF reader's geometry, material and animation parts: every element
 *  bounds-checked against its buffer view (tinygltf checks nothing), sparse substitutions applied, normalized integers
 *  turned into floats by glTF's rules. Internal to the scene layer. */

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

namespace inkgraph::detail {

/** Components per element of a glTF accessor type (TINYGLTF_TYPE_SCALAR 1 ... VEC4 4, MAT2 4, MAT3 9, MAT4 16); 0 for
 *  an unknown type. */
int componentsOf(int accessorType);

/** Accessor `index` of `model` as floats, componentsOf(expectedType) per element: float components as they are;
 *  normalized integer components by glTF's rule (e.g. max(c / 32767, -1) for signed short, c / 255 for unsigned
 *  byte); non-normalized integers (KHR_mesh_quantization) as their value; sparse substitutions applied (without a
 *  bufferView the base values are zeros). Every read is bounds-checked and every value finite; failures throw
 *  through throwLoadError(path, "<role> accessor <n>: ..."). */
std::vector<float> readAccessorFloats(const std::string& path, const tinygltf::Model& model, int index,
                                      int expectedType, const std::string& role);

/** Unsigned integer components (indices, JOINTS_0): unsigned byte, short or int, sparse applied, bounds-checked. */
std::vector<std::uint32_t> readAccessorIntegers(const std::string& path, const tinygltf::Model& model, int index,
                                                int expectedType, const std::string& role);

/** The element count of accessor `index` after checking its index, type and component type and that its buffer view
 *  holds that many, without reading it: for MeshBudget charges and count comparisons before anything is allocated. */
std::size_t accessorCount(const std::string& path, const tinygltf::Model& model, int index, int expectedType,
                          const std::string& role);

} // namespace inkgraph::detail
