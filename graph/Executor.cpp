#include "graph/Executor.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <new>

namespace inkgraph {
namespace {

double nowMilliseconds() {
    using Clock = std::chrono::steady_clock;
    return std::chrono::duration<double, std::milli>(Clock::now().time_since_epoch()).count();
}

/** Runs one step of a pass, naming the pass in what it throws. Failures the caller reports by their cause keep their
 *  type: the backend's (shaders that cannot be read, the driver out of memory), and memory running out. */
void runPassStep(ExecutorBackend& backend, const std::string& where, const char* failed, std::size_t passIndex,
                 const PlannedPass& planned, PassPhase phase) {
    try {
        backend.runPass(passIndex, planned, phase);
    } catch (...) {
        const std::exception_ptr failure = std::current_exception();
        backend.rethrowByCause(failure, where);
        try {
            std::rethrow_exception(failure);
        } catch (const std::bad_alloc&) {
            throw OutOfMemoryError(where + " ran out of memory");
        } catch (const std::exception& error) {
            // Nested, so a caller that knows the cause's type (the app: a SceneError is bad input) can still tell.
            std::throw_with_nested(std::runtime_error(where + " " + failed + ": " + error.what()));
        }
    }
}

} // namespace

std::vector<PassTiming> executePlan(std::string_view caller, const Plan& plan,
                                    const std::vector<std::string_view>& passNames, ExecutorBackend& backend,
                                    bool keepAllResources) {
    const std::string function(caller);
    std::vector<std::size_t> objectOf; // plan index -> index into passNames
    for (const PlannedPass& planned : plan.passes) {
        auto found = std::find(passNames.begin(), passNames.end(), planned.name);
        if (found == passNames.end())
            throw std::logic_error(function + ": the plan names pass '" + planned.name +
                                   "' but no such pass object was given");
        objectOf.push_back(std::size_t(found - passNames.begin()));
    }

    // Every prepare before any execute: shader builds and uploads stay out of the executes' times.
    std::vector<PassTiming> timings(plan.passes.size());
    for (std::size_t index = 0; index < plan.passes.size(); ++index) {
        const PlannedPass& planned = plan.passes[index];
        const std::string where = function + ": pass '" + planned.name + "'";
        const double start = nowMilliseconds();
        runPassStep(backend, where, "failed to prepare", objectOf[index], planned, PassPhase::Prepare);
        backend.finishStep(planned, PassPhase::Prepare);
        timings[index].pass = planned.name;
        timings[index].prepareMilliseconds = nowMilliseconds() - start;
    }

    for (std::size_t index = 0; index < plan.passes.size(); ++index) {
        const PlannedPass& planned = plan.passes[index];
        const std::string where = function + ": pass '" + planned.name + "'";
        const double start = nowMilliseconds();
        runPassStep(backend, where, "failed", objectOf[index], planned, PassPhase::Execute);
        // Waiting here makes the milliseconds mean the pass's own work, not whatever the backend queued.
        backend.finishStep(planned, PassPhase::Execute);
        timings[index].milliseconds = nowMilliseconds() - start;

        if (const std::string problem = backend.afterPass(planned); !problem.empty())
            throw std::runtime_error(where + " " + problem);
        for (const std::string& written : planned.liveWrites)
            if (!backend.wrote(written))
                throw std::logic_error(where + " did not write its live output '" + written + "'");

        if (keepAllResources) continue;
        for (const PlannedResource& resource : plan.resources)
            if (!resource.requested && resource.lastUse == index) backend.release(resource.name);
    }
    return timings;
}

} // namespace inkgraph
