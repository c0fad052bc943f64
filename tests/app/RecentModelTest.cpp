// The model a batch's session loaded last (app/RecentModel.h): taken by a still that loads the same file the same way,
// never by one whose file changed or whose load options differ. No GL.
#include "app/RecentModel.h"
#include "tests/support/TestFolder.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace inkgraph {
namespace {

namespace fs = std::filesystem;

class RecentModelTest : public test::TestFolder {
protected:
    void SetUp() override {
        TestFolder::SetUp();
        model = (directory / "tetra.obj").string();
        std::ofstream(model) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
        request.modelPath = model;
    }

    /** The model remembered for `request`, then looked up for `changed`. */
    std::shared_ptr<const Scene> foundAfter(const std::function<void(StillRequest&)>& change) {
        RecentModel recent;
        recent.remember(RecentModel::keyOf(request), {scene, derived});
        StillRequest changed = request;
        change(changed);
        return recent.find(RecentModel::keyOf(changed)).scene;
    }

    std::string model;
    StillRequest request;
    std::shared_ptr<const Scene> scene = std::make_shared<const Scene>();
    std::shared_ptr<SceneDerivedData> derived = std::make_shared<SceneDerivedData>(*scene);
};

TEST_F(RecentModelTest, TheSameFileLoadedTheSameWayIsTaken) {
    RecentModel recent;
    EXPECT_EQ(recent.find(RecentModel::keyOf(request)).scene, nullptr) << "nothing remembered yet";
    recent.remember(RecentModel::keyOf(request), {scene, derived});
    // The camera, the look and the outputs are no part of the load: another view takes the model.
    StillRequest otherView = request;
    otherView.camera.fovYDegrees = 20.0;
    otherView.look.shading = ShadingModel::Phong;
    otherView.extraOutputs = {"gbuffer.normal"};
    const RecentModel::Model found = recent.find(RecentModel::keyOf(otherView));
    EXPECT_EQ(found.scene, scene);
    EXPECT_EQ(found.derived, derived) << "what the views derived goes with the model";
    recent.forget();
    EXPECT_EQ(recent.find(RecentModel::keyOf(request)).scene, nullptr);
    EXPECT_EQ(recent.find(RecentModel::keyOf(request)).derived, nullptr);
}

TEST_F(RecentModelTest, AnyLoadOptionThatDiffersLoadsAgain) {
    const std::vector<std::pair<const char*, std::function<void(StillRequest&)>>> changes = {
        {"path", [&](StillRequest& r) { r.modelPath = (fs::path(directory) / "." / "tetra.obj").string(); }},
        {"memory limit", [](StillRequest& r) { r.memoryLimitBytes /= 2; }},
        {"animation", [](StillRequest& r) { r.animation = "walk"; }},
        {"time", [](StillRequest& r) { r.animationTime = 0.5; }},
        {"pose", [](StillRequest& r) { r.pose = "a-pose"; }},
        {"expressions",
         [](StillRequest& r) {
             r.expressions = {{"happy", 1.0}};
         }},
        {"look-at", [](StillRequest& r) { r.lookAt = glm::dvec3(0.0, 1.0, 2.0); }},
    };
    for (const auto& [what, change] : changes) EXPECT_EQ(foundAfter(change), nullptr) << what;
    EXPECT_EQ(foundAfter([](StillRequest&) {}), scene) << "the test's control";
}

TEST_F(RecentModelTest, AFileChangedSinceItsLoadIsReadAgain) {
    const std::optional<RecentModel::Key> before = RecentModel::keyOf(request);
    ASSERT_TRUE(before.has_value());
    RecentModel recent;
    recent.remember(before, {scene, derived});

    // Rewritten in place with the same size and its modification time set back: the change time still moves.
    std::ofstream(model) << "v 0 0 0\nv 2 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    fs::last_write_time(model, fs::last_write_time(model) - std::chrono::hours(1));
    const auto rewrittenKey = RecentModel::keyOf(request);
    ASSERT_TRUE(rewrittenKey.has_value());
    EXPECT_NE(rewrittenKey->changedNanoseconds, before->changedNanoseconds);
    EXPECT_EQ(recent.find(rewrittenKey).scene, nullptr);

    // Replaced by another file of the same name (a new inode).
    recent.remember(rewrittenKey, {scene, derived});
    const fs::path replacement = directory / "replacement.obj";
    fs::copy_file(model, replacement);
    fs::rename(replacement, model);
    EXPECT_EQ(recent.find(RecentModel::keyOf(request)).scene, nullptr);
}

TEST_F(RecentModelTest, AModelThatCannotBeExaminedIsNeverKept) {
    StillRequest missing = request;
    missing.modelPath = (directory / "missing.obj").string();
    EXPECT_FALSE(RecentModel::keyOf(missing).has_value());
    StillRequest folder = request;
    folder.modelPath = directory.string();
    EXPECT_FALSE(RecentModel::keyOf(folder).has_value());

    RecentModel recent;
    recent.remember(RecentModel::keyOf(request), {scene, derived});
    recent.remember(std::nullopt, {scene, derived}); // a still without a key replaces the one before, keeping nothing
    EXPECT_EQ(recent.find(RecentModel::keyOf(request)).scene, nullptr);
    EXPECT_EQ(recent.find(std::nullopt).scene, nullptr);
}

} // namespace
} // namespace inkgraph
