#include "gl/BinaryLocation.h"

#include <dlfcn.h>
#include <link.h>

#include <algorithm>
#include <system_error>

namespace inkgraph {
namespace {

/** Lies in this binary, whichever binary that is: its address is what dladdr() is asked about. */
const char kAnchor = 0;

std::filesystem::path findContainingBinary() {
    Dl_info info{};
    link_map* map = nullptr;
    std::filesystem::path binary;
    if (dladdr1(&kAnchor, &info, reinterpret_cast<void**>(&map), RTLD_DL_LINKMAP) != 0 && map != nullptr &&
        map->l_name != nullptr && map->l_name[0] != '\0')
        binary = map->l_name; // a shared library, as it was loaded
    else
        binary = "/proc/self/exe"; // the main program: its link map has no name, and dli_fname is only argv[0]
    std::error_code error;
    std::filesystem::path resolved = std::filesystem::weakly_canonical(binary, error);
    return error ? std::filesystem::path() : resolved;
}

/** Whether `inner` is `outer` or lies below it (both canonical). */
bool within(const std::filesystem::path& inner, const std::filesystem::path& outer) {
    const auto [outerEnd, innerEnd] = std::mismatch(outer.begin(), outer.end(), inner.begin(), inner.end());
    return outerEnd == outer.end();
}

} // namespace

const std::filesystem::path& containingBinary() {
    static const std::filesystem::path kBinary = findContainingBinary();
    return kBinary;
}

bool runsFromBuildTree() {
    static const bool kInBuildTree = [] {
        std::error_code error;
        const std::filesystem::path buildTree = std::filesystem::weakly_canonical(INKGRAPH_BUILD_TREE, error);
        return !error && !containingBinary().empty() && within(containingBinary(), buildTree);
    }();
    return kInBuildTree;
}

std::vector<std::filesystem::path> installedCandidates(const std::filesystem::path& installedPath) {
    if (installedPath.is_absolute()) return {installedPath.lexically_normal()};
    if (containingBinary().empty()) return {};
    const std::filesystem::path folder = containingBinary().parent_path();
    return {(folder / ".." / installedPath).lexically_normal(), (folder / "../.." / installedPath).lexically_normal()};
}

std::filesystem::path installedDataFolder() { return std::filesystem::path(INKGRAPH_INSTALL_DATADIR) / "inkgraph"; }

std::filesystem::path installedShaderFolder() { return installedDataFolder() / "shaders"; }

std::filesystem::path installedModuleFolder() { return std::filesystem::path(INKGRAPH_INSTALL_LIBDIR) / "inkgraph"; }

} // namespace inkgraph
