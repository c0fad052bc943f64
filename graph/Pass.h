#pragma once
/** @file The Pass interface: a pass declares by name what it reads and writes, then executes.
 *  Declaring is pure (no GL, deterministic) so the graph compiles and is tested without a context. */

#include "graph/Resource.h"

#include <string>
#include <string_view>
#include <vector>

namespace inkgraph {

class PassContext;

/** Records one pass's declarations; handed to Pass::declare(). Never touches GL. */
class PassBuilder {
public:
    struct Read {
        std::string resource; ///< full name, "gbuffer.normal"
    };
    struct Write {
        std::string field;    ///< own field, "normal"; the resource is "<pass>.<field>"
        TextureDesc desc;
        Need need = Need::Required;
    };

    explicit PassBuilder(std::string passName) : mPassName(std::move(passName)) {}

    /** Reads any resource by its full name. */
    void read(std::string_view resource);
    /** Writes a field in this pass's own namespace. */
    void write(std::string_view field, const TextureDesc& desc, Need need = Need::Required);
    /** Never culled. Use sparingly (nothing in the core pipeline needs it). */
    void markSideEffect() { mSideEffect = true; }

    const std::string& passName() const { return mPassName; }
    const std::vector<Read>& reads() const { return mReads; }
    const std::vector<Write>& writes() const { return mWrites; }
    bool hasSideEffect() const { return mSideEffect; }

private:
    std::string mPassName;
    std::vector<Read> mReads;
    std::vector<Write> mWrites;
    bool mSideEffect = false;
};

class Pass {
public:
    virtual ~Pass() = default;
    /** Instance name, unique in the graph; the namespace of everything it writes. */
    virtual std::string_view name() const = 0;
    /** Cheap, deterministic, no GL. */
    virtual void declare(PassBuilder& builder) const = 0;
    /** Once per run, before anything executes and outside the timed execute(): build programs, upload meshes.
     *  May ask the context which outputs are live; must not touch resources. */
    virtual void prepare(PassContext& context) { (void)context; }
    /** Runs the pass. The context knows which optional outputs are live. */
    virtual void execute(PassContext& context) = 0;
};

/** What a pass sees while it executes. The graph core knows only names; a backend (gl/GlPassContext) adds
 *  access to the textures behind them. */
class PassContext {
public:
    virtual ~PassContext() = default;
    /** True when this pass's field (e.g. "normal") is consumed or requested in the plan. */
    virtual bool isLive(std::string_view field) const = 0;
    /** The frame size (the output image's size). A field with a scale is larger: see the backend's widthOf(). */
    virtual int width() const = 0;
    virtual int height() const = 0;
};

} // namespace inkgraph
