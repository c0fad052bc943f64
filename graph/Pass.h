#pragma once
/** @file The Pass interface: a pass declares by name what it reads and writes. Declaring is pure (no GL,
 *  deterministic) so the graph compiles and is tested without a context; how a pass runs is its backend's business
 *  (gl/GlPass.h). */

#include "graph/Resource.h"

#include <nlohmann/json_fwd.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace inkgraph {

struct Plan;

/** What a second round of declarations knows (after Falcor's reflect with compile data): the plan of the first
 *  round, in which no pass knew anything. */
struct CompileData {
    const Plan* firstRound = nullptr;
};

/** Records one pass's declarations; handed to Pass::declare(). Never touches GL. */
class PassBuilder {
public:
    struct Read {
        std::string resource;                       ///< full name, "gbuffer.normal"
        std::string objectType;                     ///< readObject()'s type; empty: a texture
        ReadExtent extent = ReadExtent::WholeImage; ///< a texture's: which of its pixels the pass reads
    };
    struct Write {
        std::string field; ///< own field, "normal"; the resource is "<pass>.<field>"
        TextureDesc desc;  ///< a texture's; an object's picture (ObjectDesc::pictureFormat at its scale)
        Need need = Need::Required;
        Presentation presentation;
        ResourceKind kind = ResourceKind::Texture;
        ObjectDesc object; ///< kind Object only
        /** A texture, or an object with a picture: something a caller can be handed as an image. */
        bool isImage() const { return kind == ResourceKind::Texture || object.hasPicture; }
    };
    /** Working memory a pass holds while it executes and frees before it returns (Falcor's internal resources): not a
     *  resource, but the memory budget sums it over the plan. */
    struct Scratch {
        std::size_t bytesPerPixel = 0; ///< per pixel of the frame at `scale` / `divisor`
        int scale = 1;
        int divisor = 1;
        /** A target the pass keeps from its first run to the still's end (ownTarget()), not memory it frees. */
        bool kept = false;
    };

    /** `compileData`: what the compiler knows of the plan when it asks a second time (CompileData). */
    explicit PassBuilder(std::string passName, const CompileData* compileData = nullptr)
        : mPassName(std::move(passName)), mCompileData(compileData) {}

    /** Reads a texture by its full name; `extent`: which of its pixels (ReadExtent). */
    void read(std::string_view resource, ReadExtent extent = ReadExtent::WholeImage);
    /** Reads a CPU object by its full name; `type` must be the one its writer declares (ObjectDesc::type). */
    void readObject(std::string_view resource, std::string_view type);
    /** Writes a texture field in this pass's own namespace. */
    void write(std::string_view field, const TextureDesc& desc, Need need = Need::Required,
               Presentation presentation = {});
    /** Writes a CPU object field in this pass's own namespace. */
    void writeObject(std::string_view field, const ObjectDesc& desc, Need need = Need::Required,
                     Presentation presentation = {});
    /** Declares scene data the pass takes from outside the graph ("scene.edge-adjacency"): the plan lists it, and
     *  the executor's importer derives what the live passes import once, before any pass prepares
     *  (ExecuteOptions::importData), so no pass derives shared data itself. */
    void import(std::string_view name) { mImports.emplace_back(name); }
    /** Declares working memory (summed per pass). */
    void scratch(std::size_t bytesPerPixel, int scale = 1, int divisor = 1) {
        mScratch.push_back({bytesPerPixel, scale, divisor, false});
    }
    /** Declares a GL target of the pass's own that it keeps between runs (a multisampled colour and depth): not a
     *  resource, but the memory budget counts it with the plan's textures, which the still holds to its end. */
    void ownTarget(std::size_t bytesPerPixel, int scale = 1, int divisor = 1) {
        mScratch.push_back({bytesPerPixel, scale, divisor, true});
    }
    /** Never culled. Use sparingly (nothing in the core pipeline needs it). */
    void markSideEffect() { mSideEffect = true; }
    /** Declares that execute() needs no GPU context: it reads its textures as CPU images and writes only images and
     *  objects. The plan runs such passes after the GPU ones where their reads allow, and a batch runs that tail of
     *  host passes on a worker thread while the next still draws (Plan::hostTailStart()). */
    void runsOnHost() { mRunsOnHost = true; }

    /** Whether pass `name` runs in the plan of the first round (false in the first round itself). A pass that asks
     *  makes the compiler declare every pass a second time with the first round's answers (GraphCompiler.h), so a
     *  pass may read what runs anyway (the G-buffer's fields, its z-buffer) without deciding that it runs. */
    bool runsAnyway(std::string_view name);
    /** The live fields of pass `name` in the first round ("normal", "depth"); empty in the first round. */
    std::vector<std::string> liveFieldsAnyway(std::string_view name);

    const std::string& passName() const { return mPassName; }
    const std::vector<Read>& reads() const { return mReads; }
    const std::vector<Write>& writes() const { return mWrites; }
    const std::vector<Scratch>& scratches() const { return mScratch; }
    const std::vector<std::string>& imports() const { return mImports; }
    bool hasSideEffect() const { return mSideEffect; }
    bool declaredRunsOnHost() const { return mRunsOnHost; }
    bool askedCompileData() const { return mAskedCompileData; }

private:
    std::string mPassName;
    const CompileData* mCompileData;
    std::vector<Read> mReads;
    std::vector<Write> mWrites;
    std::vector<Scratch> mScratch;
    std::vector<std::string> mImports;
    bool mSideEffect = false;
    bool mRunsOnHost = false;
    bool mAskedCompileData = false;
};

class Pass {
public:
    virtual ~Pass() = default;
    /** Instance name, unique in the graph; the namespace of everything it writes. */
    virtual std::string_view name() const = 0;
    /** Cheap, deterministic, no GL. */
    virtual void declare(PassBuilder& builder) const = 0;
    /** What the last run did, for --stats (e.g. "skipped_eye_inside"); default nothing. Adds keys to `report`. */
    virtual void describe(nlohmann::ordered_json& report) const { (void)report; }
};

} // namespace inkgraph
