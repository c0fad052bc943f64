#pragma once
/** @file The compiled plan: plain data, printable. */

#include "graph/Pass.h"
#include "graph/Resource.h"

#include <cstddef>
#include <string>
#include <vector>

namespace inkgraph {

struct PlannedPass {
    std::string name;
    std::size_t registrationIndex = 0;           ///< position in the list given to compile()
    std::vector<std::string> reads;              ///< full resource names, declaration order, each once
    std::vector<std::string> liveWrites;         ///< full names of the written resources that are live
    std::vector<std::string> deadOptionalWrites; ///< optional outputs nobody needs: not bound, not computed
    bool hasSideEffect = false;                  ///< declared markSideEffect(): live even if nothing reads it
    bool runsOnHost = false;                     ///< declared runsOnHost(): execute() needs no GPU context
    std::vector<PassBuilder::Scratch> scratch; ///< working memory and own targets it declared (scratch(), ownTarget())
    std::vector<std::string> imports;          ///< scene data it declared (PassBuilder::import()), each once
};

struct CulledPass {
    std::string name;
    std::string reason;              ///< e.g. "no requested output depends on 'hull.color'"
    std::vector<std::string> reads;  ///< full resource names, declaration order (for graphviz())
    std::vector<std::string> writes; ///< full names of everything it would have written
};

struct PlannedResource {
    std::string name; ///< "gbuffer.normal"
    ResourceKind kind = ResourceKind::Texture;
    TextureDesc desc;                 ///< a texture's; an object's picture (its format, at the object's scale)
    ObjectDesc object;                ///< kind Object only
    Presentation presentation;        ///< as its writer declared it
    std::string writer;               ///< pass name
    std::vector<std::string> readers; ///< live readers, in plan order
    std::size_t firstUse = 0;         ///< index into Plan::passes of the writer
    std::size_t lastUse = 0;          ///< index of the last live reader; passes.size()-1 if requested
    bool requested = false;
    /** Whether anything reads the pixels its writer does not cover: a request (every pixel is handed out), or a live
     *  reader that reads ReadExtent::WholeImage. False when every live reader reads ReadExtent::CoveredPixels: the
     *  writer then need not clear the rest. */
    bool backgroundRead = true;
};

struct Plan {
    std::vector<PlannedPass> passes;        ///< topological order, ties broken by registration order
    std::vector<CulledPass> culled;         ///< registration order
    std::vector<PlannedResource> resources; ///< live resources, ordered by firstUse then name
    std::vector<std::string> requested;     ///< as given to compile()

    const PlannedResource* findResource(const std::string& name) const;
    const PlannedPass* findPass(const std::string& name) const;
    /** Every import of the live passes, each once, in plan order: what the importer derives before the passes
     *  prepare. */
    std::vector<std::string> imports() const;
    /** The index of the first pass of the plan's host tail: the passes from there to the end all run on the host
     *  (PlannedPass::runsOnHost), the one before it does not. passes.size() when the last pass needs the GPU. */
    std::size_t hostTailStart() const;
    /** Whether the live resource `name` is a CPU object (ResourceKind::Object). */
    bool isObject(const std::string& name) const {
        const PlannedResource* found = findResource(name);
        return found && found->kind == ResourceKind::Object;
    }
    /** Human-readable plan for --print-plan: one line per pass with its reads and live writes, then the culled
     *  passes with reasons, then resource lifetimes. */
    std::string describe() const;
    /** The plan as a Graphviz DOT digraph (passes are boxes, resources ellipses); culled passes and the resources
     *  nothing computes are drawn grey and dashed. Render with `dot -Tsvg`. */
    std::string graphviz() const;
};

} // namespace inkgraph
