#pragma once
/** @file The start the mesh-drawing line passes (outline, silhouette) share: their mask and depth bound and cleared,
 *  and the eye-inside check. */

#include "gl/GlObjects.h"
#include "gl/GraphExecutor.h"
#include "passes/GpuScene.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace inkgraph {

/** Binds `framebuffer` with the pass's "lines" output and `depth` sized to it, sets the viewport and clears both.
 *  Returns false, with the framebuffer unbound, when `eye` is inside the model: the mask then stays empty, because
 *  back faces and the hull would flood the picture (docs/stability.md). */
bool beginLineMask(GlPassContext& gl, GlFramebuffer& framebuffer, PassDepthBuffer& depth, GpuScene& scene,
                   const glm::dvec3& eye);
/** The same with the model's depth already drawn by another pass (a Format::Depth32F graph texture of the mask's
 *  size): it is attached as it is and only the mask is cleared. */
bool beginLineMask(GlPassContext& gl, GlFramebuffer& framebuffer, const GlTexture& modelDepth, GpuScene& scene,
                   const glm::dvec3& eye);

/** Draws every face of the scene's meshes into the depth buffer only, colour writes off (they stay off), with
 *  `program`, whose uniforms "viewFromModel" and "clipFromView" are set here. When the scene has cut-out or blended
 *  materials, each mesh's material is bound, so a program built with materialAlphaDefines() leaves the cut-out parts
 *  out of the depth (lines behind them stay visible). */
void drawModelDepth(const GlProgram& program, GpuScene& scene, const glm::mat4& viewFromModel,
                    const glm::mat4& clipFromView);

/** The defines that make common/line_mask.frag (with the common/material.glsl snippet) discard what a material cuts
 *  out, as the G-buffer does: none for a scene without MASK or BLEND materials, so opaque scenes sample nothing. */
std::vector<std::string> materialAlphaDefines(const GpuScene& scene);

} // namespace inkgraph
