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

/** Records one pass's declarations; handed to Pass::declare(). Never touches GL. */
class PassBuilder {
public:
    struct Read {
        std::string resource; ///< full name, "gbuffer.normal"
    };
    struct Write {
        std::string field; ///< own field, "normal"; the resource is "<pass>.<field>"
        TextureDesc desc;
        Need need = Need::Required;
        Presentation presentation;
    };

    explicit PassBuilder(std::string passName) : mPassName(std::move(passName)) {}

    /** Reads any resource by its full name. */
    void read(std::string_view resource);
    /** Writes a field in this pass's own namespace. */
    void write(std::string_view field, const TextureDesc& desc, Need need = Need::Required,
               Presentation presentation = {});
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
    /** What the last run did, for --stats (e.g. "skipped_eye_inside"); default nothing. Adds keys to `report`. */
    virtual void describe(nlohmann::ordered_json& report) const { (void)report; }
};

} // namespace inkgraph
