// PreparedStill::warnings (render/StillRenderer.h): every warning a still printed, as records, for a library to return;
// and the command line's text unchanged. No GL: load() and plan() touch none.
#include "render/StillRenderer.h"
#include "scene/Scene.h"
#include "tests/scene/SceneTestSupport.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

using test::TempFolder;

const std::string kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n";

TEST(StillWarnings, AMissingTextureAndAnEmptyViewAreRecordsAndPrintedAsBefore) {
    const TempFolder folder;
    const std::string library = folder.write("gone.mtl", "newmtl skin\nmap_Kd skin.png\n");
    const std::string model = folder.write("gone.obj", "mtllib gone.mtl\nusemtl skin\n" + kTriangle);
    StillRequest request;
    request.modelPath = model;
    request.camera.zNear = 0.001; // the model lies beyond the far plane: the camera sees none of it
    request.camera.zFar = 0.002;
    std::ostringstream log;
    const std::unique_ptr<PreparedStill> still = StillRenderer().prepare(request, StillLog{log});

    ASSERT_EQ(still->warnings.size(), 2u) << ::testing::PrintToString(still->warnings);
    const Warning& texture = still->warnings[0];
    EXPECT_EQ(texture.code, "texture-missing");
    EXPECT_EQ(texture.file, folder.path("skin.png"));
    EXPECT_EQ(texture.item, "skin");
    EXPECT_EQ(texture.message, "material library '" + library + "' line 2: map_Kd 'skin.png': '" +
                                   folder.path("skin.png") +
                                   "' is missing or not a regular file; material 'skin' is drawn without it");
    const Warning& view = still->warnings[1];
    EXPECT_EQ(view.code, "model-outside-view");
    EXPECT_EQ(view.file, model);
    EXPECT_EQ(view.item, "");
    EXPECT_EQ(view.message.rfind("the auto-framed camera sees none of the model: every vertex lies beyond the far "
                                 "plane at 0.002 (--clip)",
                                 0),
              0u)
        << view.message;
    // The command line's lines, as before: the message after "inkgraph: warning: ", in the same order.
    const std::string printed = log.str();
    const std::size_t first = printed.find("inkgraph: warning: " + texture.message + "\n");
    const std::size_t second = printed.find("inkgraph: warning: " + view.message + "\n");
    EXPECT_NE(first, std::string::npos) << printed;
    EXPECT_NE(second, std::string::npos) << printed;
    EXPECT_LT(first, second) << printed;
}

TEST(StillWarnings, ALoadedScenesWarningsAreItsLoadersUnlessTheStillStandsForTheLoad) {
    const TempFolder folder;
    folder.write("gone.mtl", "newmtl skin\nmap_Kd skin.png\n");
    const std::string model = folder.write("gone.obj", "mtllib gone.mtl\nusemtl skin\n" + kTriangle);
    StillRequest request;
    request.modelPath = model;
    request.loadedScene = std::make_shared<const Scene>(loadScene(model));
    ASSERT_EQ(request.loadedScene->report.warnings.size(), 1u);
    std::ostringstream log;
    // The library's scene: its loader has them (Scene::warnings()); every still of it repeated them.
    const std::unique_ptr<PreparedStill> still = StillRenderer().prepare(request, StillLog{log});
    EXPECT_TRUE(still->warnings.empty());
    EXPECT_EQ(log.str().find("warning"), std::string::npos) << log.str();
    // A batch's still that reuses an earlier still's load stands for loading the file: told and kept again.
    request.reusesEarlierLoad = true;
    const std::unique_ptr<PreparedStill> reused = StillRenderer().prepare(request, StillLog{log});
    EXPECT_EQ(reused->warnings, request.loadedScene->report.warnings);
    EXPECT_EQ(reused->warnings[0].code, "texture-missing");
    EXPECT_NE(log.str().find("warning"), std::string::npos) << log.str();
}

} // namespace
} // namespace inkgraph
