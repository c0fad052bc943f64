#pragma once
/** @file `inkgraph render`: load, frame, build the graph, compile, execute, write. */

#include "app/Batch.h"
#include "app/Options.h"
#include "gl/HeadlessContext.h"
#include "gl/ShaderLibrary.h"
#include "passes/FrameParams.h"
#include "passes/shade/ShadeMap.h"
#include "scene/Camera.h"

#include <cstddef>
#include <iosfwd>
#include <optional>
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

/** Where a still stands in a batch, for its --stats. */
struct BatchPosition {
    BatchModel model;
    std::size_t listLength = 0;
};

/** What one still did, for the batch's progress line. */
struct StillReport {
    std::size_t triangles = 0;
    double milliseconds = 0.0;
};

/** The stills of one process: one GL context, made by the first still that renders, and one ShaderLibrary that
 *  keeps every program, so a batch makes the context once and compiles each program once (--stats:
 *  context_reused, programs_compiled, programs_reused). Members are declared so the programs are deleted before
 *  the context. */
class RenderSession {
public:
    /** `out` receives --print-plan, `log` the progress lines. */
    RenderSession(std::ostream& out, std::ostream& log);
    ~RenderSession();
    RenderSession(const RenderSession&) = delete;
    RenderSession& operator=(const RenderSession&) = delete;

    /** Renders one still as the options say (the model and outputs of that still: app/Batch.h stillOptions()).
     *  With `batch`, the still's own progress lines are left to the caller. Throws the layer's own exceptions
     *  (SceneError, InputFileError, HeadlessContextError, FileError, UsageError, GraphError); runCommandLine maps
     *  them to exit codes. */
    StillReport render(const RenderOptions& options, const BatchPosition* batch = nullptr);

private:
    std::ostream& mOut;
    std::ostream& mLog;
    std::optional<HeadlessContext> mContext;
    ShaderLibrary mShaders;
};

/** One still in a session of its own. */
void renderStill(const RenderOptions& options, std::ostream& out, std::ostream& log);

/** Every model of the run (app/Batch.h) in one RenderSession, with a progress line per model on `log` (unless
 *  --quiet) when there are several. A model that cannot be read (exit 3) is reported and the others go on; the
 *  first such failure's exit code is returned after the last model. Any other error stops the batch (models done
 *  so far keep their outputs). `standardInput` is read for --list -. Returns the exit code. */
int renderBatch(const RenderOptions& options, std::istream& standardInput, std::ostream& out, std::ostream& log);

/** The whole CLI: parses argv, runs, catches once, prints "inkgraph: <message>" to `err`, returns the exit code.
 *  `--list -` reads std::cin. */
int runCommandLine(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

/** The file name --dump gives a resource: "gbuffer.normal" -> "normal.exr", the shading colour -> "shading.png",
 *  "composite.final" -> "final.png", "<type>.lines" -> "lines-<type>.png"; others "<pass>-<field>.exr|png". */
std::string dumpFileName(const std::string& resource, bool isFloat, const std::string& shadingResource);

} // namespace inkgraph
