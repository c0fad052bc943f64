#pragma once
/** @file `inkgraph render`: load, frame, build the graph, compile, execute, write. */

#include "app/Options.h"
#include "passes/FrameParams.h"
#include "passes/shade/ShadeMap.h"
#include "scene/Camera.h"

#include <cstddef>
#include <iosfwd>
#include <stdexcept>

namespace inkgraph {

/** An input file other than the model (--shademap) is missing or unusable; exit code 3 like a bad model. The message
 *  names the flag and the file. */
class InputFileError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/** Exit codes of the command line (README "Errors and exit codes"). */
enum ExitCode : int {
    kExitOk = 0,
    kExitInternal = 1,
    kExitUsage = 2,
    kExitBadInput = 3,
    kExitNoGl = 4,
    kExitOutput = 5,
};

/** One buffer must stay under 2 GiB: GL's byte counts are 32-bit (llvmpipe refuses larger RGBA32F targets). */
inline constexpr std::size_t kMaxTextureBytes = std::size_t(2) << 30;

/** --memory-limit, else half the machine's memory (at least 1 GiB): the bound on one model load (checked before
 *  allocating, from the file's declared counts) and on the buffers one plan keeps (checked before any GL work). */
std::size_t memoryLimitOf(const RenderOptions& options);

/** Reads and checks a --shademap file: 8-bit, 1 to 4 channels, at most 4096 a side (judged from the header before
 *  the pixels are read), one row when `oneDimensional`. Throws InputFileError naming --shademap and the file. */
ShadeMap readShadeMapFile(const std::string& path, bool oneDimensional);

/** The camera the flags ask for (--eye, --target, --up, --fov, --clip, --size); resolveCamera() fills the rest. */
CameraRequest cameraRequestOf(const RenderOptions& options);

/** The per-still parameters of `camera` for the options (--light, else the file's light, else the default key
 *  light; --background) and the model's bounding sphere. */
FrameParams frameParamsOf(const RenderOptions& options, const Scene& scene, const Camera& camera,
                          const BoundingSphere& sphere);

/** Renders as the options say. `out` receives --print-plan, `log` the progress lines. Throws the layer's own
 *  exceptions (SceneError, InputFileError, HeadlessContextError, FileError, UsageError, GraphError); runCommandLine maps them to
 *  exit codes. */
void renderStill(const RenderOptions& options, std::ostream& out, std::ostream& log);

/** The whole CLI: parses argv, runs, catches once, prints "inkgraph: <message>" to `err`, returns the exit code. */
int runCommandLine(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

/** The file name --dump gives a resource: "gbuffer.normal" -> "normal.exr", the shading colour -> "shading.png",
 *  "composite.final" -> "final.png", "<type>.lines" -> "lines-<type>.png"; others "<pass>-<field>.exr|png". */
std::string dumpFileName(const std::string& resource, bool isFloat, const std::string& shadingResource);

} // namespace inkgraph
