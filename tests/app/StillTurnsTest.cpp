// The order of a batch's stills across drawing threads (app/StillTurns.h, --draw-threads).
#include "app/StillTurns.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

namespace inkgraph {
namespace {

TEST(StillTurns, ThreadsThatAskOutOfOrderAreServedInOrder) {
    StillTurns turns;
    std::mutex mutex;
    std::vector<std::size_t> order;
    std::vector<std::thread> threads;
    // Stills 5 down to 0 each on a thread of its own, started last first: each enters only after the one before it.
    for (std::size_t still = 6; still-- > 0;)
        threads.emplace_back([&turns, &mutex, &order, still] {
            const StillTurn turn(&turns, still);
            const std::lock_guard<std::mutex> lock(mutex);
            order.push_back(still);
        });
    for (std::thread& thread : threads) thread.join();
    EXPECT_EQ(order, (std::vector<std::size_t>{0, 1, 2, 3, 4, 5}));
    EXPECT_TRUE(turns.isDue(6));
    EXPECT_FALSE(turns.stopped());
}

TEST(StillTurns, AStillThatHoldsItsTurnEntersAgainAtOnceAndOnlyItsOwnLeaveCounts) {
    StillTurns turns;
    EXPECT_TRUE(turns.isDue(0));
    EXPECT_FALSE(turns.isDue(1));
    turns.enter(0);
    turns.enter(0); // render() entered it to tell the still's warnings; the caller's failure enters again
    EXPECT_FALSE(turns.isDue(1)) << "held";
    turns.leave(3); // not the holder: nothing
    EXPECT_FALSE(turns.isDue(1));
    turns.leave(0);
    EXPECT_TRUE(turns.isDue(1));
    EXPECT_FALSE(turns.isDue(2));
}

/** How many threads hold a turn at once, at most: each holder stays `stay` inside. */
class Holders {
public:
    void holdFor(std::chrono::microseconds stay) {
        {
            const std::lock_guard<std::mutex> lock(mMutex);
            mMost = std::max(mMost, ++mInside);
        }
        std::this_thread::sleep_for(stay);
        const std::lock_guard<std::mutex> lock(mMutex);
        --mInside;
    }
    int most() {
        const std::lock_guard<std::mutex> lock(mMutex);
        return mMost;
    }

private:
    std::mutex mMutex;
    int mInside = 0;
    int mMost = 0;
};

TEST(StillTurns, AStopLetsEveryWaiterThroughOneAtATimeAndKeepsTheFirstError) {
    StillTurns turns;
    std::vector<std::thread> threads;
    Holders holders;
    // Stills 3 and 4 wait for still 0, which is never drawn: only the stop lets them through.
    for (const std::size_t still : {3, 4})
        threads.emplace_back([&, still] {
            const StillTurn turn(&turns, still);
            holders.holdFor(std::chrono::milliseconds(5));
        });
    const auto first = std::make_exception_ptr(std::runtime_error("first"));
    EXPECT_TRUE(turns.stop(first));
    EXPECT_FALSE(turns.stop(std::make_exception_ptr(std::runtime_error("second"))));
    for (std::thread& thread : threads) thread.join();
    EXPECT_EQ(holders.most(), 1) << "one holder at a time, also after the stop";
    EXPECT_TRUE(turns.stopped());
    EXPECT_EQ(turns.firstError(), first);
    EXPECT_TRUE(turns.stop(first)) << "the kept error given again is still the first";
}

TEST(StillTurns, TwoThreadsAskingForOneNumberTakeItInTurn) {
    // After a stop every teller of a later error asks for the same number (BatchRun's tellError()): the second
    // waits for the first to leave, so their lines never run together.
    StillTurns turns;
    turns.stop();
    constexpr std::size_t kTellers = 99;
    Holders holders;
    std::vector<std::thread> threads;
    for (int thread = 0; thread < 4; ++thread)
        threads.emplace_back([&] {
            for (int told = 0; told < 50; ++told) {
                const StillTurn turn(&turns, kTellers);
                holders.holdFor(std::chrono::microseconds(200));
            }
        });
    for (std::thread& thread : threads) thread.join();
    EXPECT_EQ(holders.most(), 1);
}

} // namespace
} // namespace inkgraph
