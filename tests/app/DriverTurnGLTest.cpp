/** @file Renderers of one process take turns at a software driver (StillRenderer::driverTurn()): llvmpipe is not safe
 *  with several contexts working at once (docs/batch.md, "On a software renderer the threads take turns at the
 *  driver"). While one renderer holds its turn, another cannot make its context or draw. */

#include "flags/Options.h"
#include "app/Render.h"
#include "render/StillRenderer.h"
#include "tests/support/TestFolder.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <thread>

namespace inkgraph {
namespace {

class DriverTurnGL : public test::TestFolder {};

/** A 32x32 still of the bundled spot, drawn by `renderer`. */
void renderSpot(StillRenderer& renderer) {
    StillRequest request = stillRequestOf(parseRenderFlags({"--size", "32x32", "--lines", "contour"}));
    request.modelPath = (std::filesystem::path(INKGRAPH_SOURCE_ROOT) / "models" / "spot_c3d.obj").string();
    std::ostringstream log;
    const StillLog stillLog{log, false, true};
    const std::unique_ptr<PreparedStill> still = renderer.prepare(std::move(request), stillLog);
    const StillResult result = renderer.execute(*still, stillLog);
}

TEST_F(DriverTurnGL, ARendererOnASoftwareDriverWaitsForAnotherOnesTurn) {
    StillRenderer first;
    renderSpot(first);
    ASSERT_NE(first.context(), nullptr);
    std::unique_lock<std::mutex> turn = first.driverTurn();
    if (!first.context()->isSoftware()) {
        EXPECT_FALSE(turn.owns_lock()) << "a GPU's contexts draw at once";
        return;
    }
    ASSERT_TRUE(turn.owns_lock());
    std::atomic<bool> drawn{false};
    std::thread second([&drawn] {
        StillRenderer other; // its context is made, and its still drawn, only in its turn
        renderSpot(other);
        drawn = true;
    });
    // Whatever the timing, the other renderer cannot have drawn while this one holds the turn.
    std::this_thread::sleep_for(std::chrono::milliseconds(1000));
    EXPECT_FALSE(drawn);
    turn.unlock();
    second.join();
    EXPECT_TRUE(drawn);
    // The turn is free again once the other renderer is gone (its destructor held it while its context ended).
    EXPECT_TRUE(first.driverTurn().owns_lock());
}

} // namespace
} // namespace inkgraph
