/** VRM humanoid poses (LoadOptions::pose) and framing by joint and bone, on a humanoid the tests write with known
 *  joint positions and rest rotations: every expected vertex is worked out by hand from the normalized pose
 *  convention (a bone's rotation about world axes of a character facing +Z, from the rest T-pose). */

#include "scene/Camera.h"
#include "scene/Scene.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <sys/stat.h>

namespace inkgraph {
namespace {

using test::TempFile;

glm::dquat turn(double degrees, const glm::dvec3& axis) { return glm::angleAxis(glm::radians(degrees), axis); }

/** `q` as [x, y, z, w]; an `exponent` ("e300") is written after each component, scaling the quaternion. */
std::string quaternionJson(const glm::dquat& q, const std::string& exponent = "") {
    // Appended, not "[" + ...: GCC 12 -O3 warns falsely (-Wstringop-overflow) on the literal-plus-temporary form.
    std::string json = "[";
    for (const double component : {q.x, q.y, q.z, q.w}) json += std::to_string(component) + exponent + ", ";
    json.replace(json.size() - 2, 2, "]");
    return json;
}

const glm::dvec3 kX(1, 0, 0);
const glm::dvec3 kY(0, 1, 0);
const glm::dvec3 kZ(0, 0, 1);

/** A character of five joints in a T-pose, facing +Z as VRM 1.0 draws it (hips at y 1, spine 0.2 above, head 0.4
 *  above the spine, upper arms 0.3 above the spine and 0.2 to each side, each 0.5 long), given as VRM 1.0 or, turned
 *  half a turn about Y by its root node to face -Z, as VRM 0.x. The spine's rest rotation is a quarter turn about Y
 *  and the head's and left arm's are tilted, with translations to match, so the rest pose's local frames are not
 *  the world's: the pose must compose them. Each joint weights one small triangle whose first corner (the anchor)
 *  lies at the hips (0, 1, 0.1), the spine (0, 1.3, 0.1), the head's top (0, 1.8, 0), the left hand (0.7, 1.5, 0)
 *  or the right hand (-0.7, 1.5, 0); a sixth node, a thumb under the left arm, is a bone that weights nothing. */
class TestHumanoid {
public:
    explicit TestHumanoid(bool vrm0) : mVrm0(vrm0) {}

    /** Where `point`, given as the 1.0 character has it, lies in the file's world (0.x: turned about Y). */
    glm::dvec3 world(const glm::dvec3& point) const { return mVrm0 ? glm::dvec3(-point.x, point.y, -point.z) : point; }

    std::string file() const {
        const glm::dquat root = mVrm0 ? turn(180.0, kY) : glm::dquat(1, 0, 0, 0);
        const glm::dquat spine = turn(90.0, kY);
        const glm::dquat head = turn(20.0, kX);
        const glm::dquat leftArm = turn(37.0, kX);
        // Local translations: the world offsets from the parent, in the spine's turned frame under the spine.
        const glm::dvec3 headAt = glm::inverse(spine) * glm::dvec3(0, 0.4, 0);
        const glm::dvec3 leftAt = glm::inverse(spine) * glm::dvec3(0.2, 0.3, 0);
        const glm::dvec3 rightAt = glm::inverse(spine) * glm::dvec3(-0.2, 0.3, 0);
        const auto matrix = [](const glm::dvec3& at, const glm::dquat& rotation) {
            return glm::translate(glm::dmat4(1.0), at) * glm::mat4_cast(rotation);
        };
        const glm::dmat4 rootWorld = matrix({0, 0, 0}, root);
        const glm::dmat4 hipsWorld = rootWorld * matrix({0, 1, 0}, glm::dquat(1, 0, 0, 0));
        const glm::dmat4 spineWorld = hipsWorld * matrix({0, 0.2, 0}, spine);
        const std::vector<glm::dmat4> jointWorlds = {hipsWorld, spineWorld, spineWorld * matrix(headAt, head),
                                                     spineWorld * matrix(leftAt, leftArm),
                                                     spineWorld * matrix(rightAt, glm::dquat(1, 0, 0, 0))};
        const std::vector<glm::dvec3> anchors = {
            {0, 1, 0.1}, {0, 1.3, 0.1}, {0, 1.8, 0}, {0.7, 1.5, 0}, {-0.7, 1.5, 0}};

        test::GltfWriter writer;
        std::vector<glm::vec3> positions;
        std::vector<std::uint8_t> joints;
        std::vector<float> weights;
        std::vector<std::uint32_t> indices;
        for (std::size_t j = 0; j < anchors.size(); ++j) {
            for (const glm::dvec3& corner : {glm::dvec3(0), glm::dvec3(0.02, 0, 0), glm::dvec3(0, 0.02, 0)}) {
                indices.push_back(std::uint32_t(positions.size()));
                positions.push_back(glm::vec3(world(anchors[j] + corner)));
                joints.insert(joints.end(), {std::uint8_t(j), 0, 0, 0});
                weights.insert(weights.end(), {1, 0, 0, 0});
            }
        }
        std::vector<float> inverseBinds;
        for (const glm::dmat4& jointWorld : jointWorlds) {
            const glm::dmat4 inverse = glm::inverse(jointWorld);
            for (int column = 0; column < 4; ++column)
                for (int row = 0; row < 4; ++row) inverseBinds.push_back(float(inverse[column][row]));
        }
        const int positionAccessor = writer.addVec3(positions);
        const int jointAccessor = writer.addJoints(joints);
        const int weightAccessor = writer.addFloats(weights, "VEC4", 4);
        const int bindAccessor = writer.addFloats(inverseBinds, "MAT4", 16);
        const int indexAccessor = writer.addIndices(indices, 2);

        const auto trs = [](const glm::dvec3& at, const glm::dquat& rotation) {
            return "\"translation\": [" + std::to_string(at.x) + ", " + std::to_string(at.y) + ", " +
                   std::to_string(at.z) + "], \"rotation\": " + quaternionJson(rotation);
        };
        const std::vector<std::pair<std::string, int>> bones = {
            {"hips", 2},
            {"spine", 3},
            {"head", 4},
            {"leftUpperArm", 5},
            {"rightUpperArm", 6},
            // 0.x counts the thumb from its proximal bone: its Intermediate is 1.0's Proximal.
            {mVrm0 ? "leftThumbIntermediate" : "leftThumbProximal", 7}};
        std::string humanBones;
        for (const auto& [bone, node] : bones) {
            humanBones += humanBones.empty() ? "" : ", ";
            humanBones += mVrm0 ? "{\"bone\": \"" + bone + "\", \"node\": " + std::to_string(node) + "}"
                                : "\"" + bone + "\": {\"node\": " + std::to_string(node) + "}";
        }
        const std::string extension =
            mVrm0 ? "\"VRM\": {\"humanoid\": {\"humanBones\": [" + humanBones + "]}}"
                  : "\"VRMC_vrm\": {\"specVersion\": \"1.0\", \"humanoid\": {\"humanBones\": {" + humanBones + "}}}";
        return writer.glb(
            "\"extensionsUsed\": [\"" + std::string(mVrm0 ? "VRM" : "VRMC_vrm") + "\"], \"extensions\": {" + extension +
            "}, \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(positionAccessor) +
            ", \"JOINTS_0\": " + std::to_string(jointAccessor) + ", \"WEIGHTS_0\": " + std::to_string(weightAccessor) +
            "}, \"indices\": " + std::to_string(indexAccessor) +
            "}]}], \"skins\": [{\"joints\": [2, 3, 4, 5, 6], \"inverseBindMatrices\": " + std::to_string(bindAccessor) +
            "}], \"nodes\": [{\"name\": \"Body\", \"mesh\": 0, \"skin\": 0}, {\"name\": \"Root\", " +
            trs({0, 0, 0}, root) + ", \"children\": [2]}, {\"name\": \"J_Hips\", \"translation\": [0, 1, 0], " +
            "\"children\": [3]}, {\"name\": \"J_Spine\", " + trs({0, 0.2, 0}, spine) +
            ", \"children\": [4, 5, 6]}, {\"name\": \"J_Head\", " + trs(headAt, head) +
            "}, {\"name\": \"J_LeftArm\", " + trs(leftAt, leftArm) +
            ", \"children\": [7]}, {\"name\": \"J_RightArm\", " + trs(rightAt, glm::dquat(1, 0, 0, 0)) +
            "}, {\"name\": \"J_Thumb\", \"translation\": [0.5, 0, 0]}], \"scenes\": [{\"nodes\": [0, 1]}], "
            "\"scene\": 0");
    }

private:
    bool mVrm0;
};

/** The scene's vertex nearest `expected` (world coordinates), and its distance. */
double distanceToNearestVertex(const Scene& scene, const glm::dvec3& expected) {
    double nearest = 1e300;
    for (const Mesh& mesh : scene.meshes)
        for (const glm::vec3& position : mesh.positions)
            nearest = std::min(nearest, glm::length(test::worldPosition(scene, position) - expected));
    return nearest;
}

constexpr double kTolerance = 1e-5; // float positions of a model 2 units across

Scene loadPosed(const TempFile& model, const std::string& pose) {
    LoadOptions options;
    options.pose = pose;
    return loadScene(model.path(), options);
}

class VrmHumanoidPose : public testing::TestWithParam<bool> {};

TEST_P(VrmHumanoidPose, RestPoseIsTheFilesTPose) {
    const TestHumanoid humanoid(GetParam());
    const TempFile model("humanoid.vrm", humanoid.file());
    const Scene scene = loadScene(model.path());
    for (const glm::dvec3 anchor : {glm::dvec3(0.7, 1.5, 0), glm::dvec3(-0.7, 1.5, 0), glm::dvec3(0, 1.8, 0)})
        EXPECT_LT(distanceToNearestVertex(scene, humanoid.world(anchor)), kTolerance);
}

TEST_P(VrmHumanoidPose, APoseLowersBothUpperArmsBy45Degrees) {
    const TestHumanoid humanoid(GetParam());
    const TempFile model("humanoid.vrm", humanoid.file());
    const Scene scene = loadPosed(model, "a-pose");
    // Each hand turns 45 degrees down about the forward axis around its shoulder (+-0.2, 1.5, 0), 0.5 away.
    const double down = 0.5 * std::sqrt(0.5);
    EXPECT_LT(distanceToNearestVertex(scene, humanoid.world({0.2 + down, 1.5 - down, 0})), kTolerance);
    EXPECT_LT(distanceToNearestVertex(scene, humanoid.world({-0.2 - down, 1.5 - down, 0})), kTolerance);
    EXPECT_GT(distanceToNearestVertex(scene, humanoid.world({0.7, 1.5, 0})), 0.1);
    // Nothing else moves.
    EXPECT_LT(distanceToNearestVertex(scene, humanoid.world({0, 1.8, 0})), kTolerance);
    EXPECT_LT(distanceToNearestVertex(scene, humanoid.world({0, 1.3, 0.1})), kTolerance);
    EXPECT_TRUE(scene.report.warnings.empty());
}

TEST_P(VrmHumanoidPose, PoseFileTurnsBonesAboutWorldAxes) {
    const TestHumanoid humanoid(GetParam());
    const TempFile model("humanoid.vrm", humanoid.file());
    // A quarter turn about +Y swings the left arm (+X) behind the character (-Z); one about +X tips the head's top
    // (+Y) forward (+Z). Both bones' rest rotations are tilted, and their parent's a quarter turn.
    const TempFile pose("pose.json", "{\"leftUpperArm\": " + quaternionJson(turn(90, kY)) +
                                         ", \"head\": " + quaternionJson(turn(90, kX)) + "}");
    const Scene scene = loadPosed(model, pose.path());
    EXPECT_LT(distanceToNearestVertex(scene, humanoid.world({0.2, 1.5, -0.5})), kTolerance);
    EXPECT_LT(distanceToNearestVertex(scene, humanoid.world({0, 1.6, 0.2})), kTolerance);
    EXPECT_LT(distanceToNearestVertex(scene, humanoid.world({-0.7, 1.5, 0})), kTolerance);
    EXPECT_NE(std::find(scene.report.inputFiles.begin(), scene.report.inputFiles.end(), pose.path()),
              scene.report.inputFiles.end())
        << "the pose file is one of the load's input files";
    // Scaled by 1e300 or 1e-200, whose sums of squares overflow or underflow a double, the quaternions turn the bones
    // alike (such a pose was refused as of length 0 or infinite).
    for (const std::string exponent : {"e300", "e-200"}) {
        SCOPED_TRACE(exponent);
        const TempFile scaled("pose.json", "{\"leftUpperArm\": " + quaternionJson(turn(90, kY), exponent) +
                                               ", \"head\": " + quaternionJson(turn(90, kX), exponent) + "}");
        const Scene turned = loadPosed(model, scaled.path());
        EXPECT_LT(distanceToNearestVertex(turned, humanoid.world({0.2, 1.5, -0.5})), kTolerance);
        EXPECT_LT(distanceToNearestVertex(turned, humanoid.world({0, 1.6, 0.2})), kTolerance);
    }
}

TEST_P(VrmHumanoidPose, ParentAndChildRotationsCompose) {
    const TestHumanoid humanoid(GetParam());
    const TempFile model("humanoid.vrm", humanoid.file());
    // The spine turns a quarter about +Y and the left arm a quarter about -Z under it: the arm's joint goes from
    // (0.2, 0.3, 0) above the spine to (0, 0.3, -0.2), the hand hangs 0.5 below it.
    const TempFile pose("pose.json", "{\"spine\": " + quaternionJson(turn(90, kY)) +
                                         ", \"leftUpperArm\": " + quaternionJson(turn(90, -kZ)) + "}");
    const Scene scene = loadPosed(model, pose.path());
    EXPECT_LT(distanceToNearestVertex(scene, humanoid.world({0, 1.0, -0.2})), kTolerance);
    EXPECT_LT(distanceToNearestVertex(scene, humanoid.world({0.1, 1.3, 0})), kTolerance) << "the spine's anchor";
    EXPECT_LT(distanceToNearestVertex(scene, humanoid.world({0, 1.8, 0})), kTolerance) << "the head's top, on the axis";
    EXPECT_LT(distanceToNearestVertex(scene, humanoid.world({0, 1, 0.1})), kTolerance) << "the hips do not move";
}

TEST_P(VrmHumanoidPose, ABoneTheModelLacksIsAWarning) {
    const TestHumanoid humanoid(GetParam());
    const TempFile model("humanoid.vrm", humanoid.file());
    const TempFile pose("pose.json", "{\"jaw\": [0, 0, 0.7071068, 0.7071068]}");
    const Scene scene = loadPosed(model, pose.path());
    ASSERT_EQ(scene.report.warnings.size(), 1u);
    EXPECT_EQ(scene.report.warnings[0].code, "pose-bone-missing");
    EXPECT_EQ(scene.report.warnings[0].message, "the pose turns 'jaw', which the model's humanoid lacks; ignored");
    EXPECT_LT(distanceToNearestVertex(scene, humanoid.world({0.7, 1.5, 0})), kTolerance);
}

TEST_P(VrmHumanoidPose, JointsCarryTheBoxesOfWhatTheyWeight) {
    const TestHumanoid humanoid(GetParam());
    const TempFile model("humanoid.vrm", humanoid.file());
    const Scene scene = loadPosed(model, "a-pose");
    const auto jointNamed = [&](const std::string& node) -> const SceneJoint& {
        for (const SceneJoint& joint : scene.joints)
            if (joint.node == node) return joint;
        throw std::runtime_error("no joint " + node);
    };
    const auto worldBox = [&](const SceneJoint& joint) {
        const glm::dvec3 a = scene.origin + joint.lower;
        const glm::dvec3 b = scene.origin + joint.upper;
        return std::pair{glm::min(a, b), glm::max(a, b)};
    };
    ASSERT_EQ(scene.joints.size(), 6u) << "five skin joints and the thumb, a bone";
    EXPECT_EQ(jointNamed("J_Head").bone, "head");
    EXPECT_EQ(jointNamed("J_Thumb").bone, "leftThumbProximal");
    EXPECT_GT(jointNamed("J_Thumb").lower.x, jointNamed("J_Thumb").upper.x) << "the thumb weights nothing";
    // The head weights its triangle alone: (0, 1.8, 0) to (0.02, 1.82, 0), turned with the model.
    const auto [headLow, headHigh] = worldBox(jointNamed("J_Head"));
    const glm::dvec3 corner = humanoid.world({0.02, 1.82, 0});
    EXPECT_LT(glm::length(headLow - glm::min(humanoid.world({0, 1.8, 0}), corner)), kTolerance);
    EXPECT_LT(glm::length(headHigh - glm::max(humanoid.world({0, 1.8, 0}), corner)), kTolerance);
    // The spine's box takes its descendants': the posed hands' triangles (turned 45 degrees with the arms, so their
    // 0.02 legs reach 0.02 sqrt(1/2) out and down) to either side and below, the head's top above.
    const auto [spineLow, spineHigh] = worldBox(jointNamed("J_Spine"));
    const double reach = 0.2 + 0.5 * std::sqrt(0.5) + 0.02 * std::sqrt(0.5);
    EXPECT_NEAR(spineHigh.x - spineLow.x, 2 * reach, kTolerance);
    EXPECT_NEAR(spineHigh.y, 1.82, kTolerance);
    EXPECT_NEAR(spineLow.y, 1.5 - 0.5 * std::sqrt(0.5) - 0.02 * std::sqrt(0.5), kTolerance);
}

TEST_P(VrmHumanoidPose, FrameByBoneFitsWhatTheBoneWeights) {
    const TestHumanoid humanoid(GetParam());
    const TempFile model("humanoid.vrm", humanoid.file());
    const Scene scene = loadScene(model.path());
    CameraRequest byBone;
    byBone.frameNodes = {"head"};
    CameraRequest byJoint;
    byJoint.frameNodes = {"J_Head"};
    const Camera bone = resolveCamera(byBone, scene);
    const glm::dvec3 target = scene.origin + bone.target;
    EXPECT_LT(glm::length(target - humanoid.world({0.01, 1.81, 0})), kTolerance);
    EXPECT_LT(glm::length(resolveCamera(byJoint, scene).eye - bone.eye), 1e-9);
    // The box's half diagonal, 0.01 sqrt 2, is the framed radius: the eye stands 1.05 r / sin(17.5 degrees) away.
    EXPECT_NEAR(glm::length(bone.eye - bone.target), 1.05 * 0.01 * std::sqrt(2.0) / std::sin(glm::radians(17.5)), 1e-6);
    const Camera whole = resolveCamera({}, scene);
    EXPECT_GT(glm::length(whole.eye - whole.target), 10.0 * glm::length(bone.eye - bone.target));
}

/** A VRM Animation of three bones whose rest pose differs from the model's (hips 0.9 high, a spine tilted 30 degrees
 *  about X, a left arm rolled 10 degrees about Z), animated over one second: the left arm's raw rotation goes from
 *  its rest to the one that turns it a quarter about -Z in world axes, the hips 0.09 along +X. */
std::string vrmaFile() {
    const glm::dquat spine = turn(30.0, kX);
    const glm::dquat arm = turn(10.0, kZ);
    // raw = P^-1 q P R: the normalized quarter turn q expressed in the arm's parent's rest frame P.
    const glm::dquat turned = glm::inverse(spine) * turn(90.0, -kZ) * spine * arm;
    test::GltfWriter writer;
    const int times = writer.addFloats({0.0f, 1.0f}, "SCALAR", 1);
    const int rotations = writer.addFloats({float(arm.x), float(arm.y), float(arm.z), float(arm.w), float(turned.x),
                                            float(turned.y), float(turned.z), float(turned.w)},
                                           "VEC4", 4);
    const int translations = writer.addFloats({0.0f, 0.9f, 0.0f, 0.09f, 0.9f, 0.0f}, "VEC3", 3);
    return writer.glb(
        "\"extensionsUsed\": [\"VRMC_vrm_animation\"], \"extensions\": {\"VRMC_vrm_animation\": {\"specVersion\": "
        "\"1.0\", \"humanoid\": {\"humanBones\": {\"hips\": {\"node\": 0}, \"spine\": {\"node\": 1}, "
        "\"leftUpperArm\": {\"node\": 2}}}}}, \"nodes\": [{\"name\": \"hips\", \"translation\": [0, 0.9, 0], "
        "\"children\": [1]}, {\"name\": \"spine\", \"translation\": [0, 0.2, 0], \"rotation\": " +
        quaternionJson(spine) +
        ", \"children\": [2]}, {\"name\": \"arm\", \"translation\": [0.2, 0.3, 0], \"rotation\": " +
        quaternionJson(arm) +
        "}], \"scenes\": [{\"nodes\": [0]}], \"animations\": [{\"channels\": [{\"sampler\": 0, \"target\": "
        "{\"node\": 2, \"path\": \"rotation\"}}, {\"sampler\": 1, \"target\": {\"node\": 0, \"path\": "
        "\"translation\"}}], \"samplers\": [{\"input\": " +
        std::to_string(times) + ", \"output\": " + std::to_string(rotations) +
        "}, {\"input\": " + std::to_string(times) + ", \"output\": " + std::to_string(translations) + "}]}]");
}

TEST_P(VrmHumanoidPose, VrmAnimationIsRetargetedThroughTheBones) {
    const TestHumanoid humanoid(GetParam());
    const TempFile model("humanoid.vrm", humanoid.file());
    const TempFile animation("wave.vrma", vrmaFile());
    const auto posedAt = [&](double time) {
        LoadOptions options;
        options.animation = animation.path();
        options.time = time;
        return loadScene(model.path(), options);
    };
    // At 1 s the left arm hangs straight down from its shoulder (0.2, 1.5, 0); the hips (1 high, the .vrma's 0.9)
    // moved 0.09 x 1 / 0.9 = 0.1 along +X, and everything with them.
    const Scene end = posedAt(1.0);
    EXPECT_LT(distanceToNearestVertex(end, humanoid.world({0.3, 1.0, 0})), kTolerance);
    EXPECT_LT(distanceToNearestVertex(end, humanoid.world({0.1, 1.8, 0})), kTolerance) << "the head, unturned";
    EXPECT_LT(distanceToNearestVertex(end, humanoid.world({-0.6, 1.5, 0})), kTolerance) << "the right hand";
    // Half-way the raw rotations slerp, and so does the normalized one: the arm is 45 degrees down, as in a-pose.
    const Scene half = posedAt(0.5);
    const double down = 0.5 * std::sqrt(0.5);
    EXPECT_LT(distanceToNearestVertex(half, humanoid.world({0.25 + down, 1.5 - down, 0})), kTolerance);
    // At 0 s the .vrma is at its rest: the model's T-pose.
    EXPECT_LT(distanceToNearestVertex(posedAt(0.0), humanoid.world({0.7, 1.5, 0})), kTolerance);
    const std::vector<std::string>& inputs = end.report.inputFiles;
    EXPECT_NE(std::find(inputs.begin(), inputs.end(), animation.path()), inputs.end());
}

INSTANTIATE_TEST_SUITE_P(Vrm, VrmHumanoidPose, testing::Values(false, true),
                         [](const testing::TestParamInfo<bool>& vrm0x) { return vrm0x.param ? "Vrm0x" : "Vrm10"; });

TEST(VrmHumanoid, UnknownFrameNameListsNodesBonesAndJoints) {
    const TempFile model("humanoid.vrm", TestHumanoid(false).file());
    const Scene scene = loadScene(model.path());
    CameraRequest request;
    request.frameNodes = {"tail"};
    try {
        resolveCamera(request, scene);
        ADD_FAILURE() << "expected a refusal";
    } catch (const SceneError& error) {
        EXPECT_EQ(std::string(error.what()),
                  "resolveCamera(): --frame 'tail': no mesh lies under a node of that name, and no joint or humanoid "
                  "bone has it (the model's nodes with meshes under them: 'Body'; its humanoid bones: 'hips', "
                  "'spine', 'head', 'leftUpperArm', 'rightUpperArm', 'leftThumbProximal'; its joints: 'J_Hips', "
                  "'J_Spine', 'J_Head', 'J_LeftArm', 'J_RightArm', 'J_Thumb')");
    }
}

TEST(VrmHumanoid, BadPoseFilesAreRefusedNamingTheFile) {
    const TempFile model("humanoid.vrm", TestHumanoid(false).file());
    const auto refusal = [&](const std::string& content) {
        const TempFile pose("pose.json", content);
        const std::string message = test::sceneErrorMessage([&] { loadPosed(model, pose.path()); });
        const std::string start = "loadScene(): '" + pose.path() + "': ";
        EXPECT_EQ(message.rfind(start, 0), 0u) << message;
        const std::string problem = message.substr(std::min(message.size(), start.size()));
        // Judged alike without a model, before a run's first still, speaking for the flag that named the file.
        EXPECT_EQ(test::sceneErrorMessage([&] { checkPoseFile(pose.path(), kDefaultLoadMemoryLimit, "--poses"); }),
                  "--poses: '" + pose.path() + "': " + problem);
        return problem;
    };
    EXPECT_EQ(refusal("{\"leftUpperArm\": [0, 0, 0, 1]").rfind("not a pose file: invalid JSON (", 0), 0u);
    EXPECT_EQ(refusal("[1, 2]"),
              "not a pose file: expected a JSON object of humanoid bone names to quaternions [x, y, z, w]");
    EXPECT_EQ(refusal("{\"head\": [0, 0, 1]}"), "'head': expected a quaternion [x, y, z, w] of four numbers");
    EXPECT_EQ(refusal("{\"head\": [0, 0, \"1\", 0]}"), "'head': expected a quaternion [x, y, z, w] of four numbers");
    EXPECT_EQ(refusal("{\"head\": [0, 0, 0, 0]}"), "'head': the quaternion must be finite and of non-zero length");
    EXPECT_EQ(refusal("{\"head\": [0, 0, 0, 1], \"neck\": [0, 0, 0, 1], \"head\": [0, 0, 1, 0]}"),
              "'head' is given twice (a bone takes one quaternion)");
    const std::string unknown = refusal("{\"tail\": [0, 0, 0, 1]}");
    EXPECT_EQ(unknown.rfind("unknown humanoid bone 'tail' (VRM's humanoid bones: hips, spine, chest, upperChest, "
                            "neck, head, leftEye, rightEye, jaw, leftUpperLeg, ",
                            0),
              0u)
        << unknown;
    EXPECT_NE(unknown.find("leftThumbMetacarpal"), std::string::npos) << unknown;
    // A NUL in a name is written out: the message, read through what(), ended at it ("unknown humanoid bone 'he").
    const std::string nulName = refusal("{\"he\\u0000ad\": [0, 0, 0, 1]}");
    EXPECT_EQ(nulName.rfind("unknown humanoid bone 'he\\x00ad' (VRM's humanoid bones: hips, ", 0), 0u) << nulName;
    // A NUL byte after the JSON ended the parser's input: what followed was never read.
    EXPECT_EQ(refusal(std::string("{\"head\": [0, 0, 0, 1]}\0junk", 27)),
              "not a pose file: a NUL byte at byte 22 (JSON is text)");
    EXPECT_NE(unknown.find("rightLittleDistal)"), std::string::npos) << unknown;

    const std::string missing = test::sceneErrorMessage([&] { loadPosed(model, model.path() + ".missing.json"); });
    EXPECT_EQ(missing, "loadScene(): '" + model.path() + ".missing.json': the pose file cannot be found");
    // A FIFO is refused before it is opened: opening one blocks until a writer comes, for ever here.
    const std::string fifo = model.path() + ".fifo.json";
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    const std::string blocked = test::sceneErrorMessage([&] { loadPosed(model, fifo); });
    const std::string checkedFifo = test::sceneErrorMessage([&] { checkPoseFile(fifo); });
    std::filesystem::remove(fifo);
    EXPECT_EQ(blocked, "loadScene(): '" + fifo + "': the pose file is not a regular file (a folder, FIFO or device)");
    EXPECT_EQ(checkedFifo,
              "checkPoseFile(): '" + fifo + "': the pose file is not a regular file (a folder, FIFO or device)");
    EXPECT_EQ(test::sceneErrorMessage([&] { checkPoseFile(model.path() + ".missing.json", 1 << 20, "--pose"); }),
              "--pose: '" + model.path() + ".missing.json': the pose file cannot be found");
}

TEST(VrmHumanoid, APoseThatEveryModelWouldTakePassesTheCheckWithoutAModel) {
    EXPECT_NO_THROW(checkPoseFile(""));
    EXPECT_NO_THROW(checkPoseFile("a-pose"));
    const TempFile pose("pose.json", "{\"head\": [0, 0.1, 0, 1], \"leftEye\": [0, 0, 0, 2]}");
    EXPECT_NO_THROW(checkPoseFile(pose.path()));
    // The file is charged to the run's memory limit as the load charges it.
    const std::string message = test::sceneErrorMessage([&] { checkPoseFile(pose.path(), 8, "--pose"); });
    EXPECT_EQ(message.rfind("--pose: ", 0), 0u) << message;
    EXPECT_NE(message.find("--memory-limit"), std::string::npos) << message;
}

TEST(VrmHumanoid, AVrmaNeedsItsExtensionAndAHumanoid) {
    const TempFile model("humanoid.vrm", TestHumanoid(false).file());
    test::GltfWriter writer;
    writer.addVec3({{0, 0, 0}});
    const TempFile bare("bare.vrma", writer.glb("\"nodes\": [{\"name\": \"hips\"}]"));
    LoadOptions options;
    options.animation = bare.path();
    EXPECT_EQ(test::sceneErrorMessage([&] { loadScene(model.path(), options); }),
              "loadScene(): '" + bare.path() + "': not a VRM Animation file: it has no VRMC_vrm_animation extension");
    const TempFile animation("wave.vrma", vrmaFile());
    const TempFile plain("plain.glb", writer.glb("\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": "
                                                 "0}}]}], \"nodes\": [{\"mesh\": 0}]"));
    options.animation = animation.path();
    EXPECT_EQ(test::sceneErrorMessage([&] { loadScene(plain.path(), options); }),
              "loadScene(): '" + plain.path() +
                  "': cannot take a humanoid animation: not a VRM model (no VRMC_vrm or VRM extension)");
}

TEST(VrmHumanoid, ABoneGivenTwiceOrTwoBonesOnOneNodeOrHumanBonesOfTheOtherVersionsFormAreSaid) {
    // A 0.x bone given twice kept the last without a word, two bones on one node loaded silently, and humanBones in
    // the other version's form (0.x's array, 1.0's object) was told as a humanoid without a head.
    const auto vrmWith = [](const std::string& extension) {
        test::GltfWriter writer;
        const int positions = writer.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
        return writer.glb("\"extensions\": {" + extension + "}, \"meshes\": [{\"primitives\": [{\"attributes\": " +
                          "{\"POSITION\": " + std::to_string(positions) +
                          "}}]}], \"nodes\": [{\"mesh\": 0}, {\"name\": \"A\"}, {\"name\": \"B\"}], "
                          "\"scenes\": [{\"nodes\": [0, 1, 2]}]");
    };
    const TempFile pose("pose.json", "{\"head\": [0, 0, 0, 1]}");
    const auto messagesOf = [&](const std::string& extension) {
        const TempFile model("humanoid.vrm", vrmWith(extension));
        std::vector<std::string> messages;
        for (const Warning& warning : loadPosed(model, pose.path()).report.warnings)
            messages.push_back("[" + warning.code + "] " + warning.message);
        return messages;
    };
    EXPECT_EQ(messagesOf(R"("VRM": {"humanoid": {"humanBones": [{"bone": "head", "node": 1},
                                      {"bone": "head", "node": 2}, {"bone": "neck", "node": 1}]}})"),
              (std::vector<std::string>{
                  "[vrm-property-invalid] VRM.humanoid.humanBones[1] 'head' is given twice (node 1, then node 2); the "
                  "first is kept",
                  "[vrm-property-invalid] VRM.humanoid.humanBones[2] 'neck': node 1 is already bone 'head' (a node is "
                  "one bone); ignored"}));
    const std::vector<std::string> object = messagesOf(R"("VRM": {"humanoid": {"humanBones": {"head": {"node": 1}}}})");
    ASSERT_FALSE(object.empty());
    EXPECT_EQ(object.front(), "[vrm-property-invalid] VRM.humanoid.humanBones is not an array (an object, as VRM "
                              "1.0's VRMC_vrm writes it); ignored");
    const std::vector<std::string> array =
        messagesOf(R"("VRMC_vrm": {"specVersion": "1.0", "humanoid": {"humanBones": [{"bone": "head", "node": 1}]}})");
    ASSERT_FALSE(array.empty());
    EXPECT_EQ(array.front(), "[vrm-property-invalid] VRMC_vrm.humanoid.humanBones is not an object (an array, as VRM "
                             "0.x's VRM writes it); ignored");
}

TEST(VrmHumanoid, AModelWithoutAHumanoidIsRefused) {
    test::GltfWriter writer;
    const int positions = writer.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const TempFile gltf("plain.gltf", writer.gltf("\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " +
                                                  std::to_string(positions) + "}}]}], \"nodes\": [{\"mesh\": 0}]"));
    EXPECT_EQ(test::sceneErrorMessage([&] { loadPosed(gltf, "a-pose"); }),
              "loadScene(): '" + gltf.path() +
                  "': cannot take a humanoid pose: not a VRM model (no VRMC_vrm or VRM extension)");
    const TempFile obj("plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_EQ(test::sceneErrorMessage([&] { loadPosed(obj, "a-pose"); }),
              "loadScene(): '" + obj.path() +
                  "': cannot take a humanoid pose: not a VRM model (obj files have no humanoid bones)");
}

} // namespace
} // namespace inkgraph
