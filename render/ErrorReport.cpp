#include "render/ErrorReport.h"

#include "gl/HeadlessContext.h"
#include "gl/ShaderLibrary.h"
#include "render/ImageFiles.h"
#include "render/Messages.h"
#include "render/StillRenderer.h"
#include "render/UsageError.h"
#include "scene/Scene.h"

#include <opencv2/core.hpp>

#include <new>
#include <stdexcept>

namespace inkgraph {

const std::vector<ExitCodeMeaning>& exitCodeMeanings() {
    static const std::vector<ExitCodeMeaning> kMeanings = {
        {kExitOk, "done"},
        {kExitUsage, "bad command line or style file, or a request too big for memory"},
        {kExitBadInput, "unreadable or invalid model or shade map (in a batch: some model)"},
        {kExitNoGl, "no OpenGL/EGL or no shaders"},
        {kExitOutput, "an output could not be written"},
        {kExitInternal, "anything else"},
    };
    return kMeanings;
}

namespace {

ErrorReport unboundedReportOf(const std::exception_ptr& error) {
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

} // namespace

ErrorReport reportOf(const std::exception_ptr& error) {
    ErrorReport report = unboundedReportOf(error);
    report.message = boundedMessage(report.message);
    return report;
}

} // namespace inkgraph
