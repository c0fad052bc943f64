#pragma once
/** @file The order in which a batch's stills are told and committed when several drawing threads render them
 *  (--draw-threads): each still's turn comes after every still before it in the list has had its own, so the progress
 *  lines, the failures and the commits come out exactly as from one thread. */

#include <condition_variable>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>

namespace inkgraph {

class StillTurns {
public:
    /** Waits until every still before `still` (0-based, in the list's order) has left its turn, and no other thread
     *  holds one; then `still` holds it. Once the batch has stopped, waits only for the holder. Again for the still
     *  that holds the turn, on the thread that holds it: returns at once (another thread asking for the same number,
     *  as the tellers of errors after a stop do, waits like any other). */
    void enter(std::size_t still);
    /** `still` lets go of its turn (nothing if it does not hold it); the next still's turn may come. */
    void leave(std::size_t still);
    /** Whether `still`'s turn is due now: every still before it has had its own and no one holds one. */
    bool isDue(std::size_t still);
    /** An error stops the batch: no still waits for the ones before it any more (they may never be drawn), only for
     *  whoever holds the turn, so the threads finish what they have in flight. Keeps the first `error` given; returns
     *  whether this one is it (also when it was given before). A still's failure is given while it holds its turn,
     *  so the error kept is the first in the list's order among the stills told. */
    bool stop(std::exception_ptr error = nullptr);
    bool stopped();
    /** The first error stop() was given. */
    std::exception_ptr firstError();

private:
    std::mutex mMutex;
    std::condition_variable mChanged;
    std::size_t mNext = 0; ///< the still whose turn comes next
    bool mHeld = false;
    std::size_t mHolder = 0;
    std::thread::id mHolderThread;
    bool mStopped = false;
    std::exception_ptr mFirstError;
};

/** A still's turn held for a scope (nothing without turns). */
class StillTurn {
public:
    StillTurn(StillTurns* turns, std::size_t still) : mTurns(turns), mStill(still) {
        if (mTurns) mTurns->enter(mStill);
    }
    ~StillTurn() {
        if (mTurns) mTurns->leave(mStill);
    }
    StillTurn(const StillTurn&) = delete;
    StillTurn& operator=(const StillTurn&) = delete;

private:
    StillTurns* mTurns;
    std::size_t mStill;
};

} // namespace inkgraph
