#pragma once
/** @file Assembles GLSL programs from files under shaders/ (Magnum's addSource style): the #version line, the stage
 *  define (INKGRAPH_VERTEX_STAGE, INKGRAPH_GEOMETRY_STAGE or INKGRAPH_FRAGMENT_STAGE), then generated #defines, then
 *  common/ snippets, then the stage file. Core GLSL has no #include, so each program
 *  names its snippets explicitly. */

#include "gl/GlObjects.h"

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace inkgraph {

struct ProgramDesc {
    std::string label;                 ///< e.g. "gbuffer"; used in errors and GL object labels
    std::string vertexFile;            ///< relative to the shader directory, e.g. "gbuffer/gbuffer.vert"
    std::string fragmentFile;          ///< e.g. "gbuffer/gbuffer.frag"
    std::vector<std::string> defines;  ///< "OUT_NORMAL 1" becomes "#define OUT_NORMAL 1"
    std::vector<std::string> snippets; ///< e.g. "common/fullscreen.glsl", prepended to every stage in order
    std::string geometryFile;          ///< optional, e.g. "outline/outline.geom"; empty: no geometry stage
};

class ShaderLibrary {
public:
    /** INKGRAPH_SHADER_DIR from the environment if set, else the source tree's shaders/ (a compile definition). */
    static std::filesystem::path defaultDirectory();

    /** Reads nothing yet: a missing folder is reported by the first build(), so plans compile without shaders. */
    explicit ShaderLibrary(std::filesystem::path directory = defaultDirectory());

    /** Compiles and links; throws std::runtime_error naming the file, stage, defines and the info log. */
    GlProgram build(const ProgramDesc& desc);

    const std::filesystem::path& directory() const { return mDirectory; }

private:
    const std::string& source(const std::string& relativePath);
    GLuint compileStage(const ProgramDesc& desc, GLenum stage, const std::string& file);

    std::filesystem::path mDirectory;
    std::map<std::string, std::string> mSources;
};

} // namespace inkgraph
