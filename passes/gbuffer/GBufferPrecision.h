#pragma once
/** @file Storage precision of the G-buffer's direction and derivative fields: its own header, without GL, so the
 *  command line can name it. */

namespace inkgraph {

/** Float32: rgba32f / r32f (the default). Float16: rgba16f / r16f for normal, view, wVec, nDotV and radial, kept to
 *  measure what float32 buys (docs/accuracy.md); depth stays r32f. */
enum class GBufferPrecision { Float32, Float16 };

} // namespace inkgraph
