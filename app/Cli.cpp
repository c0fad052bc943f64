#include "app/Cli.h"

#include "app/BatchRun.h"
#include "app/ImageFiles.h"
#include "app/Render.h"
#include "app/StyleFile.h"
#include "app/TemporaryFiles.h"
#include "gl/GraphExecutor.h"
#include "gl/HeadlessContext.h"
#include "gl/ShaderLibrary.h"
#include "scene/Scene.h"

#include <opencv2/core.hpp>

#include <filesystem>
#include <iostream>

namespace inkgraph {

namespace {

int runRenderCommand(const std::vector<std::string>& arguments, std::ostream& out, std::ostream& err) {
    try {
        std::error_code noFolder;
        (void)std::filesystem::current_path(noFolder);
        if (noFolder)
            throw FileError("runCommandLine(): the working folder cannot be found (" + noFolder.message() +
                            "; was it deleted?); run inkgraph from an existing folder");
        const SourcedArguments expanded = expandStyleFile(arguments);
        const RenderOptions options = parseRenderOptions(expanded.arguments, expanded.origins);
        if (options.help) {
            out << renderHelp();
            return kExitOk;
        }
        return renderBatch(options, std::cin, out, err);
    } catch (const UsageError& error) {
        err << "inkgraph: " << error.what() << "\n(see: inkgraph help render)\n";
        return kExitUsage;
    } catch (const SceneError& error) {
        err << "inkgraph: " << error.what() << "\n";
        return kExitBadInput;
    } catch (const InputFileError& error) {
        err << "inkgraph: " << error.what() << "\n";
        return kExitBadInput;
    } catch (const HeadlessContextError& error) {
        err << "inkgraph: " << error.what() << "\n";
        return kExitNoGl;
    } catch (const FileError& error) {
        err << "inkgraph: " << error.what() << "\n";
        return kExitOutput;
    } catch (const ShaderSourceError& error) {
        err << "inkgraph: " << error.what() << "\n";
        return kExitNoGl;
    } catch (const std::bad_alloc&) {
        err << "inkgraph: out of memory; make the image smaller (--size, --supersample) or request and dump fewer "
               "buffers\n(see: inkgraph help render)\n";
        return kExitUsage;
    } catch (const cv::Exception& error) {
        if (error.code != cv::Error::StsNoMem) {
            err << "inkgraph: internal error: " << error.what() << "\n";
            return kExitInternal;
        }
        err << "inkgraph: out of memory (" << error.err
            << "); make the image smaller (--size, --supersample) or "
               "request and dump fewer buffers\n(see: inkgraph help render)\n";
        return kExitUsage;
    } catch (const std::exception& error) {
        err << "inkgraph: internal error: " << error.what() << "\n";
        return kExitInternal;
    }
}

} // namespace

int runCommandLine(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
    std::vector<std::string> arguments(argv + std::min(argc, 1), argv + argc);
    if (arguments.empty()) {
        err << mainHelp();
        return kExitUsage;
    }
    if (arguments[0] == "--help" || arguments[0] == "-h" || arguments[0] == "help") {
        if (arguments.size() > 1 && arguments[1] != "render") {
            err << "inkgraph: no help on '" << arguments[1] << "' (topics: render)\n";
            return kExitUsage;
        }
        out << (arguments.size() > 1 ? renderHelp() : mainHelp());
        return kExitOk;
    }
    if (arguments[0] == "--version") {
        out << "inkgraph " << INKGRAPH_VERSION << "\n";
        return kExitOk;
    }
    if (arguments[0] != "render") {
        err << "inkgraph: unknown command '" << arguments[0] << "' (try: inkgraph --help)\n";
        return kExitUsage;
    }
    arguments.erase(arguments.begin());
    removeTemporariesOnSignals();
    const int exitCode = runRenderCommand(arguments, out, err);
    // Output that cannot be written (--help > /dev/full, a closed pipe) is a failed run, not a silent one.
    try {
        requireStandardOutputWritten(out);
    } catch (const FileError& error) {
        if (exitCode == kExitOk) err << "inkgraph: " << error.what() << "\n";
        return exitCode == kExitOk ? kExitOutput : exitCode;
    }
    return exitCode;
}

} // namespace inkgraph
