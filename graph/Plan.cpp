#include "graph/Plan.h"

#include <algorithm>
#include <set>

namespace inkgraph {
namespace {

/** " x2" for a supersampled resource, " /2" for one at half the frame's sides, " x3/2" for both; empty at the frame. */
std::string describeScale(int scale, int divisor) {
    std::string text;
    if (scale != 1) text += " x" + std::to_string(scale);
    if (divisor != 1) text += (scale != 1 ? "/" : " /") + std::to_string(divisor);
    return text;
}

/** "rgba32f", "rgba32f x2" for supersampled buffers, "r32f /2" for coarser ones, "rgba8 msaa4" for multisampled. */
std::string describeDesc(const TextureDesc& desc) {
    std::string text(formatName(desc.format));
    text += describeScale(desc.scale, desc.divisor);
    if (desc.samples != 1) text += " msaa" + std::to_string(desc.samples);
    return text;
}

/** A texture's describeDesc(); an object's type, "line-skeleton x2". */
std::string describeDesc(const PlannedResource& resource) {
    if (resource.kind == ResourceKind::Texture) return describeDesc(resource.desc);
    std::string text = resource.object.type;
    text += describeScale(resource.object.scale, resource.object.divisor);
    return text;
}

std::string joinNames(const std::vector<std::string>& names, std::string_view separator, std::string_view empty) {
    if (names.empty()) return std::string(empty);
    std::string text;
    for (std::size_t i = 0; i < names.size(); ++i) text += (i > 0 ? std::string(separator) : std::string()) + names[i];
    return text;
}

std::string quoteNames(const std::vector<std::string>& names) {
    std::vector<std::string> quoted;
    for (const std::string& name : names) quoted.push_back("'" + name + "'");
    return joinNames(quoted, ", ", "none");
}

/** Rows of cells, each column padded to its widest cell, two spaces apart, no trailing spaces. */
std::string formatTable(const std::vector<std::vector<std::string>>& rows, std::string_view indent) {
    std::vector<std::size_t> widths;
    for (const auto& row : rows) {
        widths.resize(std::max(widths.size(), row.size()), 0);
        for (std::size_t c = 0; c < row.size(); ++c) widths[c] = std::max(widths[c], row[c].size());
    }
    std::string text;
    for (const auto& row : rows) {
        std::string line(indent);
        for (std::size_t c = 0; c < row.size(); ++c) {
            if (widths[c] == 0) continue; // a column nobody uses takes no room
            line += row[c];
            if (c + 1 < row.size()) line += std::string(widths[c] - row[c].size() + 2, ' ');
        }
        line.erase(line.find_last_not_of(' ') + 1);
        text += line + "\n";
    }
    return text;
}

/** "1 pass", "3 passes". */
std::string describePassCount(std::size_t count) { return std::to_string(count) + (count == 1 ? " pass" : " passes"); }

/** A DOT double-quoted string; `lines` are joined with DOT's "\n" line break. */
std::string dotString(const std::vector<std::string>& lines) {
    std::string quoted = "\"";
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (i > 0) quoted += "\\n";
        for (char c : lines[i]) {
            if (c == '"' || c == '\\') quoted += '\\';
            quoted += c;
        }
    }
    return quoted + "\"";
}

std::string dotString(const std::string& text) { return dotString(std::vector<std::string>{text}); }

std::string passNode(const std::string& name) { return dotString("pass:" + name); }

std::string resourceNode(const std::string& name) { return dotString("res:" + name); }

} // namespace

const PlannedResource* Plan::findResource(const std::string& name) const {
    auto it = std::find_if(resources.begin(), resources.end(), [&](const auto& r) { return r.name == name; });
    return it == resources.end() ? nullptr : &*it;
}

const PlannedPass* Plan::findPass(const std::string& name) const {
    auto it = std::find_if(passes.begin(), passes.end(), [&](const auto& p) { return p.name == name; });
    return it == passes.end() ? nullptr : &*it;
}

std::size_t Plan::hostTailStart() const {
    std::size_t start = passes.size();
    while (start > 0 && passes[start - 1].runsOnHost) --start;
    return start;
}

std::vector<std::string> Plan::imports() const {
    std::vector<std::string> names;
    for (const PlannedPass& pass : passes)
        for (const std::string& name : pass.imports)
            if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    return names;
}

std::string Plan::describe() const {
    std::string text = "plan: " + describePassCount(passes.size()) + " run, " + std::to_string(culled.size()) +
                       " culled; requested: " + quoteNames(requested) + "\n";

    const std::size_t indexWidth = std::to_string(passes.size()).size();
    std::vector<std::vector<std::string>> rows;
    for (std::size_t i = 0; i < passes.size(); ++i) {
        const PlannedPass& pass = passes[i];
        std::string number = std::to_string(i + 1) + ".";
        number.insert(0, indexWidth + 1 - number.size(), ' ');

        std::vector<std::string> writes;
        for (const std::string& name : pass.liveWrites) {
            const PlannedResource* resource = findResource(name);
            writes.push_back(resource ? name + "(" + describeDesc(*resource) + ")" : name);
        }
        // Notes share one last column so a row without dead outputs doesn't push "side effect" far right.
        std::vector<std::string> notes;
        if (!pass.deadOptionalWrites.empty())
            notes.push_back("not computed: " + joinNames(pass.deadOptionalWrites, " ", ""));
        if (!pass.imports.empty()) notes.push_back("imports: " + joinNames(pass.imports, " ", ""));
        if (pass.hasSideEffect) notes.push_back("side effect");
        rows.push_back({number + " " + pass.name, "reads: " + joinNames(pass.reads, " ", "-"),
                        "writes: " + joinNames(writes, " ", "-"), joinNames(notes, "; ", "")});
    }
    text += formatTable(rows, "  ");

    if (culled.empty()) {
        text += "culled: none\n";
    } else {
        text += "culled:\n";
        for (const CulledPass& pass : culled) text += "  - " + pass.name + ": " + pass.reason + "\n";
    }

    text += "lifetimes:\n";
    rows.clear();
    for (const PlannedResource& resource : resources) {
        const char* note = "";
        if (resource.requested)
            note = "(requested)";
        else if (!resource.backgroundRead && !resource.readers.empty())
            note = "(read where covered: not cleared)";
        rows.push_back({resource.name, describeDesc(resource),
                        "passes " + std::to_string(resource.firstUse + 1) + ".." + std::to_string(resource.lastUse + 1),
                        resource.writer + " -> " + joinNames(resource.readers, ", ", "-"), note});
    }
    text += formatTable(rows, "  ");
    return text;
}

std::string Plan::graphviz() const {
    std::string dot = "digraph plan {\n"
                      "    rankdir=LR;\n"
                      "    node [fontname=\"Helvetica\", fontsize=10];\n"
                      "    edge [fontname=\"Helvetica\", fontsize=9];\n";
    const std::string grey = "style=dashed, color=grey60, fontcolor=grey50";

    // Passes, in plan order, then the culled ones with their reason as a tooltip.
    for (std::size_t i = 0; i < passes.size(); ++i) {
        const PlannedPass& pass = passes[i];
        dot += "    " + passNode(pass.name) + " [shape=box, style=" + (pass.hasSideEffect ? "bold" : "solid") +
               ", label=" + dotString(std::to_string(i + 1) + ". " + pass.name) + "];\n";
    }
    for (const CulledPass& pass : culled)
        dot += "    " + passNode(pass.name) + " [shape=box, " + grey + ", label=" + dotString(pass.name) +
               ", tooltip=" + dotString("culled: " + pass.reason) + "];\n";

    // Live resources, then everything drawn only because a dead write or a culled pass mentions it.
    std::set<std::string> drawn;
    for (const PlannedResource& resource : resources) {
        drawn.insert(resource.name);
        const std::string lifetime = describeDesc(resource) + ", passes " + std::to_string(resource.firstUse + 1) +
                                     ".." + std::to_string(resource.lastUse + 1);
        const std::string label = dotString({resource.name, lifetime});
        dot += "    " + resourceNode(resource.name) + " [shape=ellipse, label=" + label +
               (resource.requested ? ", peripheries=2" : "") + "];\n";
    }
    auto drawDead = [&](const std::string& name) {
        if (drawn.insert(name).second)
            dot += "    " + resourceNode(name) + " [shape=ellipse, " + grey + ", label=" + dotString(name) + "];\n";
    };
    for (const PlannedPass& pass : passes)
        for (const std::string& name : pass.deadOptionalWrites) drawDead(name);
    for (const CulledPass& pass : culled) {
        for (const std::string& name : pass.writes) drawDead(name);
        for (const std::string& name : pass.reads) drawDead(name);
    }

    for (const PlannedPass& pass : passes) {
        for (const std::string& name : pass.reads)
            dot += "    " + resourceNode(name) + " -> " + passNode(pass.name) + ";\n";
        for (const std::string& name : pass.liveWrites)
            dot += "    " + passNode(pass.name) + " -> " + resourceNode(name) + ";\n";
        for (const std::string& name : pass.deadOptionalWrites)
            dot += "    " + passNode(pass.name) + " -> " + resourceNode(name) + " [" + grey + "];\n";
    }
    for (const CulledPass& pass : culled) {
        for (const std::string& name : pass.reads)
            dot += "    " + resourceNode(name) + " -> " + passNode(pass.name) + " [" + grey + "];\n";
        for (const std::string& name : pass.writes)
            dot += "    " + passNode(pass.name) + " -> " + resourceNode(name) + " [" + grey + "];\n";
    }
    return dot + "}\n";
}

} // namespace inkgraph
