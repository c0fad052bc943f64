#pragma once
/** @file The parts of the docs that list what the registries hold, generated from them as the man page is
 *  (app/CommandLineDocs.h): README.md's table of `inkgraph render` flags (the flag table, flags/FlagTable.h: --help's
 *  sections and texts), its line types (passes/lines/LineTypes.h) and files `--dump` can write (each pass's declared
 *  Presentation, graph/Resource.h), docs/robustness.md's warning codes (scene/Warning.h). In the
 *  Markdown each section sits between
 *  `<!-- generated: NAME -->` and `<!-- end generated -->`; `inkgraph help --docs NAME` prints it and
 *  scripts/update-docs.sh rewrites the regions. tests/app/GeneratedDocsTest.cpp fails when a region differs from what
 *  the code generates, and when a registered line type, flag, shading model, G-buffer field or dump file is missing
 *  from the docs that list them. No GL: the still graph is built and declared, never run. */

#include <string>
#include <vector>

namespace inkgraph {

/** The names of the generated sections, in the order their docs have them: "render-flags", "line-types",
 *  "dump-files" (README.md),
 *  "warning-codes" (docs/robustness.md). */
const std::vector<std::string>& generatedDocSections();

/** The doc that holds section `name`, relative to the source root: "README.md" or "docs/robustness.md". */
std::string generatedDocPath(const std::string& name);

/** The Markdown of section `name`, ending in a newline. Throws std::invalid_argument for an unknown name. */
std::string generatedDocSection(const std::string& name);

/** One file `--dump` can write: the union, over every shading model, of what every pass of a still graph that draws
 *  every line type declares it writes, in registration order, and manifest.json last. */
struct DumpFileDoc {
    std::string file;     ///< "normal.exr"
    std::string resource; ///< "gbuffer.normal"; empty for manifest.json
    std::string storedAs; ///< "EXR, 4 x float32"
    std::string meaning;  ///< the writer's Presentation::meaning
};
std::vector<DumpFileDoc> dumpFileDocs();

} // namespace inkgraph
