#pragma once
/** @file `inkgraph --version`: the version and the git commit, and with --verbose what the program runs on. */

#include <iosfwd>
#include <string>

namespace inkgraph {

/** "inkgraph 0.1.0 (git 6e6311c)". */
std::string versionLine();

/** versionLine(), then one "name: value" line each for the binary, the shader folder in use and where it was found,
 *  EGL (version, vendor, platform), OpenGL (renderer, version, vendor), the OpenImageIO module (loaded to ask it), and
 *  the libraries' versions. Makes a GL context. Returns kExitOk, or kExitNoGl when no context can be made or no
 *  shader folder is found (what `inkgraph render` would exit with); a module that does not load is reported, not an
 *  error: only formats other than PNG need it. */
int writeVerboseVersion(std::ostream& out);

} // namespace inkgraph
