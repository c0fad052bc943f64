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
    } catch (...) {
        const ErrorReport report = reportOf(std::current_exception());
        err << "inkgraph: " << report.message << "\n";
        if (report.showsHelpHint) err << "(see: inkgraph help render)\n";
        return report.exitCode;
    }
}

} // namespace

ErrorReport reportOf(const std::exception_ptr& error) {
    const std::string outOfMemory = "make the image smaller (--size, --supersample) or request and dump fewer buffers";
    try {
        std::rethrow_exception(error);
    } catch (const UsageError& usage) {
        return {kExitUsage, usage.what(), true};
    } catch (const SceneError& input) {
        return {kExitBadInput, input.what(), false};
    } catch (const InputFileError& input) {
        return {kExitBadInput, input.what(), false};
    } catch (const HeadlessContextError& context) {
        return {kExitNoGl, context.what(), false};
    } catch (const FileError& output) {
        return {kExitOutput, output.what(), false};
    } catch (const ShaderSourceError& shaders) {
        return {kExitNoGl, shaders.what(), false};
    } catch (const std::bad_alloc&) {
        return {kExitUsage, "out of memory; " + outOfMemory, true};
    } catch (const cv::Exception& opencv) {
        if (opencv.code != cv::Error::StsNoMem) return {kExitInternal, std::string("internal error: ") + opencv.what()};
        return {kExitUsage, "out of memory (" + opencv.err + "); " + outOfMemory, true};
    } catch (const std::exception& other) {
        return {kExitInternal, std::string("internal error: ") + other.what()};
    } catch (...) {
        return {kExitInternal, "internal error: an exception that is not a std::exception"};
    }
}

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
