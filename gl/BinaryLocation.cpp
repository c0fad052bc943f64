#include "gl/BinaryLocation.h"

#include <dlfcn.h>
#include <link.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>

namespace inkgraph {
namespace {

/** Lies in this binary, whichever binary that is: its address is what dladdr() is asked about. */
const char kAnchor = 0;

/** The file mapped at `address`, from /proc/self/maps; empty if none is. */
std::filesystem::path fileMappedAt(const void* address) {
    std::ifstream maps("/proc/self/maps");
    const auto wanted = reinterpret_cast<std::uintptr_t>(address);
    // "start-end perms offset device inode   path"
    for (std::string line; std::getline(maps, line);) {
        std::istringstream fields(line);
        std::string range, perms, offset, device, inode;
        fields >> range >> perms >> offset >> device >> inode;
        const std::size_t dash = range.find('-');
        if (dash == std::string::npos) continue;
        const std::uintptr_t start = std::stoull(range.substr(0, dash), nullptr, 16);
        const std::uintptr_t end = std::stoull(range.substr(dash + 1), nullptr, 16);
        if (wanted < start || wanted >= end) continue;
        std::string path;
        std::getline(fields >> std::ws, path);
        const std::string deleted = " (deleted)"; // the file was replaced while this process runs
        if (path.size() > deleted.size() && path.compare(path.size() - deleted.size(), deleted.size(), deleted) == 0)
            path.resize(path.size() - deleted.size());
        return path.rfind('/', 0) == 0 ? std::filesystem::path(path) : std::filesystem::path();
    }
    return {};
}

std::filesystem::path findContainingBinary() {
    Dl_info info{};
    link_map* map = nullptr;
    std::filesystem::path binary;
    if (dladdr1(&kAnchor, &info, reinterpret_cast<void**>(&map), RTLD_DL_LINKMAP) != 0 && map != nullptr &&
        map->l_name != nullptr && map->l_name[0] != '\0')
        binary = map->l_name; // a shared library, as it was loaded
    // The main program's link map has no name, and dladdr() gives only argv[0]. The file mapped where this code lies
    // is right also when the program was started through the dynamic loader (ld.so PROGRAM: /proc/self/exe is then
    // the loader).
    if (binary.empty()) binary = fileMappedAt(&kAnchor);
    if (binary.empty()) binary = "/proc/self/exe";
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
