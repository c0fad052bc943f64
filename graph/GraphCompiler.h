#pragma once
/** @file compile(passes, requested outputs) -> Plan. A pure function: no GL, no globals. */

#include "graph/Pass.h"
#include "graph/Plan.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph {

/** Every problem found in one compile, reported together: the message starts with
 *  "GraphCompiler::compile():" and lists one problem per line, names in single quotes, e.g.
 *  "  - resource 'gbuffer.normal' has two writers: 'gbuffer' and 'gbuffer2'". */
class GraphError : public std::logic_error {
public:
    GraphError(const std::string& message, std::vector<std::string> problems)
        : std::logic_error(message), mProblems(std::move(problems)) {}
    const std::vector<std::string>& problems() const { return mProblems; }

private:
    std::vector<std::string> mProblems;
};

/** Compiles the passes for the requested resources (full names).
 *  Errors gathered before throwing GraphError: two passes with one name; a pass writing outside its namespace or
 *  the same field twice; two writers of one resource; a read nobody writes (by a live pass, or by any pass? by any
 *  pass, so a broken graph fails even when the broken pass would be culled); a requested resource nobody writes;
 *  a cycle (named with its passes); nothing requested and no side-effect pass (the plan would be empty).
 *  Then: live = requested + reads of live passes (+ side-effect passes) + the Required writes of live passes
 *  (Optional writes are live only when read by a live pass or requested); a pass is live if it writes a live resource
 *  or has a side effect; culled passes get a reason; order is topological with ties broken by registration order
 *  (Kahn's algorithm picking the smallest index). An object read (PassBuilder::readObject()) must name the type its
 *  writer declares, and a texture read must not name an object.
 *
 *  Compile data (after Falcor's reflect with compile data): when a pass asks what runs anyway
 *  (PassBuilder::runsAnyway(), liveFieldsAnyway()), every pass is declared a second time with the first round's plan,
 *  and the second round is the plan. The first round is compiled for `decidingRequests` when given (the still graph
 *  gives its final picture, so that a --request of a G-buffer field does not change how the still is drawn), else for
 *  `requested`. declare() stays a pure function of its pass and the compile data: no pass is changed between rounds. */
Plan compile(const std::vector<const Pass*>& passes, const std::vector<std::string>& requested,
             const std::vector<std::string>& decidingRequests = {});

} // namespace inkgraph
