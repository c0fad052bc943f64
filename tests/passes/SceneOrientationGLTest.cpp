// SceneOrientation on a UV sphere: what it uploads is exactly what orientMesh() decided (read back from the buffers),
// the vertex arrays are wired to the right buffers, empty sets upload without a GL error, and the report agrees with
// the exact per-face counts. Needs a GL context (llvmpipe in CI).
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"
#include "passes/orientation/SceneOrientation.h"
#include "scene/Camera.h"
#include "scene/mesh/FaceOrientation.h"
#include "scene/mesh/Procedural.h"
#include "tests/support/GlTestContext.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph::scene_orientation_gl_test {
namespace {

const glm::vec3 kCenter(1.0f, -2.0f, 0.5f);
constexpr float kRadius = 2.0f;

template <typename Element>
std::vector<Element> readBuffer(const GlBuffer& buffer, std::size_t count) {
    std::vector<Element> elements(count);
    if (count > 0) {
        glGetNamedBufferSubData(buffer.id(), 0, GLsizeiptr(count * sizeof(Element)), elements.data());
    }
    return elements;
}

GLint vertexArrayAttribute(const GlVertexArray& array, GLuint location, GLenum property) {
    GLint value = -1;
    glGetVertexArrayIndexediv(array.id(), location, property, &value);
    return value;
}

/** Vertex-buffer binding state of the bound vertex array. */
GLint bindingState(GLenum property, GLuint binding) {
    GLint value = -1;
    glGetIntegeri_v(property, binding, &value);
    return value;
}

GLint elementBufferOf(const GlVertexArray& array) {
    GLint id = -1;
    glGetVertexArrayiv(array.id(), GL_ELEMENT_ARRAY_BUFFER_BINDING, &id);
    return id;
}

class SceneOrientationSphere : public ::testing::Test {
protected:
    void SetUp() override {
        test::sharedGlContext();
        scene = makeScene(makeUvSphere(kCenter, kRadius, 96, 48));
        frame.worldOrigin = glm::dvec3(kCenter); // as the app does: GPU positions relative to the centre
        frame.towardLightWorld = glm::normalize(glm::dvec3(0.3, 0.5, 0.8));
        placeEye(glm::dvec3(kCenter) + 5.0 * double(kRadius) * glm::normalize(glm::dvec3(1.0, 2.0, 2.0)));
    }

    void placeEye(const glm::dvec3& eye) {
        CameraRequest request;
        request.eye = eye;
        request.target = glm::dvec3(kCenter) + glm::dvec3(0.0, 0.0, 0.1); // never equal to an eye at the centre
        request.width = 64;
        request.height = 64;
        frame.camera = resolveCamera(request, scene);
    }

    /** A new GpuScene's orientation for `settings`, as the passes get it (GpuScene::orientation()). */
    SceneOrientation& orientation(OrientationSettings settings) {
        gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
        gpuScene->setOrientation(frame, settings);
        return *gpuScene->orientation();
    }

    /** What orientMesh() decides for the same inputs, computed here independently of SceneOrientation. */
    MeshOrientation expected(const OrientationSettings& settings) const {
        const Mesh& mesh = scene.meshes.at(0);
        OrientationRequest request;
        request.method = settings.method;
        request.frontRule = settings.frontRule;
        const BoundingSphere sphere = computeBoundingSphere(scene);
        request.view = chooseViewVector(settings.viewVector, frame.camera.eye, sphere.center, sphere.radius);
        request.eye = frame.camera.eye;
        request.towardLight = frame.towardLightWorld;
        request.shininess = settings.shininess;
        return orientMesh(mesh, deriveOrientationData(mesh, true), request);
    }

    Scene scene;
    FrameParams frame;
    std::unique_ptr<GpuScene> gpuScene;
};

TEST_F(SceneOrientationSphere, AfterVerticesUploadsWhatOrientMeshDecided) {
    OrientationSettings settings;
    settings.method = FaceOrientationMethod::AfterVertices;
    settings.viewVector = ViewVectorMode::Constant;
    settings.frontRule = 3;
    SceneOrientation& subject = orientation(settings);
    EXPECT_TRUE(subject.usesCpuMarking());
    EXPECT_FALSE(gpuScene->isUploaded()) << "nothing is computed before it is asked for";

    const MeshOrientation reference = expected(settings);
    ASSERT_GT(reference.frontTriangles.size(), 0u);
    ASSERT_GT(reference.backTriangles.size(), 0u);
    const std::vector<SceneOrientation::MeshSets>& sets = subject.sets();
    ASSERT_EQ(sets.size(), 1u);
    const SceneOrientation::MeshSets& meshSets = sets[0];
    EXPECT_EQ(meshSets.frontIndexCount, GLsizei(3 * reference.frontTriangles.size()));
    EXPECT_EQ(meshSets.backIndexCount, GLsizei(3 * reference.backTriangles.size()));
    EXPECT_EQ(readBuffer<glm::uvec3>(meshSets.frontIndices, reference.frontTriangles.size()), reference.frontTriangles);
    EXPECT_EQ(readBuffer<glm::uvec3>(meshSets.backIndices, reference.backTriangles.size()), reference.backTriangles);
    EXPECT_EQ(readBuffer<glm::vec2>(meshSets.shadeCoords, reference.shadeCoords.size()), reference.shadeCoords);
    EXPECT_EQ(meshSets.shadeCoords.byteCount(), reference.shadeCoords.size() * sizeof(glm::vec2));

    // Front array: positions and normals from GpuScene, (s, t) at its location, the front indices.
    const SceneOrientation::MeshSets& s = meshSets; // short name for the wiring checks
    EXPECT_EQ(elementBufferOf(s.frontArray), GLint(s.frontIndices.id()));
    EXPECT_EQ(elementBufferOf(s.backArray), GLint(s.backIndices.id()));
    for (const GLuint location : {GpuScene::kPositionLocation, GpuScene::kNormalLocation}) {
        EXPECT_EQ(vertexArrayAttribute(s.frontArray, location, GL_VERTEX_ATTRIB_ARRAY_ENABLED), 1);
        EXPECT_EQ(vertexArrayAttribute(s.frontArray, location, GL_VERTEX_ATTRIB_ARRAY_SIZE), 3);
        EXPECT_EQ(vertexArrayAttribute(s.backArray, location, GL_VERTEX_ATTRIB_ARRAY_ENABLED), 1);
    }
    const GLuint shade = SceneOrientation::kShadeCoordLocation;
    EXPECT_EQ(vertexArrayAttribute(s.frontArray, shade, GL_VERTEX_ATTRIB_ARRAY_ENABLED), 1);
    EXPECT_EQ(vertexArrayAttribute(s.frontArray, shade, GL_VERTEX_ATTRIB_ARRAY_SIZE), 2);
    EXPECT_EQ(vertexArrayAttribute(s.frontArray, shade, GL_VERTEX_ATTRIB_ARRAY_TYPE), GL_FLOAT);
    EXPECT_EQ(vertexArrayAttribute(s.backArray, shade, GL_VERTEX_ATTRIB_ARRAY_ENABLED), 0);
    // The buffers behind each binding (the binding state is only queryable on the bound array).
    const GpuScene::DrawMesh& drawMesh = gpuScene->meshes().at(0);
    for (const GlVertexArray* array : {&s.frontArray, &s.backArray}) {
        array->bind();
        EXPECT_EQ(bindingState(GL_VERTEX_BINDING_BUFFER, GpuScene::kPositionLocation), GLint(drawMesh.positions.id()));
        EXPECT_EQ(bindingState(GL_VERTEX_BINDING_BUFFER, GpuScene::kNormalLocation), GLint(drawMesh.normals.id()));
    }
    s.frontArray.bind();
    EXPECT_EQ(bindingState(GL_VERTEX_BINDING_BUFFER, shade), GLint(s.shadeCoords.id()));
    EXPECT_EQ(bindingState(GL_VERTEX_BINDING_STRIDE, shade), 2 * GLint(sizeof(float)));
    glBindVertexArray(0);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));

    const OrientationReport& report = subject.report();
    EXPECT_EQ(report.method, "after-vertices");
    EXPECT_EQ(report.viewVector, "constant");
    EXPECT_FALSE(report.fellBack);
    EXPECT_NEAR(report.sinAlpha, 0.2, 1e-6);
    EXPECT_EQ(report.triangles, scene.triangleCount());
    EXPECT_EQ(report.vertices, scene.vertexCount());
    EXPECT_EQ(report.frontTriangles, reference.frontTriangles.size());
    EXPECT_EQ(report.frontVertices, reference.frontVertexCount);
    EXPECT_EQ(report.exactFrontTriangles, countExactFrontTriangles(scene.meshes[0], frame.camera.eye));
    EXPECT_GE(report.frontTriangles, report.exactFrontTriangles);
    EXPECT_EQ(report.missedTriangles, 0u);
    EXPECT_EQ(report.cutoff, reference.cutoff);
    EXPECT_NEAR(report.betaMaxDegrees, glm::degrees(reference.betaMaxRadians), 1e-12);
    EXPECT_GE(report.markMilliseconds, 0.0);
    EXPECT_GE(report.uploadMilliseconds, 0.0);
    EXPECT_EQ(&subject.sets(), &sets) << "computed once";
}

TEST_F(SceneOrientationSphere, EveryCpuMethodReportsNoHoles) {
    for (const FaceOrientationMethod method :
         {FaceOrientationMethod::DuringTriangles, FaceOrientationMethod::DuringVertices,
          FaceOrientationMethod::AfterVertices}) {
        for (const ViewVectorMode mode : {ViewVectorMode::Exact, ViewVectorMode::Constant}) {
            OrientationSettings settings;
            settings.method = method;
            settings.viewVector = mode;
            settings.frontRule = 1;
            const OrientationReport& report = orientation(settings).report();
            EXPECT_EQ(report.missedTriangles, 0u) << report.method << ", " << report.viewVector;
            EXPECT_GE(report.frontTriangles, report.exactFrontTriangles) << report.method;
            EXPECT_EQ(report.viewVector, viewVectorModeName(mode));
            EXPECT_EQ(gpuScene->cpuOrientation()->sets()[0].frontIndexCount, GLsizei(3 * report.frontTriangles));
        }
    }
}

TEST_F(SceneOrientationSphere, EmptyFrontSetUploadsWithoutAGlError) {
    // From the centre every sphere vertex has N.V = 1 (V = P - E is radial): nothing is front, everything is back.
    placeEye(glm::dvec3(kCenter));
    OrientationSettings settings;
    settings.method = FaceOrientationMethod::AfterVertices;
    settings.viewVector = ViewVectorMode::Constant;
    SceneOrientation& subject = orientation(settings);
    const SceneOrientation::MeshSets& meshSets = subject.sets().at(0);
    EXPECT_EQ(meshSets.frontIndexCount, 0);
    EXPECT_EQ(meshSets.backIndexCount, GLsizei(3 * scene.triangleCount()));
    EXPECT_NE(meshSets.frontIndices.id(), 0u);
    EXPECT_EQ(elementBufferOf(meshSets.frontArray), GLint(meshSets.frontIndices.id()));
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));

    const OrientationReport& report = subject.report();
    EXPECT_TRUE(report.fellBack);
    EXPECT_EQ(report.fallBackReason, "eye inside the bounding sphere");
    EXPECT_EQ(report.viewVector, "exact");
    EXPECT_EQ(report.frontTriangles, 0u);
    EXPECT_EQ(report.exactFrontTriangles, 0u);
    EXPECT_EQ(report.missedTriangles, 0u);
}

TEST_F(SceneOrientationSphere, StandardReportsTheExactShareAndHasNoSets) {
    OrientationSettings settings;
    settings.method = FaceOrientationMethod::Standard;
    SceneOrientation& subject = orientation(settings);
    EXPECT_FALSE(subject.usesCpuMarking());
    EXPECT_THROW(subject.sets(), std::logic_error);

    const Mesh& mesh = scene.meshes[0];
    const OrientationReport& report = subject.report();
    EXPECT_EQ(report.method, "standard");
    EXPECT_EQ(report.exactFrontTriangles, countExactFrontTriangles(mesh, frame.camera.eye));
    EXPECT_EQ(report.frontTriangles, report.exactFrontTriangles);
    EXPECT_EQ(report.frontVertices, countExactFrontVertices(mesh, frame.camera.eye));
    EXPECT_EQ(report.missedTriangles, 0u);
    EXPECT_EQ(report.markMilliseconds, 0.0);
    // About the visible cap from 5 radii, (1 - 1/5)/2 = 0.4 of the area; the triangle share lies near it.
    const double share = double(report.frontTriangles) / double(report.triangles);
    EXPECT_GT(share, 0.3);
    EXPECT_LT(share, 0.5);
    EXPECT_FALSE(gpuScene->isUploaded()) << "the Standard report needs no GPU";
}

TEST_F(SceneOrientationSphere, GpuSceneMakesTheCpuOrientationOnceAndOnlyForCpuMethods) {
    gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
    EXPECT_EQ(gpuScene->cpuOrientation(), nullptr) << "nothing set";
    EXPECT_EQ(gpuScene->orientation(), nullptr) << "nothing set";

    OrientationSettings standard;
    gpuScene->setOrientation(frame, standard);
    EXPECT_EQ(gpuScene->cpuOrientation(), nullptr) << "Standard: the GPU culls";
    ASSERT_NE(gpuScene->orientation(), nullptr) << "Standard still reports for --stats";
    EXPECT_FALSE(gpuScene->orientation()->usesCpuMarking());

    OrientationSettings cpu;
    cpu.method = FaceOrientationMethod::DuringTriangles;
    gpuScene->setOrientation(frame, cpu);
    SceneOrientation* first = gpuScene->cpuOrientation();
    ASSERT_NE(first, nullptr);
    EXPECT_TRUE(first->usesCpuMarking()) << "new settings drop the Standard orientation";
    EXPECT_EQ(gpuScene->cpuOrientation(), first) << "made once, then cached";
    EXPECT_EQ(gpuScene->orientation(), first);
    EXPECT_FALSE(gpuScene->isUploaded()) << "making the orientation computes and uploads nothing";
    EXPECT_EQ(first->sets().size(), 1u);
}

TEST_F(SceneOrientationSphere, DescribeGivesTheStatsObject) {
    OrientationSettings settings;
    settings.method = FaceOrientationMethod::AfterVertices;
    SceneOrientation& subject = orientation(settings);
    const nlohmann::ordered_json described = subject.describe();
    const OrientationReport& report = subject.report();
    std::vector<std::string> keys;
    for (const auto& [key, value] : described.items()) keys.push_back(key);
    EXPECT_EQ(keys, (std::vector<std::string>{"method", "view_vector", "fell_back_to_exact", "fall_back_reason",
                                              "sin_alpha", "beta_max_degrees", "cutoff", "triangles", "vertices",
                                              "front_triangles", "front_vertices", "front_triangle_share",
                                              "front_vertex_share", "exact_front_triangles", "missed_triangles",
                                              "derive_ms", "mark_ms", "upload_ms"}));
    EXPECT_EQ(described["method"], "after-vertices");
    EXPECT_EQ(described["triangles"], report.triangles);
    EXPECT_EQ(described["missed_triangles"], 0);
    EXPECT_DOUBLE_EQ(described["front_triangle_share"].get<double>(),
                     double(report.frontTriangles) / double(report.triangles));
}

TEST(SceneOrientationSettings, RejectsBadRuleAndShininess) {
    const Scene scene = makeScene(makeUvSphere({0, 0, 0}, 1.0f, 8, 4));
    GpuScene gpuScene(scene, glm::dvec3(0.0));
    const FrameParams frame;
    OrientationSettings badRule;
    badRule.frontRule = 0;
    EXPECT_THROW(SceneOrientation(scene, gpuScene, frame, badRule), std::invalid_argument);
    OrientationSettings badShininess;
    badShininess.shininess = -2.0;
    EXPECT_THROW(SceneOrientation(scene, gpuScene, frame, badShininess), std::invalid_argument);
    // GpuScene checks them when they are set, before anything runs.
    try {
        gpuScene.setOrientation(frame, badRule);
        ADD_FAILURE() << "no error for front rule 0";
    } catch (const std::invalid_argument& error) {
        EXPECT_STREQ(error.what(), "GpuScene::setOrientation(): the front rule must be 1, 2 or 3, got 0");
    }
    EXPECT_THROW(gpuScene.setOrientation(frame, badShininess), std::invalid_argument);
    EXPECT_EQ(gpuScene.orientation(), nullptr) << "bad settings are not kept";
}

} // namespace
} // namespace inkgraph::scene_orientation_gl_test
