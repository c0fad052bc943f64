#include "scene/Camera.h"

#include "scene/MessageText.h"
#include "scene/mesh/MeshOps.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

namespace inkgraph {

namespace {

constexpr double kDefaultFovYDegrees = 35.0;
const glm::dvec3 kDefaultUp(0.0, 1.0, 0.0);
/** Auto-framing looks from the model's front, raised by this much of the up vector so tops of models read as tops. */
constexpr double kAutoFrameLift = 0.25;
/** When world +Z lies this close to up (|Z . u| above it), the front is world -Y instead (Z-up CAD and STL models). */
constexpr double kMaxFrontAlongUp = 0.9;
constexpr double kFramingMargin = 1.05;
/** --orbit's elevation stops this short of +-90 degrees, where up would be parallel to the view. */
constexpr double kMaxOrbitElevationDegrees = 89.9;
/** Up must lie at least this far from the view direction: nearer, the picture's turn about the view follows the
 *  view's slightest tilt (--target moved by 1e-5 under an eye straight above turned it 180 degrees). Half --orbit's
 *  margin from +-90, so every orbit passes. */
constexpr double kMinUpToViewDegrees = 0.05;
/** A --frame error names at most this many of the scene's nodes. */
constexpr std::size_t kMaxNamedNodes = 10;
/** The eye and the target must lie farther apart than this times their distance from the scene's origin (at least
 *  1): closer, the view direction is lost to rounding. */
constexpr double kMinViewLength = 1e-12;
/** Near never drops below far x this, which bounds depth-buffer precision loss when the eye is close or inside. */
constexpr double kMinNearOverFar = 1e-4;

bool isFinite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

[[noreturn]] void invalid(const std::string& problem) { throw std::invalid_argument("resolveCamera(): " + problem); }

/** A --frame name this model lacks: the model's mismatch with the flags (as --expression on a model without a VRM
 *  face), so a batch of mixed models fails only this one, exit 3, rather than stopping as for a bad flag. */
[[noreturn]] void notInModel(const std::string& problem) { throw SceneError("resolveCamera(): " + problem); }

/** "x,y,z", the syntax of the vector flags. */
std::string formatVector(const glm::dvec3& v) {
    std::ostringstream text;
    text << v.x << ',' << v.y << ',' << v.z;
    return text.str();
}

std::string formatNumber(double value) {
    std::ostringstream text;
    text << value;
    return text.str();
}

/** Distance at which a sphere of `radius` fits the narrower of the vertical and horizontal fields of view. */
double framingDistance(double radius, double fovYRadians, double aspect) {
    const double fovXRadians = 2.0 * std::atan(std::tan(fovYRadians / 2.0) * aspect);
    return kFramingMargin * radius / std::sin(std::min(fovYRadians, fovXRadians) / 2.0);
}

/** The unit horizontal toward the side the model faces: the model's front (world +Z unless the file says, or world
 *  -Y when that is nearly along up, Blender's front view of a Z-up scene) made perpendicular to the unit up `u`. */
glm::dvec3 frontHorizontal(const glm::dvec3& u, const std::optional<glm::dvec3>& modelFront) {
    glm::dvec3 front = modelFront.value_or(glm::dvec3(0.0, 0.0, 1.0));
    if (std::abs(glm::dot(front, u)) > kMaxFrontAlongUp) {
        front = glm::dvec3(0.0, -1.0, 0.0); // |Y . u| < sqrt(1 - 0.9^2) here, so the projection below is not short
    }
    return glm::normalize(front - glm::dot(front, u) * u);
}

/** Unit direction from the target toward the auto-framed eye: the front horizontal lifted by kAutoFrameLift x up.
 *  `up` must be non-zero and finite. For up (0, 1, 0) every step is exact, giving exactly normalize(0, 0.25, 1). */
glm::dvec3 autoFrameDirection(const glm::dvec3& up, const std::optional<glm::dvec3>& modelFront) {
    const glm::dvec3 u = glm::normalize(up);
    return glm::normalize(frontHorizontal(u, modelFront) + kAutoFrameLift * u);
}

/** Unit direction from the target toward an orbit's eye: the front horizontal turned by the azimuth about up toward
 *  u x h (the front view's right), then raised by the elevation. */
glm::dvec3 orbitDirection(const glm::dvec3& up, const std::optional<glm::dvec3>& modelFront, const Orbit& orbit) {
    const glm::dvec3 u = glm::normalize(up);
    const glm::dvec3 front = frontHorizontal(u, modelFront);
    const glm::dvec3 right = glm::cross(u, front);
    const double azimuth = glm::radians(orbit.azimuthDegrees);
    const double elevation = glm::radians(orbit.elevationDegrees);
    const glm::dvec3 horizontal = std::cos(azimuth) * front + std::sin(azimuth) * right;
    return glm::normalize(std::cos(elevation) * horizontal + std::sin(elevation) * u);
}

/** "'a', 'b' and 3 more": at most kMaxNamedNodes of `names`, quoted. */
std::string namedList(const std::vector<std::string>& names) {
    std::string list;
    for (std::size_t i = 0; i < std::min(names.size(), kMaxNamedNodes); ++i) {
        list += (list.empty() ? "'" : ", '") + detail::excerptForMessage(names[i]) + "'";
    }
    if (names.size() > kMaxNamedNodes) list += " and " + std::to_string(names.size() - kMaxNamedNodes) + " more";
    return list;
}

/** The refusal of a --frame name that is no node with meshes under it, joint or humanoid bone, naming some of each. */
[[noreturn]] void unknownFrameName(const Scene& scene, const std::string& name) {
    std::vector<std::string> nodes;
    std::set<std::string> seen;
    for (const Mesh& mesh : scene.meshes) {
        for (const std::string& node : mesh.nodePath) {
            if (!node.empty() && seen.insert(node).second) nodes.push_back(node);
        }
    }
    std::vector<std::string> bones;
    std::vector<std::string> joints;
    for (const SceneJoint& joint : scene.joints) {
        if (!joint.bone.empty()) bones.push_back(joint.bone);
        if (!joint.node.empty() && seen.insert(joint.node).second) joints.push_back(joint.node);
    }
    std::string known = nodes.empty() ? std::string("the model has no named nodes")
                                      : "the model's nodes with meshes under them: " + namedList(nodes);
    if (!bones.empty()) known += "; its humanoid bones: " + namedList(bones);
    if (!joints.empty()) known += "; its joints: " + namedList(joints);
    // A mesh the load skipped (a pose that scaled its node to 0) draws nothing: say so, or the name that holds it
    // reads as a typing error.
    std::vector<std::string> skipped, skippedUnderName;
    for (const SkippedMesh& mesh : scene.skippedMeshes) {
        skipped.push_back(mesh.mesh.name);
        if (std::ranges::find(mesh.mesh.nodePath, name) != mesh.mesh.nodePath.end())
            skippedUnderName.push_back(mesh.mesh.name);
    }
    if (!skippedUnderName.empty())
        notInModel("--frame '" + detail::excerptForMessage(name) +
                   "': the meshes under that node draw nothing, their triangles all degenerate (mesh-degenerate: a "
                   "pose that collapses them?): " +
                   namedList(skippedUnderName) + " (" + known + ")");
    if (!skipped.empty())
        known +=
            "; meshes skipped as all degenerate (mesh-degenerate: a pose that collapses them?): " + namedList(skipped);
    notInModel("--frame '" + detail::excerptForMessage(name) +
               "': no mesh lies under a node of that name, and no joint or humanoid bone has it (" + known + ")");
}

/** The bounding sphere of what the named nodes frame (computed like computeBoundingSphere()): the meshes under them
 *  (any entry of Mesh::nodePath), and the posed vertices a joint of that node name or humanoid bone name weights,
 *  with its descendant joints' (SceneJoint's box, whose corners bound the radius). A name that is none of these is
 *  an error naming some of the scene's nodes, bones and joints. */
BoundingSphere framedSphere(const Scene& scene, const std::vector<std::string>& nodeNames) {
    // A bone name frames its node, by that node's name, as the node's own name would.
    std::vector<std::string> framedNodes = nodeNames;
    std::vector<const SceneJoint*> framedJoints;
    for (const std::string& name : nodeNames) {
        bool found = std::ranges::any_of(scene.meshes, [&](const Mesh& mesh) {
            return std::ranges::find(mesh.nodePath, name) != mesh.nodePath.end();
        });
        for (const SceneJoint& joint : scene.joints) {
            if (joint.node != name && joint.bone != name) continue;
            found = true;
            framedJoints.push_back(&joint);
            if (joint.bone == name) framedNodes.push_back(joint.node);
        }
        if (!found) unknownFrameName(scene, name);
    }
    const auto underNamedNode = [&](const Mesh& mesh) {
        return std::ranges::any_of(mesh.nodePath, [&](const std::string& node) {
            return std::ranges::find(framedNodes, node) != framedNodes.end();
        });
    };
    BoundingBox box;
    for (const Mesh& mesh : scene.meshes) {
        if (underNamedNode(mesh)) {
            for (const glm::vec3& p : mesh.positions) {
                box.add(glm::dvec3(p));
            }
        }
    }
    for (const SceneJoint* joint : framedJoints) {
        if (joint->lower.x > joint->upper.x) continue; // weights no vertex
        box.add(joint->lower);
        box.add(joint->upper);
    }
    if (box.empty()) {
        notInModel("--frame: the meshes under the named nodes have no vertices, and the named joints weight none");
    }
    BoundingSphere sphere;
    sphere.center = box.center();
    double maxDistanceSquared = 0.0;
    const auto reach = [&](const glm::dvec3& p) {
        const glm::dvec3 offset = p - sphere.center;
        maxDistanceSquared = std::max(maxDistanceSquared, glm::dot(offset, offset));
    };
    for (const Mesh& mesh : scene.meshes) {
        if (underNamedNode(mesh)) {
            for (const glm::vec3& p : mesh.positions) reach(glm::dvec3(p));
        }
    }
    for (const SceneJoint* joint : framedJoints) {
        if (joint->lower.x > joint->upper.x) continue;
        for (int corner = 0; corner < 8; ++corner) {
            reach(glm::dvec3(corner & 1 ? joint->upper.x : joint->lower.x, corner & 2 ? joint->upper.y : joint->lower.y,
                             corner & 4 ? joint->upper.z : joint->lower.z));
        }
    }
    sphere.radius = std::sqrt(maxDistanceSquared);
    return sphere;
}

} // namespace

glm::dmat4 Camera::viewMatrix() const { return glm::lookAt(eye, target, up); }

glm::dmat4 Camera::worldViewMatrix() const { return viewMatrix() * glm::translate(glm::dmat4(1.0), -origin); }

glm::dmat4 Camera::projectionMatrix() const {
    return glm::perspective(glm::radians(fovYDegrees), aspect(), zNear, zFar);
}

double Camera::focalPixels() const { return (double(height) / 2.0) / std::tan(glm::radians(fovYDegrees) / 2.0); }

glm::dmat3 Camera::openCvIntrinsics() const {
    const double focal = focalPixels();
    glm::dmat3 k(0.0);
    k[0][0] = focal;
    k[1][1] = focal;
    k[2] = glm::dvec3(double(width) / 2.0 - 0.5, double(height) / 2.0 - 0.5, 1.0);
    return k;
}

glm::dmat4x3 Camera::openCvExtrinsics() const {
    // The view matrix's rotation is the same in the local and the world frame (they differ by a translation), so it
    // comes from the local viewMatrix(), whose numbers are small; only t sees the world's large coordinates.
    const glm::dmat3 viewRotation(viewMatrix());
    glm::dmat3 rotation = viewRotation;
    for (int column = 0; column < 3; ++column) {
        rotation[column][1] = -viewRotation[column][1];
        rotation[column][2] = -viewRotation[column][2];
    }
    glm::dmat4x3 extrinsics(0.0);
    for (int column = 0; column < 3; ++column) extrinsics[column] = rotation[column];
    extrinsics[3] = -(rotation * worldEye());
    return extrinsics;
}

Camera resolveCamera(const CameraRequest& request, const Scene& scene) {
    if (request.width <= 0 || request.height <= 0) {
        invalid("the image size " + std::to_string(request.width) + "x" + std::to_string(request.height) +
                " (--size) must be positive");
    }
    const auto requireFinite = [](const std::optional<glm::dvec3>& vector, const char* flag) {
        if (vector && !isFinite(*vector)) {
            invalid(std::string(flag) + " " + formatVector(*vector) + " must be finite");
        }
    };
    requireFinite(request.eye, "--eye");
    requireFinite(request.target, "--target");
    requireFinite(request.up, "--up");
    std::string orbitText; // "--orbit AZ,EL[,DIST]" as given, for messages
    if (request.orbit) {
        const Orbit& orbit = *request.orbit;
        // Appended, not "," + text: GCC 12 warns falsely (-Wrestrict, bug 105329) on that inlined.
        orbitText = "--orbit " + formatNumber(orbit.azimuthDegrees);
        orbitText.append(",").append(formatNumber(orbit.elevationDegrees));
        if (orbit.distance) orbitText.append(",").append(formatNumber(*orbit.distance));
        if (!orbit.distance && orbit.distanceScale != 1.0)
            orbitText.append(",x").append(formatNumber(orbit.distanceScale));
        if (request.eye) {
            invalid(orbitText + " and --eye both place the eye: give one");
        }
        if (!std::isfinite(orbit.azimuthDegrees) || !std::isfinite(orbit.elevationDegrees)) {
            invalid(orbitText + ": the angles must be finite");
        }
        if (std::abs(orbit.elevationDegrees) > kMaxOrbitElevationDegrees) {
            invalid(orbitText + ": the elevation must lie in [-89.9, 89.9] degrees (at +-90 the view is parallel to "
                                "up)");
        }
        if (orbit.distance && !(std::isfinite(*orbit.distance) && *orbit.distance > 0.0)) {
            invalid(orbitText + ": the distance must be finite and above 0");
        }
        if (!(std::isfinite(orbit.distanceScale) && orbit.distanceScale > 0.0)) {
            invalid(orbitText + ": the distance scale must be finite and above 0");
        }
    }

    Camera camera;
    camera.width = request.width;
    camera.height = request.height;
    camera.origin = scene.origin;
    // The user speaks world coordinates; the scene and the renderer work relative to the scene origin. Messages show
    // world values (what the user typed), so `world` converts back.
    const std::optional<glm::dvec3> requestEye =
        request.eye ? std::optional<glm::dvec3>(*request.eye - scene.origin) : std::nullopt;
    const std::optional<glm::dvec3> requestTarget =
        request.target ? std::optional<glm::dvec3>(*request.target - scene.origin) : std::nullopt;
    const auto world = [&](const glm::dvec3& local) { return formatVector(scene.origin + local); };

    // The file's camera is one unit, its placement, orientation and lens: a view the flags place (--eye, --orbit,
    // --frame) is composed for the default lens, and the file's 18 degrees meant for its own eye would crop it.
    const bool flagsPlaceView = request.eye || request.orbit || !request.frameNodes.empty();
    const SceneCamera* fileCamera =
        scene.camera && !request.ignoreFileCamera && !flagsPlaceView ? &*scene.camera : nullptr;
    camera.fovYDegrees = request.fovYDegrees ? *request.fovYDegrees
                         : fileCamera        ? fileCamera->fovYDegrees
                                             : kDefaultFovYDegrees;
    if (!std::isfinite(camera.fovYDegrees) || camera.fovYDegrees <= 0.0 || camera.fovYDegrees >= 180.0) {
        const std::string fov = formatNumber(camera.fovYDegrees);
        invalid(request.fovYDegrees
                    ? "the vertical field of view (--fov " + fov + ") is outside (0, 180) degrees"
                    : "the glTF camera's vertical field of view " + fov + " degrees is outside (0, 180); set --fov");
    }

    // Unset, up follows the glTF camera when that camera places the view; an explicit --up always wins.
    camera.up = request.up ? *request.up : fileCamera ? fileCamera->up : kDefaultUp;
    const std::string upText = request.up ? "--up " + formatVector(camera.up)
                               : fileCamera
                                   ? "the glTF camera's up " + formatVector(camera.up) + "; override it with --up"
                                   : "the default " + formatVector(camera.up) + " without --up";
    if (!(glm::length(camera.up) > 0.0)) {
        invalid("the up vector (" + upText + ") is zero");
    }

    // The clip planes fit the whole scene (a ground plane under a --frame'd character must not be clipped); the
    // framing (default target, distance) fits the framed part.
    const BoundingSphere sphere = computeBoundingSphere(scene);
    const BoundingSphere framed = request.frameNodes.empty() ? sphere : framedSphere(scene, request.frameNodes);
    const std::string centreText = (request.frameNodes.empty() ? "the model's bounding-sphere centre ("
                                                               : "the bounding-sphere centre of the --frame nodes (") +
                                   world(framed.center) + ")";
    // A point-sized scene still needs a usable framing distance.
    const double radius = framed.radius > 0.0 ? framed.radius : sphere.radius > 0.0 ? sphere.radius : 1.0;

    // Each branch also says, for the error messages below, where its eye, target and view direction come from.
    std::string eyeText;
    std::string targetText;
    std::string viewText;
    if (requestEye) {
        camera.eye = *requestEye;
        camera.target = requestTarget ? *requestTarget : framed.center;
        camera.source = "flags";
        eyeText = "the eye (--eye " + formatVector(*request.eye) + ")";
        targetText = request.target ? "the target (--target " + formatVector(*request.target) + ") coincide"
                                    : "the target coincide; without --target the target is " + centreText;
        viewText = "from --eye to " + (request.target ? std::string("--target") : centreText);
    } else if (fileCamera) {
        camera.eye = fileCamera->eye;
        if (requestTarget) {
            camera.target = *requestTarget;
        } else {
            // Only the direction matters to lookAt; aim at the depth of the model so the target is meaningful.
            const double depth = glm::length(sphere.center - fileCamera->eye);
            camera.target = fileCamera->eye + fileCamera->forward * (depth > 0.0 ? depth : 1.0);
        }
        camera.source = "gltf";
        eyeText = "the glTF camera's eye (" + world(camera.eye) + "; override it with --eye)";
        targetText = request.target ? "the target (--target " + formatVector(*request.target) + ") coincide"
                                    : "its target coincide";
        viewText = request.target ? "from the glTF camera's eye to --target"
                                  : "the glTF camera's forward " + formatVector(fileCamera->forward);
    } else {
        camera.target = requestTarget ? *requestTarget : framed.center;
        const double fittedDistance = framingDistance(radius, glm::radians(camera.fovYDegrees), camera.aspect());
        if (request.orbit) {
            camera.eye =
                camera.target + orbitDirection(camera.up, scene.front, *request.orbit) *
                                    request.orbit->distance.value_or(fittedDistance * request.orbit->distanceScale);
            camera.source = "orbit";
        } else {
            camera.eye = camera.target + autoFrameDirection(camera.up, scene.front) * fittedDistance;
            camera.source = "auto-framed";
        }
        eyeText = "the " + std::string(request.orbit ? "orbit's" : "auto-framed") + " eye (" + world(camera.eye) + ")";
        // An orbit's scale the user typed (",xS") sets the eye that near, not the model's size.
        const bool scaled = request.orbit && !request.orbit->distance && request.orbit->distanceScale < 1.0;
        targetText = (request.target ? "the target (--target " + formatVector(*request.target) + ")"
                                     : "the target, " + centreText + ",") +
                     (scaled ? " coincide: the orbit's scale x" + formatNumber(request.orbit->distanceScale) +
                                   " puts the eye too near the target for their distance from the origin; raise it"
                             : " coincide: the model is too small for its distance from the origin; set --eye");
        viewText = request.orbit ? "the --orbit direction" : "the auto-framing direction";
    }

    const glm::dvec3 view = camera.target - camera.eye;
    const double viewLength = glm::length(view);
    // Closer than this, double cannot tell the eye from the target at their distance from the scene's origin.
    const double minViewLength = kMinViewLength * std::max(1.0, glm::length(camera.eye));
    if (!(viewLength > minViewLength)) {
        if (request.orbit && request.orbit->distance && camera.source == "orbit") {
            // The distance the user typed put the eye there, not the model.
            invalid(orbitText + ": the distance " + formatNumber(*request.orbit->distance) +
                    " is too small to set the eye apart from the target; give at least " +
                    formatNumber(2.0 * kMinViewLength * std::max(1.0, glm::length(camera.target))));
        }
        invalid(eyeText + " and " + targetText);
    }
    if (const double sine = glm::length(glm::cross(view / viewLength, glm::normalize(camera.up)));
        !(sine >= std::sin(glm::radians(kMinUpToViewDegrees)))) {
        invalid("the up vector (" + upText + ") is parallel to the view direction (" + viewText + ")" +
                (sine >= 1e-9 ? ", " + formatNumber(glm::degrees(std::asin(sine))) + " degrees off: within " +
                                    formatNumber(kMinUpToViewDegrees) +
                                    " degrees the picture's turn about the view would follow its slightest tilt"
                              : std::string()) +
                "; give an --up across the view (for an eye straight above, --up 0,0,-1)");
    }

    // Fit the clip planes to the bounding sphere so nothing is clipped and depth precision is spent on the model. The
    // planes are perpendicular to the view axis, so the sphere's nearest depth is its centre's depth along that axis
    // less the radius: with the model off the axis (--target elsewhere) the centre's distance would put the near
    // plane behind the front of the sphere and clip a cap off it.
    const double distance = glm::length(camera.eye - sphere.center);
    const double centreDepth = glm::dot(sphere.center - camera.eye, view / viewLength);
    camera.zFar = (distance + sphere.radius) * 1.01;
    if (!(camera.zFar > 0.0)) {
        camera.zFar = 1.0; // the eye sits on a point-sized scene
    }
    const double minNear = camera.zFar * kMinNearOverFar;
    const double nearestDepth = centreDepth - sphere.radius;
    camera.zNear = distance < sphere.radius || !(nearestDepth > 0.0) ? minNear : std::max(nearestDepth, minNear) * 0.99;
    if (request.zNear || request.zFar) {
        if (!request.zNear || !request.zFar) {
            invalid("--clip needs both the near and the far distance");
        }
        const double n = *request.zNear;
        const double f = *request.zFar;
        if (!std::isfinite(n) || !std::isfinite(f) || !(n > 0.0) || !(n < f)) {
            invalid("--clip " + formatNumber(n) + "," + formatNumber(f) + " must be finite with 0 < near < far");
        }
        camera.zNear = n;
        camera.zFar = f;
        camera.clipSource = "flags";
    }
    return camera;
}

std::optional<Warning> modelOutsideView(const Camera& camera, const Scene& scene, const PictureSampling& sampling) {
    // The half-spaces outside the view, in view space (the camera looks down -Z; depth = -z). A model wholly inside one
    // of them shows nothing. Behind the eye comes first: it is also nearer than the near plane.
    const double tanY = std::tan(glm::radians(camera.fovYDegrees) / 2.0);
    const double tanX = tanY * camera.aspect();
    const std::string clip = camera.clipSource == "flags" ? " (--clip)" : "";
    struct Side {
        std::string where;
        std::function<bool(const glm::dvec3&)> outside;
    };
    const std::vector<Side> sides = {
        {"behind the camera", [](const glm::dvec3& v) { return -v.z <= 0.0; }},
        {"nearer than the near plane at " + formatNumber(camera.zNear) + clip,
         [&](const glm::dvec3& v) { return -v.z < camera.zNear; }},
        {"beyond the far plane at " + formatNumber(camera.zFar) + clip,
         [&](const glm::dvec3& v) { return -v.z > camera.zFar; }},
        {"left of the view", [&](const glm::dvec3& v) { return v.x < v.z * tanX; }},
        {"right of the view", [&](const glm::dvec3& v) { return v.x > -v.z * tanX; }},
        {"below the view", [&](const glm::dvec3& v) { return v.y < v.z * tanY; }},
        {"above the view", [&](const glm::dvec3& v) { return v.y > -v.z * tanY; }},
    };
    std::vector<bool> allOutside(sides.size(), true);
    const glm::dmat4 view = camera.viewMatrix();
    bool anyVertex = false;
    // The model's extent on the image in pixels, of what lies beyond the near plane: the vertices there, and where an
    // edge crosses the plane, the crossing (the clipped triangle's corner). A model seen under a pixel (an eye far
    // away) covers one pixel centre or none, and with none the picture is as blank; so is a model whose vertices
    // nearer than the plane (behind a wide-angle eye) leave such a speck beyond it.
    const double focal = camera.focalPixels();
    glm::dvec2 low(std::numeric_limits<double>::infinity()), high(-std::numeric_limits<double>::infinity());
    const auto addToExtent = [&](const glm::dvec3& v) {
        const glm::dvec2 onImage = glm::dvec2(v.x, v.y) * (focal / -v.z);
        low = glm::min(low, onImage);
        high = glm::max(high, onImage);
    };
    const auto beyondNear = [&](const glm::dvec3& v) { return -v.z >= camera.zNear; };
    const auto inView = [&](const glm::vec3& p) { return glm::dvec3(view * glm::dvec4(glm::dvec3(p), 1.0)); };
    for (const Mesh& mesh : scene.meshes) {
        bool someNearer = false;
        for (const glm::vec3& p : mesh.positions) {
            anyVertex = true;
            const glm::dvec3 v = inView(p);
            for (std::size_t i = 0; i < sides.size(); ++i) {
                if (allOutside[i] && !sides[i].outside(v)) allOutside[i] = false;
            }
            if (beyondNear(v)) {
                addToExtent(v);
            } else {
                someNearer = true;
            }
        }
        if (!someNearer) continue; // the usual case: no edge crosses the plane
        // Each vertex again rather than kept: a copy in double would cost more memory than the mesh.
        for (const glm::uvec3& triangle : mesh.triangles) {
            const std::array<glm::dvec3, 3> corners{inView(mesh.positions[triangle[0]]),
                                                    inView(mesh.positions[triangle[1]]),
                                                    inView(mesh.positions[triangle[2]])};
            for (int corner = 0; corner < 3; ++corner) {
                const glm::dvec3& a = corners[corner];
                const glm::dvec3& b = corners[(corner + 1) % 3];
                if (beyondNear(a) == beyondNear(b)) continue;
                // The point of the edge at depth zNear: between a's depth and b's, so the division is by no zero.
                const double t = (camera.zNear + a.z) / (a.z - b.z);
                addToExtent(glm::mix(a, b, t));
            }
        }
    }
    const auto side = std::ranges::find(allOutside, true);
    if (!anyVertex) return std::nullopt;
    std::string where;
    std::string consequence = "the picture shows only the background";
    if (side != allOutside.end()) {
        where = "every vertex lies " + sides[std::size_t(side - allOutside.begin())].where;
    } else {
        // Lines drawn as bands round the model (an outline, a silhouette) may still leave a dot of ink.
        consequence = "no pixel shows its surface (its lines may leave a dot)";
        // Pixel centres lie at half-integers of the image (y down); the model covers none unless its extent holds one
        // both ways. A model under a pixel that holds one (a 1 x 1 picture) is drawn. --supersample samples the
        // centres of its finer grid; --msaa's sample positions lie on a grid of 1/16 pixel, each of its points taken.
        const bool multisampled = sampling.msaaSamples > 1;
        const double perPixel = double(std::max(sampling.supersample, 1)) * (multisampled ? 16.0 : 1.0);
        const double offset = multisampled ? 0.0 : 0.5;
        const auto holdsASample = [&](double from, double to, int size) {
            const double first = std::max(std::ceil(from * perPixel - offset), 0.0);
            return first + offset <= to * perPixel && first < double(size) * perPixel;
        };
        const glm::dvec2 extent = high - low;
        const glm::dvec2 centre(0.5 * camera.width, 0.5 * camera.height);
        const bool drawsAPixel = holdsASample(centre.x + low.x, centre.x + high.x, camera.width) &&
                                 holdsASample(centre.y - high.y, centre.y - low.y, camera.height);
        // Over a pixel one way is no better for the surface: a sliver under a pixel wide between two columns of
        // centres covers none. Lines drawn from the mesh still draw it, as a line of its length.
        const bool underAPixel = extent.x < 1.0 && extent.y < 1.0;
        if (drawsAPixel || (sampling.linesDrawTheMesh && !underAPixel)) return std::nullopt;
        // Or no sliver at all: what lies beyond the near plane falls beside the picture (an eye at the model's edge
        // looking away, where no single side of the view has every vertex beyond it).
        const bool besideThePicture = centre.x + high.x <= 0.0 || centre.x + low.x >= camera.width ||
                                      centre.y - low.y <= 0.0 || centre.y - high.y >= camera.height;
        if (underAPixel || !besideThePicture) {
            where = "the model spans " + detail::formatExtent(extent.x) + " x " + detail::formatExtent(extent.y) +
                    " pixels, " + (underAPixel ? "under a pixel" : "between pixel centres") +
                    " (move the eye nearer or narrow --fov)";
        } else {
            where = "what lies before the eye falls beside the picture (aim the view at the model: --target)";
        }
    }
    std::string who;
    if (camera.source == "gltf") {
        who = "the glTF camera" + (scene.camera && !scene.camera->name.empty() ? " (" + scene.camera->name + ")" : "");
    } else if (camera.source == "flags") {
        who = "the camera of --eye " + formatVector(camera.worldEye());
    } else if (camera.source == "orbit") {
        // --views places each view as an orbit too: "--orbit" named a flag the user may not have given.
        who = "the orbit camera (--orbit or a --views view)";
    } else {
        who = "the auto-framed camera";
    }
    return makeWarning(WarningKind::ModelOutsideView,
                       who + " sees none of the model: " + where + ", so " + consequence +
                           (camera.source == "gltf" ? "; --camera auto frames the model instead" : ""));
}

} // namespace inkgraph
