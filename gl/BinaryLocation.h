#pragma once
/** @file Where the binary that holds inkgraph's code is, and where an installation keeps its files relative to it.
 *  The binary is the executable or the shared library this code is linked into (the installed libinkgraph.so loaded
 *  by a Python interpreter finds its own files, not the interpreter's), so an installed tree can move: nothing here
 *  depends on the install prefix the build was configured with. No GL: the OpenImageIO module's lookup
 *  (render/ImageFiles) uses it too. */

#include <filesystem>
#include <vector>

namespace inkgraph {

/** The executable or shared library this code is linked into, links resolved; empty if the system cannot tell.
 *  dladdr() of an object of ours names the shared library; for the main program it gives only argv[0], so that
 *  case takes the file mapped at that object's address (/proc/self/maps), which is also right for a program started
 *  through the dynamic loader, whose /proc/self/exe is the loader. Computed once. */
const std::filesystem::path& containingBinary();

/** Whether containingBinary() lies in the build tree it was built in. Only then may the source tree serve files
 *  (the shaders) as a last resort: an installed binary must never read the source tree it was built from. */
bool runsFromBuildTree();

/** Where an installed file would be for each install prefix the binary may sit in, in this order: `<dir>/..` (the
 *  executable in bin/, a library in lib/) and `<dir>/../..` (a library in lib/<multiarch>/), where <dir> is
 *  containingBinary()'s folder. `installedPath` is relative to the prefix (e.g. "share/inkgraph/shaders"); an
 *  absolute one (a build configured with absolute GNUInstallDirs folders) is the only candidate. Lexically
 *  normalised, so errors can show them. */
std::vector<std::filesystem::path> installedCandidates(const std::filesystem::path& installedPath);

/** inkgraph's data folder relative to the install prefix: `${CMAKE_INSTALL_DATADIR}/inkgraph`, holding shaders/
 *  and shademaps/. */
std::filesystem::path installedDataFolder();

/** installedDataFolder() / "shaders". */
std::filesystem::path installedShaderFolder();

/** The private libraries' folder relative to the install prefix (the OpenImageIO module):
 *  `${CMAKE_INSTALL_LIBDIR}/inkgraph`. */
std::filesystem::path installedModuleFolder();

} // namespace inkgraph
