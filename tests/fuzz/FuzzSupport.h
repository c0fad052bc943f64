#pragma once
/** @file What the fuzz targets share. Each target is one LLVMFuzzerTestOneInput(): under libFuzzer (scripts/fuzz.sh,
 *  clang, -DINKGRAPH_FUZZ=ON) it is driven by coverage; in every ordinary build it is linked with FuzzReplayMain.cpp
 *  and replays the corpus and the regression inputs kept in tests/fuzz/ as a ctest test.
 *
 *  The contract every target checks: bad input ends in the one documented exception type of the reader. Anything
 *  else (another exception, a crash, a sanitizer report, a leak, a hang) escapes and fails the run. */

#include "scene/Scene.h"

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace inkgraph::fuzz {

inline std::string_view bytesOf(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

/** A budget that makes the memory limit reachable from small inputs (a glTF node list instancing one mesh, a binary
 *  STL header), so the limit's own path is fuzzed, not the machine's memory. */
inline constexpr std::size_t kFuzzMemoryLimitBytes = std::size_t(256) << 20;

/** Loads a model from bytes as loadScene() would load a file called `name`, then derives what the line passes derive
 *  from it (edge adjacency, curvature, object-space suggestive contours from one eye), so meshes that load but are
 *  odd (slivers, non-manifold fans, one triangle) reach that code too. SceneError is the only expected failure. */
void loadAndDerive(const char* name, std::string_view content);

} // namespace inkgraph::fuzz
