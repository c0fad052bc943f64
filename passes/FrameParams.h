#pragma once
/** @file Per-still parameters every pass may read: camera, light, background. Owned by the app and referenced by the
 *  passes it constructs; set before the graph executes. */

#include "graph/Resource.h"
#include "scene/Camera.h"
#include "scene/Scene.h"

#include <glm/glm.hpp>

namespace inkgraph {

struct FrameParams {
    Camera camera;
    /** World centre that GPU positions are stored relative to (the bounding-sphere centre), so view transforms of
     *  far-from-origin models are computed in double and not lost to float cancellation. */
    glm::dvec3 worldOrigin{0.0};
    glm::dvec3 towardLightWorld{0.0, 0.0, 1.0}; ///< unit
    /** Linear RGB of the uniform ambient light, for the shading models with an ambient term (ShadingModelTraits::
     *  ambient): the passes that light a surface (shade, MToon outlines) read it. */
    glm::vec3 ambientLight{0.15f};
    glm::vec4 background{1.0f, 1.0f, 1.0f, 1.0f}; ///< display RGBA of the paper behind the model
    /** The length `gbuffer.radial` is measured in (the app passes the bounding radius): its values are then of
     *  order 1 at any model scale, so they neither overflow nor underflow a float16 buffer, and a model scaled by
     *  1e-4 gives the same numbers as at scale 1. */
    double radialLengthUnit = 1.0;
    /** The render's time in seconds (--time): the clock of MToon's UV animation, which every pass that binds a
     *  material reads (makeSceneImport() hands it to SceneMaterials::setTime()). A posed model's animation is already
     *  applied to the scene. */
    double time = 0.0;
    /** Where the scene's triangles can cover the frame, in normalized device coordinates (x and y from -1 to 1, y up):
     *  the bounds of every vertex's projection (boundScene()). Work that matters only where a surface lies keeps to it
     *  (scenePixels()): deferred shading, and the read-backs of G-buffer fields read only where covered. The whole
     *  frame until bound, and when a vertex lies at or behind the eye. */
    glm::dvec2 sceneLow{-1.0};
    glm::dvec2 sceneHigh{1.0};

    /** Sets sceneLow and sceneHigh from `scene`'s vertices, projected as the G-buffer projects them (viewFromModel()
     *  and clipFromView(), in float). Call after the camera and worldOrigin are set. */
    void boundScene(const Scene& scene);
    /** The pixels of a width x height target (any scale of the frame) that a triangle of the scene can touch: every
     *  pixel with a sample inside the scene's bounds, and one more on each side for the GPU's rounding; clamped to the
     *  target. Empty (width or height 0) when the scene projects outside it. */
    PixelRect scenePixels(int width, int height) const;

    /** View matrix for positions stored relative to worldOrigin, computed in double then rounded. */
    glm::mat4 viewFromModel() const;
    /** The camera's perspective with reversed-Z depth (near -> 1, far -> 0; gl/GlObjects.h), in float. x, y and w
     *  are those of camera.projectionMatrix(). */
    glm::mat4 clipFromView() const;
    /** Light direction in view space (unit). */
    glm::vec3 towardLightView() const;
};

} // namespace inkgraph
