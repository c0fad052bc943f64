// graph/Executor's loop on a recording no-op backend (no GL), as Filament tests its FrameGraph: the order of prepares
// and executes, where resources are released, and how failures are named.
#include "graph/Executor.h"

#include "FakePass.h"

#include <gtest/gtest.h>

#include <functional>
#include <new>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph::test {
namespace {

using Names = std::vector<std::string>;

/** A backend failure type the loop must not wrap (as GL's out-of-memory error is not). */
class BackendFailure : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/** Records every call as "prepare a", "execute a", "release a.out"; an execute writes the pass's live outputs
 *  (but those in `unwritten`); `fail` may throw for a step, by its event name. */
class RecordingBackend final : public ExecutorBackend {
public:
    explicit RecordingBackend(Names passNames) : mPassNames(std::move(passNames)) {}

    void runPass(std::size_t passIndex, const PlannedPass& planned, PassPhase phase) override {
        const std::string event =
            std::string(phase == PassPhase::Prepare ? "prepare " : "execute ") + mPassNames.at(passIndex);
        EXPECT_EQ(mPassNames.at(passIndex), planned.name) << "the loop handed another pass's plan entry";
        events.push_back(event);
        if (fail) fail(event);
        if (phase == PassPhase::Execute)
            for (const std::string& resource : planned.liveWrites)
                if (!unwritten.count(resource)) written.insert(resource);
    }
    void finishStep(const PlannedPass& planned, PassPhase phase) override {
        events.push_back(std::string(phase == PassPhase::Prepare ? "finish prepare " : "finish execute ") +
                         planned.name);
    }
    std::string afterPass(const PlannedPass& planned) override {
        events.push_back("after " + planned.name);
        return planned.name == problemPass ? "raised a backend error" : "";
    }
    void rethrowByCause(const std::exception_ptr& failure, const std::string& where) const override {
        try {
            std::rethrow_exception(failure);
        } catch (const BackendFailure& error) {
            throw BackendFailure(where + ": " + error.what());
        } catch (...) {
        }
    }
    bool wrote(const std::string& resource) const override { return written.count(resource) != 0; }
    void release(const std::string& resource) override {
        events.push_back("release " + resource);
        written.erase(resource);
    }

    std::vector<std::string_view> names() const { return {mPassNames.begin(), mPassNames.end()}; }

    Names events;
    std::set<std::string> written;
    std::set<std::string> unwritten;
    std::string problemPass;
    std::function<void(const std::string& event)> fail;

private:
    Names mPassNames;
};

/** Only the events that start with `prefix`. */
Names eventsStartingWith(const Names& events, const std::string& prefix) {
    Names result;
    for (const std::string& event : events)
        if (event.rfind(prefix, 0) == 0) result.push_back(event);
    return result;
}

/** c reads b reads a, registered backwards; the plan requests c.out. */
Plan chainPlan(FakeGraph& graph) {
    graph.addPass("c", {"b.out"}, {{"out"}});
    graph.addPass("b", {"a.out"}, {{"out"}});
    graph.addPass("a", {}, {{"out"}});
    return graph.compile({"c.out"});
}

TEST(ExecutorTest, PreparesEveryPassThenExecutesInPlanOrder) {
    FakeGraph graph;
    const Plan plan = chainPlan(graph);
    RecordingBackend backend({"c", "b", "a"}); // the caller's order, not the plan's
    const std::vector<PassTiming> timings = executePlan("run()", plan, backend.names(), backend, false);

    EXPECT_EQ(backend.events,
              (Names{"prepare a", "finish prepare a", "prepare b", "finish prepare b", "prepare c", "finish prepare c",
                     "execute a", "finish execute a", "after a", "execute b", "finish execute b", "after b",
                     "release a.out", "execute c", "finish execute c", "after c", "release b.out"}));
    ASSERT_EQ(timings.size(), 3u);
    EXPECT_EQ(timings[0].pass, "a");
    EXPECT_EQ(timings[1].pass, "b");
    EXPECT_EQ(timings[2].pass, "c");
    for (const PassTiming& timing : timings) {
        EXPECT_GE(timing.prepareMilliseconds, 0.0);
        EXPECT_GE(timing.milliseconds, 0.0);
    }
}

TEST(ExecutorTest, ReleasesEachResourceAfterItsLastReaderAndKeepsRequestedOnes) {
    FakeGraph graph;
    graph.addPass("gbuffer", {}, {{"normal"}, {"depth"}});
    graph.addPass("shade", {"gbuffer.normal"}, {{"color"}});
    graph.addPass("lines", {"gbuffer.depth"}, {{"mask"}});
    graph.addPass("composite", {"shade.color", "lines.mask"}, {{"final"}});
    const Plan plan = graph.compile({"composite.final", "gbuffer.normal"});
    RecordingBackend backend({"gbuffer", "shade", "lines", "composite"});
    executePlan("run()", plan, backend.names(), backend, false);

    // gbuffer.normal is requested: never released, though shade is its last reader.
    EXPECT_EQ(eventsStartingWith(backend.events, "release "),
              (Names{"release gbuffer.depth", "release shade.color", "release lines.mask"}));
    const Names order = eventsStartingWith(backend.events, "");
    auto position = [&](const std::string& event) {
        return std::find(order.begin(), order.end(), event) - order.begin();
    };
    EXPECT_LT(position("execute lines"), position("release gbuffer.depth"));
    EXPECT_LT(position("release gbuffer.depth"), position("execute composite"));
    EXPECT_LT(position("execute composite"), position("release shade.color"));
    EXPECT_EQ(backend.written, (std::set<std::string>{"gbuffer.normal", "composite.final"}));
}

TEST(ExecutorTest, APlanRunInTwoHalvesOnTwoBackendsDoesWhatOneRunDoes) {
    // The GPU passes on the context's thread, the host tail on a worker's backend (gl/GraphExecutor.h).
    FakeGraph graph;
    graph.addPass("gbuffer", {}, {{"normal"}, {"depth"}});
    graph.addPass("lines", {"gbuffer.depth"}, {{"mask"}}).runOnHost();
    graph.addPass("shade", {"gbuffer.normal"}, {{"color"}});
    graph.addPass("composite", {"shade.color", "lines.mask"}, {{"final"}}).runOnHost();
    const Plan plan = graph.compile({"composite.final"});
    ASSERT_EQ(plan.hostTailStart(), 2u);
    const Names names{"gbuffer", "lines", "shade", "composite"};

    RecordingBackend whole(names);
    const std::vector<PassTiming> wholeTimings = executePlan("run()", plan, whole.names(), whole, false);

    RecordingBackend gpu(names);
    RecordingBackend host(names);
    PlanRun run("run()", plan, gpu.names(), false);
    run.prepare(gpu);
    run.execute(gpu, plan.hostTailStart());
    EXPECT_EQ(run.next(), 2u);
    host.written = gpu.written; // what the hand-off gives the tail
    run.execute(host, plan.passes.size());
    EXPECT_EQ(run.next(), plan.passes.size());

    Names halves = gpu.events;
    halves.insert(halves.end(), host.events.begin(), host.events.end());
    EXPECT_EQ(halves, whole.events);
    EXPECT_EQ(eventsStartingWith(host.events, "prepare "), Names{}) << "every prepare runs on the first backend";
    EXPECT_EQ(eventsStartingWith(host.events, "execute "), (Names{"execute lines", "execute composite"}));
    EXPECT_EQ(eventsStartingWith(host.events, "release "),
              (Names{"release gbuffer.depth", "release shade.color", "release lines.mask"}));
    ASSERT_EQ(run.timings().size(), wholeTimings.size());
    for (std::size_t i = 0; i < wholeTimings.size(); ++i) EXPECT_EQ(run.timings()[i].pass, wholeTimings[i].pass);
    EXPECT_EQ(host.written, (std::set<std::string>{"composite.final"}));
}

TEST(ExecutorTest, KeepAllResourcesReleasesNothing) {
    FakeGraph graph;
    const Plan plan = chainPlan(graph);
    RecordingBackend backend({"a", "b", "c"});
    executePlan("run()", plan, backend.names(), backend, true);
    EXPECT_TRUE(eventsStartingWith(backend.events, "release ").empty());
    EXPECT_EQ(backend.written, (std::set<std::string>{"a.out", "b.out", "c.out"}));
}

TEST(ExecutorTest, APlannedPassWithoutAnObjectIsNamedBeforeAnythingRuns) {
    FakeGraph graph;
    const Plan plan = chainPlan(graph);
    RecordingBackend backend({"a", "c"});
    try {
        executePlan("GraphExecutor::run()", plan, backend.names(), backend, false);
        FAIL() << "no error for the missing pass object";
    } catch (const std::logic_error& error) {
        EXPECT_STREQ(error.what(), "GraphExecutor::run(): the plan names pass 'b' but no such pass object was given");
    }
    EXPECT_TRUE(backend.events.empty());
}

TEST(ExecutorTest, ALiveOutputLeftUnwrittenNamesThePassAndTheResource) {
    FakeGraph graph;
    const Plan plan = chainPlan(graph);
    RecordingBackend backend({"a", "b", "c"});
    backend.unwritten = {"b.out"};
    try {
        executePlan("run()", plan, backend.names(), backend, false);
        FAIL() << "no error for the unwritten output";
    } catch (const std::logic_error& error) {
        EXPECT_STREQ(error.what(), "run(): pass 'b' did not write its live output 'b.out'");
    }
    EXPECT_EQ(backend.events.back(), "after b") << "nothing runs after the failing pass";
}

TEST(ExecutorTest, AFailingExecuteIsWrappedNamingThePass) {
    FakeGraph graph;
    const Plan plan = chainPlan(graph);
    RecordingBackend backend({"a", "b", "c"});
    backend.fail = [](const std::string& event) {
        if (event == "execute b") throw std::invalid_argument("bad width");
    };
    try {
        executePlan("run()", plan, backend.names(), backend, false);
        FAIL() << "no error";
    } catch (const std::runtime_error& error) {
        EXPECT_STREQ(error.what(), "run(): pass 'b' failed: bad width");
    }
    EXPECT_EQ(backend.events.back(), "execute b");
}

TEST(ExecutorTest, AFailingPrepareStopsBeforeAnyExecute) {
    FakeGraph graph;
    const Plan plan = chainPlan(graph);
    RecordingBackend backend({"a", "b", "c"});
    backend.fail = [](const std::string& event) {
        if (event == "prepare c") throw std::runtime_error("shader did not compile");
    };
    try {
        executePlan("run()", plan, backend.names(), backend, false);
        FAIL() << "no error";
    } catch (const std::runtime_error& error) {
        EXPECT_STREQ(error.what(), "run(): pass 'c' failed to prepare: shader did not compile");
    }
    EXPECT_TRUE(eventsStartingWith(backend.events, "execute ").empty());
}

TEST(ExecutorTest, RunningOutOfMemoryAndBackendFailuresKeepTheirTypes) {
    FakeGraph graph;
    const Plan plan = chainPlan(graph);
    {
        RecordingBackend backend({"a", "b", "c"});
        backend.fail = [](const std::string& event) {
            if (event == "execute a") throw std::bad_alloc();
        };
        try {
            executePlan("run()", plan, backend.names(), backend, false);
            FAIL() << "no error";
        } catch (const OutOfMemoryError& error) {
            EXPECT_STREQ(error.what(), "run(): pass 'a' ran out of memory");
        }
    }
    {
        RecordingBackend backend({"a", "b", "c"});
        backend.fail = [](const std::string& event) {
            if (event == "execute c") throw BackendFailure("the driver is out of memory");
        };
        try {
            executePlan("run()", plan, backend.names(), backend, false);
            FAIL() << "no error";
        } catch (const BackendFailure& error) {
            EXPECT_STREQ(error.what(), "run(): pass 'c': the driver is out of memory");
        }
    }
}

TEST(ExecutorTest, AProblemTheBackendFindsAfterAPassNamesThePass) {
    FakeGraph graph;
    const Plan plan = chainPlan(graph);
    RecordingBackend backend({"a", "b", "c"});
    backend.problemPass = "a";
    try {
        executePlan("run()", plan, backend.names(), backend, false);
        FAIL() << "no error";
    } catch (const std::runtime_error& error) {
        EXPECT_STREQ(error.what(), "run(): pass 'a' raised a backend error");
    }
    EXPECT_TRUE(eventsStartingWith(backend.events, "execute b").empty());
}

TEST(ExecutorTest, FakeGraphRunsThroughTheLoop) {
    FakeGraph graph;
    const Plan plan = chainPlan(graph);
    EXPECT_EQ(graph.execute(plan).executed, (Names{"a", "b", "c"}));
}

} // namespace
} // namespace inkgraph::test
