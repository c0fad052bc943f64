#pragma once
/** @file The view transforms every pass that draws the meshes sets the same way: one place, so the G-buffer, the
 *  shading and MToon's outline shells transform every vertex identically (their depths must match bit for bit where
 *  one lays its layer in by depth). */

#include "gl/GlObjects.h"
#include "passes/FrameParams.h"

namespace inkgraph {

/** Sets `program`'s (in use) viewFromModel, viewNormalFromModel (the inverse transpose of its 3x3) and clipFromView
 *  from `frame`; also, where the program has it, worldFromView (the view's rotation undone: MToon's matcap works in
 *  world directions). */
void setViewUniforms(const GlProgram& program, const FrameParams& frame);

} // namespace inkgraph
