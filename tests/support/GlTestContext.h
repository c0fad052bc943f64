#pragma once
/** @file One headless context per test process. GL tests are never skipped: when no context can be made, every
 *  test that asks for one fails with the reason (llvmpipe gives CI a real GL 4.5 context). */

#include "gl/HeadlessContext.h"

namespace inkgraph::test {

/** Creates the context on first use; throws HeadlessContextError (failing the calling test) when it cannot. */
HeadlessContext& sharedGlContext();

/** Destroys the shared context, for tests that create contexts of their own (one at a time per process). */
void releaseSharedGlContext();

} // namespace inkgraph::test
