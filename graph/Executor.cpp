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

PlanRun::PlanRun(std::string_view caller, const Plan& plan, const std::vector<std::string_view>& passNames,
                 bool keepAllResources)
    : mCaller(caller), mPlan(plan), mKeepAllResources(keepAllResources), mTimings(plan.passes.size()) {
    for (const PlannedPass& planned : plan.passes) {
        auto found = std::find(passNames.begin(), passNames.end(), planned.name);
        if (found == passNames.end())
            throw std::logic_error(mCaller + ": the plan names pass '" + planned.name +
                                   "' but no such pass object was given");
        mObjectOf.push_back(std::size_t(found - passNames.begin()));
    }
}

void PlanRun::prepare(ExecutorBackend& backend) {
    // Every prepare before any execute: shader builds and uploads stay out of the executes' times.
    for (std::size_t index = 0; index < mPlan.passes.size(); ++index) {
        const PlannedPass& planned = mPlan.passes[index];
        const std::string where = mCaller + ": pass '" + planned.name + "'";
        const double start = nowMilliseconds();
        runPassStep(backend, where, "failed to prepare", mObjectOf[index], planned, PassPhase::Prepare);
        backend.finishStep(planned, PassPhase::Prepare);
        mTimings[index].pass = planned.name;
        mTimings[index].prepareMilliseconds = nowMilliseconds() - start;
    }
}

void PlanRun::execute(ExecutorBackend& backend, std::size_t end) {
    for (; mNext < std::min(end, mPlan.passes.size()); ++mNext) {
        const std::size_t index = mNext;
        const PlannedPass& planned = mPlan.passes[index];
        const std::string where = mCaller + ": pass '" + planned.name + "'";
        const double start = nowMilliseconds();
        runPassStep(backend, where, "failed", mObjectOf[index], planned, PassPhase::Execute);
        // Waiting here makes the milliseconds mean the pass's own work, not whatever the backend queued.
        backend.finishStep(planned, PassPhase::Execute);
        mTimings[index].milliseconds = nowMilliseconds() - start;

        if (const std::string problem = backend.afterPass(planned); !problem.empty())
            throw std::runtime_error(where + " " + problem);
        for (const std::string& written : planned.liveWrites)
            if (!backend.wrote(written))
                throw std::logic_error(where + " did not write its live output '" + written + "'");

        if (mKeepAllResources) continue;
        for (const PlannedResource& resource : mPlan.resources)
            if (!resource.requested && resource.lastUse == index) backend.release(resource.name);
    }
}

std::vector<PassTiming> executePlan(std::string_view caller, const Plan& plan,
                                    const std::vector<std::string_view>& passNames, ExecutorBackend& backend,
                                    bool keepAllResources) {
    PlanRun run(caller, plan, passNames, keepAllResources);
    run.prepare(backend);
    run.execute(backend, plan.passes.size());
    return run.timings();
}

} // namespace inkgraph
