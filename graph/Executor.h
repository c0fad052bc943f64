#pragma once
/** @file The executor loop, apart from any backend (after Filament's FrameGraph, whose loop is tested on a no-op
 *  backend): order the pass objects by the plan, prepare them all, execute them in order, time each, check that
 *  every live output was written, and release each resource after its last reader. gl/GraphExecutor is the GL
 *  backend; tests/graph/ExecutorTest.cpp runs the loop on a recording one without a context. */

#include "graph/Plan.h"

#include <cstddef>
#include <exception>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace inkgraph {

/** A pass's CPU work ran out of memory (std::bad_alloc, or what a backend knows as running out), named by the
 *  pass. A GPU driver running out is the backend's own type (gl: GlOutOfMemoryError). */
class OutOfMemoryError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct PassTiming {
    std::string pass;
    double prepareMilliseconds = 0.0; ///< shader compilation and uploads, once per run
    double milliseconds = 0.0;        ///< execute(): wall time from the call to the backend's finishStep() returning
};

enum class PassPhase { Prepare, Execute };

/** What the loop asks of a backend. Pass objects are the backend's own type: the loop knows them by position in
 *  the list whose names it was given. */
class ExecutorBackend {
public:
    virtual ~ExecutorBackend() = default;
    /** Runs the prepare or execute of the pass object at `passIndex` (in the list given to executePlan()) for
     *  `planned`. */
    virtual void runPass(std::size_t passIndex, const PlannedPass& planned, PassPhase phase) = 0;
    /** Inside the timed span, after runPass() returned: wait for the work the pass queued (GL: glFinish), so the
     *  time is the pass's own. */
    virtual void finishStep(const PlannedPass& planned, PassPhase phase) {
        (void)planned;
        (void)phase;
    }
    /** After an execute, outside its time: restores the backend's state for the next pass and returns a problem the
     *  pass left behind (GL: "raised GL_INVALID_ENUM"), or an empty string. */
    virtual std::string afterPass(const PlannedPass& planned) {
        (void)planned;
        return {};
    }
    /** Called in a catch block with a failure escaping runPass(): rethrows the failures the backend reports by
     *  cause (their own type, `where` prefixed) and returns for the others, which the loop wraps itself. */
    virtual void rethrowByCause(const std::exception_ptr& failure, const std::string& where) const {
        (void)failure;
        (void)where;
    }
    /** Whether the pass just executed wrote `resource`. */
    virtual bool wrote(const std::string& resource) const = 0;
    /** Frees `resource`: nothing later reads it and nobody asked to keep it. */
    virtual void release(const std::string& resource) = 0;
};

/** One run of a plan, step by step, so its passes may execute on more than one backend: the GPU passes on the
 *  thread that holds the context, the host tail (Plan::hostTailStart()) afterwards on a worker with a backend that
 *  needs no context. `passNames` are the names of the pass objects the backends hold, in their order; messages start
 *  with `caller` ("GraphExecutor::run()"). Throws std::logic_error for a planned pass with no object. */
class PlanRun {
public:
    PlanRun(std::string_view caller, const Plan& plan, const std::vector<std::string_view>& passNames,
            bool keepAllResources);
    /** Prepares every planned pass (timed as prepareMilliseconds). Once, first. */
    void prepare(ExecutorBackend& backend);
    /** Executes the passes from the next one not yet executed up to (not including) `end`, in plan order, releasing
     *  every resource that is not requested after its lastUse unless keepAllResources. Throws std::logic_error for a
     *  live output a pass did not write; std::runtime_error for what afterPass() reports; a failing step's exception
     *  is rethrown naming the pass: OutOfMemoryError for std::bad_alloc, the backend's types (rethrowByCause()), else
     *  std::runtime_error. */
    void execute(ExecutorBackend& backend, std::size_t end);
    /** The index of the next pass to execute (plan.passes.size() once all have). */
    std::size_t next() const { return mNext; }
    const std::vector<PassTiming>& timings() const { return mTimings; }

private:
    std::string mCaller;
    const Plan& mPlan;
    bool mKeepAllResources;
    std::vector<std::size_t> mObjectOf; ///< plan index -> index into passNames
    std::vector<PassTiming> mTimings;
    std::size_t mNext = 0;
};

/** Runs the whole of `plan` on `backend` (PlanRun: prepare, then execute every pass) and returns its timings. */
std::vector<PassTiming> executePlan(std::string_view caller, const Plan& plan,
                                    const std::vector<std::string_view>& passNames, ExecutorBackend& backend,
                                    bool keepAllResources);

} // namespace inkgraph
