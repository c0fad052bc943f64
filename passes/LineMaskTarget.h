#pragma once
/** @file The start the mesh-drawing line passes (outline, silhouette) share: their mask and depth bound and cleared,
 *  and the eye-inside check. */

#include "gl/GlObjects.h"
#include "gl/GraphExecutor.h"
#include "passes/GpuScene.h"

#include <glm/glm.hpp>
#include <opencv2/core.hpp>

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

/** Up to this many rows a band that finds an outline or silhouette is its line's width in pixels; above, it is the
 *  same share of the mask's height. */
constexpr int kBandReferenceRows = 1024;

/** The width in mask pixels of the band that finds a line `widthPixels` wide (outline, silhouette): widthPixels up to
 *  kBandReferenceRows rows, widthPixels x rows / kBandReferenceRows above. The band only finds the line (its middle,
 *  thinned); the stroke is drawn at the style's width. Fixed in pixels, a band covered half as much surface at 2048²
 *  as at 1024², so where the model hides part of it (the back faces of a thin wing) or two rims lie close, its middle
 *  moved and split between the sizes (docs/strokes.md). The masks are drawn at the output size (--supersample does
 *  not apply to them). */
float bandWidthPixels(float widthPixels, int maskRows);

/** The side in mask pixels of the square that opens a band of one width (bandWidthPixels() of `widthPixels`
 *  everywhere) before the stroke stage thins it: maskRows / kBandReferenceRows pixels, so what is left is what would
 *  be a pixel wide or more at kBandReferenceRows rows, and at most half the band's width, so the band itself is never
 *  opened away. 1 (nothing opened) up to 2 x kBandReferenceRows - 1 rows and for bands under 4 pixels. Above, the
 *  band finds slivers a pixel wide that are under a pixel at the reference size (the inflated hull poking through a
 *  thin part, Lucy's wings at 2048^2), which the stroke stage chained into strokes drawn at one size and not at the
 *  other (docs/strokes.md). */
int bandOpeningPixels(float widthPixels, int maskRows);

/** `band` (CV_8UC1, a band of one width drawn for a line `widthPixels` wide) opened by a square of side
 *  bandOpeningPixels(widthPixels, band.rows), with the band's pixels within that side of what the opening kept put
 *  back: what the stroke stage thins. Slivers apart from the band's full-width stretches go; a remnant a pixel wide
 *  between two of them (where the model hides most of the band) stays. The band itself where the side is 1. */
cv::Mat openedBand(const cv::Mat& band, float widthPixels);

/** `band` (CV_8UC1) as the local width of each of its pixels, in its pixels (CV_32FC1, 0 off the band): twice the
 *  distance to the nearest pixel off it, plus half a pixel. A band W pixels wide measures W + 0.5 (W even) or W + 1.5
 *  (odd) on its middle line, where the stroke stage's points lie: a disc that wide on either middle pixel of an even
 *  band, half a pixel off its middle, still covers both of its edge pixels (three quarters), so no paper shows
 *  between the model and the line. What a band of varying width (--outline-width-map, --silhouette-object-width) is
 *  drawn again at, point by point. The picture's edge counts as off the band. */
cv::Mat1f bandLocalWidths(const cv::Mat& band);

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
