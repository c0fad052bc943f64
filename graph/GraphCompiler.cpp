#include "graph/GraphCompiler.h"

#include <algorithm>
#include <cassert>
#include <cctype>
#include <functional>
#include <limits>
#include <queue>
#include <string_view>
#include <unordered_map>
#include <unordered_set>

namespace inkgraph {
namespace {

constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

std::string quote(std::string_view name) { return "'" + std::string(name) + "'"; }

/** "'a'", "'a' and 'b'", "'a', 'b' and 'c'" (or "or" in place of "and"). */
std::string quoteList(const std::vector<std::string>& names, std::string_view lastSeparator = "and") {
    std::string text;
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (i > 0) text += (i + 1 == names.size()) ? " " + std::string(lastSeparator) + " " : ", ";
        text += quote(names[i]);
    }
    return text;
}

/** A well-formed written field: non-empty, no dot (a pass writes only inside its own namespace). */
bool isValidField(std::string_view field) { return !field.empty() && field.find('.') == std::string_view::npos; }

/** One written resource and everyone who touches it, by registration index. */
struct ResourceInfo {
    std::string name;
    ResourceKind kind = ResourceKind::Texture;
    ObjectDesc object;
    TextureDesc desc;
    Need need = Need::Required;
    Presentation presentation;
    std::vector<std::size_t> writers;
    std::vector<std::size_t> readers;    ///< registration order, each once
    std::vector<ReadExtent> readExtents; ///< parallel to readers: the widest extent that reader declared
};

/** One pass after declare(). */
struct DeclaredPass {
    const Pass* pass = nullptr;
    std::string name;
    bool hasSideEffect = false;
    bool runsOnHost = false;
    std::vector<std::string> reads;         ///< declaration order, each once
    std::vector<std::size_t> readResources; ///< parallel to reads: index into resources, or kNone if nobody writes it
    std::vector<std::size_t> writes;        ///< well-formed writes, declaration order: indices into resources
    std::vector<std::string> allWrites;     ///< every declared write as a full name, for CulledPass
    std::vector<PassBuilder::Scratch> scratch;
    std::vector<std::string> imports; ///< each once, declaration order
};

/** Everything compile() derives from the declarations, before liveness. */
class Declarations {
public:
    Declarations(const std::vector<const Pass*>& passList, const CompileData& compileData,
                 std::vector<std::string>& problems)
        : mProblems(problems) {
        declarePasses(passList, compileData);
        checkPassNames();
        collectWrites();
        checkWriters();
        resolveReads();
        buildEdges();
    }

    std::vector<DeclaredPass> passes;
    std::vector<ResourceInfo> resources;
    std::unordered_map<std::string, std::size_t> resourceIndex;
    std::vector<std::vector<std::size_t>> successors; ///< writer -> readers, sorted, each once

    std::size_t findResource(const std::string& name) const {
        auto it = resourceIndex.find(name);
        return it == resourceIndex.end() ? kNone : it->second;
    }

    /** " (did you mean 'gbuffer.normal'?)" when a written resource looks like `wanted`, else "". */
    std::string suggest(std::string_view wanted) const;
    /** Whether a pass asked what runs anyway (PassBuilder::runsAnyway()): the compiler then declares again. */
    bool askedCompileData = false;

private:
    void declarePasses(const std::vector<const Pass*>& passes, const CompileData& compileData);
    void checkPassNames();
    void collectWrites();
    void checkWriters();
    void resolveReads();
    void buildEdges();

    std::vector<std::string>& mProblems;
    std::vector<PassBuilder> mBuilders;
};

void Declarations::declarePasses(const std::vector<const Pass*>& passList, const CompileData& compileData) {
    passes.resize(passList.size());
    mBuilders.reserve(passList.size());
    for (std::size_t i = 0; i < passList.size(); ++i) {
        DeclaredPass& declared = passes[i];
        declared.pass = passList[i];
        if (!declared.pass) {
            mProblems.push_back("pass #" + std::to_string(i) + " is null");
            mBuilders.emplace_back(std::string());
            continue;
        }
        declared.name = std::string(declared.pass->name());
        mBuilders.emplace_back(declared.name, &compileData);
        declared.pass->declare(mBuilders.back());
        declared.hasSideEffect = mBuilders.back().hasSideEffect();
        declared.runsOnHost = mBuilders.back().declaredRunsOnHost();
        declared.scratch = mBuilders.back().scratches();
        for (const std::string& name : mBuilders.back().imports())
            if (std::find(declared.imports.begin(), declared.imports.end(), name) == declared.imports.end())
                declared.imports.push_back(name);
        askedCompileData = askedCompileData || mBuilders.back().askedCompileData();
    }
}

void Declarations::checkPassNames() {
    // Reported once per name, at its first use, listing every position it appears at.
    std::unordered_map<std::string, std::vector<std::size_t>> positions;
    for (std::size_t i = 0; i < passes.size(); ++i)
        if (passes[i].pass) positions[passes[i].name].push_back(i);

    for (std::size_t i = 0; i < passes.size(); ++i) {
        const DeclaredPass& declared = passes[i];
        if (!declared.pass) continue;
        if (declared.name.empty())
            mProblems.push_back("pass #" + std::to_string(i) + " has an empty name");
        else if (declared.name.find('.') != std::string::npos)
            mProblems.push_back("pass " + quote(declared.name) +
                                " has a '.' in its name; '.' separates a pass from "
                                "its field in resource names");

        const std::vector<std::size_t>& same = positions[declared.name];
        if (same.size() > 1 && same.front() == i) {
            std::string where;
            for (std::size_t k = 0; k < same.size(); ++k)
                where += (k == 0 ? "#" : (k + 1 == same.size() ? " and #" : ", #")) + std::to_string(same[k]);
            mProblems.push_back("pass name " + quote(declared.name) + " is used by " + std::to_string(same.size()) +
                                " passes (" + where + "); pass names must be unique");
        }
    }
}

void Declarations::collectWrites() {
    for (std::size_t i = 0; i < passes.size(); ++i) {
        DeclaredPass& declared = passes[i];
        std::unordered_set<std::string> seenFields;
        for (const PassBuilder::Write& write : mBuilders[i].writes()) {
            const std::string full = declared.name + "." + write.field;
            declared.allWrites.push_back(full);
            if (!isValidField(write.field)) {
                if (write.field.empty())
                    mProblems.push_back("pass " + quote(declared.name) + " writes a field with an empty name");
                else
                    mProblems.push_back("pass " + quote(declared.name) + " writes field " + quote(write.field) +
                                        ", which has a '.': a pass writes only its own fields ('" + declared.name +
                                        ".<field>')");
                continue;
            }
            if (!seenFields.insert(write.field).second) {
                mProblems.push_back("pass " + quote(declared.name) + " writes " + quote(full) + " twice");
                continue;
            }
            auto [it, inserted] = resourceIndex.try_emplace(full, resources.size());
            if (inserted)
                resources.push_back(
                    {full, write.kind, write.object, write.desc, write.need, write.presentation, {}, {}});
            resources[it->second].writers.push_back(i);
            declared.writes.push_back(it->second);
        }
    }
}

void Declarations::checkWriters() {
    // Resources are in first-written order, so this is deterministic.
    for (const ResourceInfo& resource : resources) {
        if (resource.writers.size() < 2) continue;
        std::vector<std::string> writers;
        for (std::size_t writer : resource.writers) writers.push_back(passes[writer].name);
        std::string where;
        for (std::size_t k = 0; k < resource.writers.size(); ++k)
            where += (k == 0 ? "#" : ", #") + std::to_string(resource.writers[k]);
        const std::string count = resource.writers.size() == 2 ? "two" : std::to_string(resource.writers.size());
        mProblems.push_back("resource " + quote(resource.name) + " has " + count + " writers: " + quoteList(writers) +
                            " (passes " + where + ")");
    }
}

void Declarations::resolveReads() {
    // Every pass is checked, not only live ones: a broken graph fails even when the broken pass would be culled.
    for (std::size_t i = 0; i < passes.size(); ++i) {
        DeclaredPass& declared = passes[i];
        std::unordered_set<std::string> seen;
        for (const PassBuilder::Read& read : mBuilders[i].reads()) {
            if (!seen.insert(read.resource).second) {
                // Read twice: the whole image wins over the covered pixels.
                const std::size_t again = findResource(read.resource);
                if (again != kNone && read.extent == ReadExtent::WholeImage) {
                    ResourceInfo& info = resources[again];
                    const auto reader = std::find(info.readers.begin(), info.readers.end(), i);
                    if (reader != info.readers.end())
                        info.readExtents[std::size_t(reader - info.readers.begin())] = ReadExtent::WholeImage;
                }
                continue;
            }
            const std::size_t resource = findResource(read.resource);
            declared.reads.push_back(read.resource);
            declared.readResources.push_back(resource);
            if (resource == kNone) {
                mProblems.push_back("pass " + quote(declared.name) + " reads " + quote(read.resource) +
                                    " but no pass writes it" + suggest(read.resource));
                continue;
            }
            resources[resource].readers.push_back(i);
            resources[resource].readExtents.push_back(read.extent);
            const ResourceInfo& written = resources[resource];
            if (read.objectType.empty() && written.kind == ResourceKind::Object)
                mProblems.push_back("pass " + quote(declared.name) + " reads " + quote(read.resource) +
                                    " as a texture, but it is a " + quote(written.object.type) +
                                    " object (PassBuilder::readObject())");
            else if (!read.objectType.empty() && written.kind == ResourceKind::Texture)
                mProblems.push_back("pass " + quote(declared.name) + " reads " + quote(read.resource) + " as a " +
                                    quote(read.objectType) + " object, but it is a texture");
            else if (!read.objectType.empty() && read.objectType != written.object.type)
                mProblems.push_back("pass " + quote(declared.name) + " reads " + quote(read.resource) + " as a " +
                                    quote(read.objectType) + " object, but " +
                                    quote(passes[written.writers.front()].name) + " writes a " +
                                    quote(written.object.type));
        }
    }
}

void Declarations::buildEdges() {
    successors.assign(passes.size(), {});
    for (std::size_t reader = 0; reader < passes.size(); ++reader)
        for (std::size_t resource : passes[reader].readResources)
            if (resource != kNone)
                for (std::size_t writer : resources[resource].writers) successors[writer].push_back(reader);
    for (std::vector<std::size_t>& next : successors) {
        std::sort(next.begin(), next.end());
        next.erase(std::unique(next.begin(), next.end()), next.end());
    }
}

std::string toLower(std::string_view text) {
    std::string lower(text);
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return lower;
}

/** Levenshtein distance, ignoring case (a misspelt "wvec" should find "wVec"). */
std::size_t editDistance(std::string_view a, std::string_view b) {
    const std::string x = toLower(a), y = toLower(b);
    std::vector<std::size_t> row(y.size() + 1);
    for (std::size_t j = 0; j <= y.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= x.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= y.size(); ++j) {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (x[i - 1] == y[j - 1] ? 0 : 1)});
            diagonal = up;
        }
    }
    return row[y.size()];
}

std::string_view fieldOf(std::string_view resource) {
    const std::size_t dot = resource.rfind('.');
    return dot == std::string_view::npos ? resource : resource.substr(dot + 1);
}

std::string Declarations::suggest(std::string_view wanted) const {
    // Prefer the same field under another pass ("gbufer.normal" -> "gbuffer.normal"), then anything close enough.
    const ResourceInfo* best = nullptr;
    bool bestSameField = false;
    std::size_t bestDistance = kNone;
    for (const ResourceInfo& resource : resources) {
        const bool sameField = fieldOf(resource.name) == fieldOf(wanted);
        const std::size_t distance = editDistance(wanted, resource.name);
        const bool better = !best || (sameField && !bestSameField) ||
                            (sameField == bestSameField &&
                             (distance < bestDistance || (distance == bestDistance && resource.name < best->name)));
        if (better) {
            best = &resource;
            bestSameField = sameField;
            bestDistance = distance;
        }
    }
    const std::size_t closeEnough = std::max<std::size_t>(1, wanted.size() / 3);
    if (!best || (!bestSameField && bestDistance > closeEnough)) return {};
    return " (did you mean " + quote(best->name) + "?)";
}

/** Reports every cycle (one per strongly connected component), each as its shortest loop through the component's
 *  first-registered pass, so the message is deterministic. */
void checkCycles(const Declarations& graph, std::vector<std::string>& problems) {
    const std::size_t passCount = graph.passes.size();
    const auto& successors = graph.successors;

    // Tarjan's strongly connected components; graphs are small (< 50 passes), so recursion depth is no concern.
    std::vector<std::size_t> index(passCount, kNone), lowLink(passCount, 0), component(passCount, kNone);
    std::vector<bool> onStack(passCount, false);
    std::vector<std::size_t> stack;
    std::size_t nextIndex = 0, componentCount = 0;
    std::function<void(std::size_t)> visit = [&](std::size_t v) {
        index[v] = lowLink[v] = nextIndex++;
        stack.push_back(v);
        onStack[v] = true;
        for (std::size_t w : successors[v]) {
            if (index[w] == kNone) {
                visit(w);
                lowLink[v] = std::min(lowLink[v], lowLink[w]);
            } else if (onStack[w]) {
                lowLink[v] = std::min(lowLink[v], index[w]);
            }
        }
        if (lowLink[v] == index[v]) {
            std::size_t w;
            do {
                w = stack.back();
                stack.pop_back();
                onStack[w] = false;
                component[w] = componentCount;
            } while (w != v);
            ++componentCount;
        }
    };
    for (std::size_t v = 0; v < passCount; ++v)
        if (index[v] == kNone) visit(v);

    std::vector<std::size_t> componentSize(componentCount, 0);
    for (std::size_t v = 0; v < passCount; ++v) ++componentSize[component[v]];

    std::vector<bool> reported(componentCount, false);
    for (std::size_t start = 0; start < passCount; ++start) {
        const std::size_t c = component[start];
        const bool selfLoop = std::binary_search(successors[start].begin(), successors[start].end(), start);
        if (reported[c] || (componentSize[c] < 2 && !selfLoop)) continue;
        reported[c] = true;

        // Breadth-first from `start` inside the component: the first pass found that feeds `start` closes the
        // shortest loop.
        std::vector<std::size_t> parent(passCount, kNone);
        std::queue<std::size_t> queue;
        queue.push(start);
        parent[start] = start;
        std::size_t last = kNone;
        while (!queue.empty() && last == kNone) {
            const std::size_t v = queue.front();
            queue.pop();
            for (std::size_t w : successors[v]) {
                if (w == start) {
                    last = v;
                    break;
                }
                if (component[w] == c && parent[w] == kNone) {
                    parent[w] = v;
                    queue.push(w);
                }
            }
        }
        assert(last != kNone);
        std::vector<std::size_t> loop;
        for (std::size_t v = last; v != start; v = parent[v]) loop.push_back(v);
        loop.push_back(start);
        std::reverse(loop.begin(), loop.end());

        std::string text = "cycle: ";
        for (std::size_t v : loop) text += quote(graph.passes[v].name) + " -> ";
        text += quote(graph.passes[start].name);
        problems.push_back(text);
    }
}

void checkRequests(const Declarations& graph, const std::vector<std::string>& requested,
                   std::vector<std::string>& problems) {
    std::unordered_set<std::string> seen;
    for (const std::string& name : requested)
        if (seen.insert(name).second && graph.findResource(name) == kNone)
            problems.push_back("requested resource " + quote(name) + " is not written by any pass" +
                               graph.suggest(name));

    const bool anySideEffect = std::any_of(graph.passes.begin(), graph.passes.end(),
                                           [](const DeclaredPass& pass) { return pass.hasSideEffect; });
    if (requested.empty() && !anySideEffect)
        problems.push_back("nothing is requested and no pass has a side effect, so the plan would be empty");
}

[[noreturn]] void throwProblems(std::vector<std::string> problems) {
    std::string message =
        "GraphCompiler::compile(): " + std::to_string(problems.size()) + " problem(s) in the render graph:";
    for (const std::string& problem : problems) message += "\n  - " + problem;
    throw GraphError(message, std::move(problems));
}

/** Why a pass did not make it into the plan, naming its outputs and whoever (culled) reads them. */
std::string explainCulled(const Declarations& graph, std::size_t pass, const std::vector<bool>& passLive) {
    (void)passLive; // only checked in debug builds
    const DeclaredPass& declared = graph.passes[pass];
    if (declared.writes.empty()) return "writes nothing and has no side effect";

    std::vector<std::string> outputs;
    std::vector<std::size_t> readers;
    for (std::size_t resource : declared.writes) {
        outputs.push_back(graph.resources[resource].name);
        for (std::size_t reader : graph.resources[resource].readers) {
            assert(!passLive[reader] && "a live reader would have made the writer live");
            readers.push_back(reader);
        }
    }
    std::sort(readers.begin(), readers.end());
    readers.erase(std::unique(readers.begin(), readers.end()), readers.end());

    std::string reason = "no requested output depends on " + quoteList(outputs, "or");
    if (readers.empty()) {
        reason += outputs.size() == 1 ? " (nothing reads it)" : " (nothing reads them)";
    } else {
        std::vector<std::string> names;
        for (std::size_t reader : readers) names.push_back(graph.passes[reader].name);
        reason += " (read only by culled " + quoteList(names) + ")";
    }
    return reason;
}

/** One round: declare every pass with `compileData`, check, cull, order. `asked`: whether a pass asked compile
 *  data. */
Plan compileRound(const std::vector<const Pass*>& passes, const std::vector<std::string>& requested,
                  const CompileData& compileData, bool& asked) {
    std::vector<std::string> problems;
    const Declarations graph(passes, compileData, problems);
    asked = graph.askedCompileData;
    checkRequests(graph, requested, problems);
    checkCycles(graph, problems);
    if (!problems.empty()) throwProblems(std::move(problems));

    // From here the graph is valid: unique names, one writer per resource, every read resolves, no cycle.
    const std::size_t passCount = graph.passes.size();
    std::vector<bool> passLive(passCount, false), resourceLive(graph.resources.size(), false);
    std::vector<bool> resourceRequested(graph.resources.size(), false);

    // Backwards from the requested resources and side-effect passes. A live pass computes all its Required writes,
    // and pulls in the writers of everything it reads; Optional writes stay dead unless read or requested.
    std::vector<std::size_t> pending;
    auto markResource = [&](std::size_t resource) {
        if (!resourceLive[resource]) {
            resourceLive[resource] = true;
            pending.push_back(resource);
        }
    };
    auto markPass = [&](std::size_t pass) {
        if (passLive[pass]) return;
        passLive[pass] = true;
        for (std::size_t resource : graph.passes[pass].writes)
            if (graph.resources[resource].need == Need::Required) markResource(resource);
        for (std::size_t resource : graph.passes[pass].readResources) markResource(resource);
    };
    for (const std::string& name : requested) {
        const std::size_t resource = graph.findResource(name);
        resourceRequested[resource] = true;
        markResource(resource);
    }
    for (std::size_t pass = 0; pass < passCount; ++pass)
        if (graph.passes[pass].hasSideEffect) markPass(pass);
    while (!pending.empty()) {
        const std::size_t resource = pending.back();
        pending.pop_back();
        markPass(graph.resources[resource].writers.front());
    }

    // Kahn's algorithm over the live passes, always taking a ready GPU pass before a ready host pass, then the
    // smallest registration index: the host passes gather at the end, where a batch runs them on a worker thread
    // while the next still draws (Plan::hostTailStart()).
    std::vector<std::size_t> inDegree(passCount, 0);
    for (std::size_t pass = 0; pass < passCount; ++pass)
        if (passLive[pass])
            for (std::size_t reader : graph.successors[pass])
                if (passLive[reader]) ++inDegree[reader];
    const auto readyOrder = [&graph](std::size_t pass) { return std::make_pair(graph.passes[pass].runsOnHost, pass); };
    using ReadyKey = std::pair<bool, std::size_t>;
    std::priority_queue<ReadyKey, std::vector<ReadyKey>, std::greater<>> ready;
    for (std::size_t pass = 0; pass < passCount; ++pass)
        if (passLive[pass] && inDegree[pass] == 0) ready.push(readyOrder(pass));

    Plan plan;
    plan.requested = requested;
    std::vector<std::size_t> planIndex(passCount, kNone);
    while (!ready.empty()) {
        const std::size_t pass = ready.top().second;
        ready.pop();
        planIndex[pass] = plan.passes.size();

        const DeclaredPass& declared = graph.passes[pass];
        PlannedPass planned;
        planned.name = declared.name;
        planned.registrationIndex = pass;
        planned.reads = declared.reads;
        planned.hasSideEffect = declared.hasSideEffect;
        planned.runsOnHost = declared.runsOnHost;
        planned.scratch = declared.scratch;
        planned.imports = declared.imports;
        for (std::size_t resource : declared.writes)
            (resourceLive[resource] ? planned.liveWrites : planned.deadOptionalWrites)
                .push_back(graph.resources[resource].name);
        plan.passes.push_back(std::move(planned));

        for (std::size_t reader : graph.successors[pass])
            if (passLive[reader] && --inDegree[reader] == 0) ready.push(readyOrder(reader));
    }

    for (std::size_t pass = 0; pass < passCount; ++pass) {
        if (passLive[pass]) continue;
        const DeclaredPass& declared = graph.passes[pass];
        plan.culled.push_back(
            {declared.name, explainCulled(graph, pass, passLive), declared.reads, declared.allWrites});
    }

    for (std::size_t resource = 0; resource < graph.resources.size(); ++resource) {
        if (!resourceLive[resource]) continue;
        const ResourceInfo& info = graph.resources[resource];
        PlannedResource planned;
        planned.name = info.name;
        planned.kind = info.kind;
        planned.object = info.object;
        planned.desc = info.desc;
        planned.presentation = info.presentation;
        planned.writer = graph.passes[info.writers.front()].name;
        planned.firstUse = planIndex[info.writers.front()];
        planned.lastUse = planned.firstUse;
        planned.requested = resourceRequested[resource];

        std::vector<std::size_t> readers;
        planned.backgroundRead = planned.requested;
        for (std::size_t r = 0; r < info.readers.size(); ++r) {
            if (!passLive[info.readers[r]]) continue;
            readers.push_back(planIndex[info.readers[r]]);
            if (info.readExtents[r] == ReadExtent::WholeImage) planned.backgroundRead = true;
        }
        std::sort(readers.begin(), readers.end());
        for (std::size_t index : readers) planned.readers.push_back(plan.passes[index].name);
        if (!readers.empty()) planned.lastUse = readers.back();
        // Requested outputs are read back after the last pass, so they live to the end.
        if (planned.requested) planned.lastUse = plan.passes.size() - 1;
        plan.resources.push_back(std::move(planned));
    }
    std::sort(plan.resources.begin(), plan.resources.end(), [](const PlannedResource& a, const PlannedResource& b) {
        return a.firstUse != b.firstUse ? a.firstUse < b.firstUse : a.name < b.name;
    });
    return plan;
}

} // namespace

Plan compile(const std::vector<const Pass*>& passes, const std::vector<std::string>& requested,
             const std::vector<std::string>& decidingRequests) {
    bool asked = false;
    const CompileData none;
    if (decidingRequests.empty() || decidingRequests == requested) {
        Plan first = compileRound(passes, requested, none, asked);
        if (!asked) return first;
        const CompileData data{&first};
        return compileRound(passes, requested, data, asked);
    }
    const Plan first = compileRound(passes, decidingRequests, none, asked);
    const CompileData data{&first};
    return compileRound(passes, requested, asked ? data : none, asked);
}

} // namespace inkgraph
