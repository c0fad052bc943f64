#include "api/Internal.h"

#include "render/ErrorReport.h"

namespace inkgraph::api {
inline namespace INKGRAPH_ABI_NAMESPACE {
namespace {

Error::Kind kindOf(ExitCode exitCode) {
    switch (exitCode) {
    case kExitUsage: return Error::Kind::Usage;
    case kExitBadInput: return Error::Kind::Input;
    case kExitNoGl: return Error::Kind::Context;
    case kExitOutput: return Error::Kind::Output;
    case kExitOk:
    case kExitInternal: break;
    }
    return Error::Kind::Render;
}

} // namespace

int Error::exitCode() const noexcept {
    switch (mKind) {
    case Kind::Usage: return kExitUsage;
    case Kind::Input: return kExitBadInput;
    case Kind::Context: return kExitNoGl;
    case Kind::Output: return kExitOutput;
    case Kind::Render: break;
    }
    return kExitInternal;
}

Error errorOf(const std::exception_ptr& error) {
    const ErrorReport report = reportOf(error);
    return Error(kindOf(report.exitCode), report.message);
}

} // namespace INKGRAPH_ABI_NAMESPACE
} // namespace inkgraph::api
