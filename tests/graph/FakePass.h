#pragma once
/** @file Fake passes and a null executor for the no-GL graph tests (after Filament's NOOP-backend frame-graph tests):
 *  a FakePass declares the reads and writes it was constructed with, and execute() only records that it ran and
 *  which of its fields the context said were live. */

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

inline FakeWrite optionalWrite(std::string field, TextureDesc desc = {})
{
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
        : mName(std::move(name)), mReads(std::move(reads)), mWrites(std::move(writes)), mSideEffect(sideEffect)
    {}

    std::string_view name() const override { return mName; }

    void declare(PassBuilder& builder) const override
    {
        for (const std::string& resource : mReads)
            builder.read(resource);
        for (const FakeWrite& write : mWrites)
            builder.write(write.field, write.desc, write.need);
        if (mSideEffect)
            builder.markSideEffect();
    }

    void execute(PassContext& context) override
    {
        if (!mLog)
            throw std::logic_error("FakePass::execute(): pass '" + mName + "' has no log");
        mLog->executed.push_back(mName);
        std::vector<std::string>& live = mLog->liveFields[mName];
        for (const FakeWrite& write : mWrites)
            if (context.isLive(write.field))
                live.push_back(write.field);
    }

    void setLog(ExecutionLog* log) { mLog = log; }

private:
    std::string mName;
    std::vector<std::string> mReads;
    std::vector<FakeWrite> mWrites;
    bool mSideEffect = false;
    ExecutionLog* mLog = nullptr;
};

/** A PassContext that answers isLive() from the planned pass, as gl/GlPassContext does with real textures. */
class FakeContext final : public PassContext {
public:
    explicit FakeContext(const PlannedPass& pass) : mPass(pass) {}

    bool isLive(std::string_view field) const override
    {
        const std::string full = mPass.name + "." + std::string(field);
        return std::find(mPass.liveWrites.begin(), mPass.liveWrites.end(), full) != mPass.liveWrites.end();
    }
    int width() const override { return 64; }
    int height() const override { return 48; }

private:
    const PlannedPass& mPass;
};

/** A graph of fake passes in registration order, with the null executor. */
class FakeGraph {
public:
    FakePass& addPass(std::string name, std::vector<std::string> reads, std::vector<FakeWrite> writes,
                      bool sideEffect = false)
    {
        mPasses.push_back(std::make_unique<FakePass>(std::move(name), std::move(reads), std::move(writes), sideEffect));
        mPasses.back()->setLog(&mLog);
        return *mPasses.back();
    }

    std::vector<const Pass*> passes() const
    {
        std::vector<const Pass*> list;
        for (const auto& pass : mPasses)
            list.push_back(pass.get());
        return list;
    }

    Plan compile(const std::vector<std::string>& requested) const { return inkgraph::compile(passes(), requested); }

    /** The null executor: runs the plan's passes in order with a FakeContext and returns the log. */
    const ExecutionLog& execute(const Plan& plan)
    {
        mLog = {};
        for (const PlannedPass& planned : plan.passes) {
            auto it = std::find_if(mPasses.begin(), mPasses.end(),
                                   [&](const auto& pass) { return pass->name() == planned.name; });
            if (it == mPasses.end())
                throw std::logic_error("FakeGraph::execute(): plan names unknown pass '" + planned.name + "'");
            FakeContext context(planned);
            (*it)->execute(context);
        }
        return mLog;
    }

private:
    std::vector<std::unique_ptr<FakePass>> mPasses;
    ExecutionLog mLog;
};

/** The names of a plan's passes, in plan order. */
inline std::vector<std::string> passNames(const Plan& plan)
{
    std::vector<std::string> names;
    for (const PlannedPass& pass : plan.passes)
        names.push_back(pass.name);
    return names;
}

/** The names of a plan's culled passes, in registration order. */
inline std::vector<std::string> culledNames(const Plan& plan)
{
    std::vector<std::string> names;
    for (const CulledPass& pass : plan.culled)
        names.push_back(pass.name);
    return names;
}

/** Compiles and returns the GraphError's problems; fails the test (returns {}) when compile() does not throw. */
inline std::vector<std::string> compileProblems(const FakeGraph& graph, const std::vector<std::string>& requested,
                                                std::string* message = nullptr)
{
    try {
        graph.compile(requested);
    } catch (const GraphError& error) {
        if (message)
            *message = error.what();
        return error.problems();
    }
    return {};
}

} // namespace inkgraph::test
