// The flags that aim the camera: --orbit and --frame parsed into the camera request, and their refusals. No GL.
#include "flags/Options.h"
#include "app/Render.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace inkgraph::camera_flags_test {
namespace {

RenderOptions parse(std::vector<std::string> arguments) {
    arguments.insert(arguments.begin(), {"m.glb", "-o", "x.png"});
    return parseRenderOptions(arguments);
}

std::string usageMessage(std::vector<std::string> arguments) {
    try {
        parse(std::move(arguments));
    } catch (const UsageError& error) {
        return error.what();
    }
    ADD_FAILURE() << "expected a UsageError";
    return {};
}

TEST(CameraFlags, OrbitParsesIntoTheRequest) {
    EXPECT_FALSE(parse({}).orbit.has_value());
    const RenderOptions options = parse({"--orbit", "90,-12.5"});
    ASSERT_TRUE(options.orbit.has_value());
    EXPECT_EQ(options.orbit->azimuthDegrees, 90.0);
    EXPECT_EQ(options.orbit->elevationDegrees, -12.5);
    EXPECT_FALSE(options.orbit->distance.has_value());
    const CameraRequest request = cameraRequestOf(parse({"--orbit", "-30,89.9,7.5", "--target", "1,2,3"}));
    ASSERT_TRUE(request.orbit.has_value());
    EXPECT_EQ(request.orbit->azimuthDegrees, -30.0);
    EXPECT_EQ(request.orbit->elevationDegrees, 89.9);
    EXPECT_EQ(request.orbit->distance, 7.5);
    EXPECT_EQ(request.target, glm::dvec3(1, 2, 3));
}

TEST(CameraFlags, OrbitRefusals) {
    EXPECT_NE(usageMessage({"--orbit", "10"}).find("--orbit: expected AZIMUTH,ELEVATION"), std::string::npos);
    EXPECT_NE(usageMessage({"--orbit", "1,2,3,4"}).find("--orbit: expected"), std::string::npos);
    EXPECT_NE(usageMessage({"--orbit", "a,2"}).find("--orbit: 'a' is not a number"), std::string::npos);
    for (const char* elevation : {"0,90", "0,-90", "0,89.95"})
        EXPECT_NE(usageMessage({"--orbit", elevation}).find("--orbit: the elevation must lie in [-89.9, 89.9]"),
                  std::string::npos)
            << elevation;
    EXPECT_NE(usageMessage({"--orbit", "361,0"}).find("--orbit: the azimuth"), std::string::npos);
    for (const char* distance : {"0,0,0", "0,0,-2", "0,0,1e16"})
        EXPECT_NE(usageMessage({"--orbit", distance}).find("--orbit: the distance must be above 0"), std::string::npos)
            << distance;
    EXPECT_NE(usageMessage({"--orbit", "30,10", "--eye", "0,0,5"}).find("--orbit and --eye both place the eye"),
              std::string::npos);
}

TEST(CameraFlags, FrameParsesNodeNames) {
    EXPECT_TRUE(parse({}).frameNodes.empty());
    const RenderOptions options = parse({"--frame", "Body,Hair Back", "--frame", "Hat"});
    EXPECT_EQ(options.frameNodes, (std::vector<std::string>{"Body", "Hair Back", "Hat"}));
    EXPECT_EQ(cameraRequestOf(options).frameNodes, options.frameNodes);
    EXPECT_NE(usageMessage({"--frame", "Body,"}).find("--frame: empty node name"), std::string::npos);
    EXPECT_NE(usageMessage({"--frame", ",Body"}).find("--frame: empty node name"), std::string::npos);
    // With the target and the distance both fixed, --frame would change nothing.
    EXPECT_NE(usageMessage({"--frame", "Body", "--eye", "0,0,5", "--target", "0,1,0"}).find("--frame has no effect"),
              std::string::npos);
    EXPECT_NE(usageMessage({"--frame", "Body", "--orbit", "0,0,5", "--target", "0,1,0"}).find("--orbit's distance"),
              std::string::npos);
    EXPECT_NO_THROW(parse({"--frame", "Body", "--eye", "0,0,5"}));    // the target
    EXPECT_NO_THROW(parse({"--frame", "Body", "--target", "0,1,0"})); // the distance
    EXPECT_NO_THROW(parse({"--frame", "Body", "--orbit", "0,0,5"}));  // the target
}

} // namespace
} // namespace inkgraph::camera_flags_test
