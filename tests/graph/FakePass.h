#pragma once
/** @file Fake passes and a null executor for the no-GL graph tests (after Filament's NOOP-backend frame-graph tests):
 *  a FakePass declares the reads and writes it was constructed with, and execute() only records that it ran and
 *  which of its fields the plan made live. FakeGraph::execute() runs them through graph/Executor's loop. */

#include "graph/Executor.h"
#include "graph/GraphCompiler.h"
#include "graph/Pass.h"
#include "graph/Plan.h"

#include <algorithm>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph::test {

/** One field a FakePass writes. */
struct FakeWrite {
    std::string field;
    Need need = Need::Required;
    TextureDesc desc = {};
};

inline FakeWrite optionalWrite(std::string field, TextureDesc desc = {}) {
    return {std::move(field), Need::Optional, desc};
}

/** What the null executor saw: the passes that ran, in order, and the fields each was told were live. */
struct ExecutionLog {
    std::vector<std::string> executed;
    std::map<std::string, std::vector<std::string>> liveFields;
};

class FakePass final : public Pass {
public:
    FakePass(std::string name, std::vector<std::string> reads, std::vector<FakeWrite> writes, bool sideEffect = false)
        : mName(std::move(name)), mReads(std::move(reads)), mWrites(std::move(writes)), mSideEffect(sideEffect) {}

    std::string_view name() const override { return mName; }

    void declare(PassBuilder& builder) const override {
        for (const std::string& resource : mCoveredReads) builder.read(resource, ReadExtent::CoveredPixels);
        for (const std::string& resource : mReads) builder.read(resource);
        for (const FakeWrite& write : mWrites) builder.write(write.field, write.desc, write.need);
        if (mSideEffect) builder.markSideEffect();
        if (mRunsOnHost) builder.runsOnHost();
    }

    /** Also reads `resource` only where it is covered (ReadExtent::CoveredPixels), declared before the other reads. */
    FakePass& readWhereCovered(std::string resource) {
        mCoveredReads.push_back(std::move(resource));
        return *this;
    }

    /** Declares the pass host-only (PassBuilder::runsOnHost()). */
    FakePass& runOnHost() {
        mRunsOnHost = true;
        return *this;
    }

    /** What a backend's execute would do: records the run and the fields `planned` makes live. */
    void execute(const PlannedPass& planned) {
        if (!mLog) throw std::logic_error("FakePass::execute(): pass '" + mName + "' has no log");
        mLog->executed.push_back(mName);
        std::vector<std::string>& live = mLog->liveFields[mName];
        for (const FakeWrite& write : mWrites)
            if (isLive(planned, write.field)) live.push_back(write.field);
    }

    /** True when this pass's `field` is among `planned`'s live writes, as gl/GlPassContext answers it. */
    static bool isLive(const PlannedPass& planned, const std::string& field) {
        const std::string full = planned.name + "." + field;
        return std::find(planned.liveWrites.begin(), planned.liveWrites.end(), full) != planned.liveWrites.end();
    }

    void setLog(ExecutionLog* log) { mLog = log; }

private:
    std::string mName;
    std::vector<std::string> mReads;
    std::vector<std::string> mCoveredReads;
    std::vector<FakeWrite> mWrites;
    bool mSideEffect = false;
    bool mRunsOnHost = false;
    ExecutionLog* mLog = nullptr;
};

/** A graph of fake passes in registration order, with the null executor. */
class FakeGraph {
public:
    FakePass& addPass(std::string name, std::vector<std::string> reads, std::vector<FakeWrite> writes,
                      bool sideEffect = false) {
        mPasses.push_back(std::make_unique<FakePass>(std::move(name), std::move(reads), std::move(writes), sideEffect));
        mPasses.back()->setLog(&mLog);
        return *mPasses.back();
    }

    std::vector<const Pass*> passes() const {
        std::vector<const Pass*> list;
        for (const auto& pass : mPasses) list.push_back(pass.get());
        return list;
    }

    Plan compile(const std::vector<std::string>& requested) const { return inkgraph::compile(passes(), requested); }

    /** The null executor: runs the plan through graph/Executor's loop, each execute calling FakePass::execute(),
     *  and returns the log. */
    const ExecutionLog& execute(const Plan& plan) {
        mLog = {};
        NullBackend backend(mPasses);
        std::vector<std::string_view> names;
        for (const auto& pass : mPasses) names.push_back(pass->name());
        executePlan("FakeGraph::execute()", plan, names, backend, false);
        return mLog;
    }

private:
    /** Executes FakePasses and counts every live write as written. */
    class NullBackend final : public ExecutorBackend {
    public:
        explicit NullBackend(const std::vector<std::unique_ptr<FakePass>>& passes) : mPasses(passes) {}
        void runPass(std::size_t passIndex, const PlannedPass& planned, PassPhase phase) override {
            if (phase == PassPhase::Execute) mPasses[passIndex]->execute(planned);
        }
        bool wrote(const std::string&) const override { return true; }
        void release(const std::string&) override {}

    private:
        const std::vector<std::unique_ptr<FakePass>>& mPasses;
    };

    std::vector<std::unique_ptr<FakePass>> mPasses;
    ExecutionLog mLog;
};

/** The names of a plan's passes, in plan order. */
inline std::vector<std::string> passNames(const Plan& plan) {
    std::vector<std::string> names;
    for (const PlannedPass& pass : plan.passes) names.push_back(pass.name);
    return names;
}

/** The names of a plan's culled passes, in registration order. */
inline std::vector<std::string> culledNames(const Plan& plan) {
    std::vector<std::string> names;
    for (const CulledPass& pass : plan.culled) names.push_back(pass.name);
    return names;
}

/** Compiles and returns the GraphError's problems; fails the test (returns {}) when compile() does not throw. */
inline std::vector<std::string> compileProblems(const FakeGraph& graph, const std::vector<std::string>& requested,
                                                std::string* message = nullptr) {
    try {
        graph.compile(requested);
    } catch (const GraphError& error) {
        if (message) *message = error.what();
        return error.problems();
    }
    return {};
}

} // namespace inkgraph::test
