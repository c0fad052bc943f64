#include "app/MemoryLedger.h"

#include <iterator>

namespace inkgraph {

MemoryLedger::MemoryLedger(std::size_t limitBytes, int threads, std::size_t fixedBytes)
    : mLimitBytes(limitBytes), mFixedBytes(fixedBytes), mHoldings(std::size_t(threads)),
      mSeen(std::size_t(threads), 0) {}

bool MemoryLedger::tryLetIn(std::size_t still, int thread, const MemoryHoldings& drawing, std::size_t baselineBytes,
                            bool ownStillsInFlight) {
    {
        const std::lock_guard<std::mutex> lock(mMutex);
        mSeen[std::size_t(thread)] = mChanges;
        // The stills before this one that have yet to be let in (none once the batch stopped: they may never ask).
        std::size_t earlierToCome = 0;
        if (!mStopped && still > mNext) {
            const auto doneBefore = std::distance(mPassedEarly.begin(), mPassedEarly.lower_bound(still));
            earlierToCome = still - mNext - std::size_t(doneBefore);
        }
        std::size_t others = 0;
        bool earlierWorking = ownStillsInFlight;
        std::size_t othersSheddable = 0;
        for (std::size_t other = 0; other < mHoldings.size(); ++other) {
            if (other == std::size_t(thread)) continue;
            const MemoryHoldings& held = mHoldings[other];
            others += held.total();
            othersSheddable += held.sheddable;
            if (held.working > 0 && held.earliestStill < still) earlierWorking = true;
        }
        // A still ahead of its turn leaves room for each still before it that is still to come, as large as itself:
        // those may not wait for it (it commits after them), so it goes ahead only where it cannot stand in their way.
        const std::size_t needed = drawing.total() * (1 + earlierToCome);
        const bool fits = baselineBytes + mFixedBytes + others + needed <= mLimitBytes;
        if (!fits) {
            // A still in its turn waits only for the stills before it, which finish on their own. Once none holds
            // working memory, what stands in its way is the waiting threads' pools and models loaded ahead, which
            // are asked to let go, and then nothing it could wait for: it draws, as a still alone always does.
            if (earlierToCome > 0 || earlierWorking) return false;
            if (othersSheddable > 0) {
                if (!mShed) {
                    mShed = true;
                    ++mChanges;
                    mChanged.notify_all();
                }
                return false;
            }
        }
        mHoldings[std::size_t(thread)] = drawing;
        if (still == mNext) {
            ++mNext;
        } else if (still > mNext) {
            mPassedEarly.insert(still);
        }
        advancePastLetIn();
        mShed = false;
        ++mChanges;
    }
    mChanged.notify_all();
    return true;
}

void MemoryLedger::pass(std::size_t still) {
    {
        const std::lock_guard<std::mutex> lock(mMutex);
        if (still < mNext) return;
        mPassedEarly.insert(still);
        advancePastLetIn();
        ++mChanges;
    }
    mChanged.notify_all();
}

void MemoryLedger::advancePastLetIn() {
    while (!mPassedEarly.empty() && *mPassedEarly.begin() <= mNext) {
        if (*mPassedEarly.begin() == mNext) ++mNext;
        mPassedEarly.erase(mPassedEarly.begin());
    }
}

void MemoryLedger::update(int thread, const MemoryHoldings& holdings) {
    {
        const std::lock_guard<std::mutex> lock(mMutex);
        MemoryHoldings& held = mHoldings[std::size_t(thread)];
        if (held.working == holdings.working && held.sheddable == holdings.sheddable &&
            held.waiting == holdings.waiting)
            return;
        held = holdings;
        ++mChanges;
    }
    mChanged.notify_all();
}

bool MemoryLedger::shouldShed() {
    const std::lock_guard<std::mutex> lock(mMutex);
    return mShed;
}

void MemoryLedger::stop() {
    {
        const std::lock_guard<std::mutex> lock(mMutex);
        if (mStopped) return;
        mStopped = true;
        ++mChanges;
    }
    mChanged.notify_all();
}

void MemoryLedger::waitForChange(int thread, std::chrono::milliseconds timeout) {
    std::unique_lock<std::mutex> lock(mMutex);
    const unsigned long long seen = mSeen[std::size_t(thread)];
    mChanged.wait_for(lock, timeout, [this, seen] { return mChanges != seen; });
}

} // namespace inkgraph
