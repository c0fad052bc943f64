#pragma once
/** @file One memory limit for all the drawing threads of a batch (--draw-threads): a still draws once what every
 *  thread holds and what it needs fit under the limit together. When memory is short the stills are let in in the
 *  list's order, so a still waiting for memory waits only for stills before it, which finish on their own; a later
 *  still goes ahead of its turn only where it fits with room left for every still before it still to come, counted
 *  at its own size, so the drawing threads do not wait on each other while memory is plentiful. */

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <limits>
#include <mutex>
#include <set>
#include <vector>

namespace inkgraph {

/** What one drawing thread (a RenderSession) holds, in bytes of the batch's memory estimate (render/MemoryBudget.h),
 *  the process's baseline left out (the ledger counts it once). */
struct MemoryHoldings {
    /** Freed as the thread's work goes on: the still it draws, its stills in flight (post stages, pictures). */
    std::size_t working = 0;
    /** Kept until the thread lets go of it (MemoryLedger::shouldShed()): its texture pool between stills, the next
     *  model it loaded ahead. */
    std::size_t sheddable = 0;
    /** The model of the still it waits to draw: loaded before its size could be known, kept until it draws. */
    std::size_t waiting = 0;
    /** The first still (its place in the list) that `working` holds memory for. */
    std::size_t earliestStill = std::numeric_limits<std::size_t>::max();
    std::size_t total() const { return working + sheddable + waiting; }
};

class MemoryLedger {
public:
    /** `limitBytes`: the batch's memory limit; `threads`: the drawing threads, numbered from 0; `fixedBytes`: what
     *  they hold beyond the process's baseline whatever they draw (the GL contexts after the first). */
    MemoryLedger(std::size_t limitBytes, int threads, std::size_t fixedBytes);

    /** Whether `still` (its place in the list, 0-based) may draw now on `thread`, which would then hold `drawing`
     *  (its stills in flight, the still itself, the model loading ahead). Yes when `baselineBytes` (the process before
     *  any still: libraries, the driver; counted once), the fixed bytes, every other thread's holdings and `drawing`
     *  fit under the limit, with `drawing` counted again for each still before this one that is neither let in nor
     *  passed (none once the batch stopped). When they do not, a still whose earlier stills have all been let in or
     *  passed, that holds no still in flight on its thread (`ownStillsInFlight` false) and with no other thread
     *  holding working memory for a still before it, first has the waiting threads shed (shouldShed()), then draws
     *  anyway: it is then above what is left, as one thread's still that fits the limit alone always draws. On yes,
     *  `drawing` is this thread's holdings. */
    bool tryLetIn(std::size_t still, int thread, const MemoryHoldings& drawing, std::size_t baselineBytes,
                  bool ownStillsInFlight);
    /** `still` will not ask (it failed before drawing, or drew nothing): the stills after it need not wait for it.
     *  Nothing for a still let in. */
    void pass(std::size_t still);
    /** What `thread` holds now (after a still finished, a hand-off, shedding, at its end: {}). */
    void update(int thread, const MemoryHoldings& holdings);
    /** Whether a still waiting to draw needs the sheddable memory of the threads that wait (their pools, the models
     *  they loaded ahead). */
    bool shouldShed();
    /** The batch stopped: no still leaves room for the stills before it that have not asked, nor waits for their
     *  turn (they may never ask). */
    void stop();
    /** Waits until anything above changed since `thread`'s last tryLetIn(), or `timeout` passes. */
    void waitForChange(int thread, std::chrono::milliseconds timeout);

private:
    void advancePastLetIn();

    std::mutex mMutex;
    std::condition_variable mChanged;
    const std::size_t mLimitBytes;
    const std::size_t mFixedBytes;
    std::vector<MemoryHoldings> mHoldings;
    std::size_t mNext = 0;              ///< the still whose turn to be let in comes next
    std::set<std::size_t> mPassedEarly; ///< stills after mNext already let in or passed
    bool mStopped = false;
    bool mShed = false;
    unsigned long long mChanges = 0;       ///< counts every change, so waitForChange() returns on any
    std::vector<unsigned long long> mSeen; ///< per thread, mChanges at its last tryLetIn()
};

} // namespace inkgraph
