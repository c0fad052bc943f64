// One memory limit for a batch's drawing threads (app/MemoryLedger.h, --draw-threads): who may draw when, without GL.
#include "app/MemoryLedger.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <condition_variable>
#include <chrono>
#include <cstddef>
#include <mutex>
#include <random>
#include <thread>
#include <vector>

namespace inkgraph {
namespace {

constexpr std::size_t kLimit = 1000;
constexpr std::size_t kBaseline = 100;

MemoryHoldings working(std::size_t bytes, std::size_t earliestStill) {
    MemoryHoldings holdings;
    holdings.working = bytes;
    holdings.earliestStill = earliestStill;
    return holdings;
}

TEST(MemoryLedger, StillsThatFitDrawAtOnceInAnyOrderWhileMemoryIsPlentiful) {
    MemoryLedger ledger(kLimit, 3, 0);
    // Still 2 asks before still 1: 100 + 200 + 200 x 2 (itself and room for still 1) fits.
    EXPECT_TRUE(ledger.tryLetIn(0, 0, working(200, 0), kBaseline, false));
    EXPECT_TRUE(ledger.tryLetIn(2, 2, working(200, 2), kBaseline, false));
    EXPECT_TRUE(ledger.tryLetIn(1, 1, working(200, 1), kBaseline, false));
    EXPECT_FALSE(ledger.shouldShed());
}

TEST(MemoryLedger, AStillAheadOfItsTurnLeavesRoomForEachStillBeforeIt) {
    MemoryLedger ledger(kLimit, 3, 0);
    EXPECT_TRUE(ledger.tryLetIn(0, 0, working(300, 0), kBaseline, false));
    // Still 2 with still 1 to come: 100 + 300 + 300 x 2 = 1000 fits exactly; 301 would not.
    EXPECT_FALSE(ledger.tryLetIn(2, 2, working(301, 2), kBaseline, false));
    EXPECT_TRUE(ledger.tryLetIn(2, 2, working(300, 2), kBaseline, false));
    // Still 1 in its turn: 100 + 300 + 300 + 300 = 1000.
    EXPECT_TRUE(ledger.tryLetIn(1, 1, working(300, 1), kBaseline, false));
}

TEST(MemoryLedger, AStillThatDoesNotFitWaitsForTheStillsBeforeItThenDraws) {
    MemoryLedger ledger(kLimit, 2, 0);
    EXPECT_TRUE(ledger.tryLetIn(0, 0, working(600, 0), kBaseline, false));
    EXPECT_FALSE(ledger.tryLetIn(1, 1, working(600, 1), kBaseline, false)); // still 0 holds working memory
    EXPECT_FALSE(ledger.shouldShed());
    ledger.update(0, working(350, 0)); // handed over: its post stage in flight
    EXPECT_FALSE(ledger.tryLetIn(1, 1, working(600, 1), kBaseline, false));
    ledger.update(0, {}); // committed
    EXPECT_TRUE(ledger.tryLetIn(1, 1, working(600, 1), kBaseline, false));
}

TEST(MemoryLedger, AStillAboveWhatIsLeftDrawsOnceNothingBeforeItHoldsMemoryAndTheOthersHaveShed) {
    MemoryLedger ledger(kLimit, 3, 0);
    MemoryHoldings idle; // thread 1: its pool between stills and a model loading ahead
    idle.sheddable = 300;
    ledger.update(1, idle);
    MemoryHoldings loaded; // thread 2: the model of the still it waits to draw, which it cannot let go
    loaded.waiting = 200;
    ledger.update(2, loaded);
    // 100 + 300 + 200 + 500 > 1000, and nothing working: the threads that keep memory while they wait shed.
    EXPECT_FALSE(ledger.tryLetIn(0, 0, working(500, 0), kBaseline, false));
    EXPECT_TRUE(ledger.shouldShed());
    ledger.update(1, {});
    // 100 + 200 + 700 = 1000 would fit; 800 does not, but there is nothing left to wait for.
    EXPECT_TRUE(ledger.tryLetIn(0, 0, working(800, 0), kBaseline, false));
    EXPECT_FALSE(ledger.shouldShed()); // asked of the waiting threads only until the still drew
}

TEST(MemoryLedger, OnlyAStillInItsTurnWithNoStillInFlightOnItsThreadDrawsAboveWhatIsLeft) {
    MemoryLedger ledger(kLimit, 2, 0);
    EXPECT_FALSE(ledger.tryLetIn(0, 0, working(950, 0), kBaseline, true)); // its own stills in flight finish first
    EXPECT_FALSE(ledger.shouldShed());
    EXPECT_FALSE(ledger.tryLetIn(1, 1, working(950, 1), kBaseline, false)); // not its turn: still 0 comes first
    EXPECT_TRUE(ledger.tryLetIn(0, 0, working(950, 0), kBaseline, false));
    ledger.update(0, {});
    EXPECT_TRUE(ledger.tryLetIn(1, 1, working(950, 1), kBaseline, false));
}

TEST(MemoryLedger, WorkingMemoryOfStillsAfterItDoesNotHoldAStillInItsTurnBack) {
    // Still 2 went ahead of still 1; it commits only after still 1, so still 1 waiting for its memory would wait
    // for ever: still 1 draws above what is left instead.
    MemoryLedger ledger(kLimit, 3, 0);
    EXPECT_TRUE(ledger.tryLetIn(0, 0, working(100, 0), kBaseline, false));
    EXPECT_TRUE(ledger.tryLetIn(2, 2, working(200, 2), kBaseline, false));
    ledger.update(0, {});
    EXPECT_TRUE(ledger.tryLetIn(1, 1, working(800, 1), kBaseline, false));
}

TEST(MemoryLedger, AStillThatPassesLetsTheStillsAfterItTakeTheirTurn) {
    MemoryLedger ledger(kLimit, 3, 0);
    EXPECT_TRUE(ledger.tryLetIn(0, 0, working(100, 0), kBaseline, false));
    ledger.update(0, {});
    // Still 2, ahead of still 1 and too large to leave it room: waits.
    EXPECT_FALSE(ledger.tryLetIn(2, 2, working(800, 2), kBaseline, false));
    ledger.pass(1); // still 1 failed to load
    EXPECT_TRUE(ledger.tryLetIn(2, 2, working(800, 2), kBaseline, false));
    ledger.pass(2); // a still already let in: nothing
    ledger.update(2, {});
    EXPECT_TRUE(ledger.tryLetIn(3, 0, working(800, 3), kBaseline, false));
}

TEST(MemoryLedger, AfterAStopNoStillLeavesRoomForOrWaitsOnStillsBeforeIt) {
    MemoryLedger ledger(kLimit, 2, 0);
    EXPECT_FALSE(ledger.tryLetIn(5, 1, working(800, 5), kBaseline, false));
    ledger.stop();
    EXPECT_TRUE(ledger.tryLetIn(5, 1, working(800, 5), kBaseline, false));
}

TEST(MemoryLedger, TheFixedBytesCountOnce) {
    MemoryLedger ledger(kLimit, 2, 150);
    EXPECT_FALSE(ledger.tryLetIn(0, 0, working(760, 0), kBaseline, true));
    EXPECT_TRUE(ledger.tryLetIn(0, 0, working(750, 0), kBaseline, true));
}

TEST(MemoryLedger, WaitForChangeReturnsOnAChangeSinceTheThreadLastAskedAndOtherwiseAfterItsTimeout) {
    MemoryLedger ledger(kLimit, 2, 0);
    EXPECT_FALSE(ledger.tryLetIn(1, 1, working(500, 1), kBaseline, false)); // no room for still 0 beside it
    ledger.pass(0);                                                         // a change after thread 1 asked: no wait
    const auto start = std::chrono::steady_clock::now();
    ledger.waitForChange(1, std::chrono::seconds(30));
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
    EXPECT_TRUE(ledger.tryLetIn(1, 1, working(500, 1), kBaseline, false));
    ledger.waitForChange(1, std::chrono::milliseconds(1)); // nothing changed since: the timeout
}

TEST(MemoryLedger, ThreadsDrawingAStillListTogetherAllFinishAndPassTheLimitOnlyByAStillAloneInItsTurn) {
    // Four threads deal 300 stills of random sizes (up to 90% of what the baseline leaves) round robin, as
    // --draw-threads does; each still is let in, works a moment, then commits in list order and lets go. What the
    // threads hold passes the limit only when the still just let in draws above what is left: then it is the first
    // still in the list of all those held (the others went ahead of it and wait for it to commit).
    constexpr int kThreads = 4;
    constexpr std::size_t kStills = 300;
    MemoryLedger ledger(kLimit, kThreads, 0);
    std::mt19937 random(7);
    std::vector<std::size_t> sizes(kStills);
    for (std::size_t& size : sizes) size = 20 + random() % 790;
    std::mutex mutex;
    std::condition_variable committed;
    std::vector<std::size_t> heldBytes(kThreads, 0);
    std::vector<std::size_t> heldStill(kThreads, kStills);
    std::size_t nextCommit = 0;
    std::size_t overLimitAlone = 0;
    std::size_t overLimitOtherwise = 0;
    const auto work = [&](int thread) {
        const auto self = std::size_t(thread);
        std::minstd_rand pause(unsigned(thread) + 1);
        for (std::size_t still = self; still < kStills; still += kThreads) {
            // Each grant and its record (and below each commit and its update) under one lock, so the record is
            // exactly what the ledger counted.
            for (;;) {
                std::unique_lock<std::mutex> lock(mutex);
                if (ledger.tryLetIn(still, thread, working(sizes[still], still), kBaseline, false)) {
                    heldBytes[self] = sizes[still];
                    heldStill[self] = still;
                    std::size_t total = kBaseline;
                    for (const std::size_t bytes : heldBytes) total += bytes;
                    if (total > kLimit)
                        ++(*std::min_element(heldStill.begin(), heldStill.end()) == still ? overLimitAlone
                                                                                          : overLimitOtherwise);
                    break;
                }
                lock.unlock();
                ledger.waitForChange(thread, std::chrono::milliseconds(5));
            }
            std::this_thread::sleep_for(std::chrono::microseconds(100 + pause() % 300));
            {
                std::unique_lock<std::mutex> lock(mutex);
                committed.wait(lock, [&] { return nextCommit == still; });
                heldBytes[self] = 0;
                heldStill[self] = kStills;
                ++nextCommit;
                ledger.update(thread, {});
            }
            committed.notify_all();
        }
    };
    std::vector<std::thread> threads;
    for (int thread = 0; thread < kThreads; ++thread) threads.emplace_back(work, thread);
    for (std::thread& thread : threads) thread.join();
    EXPECT_EQ(nextCommit, kStills);
    EXPECT_EQ(overLimitOtherwise, 0u);
    RecordProperty("stills_drawn_alone_above_what_was_left", int(overLimitAlone));
}

} // namespace
} // namespace inkgraph
