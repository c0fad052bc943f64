#include "tests/support/GlTestContext.h"

#include <memory>

namespace inkgraph::test {
namespace {
std::unique_ptr<HeadlessContext>& slot() {
    static std::unique_ptr<HeadlessContext> context;
    return context;
}
} // namespace

HeadlessContext& sharedGlContext() {
    if (!slot()) slot() = std::make_unique<HeadlessContext>();
    return *slot();
}

void releaseSharedGlContext() { slot().reset(); }

} // namespace inkgraph::test
