#pragma once
/** @file The `inkgraph render` command line: parsing and help. No GL, no files touched. */

#include <glm/glm.hpp>

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph {

/** A wrong flag or value. The CLI prints it with a hint to --help and exits with 2. */
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

enum class ShadingMode { None, Lambert };

struct RenderOptions {
    std::string modelPath;
    std::string outputPath;                 ///< -o; may be empty with --print-plan only
    int width = 1024;
    int height = 1024;
    std::optional<glm::dvec3> eye;
    std::optional<glm::dvec3> target;
    std::optional<glm::dvec3> up;           ///< default: the glTF camera's, else 0,1,0
    std::optional<double> fovYDegrees;      ///< default 35 unless the glTF camera says otherwise
    std::optional<glm::dvec3> towardLight;  ///< world direction toward the light
    ShadingMode shading = ShadingMode::Lambert;
    std::vector<std::string> lines;         ///< line types; empty = none
    glm::dvec3 background{1.0, 1.0, 1.0};
    std::vector<std::string> extraOutputs;  ///< --request: extra graph resources kept and dumped ("gbuffer.*")
    std::string dumpDirectory;
    std::string statsPath;
    std::string graphvizPath;               ///< --graphviz: the plan as DOT
    bool printPlan = false;
    std::string eglPlatform = "auto";       ///< auto, device, surfaceless
    bool quiet = false;
    bool help = false;                      ///< --help or -h in a flag's place: print help, do nothing else
};

/** Line types this build knows (later issues add contour, suggestive, silhouette, ...). */
const std::vector<std::string>& knownLineTypes();
std::string shadingModeName(ShadingMode mode);

/** Parses the arguments after "render". Throws UsageError with a message naming the flag and the bad value.
 *  --help (or -h) where a flag may stand stops parsing and sets `help`; as the value of a flag it is just a value. */
RenderOptions parseRenderOptions(const std::vector<std::string>& arguments);

/** The text of `inkgraph render --help`. */
std::string renderHelp();
/** The text of `inkgraph --help`. */
std::string mainHelp();

} // namespace inkgraph
