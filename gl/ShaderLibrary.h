#pragma once
/** @file Assembles GLSL programs from files under shaders/ (Magnum's addSource style): the #version line, the stage
 *  define (INKGRAPH_VERTEX_STAGE, INKGRAPH_GEOMETRY_STAGE, INKGRAPH_FRAGMENT_STAGE or INKGRAPH_COMPUTE_STAGE),
 *  then generated #defines, then common/ snippets, then the stage file. Core GLSL has no #include, so each program
 *  names its snippets explicitly. */

#include "gl/GlObjects.h"

#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph {

/** The shaders are not this inkgraph's: a file cannot be read (no shader folder was found, the installation is
 *  incomplete or INKGRAPH_SHADER_DIR names the wrong folder), or a program does not compile or link (a folder of
 *  another version, or an edited shader). An error of the environment (exit 4), not of the render. */
class ShaderSourceError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct ProgramDesc {
    std::string label;                 ///< e.g. "gbuffer"; used in errors and GL object labels
    std::string vertexFile;            ///< relative to the shader directory, e.g. "gbuffer/gbuffer.vert"
    std::string fragmentFile;          ///< e.g. "gbuffer/gbuffer.frag"
    std::vector<std::string> defines;  ///< "OUT_NORMAL 1" becomes "#define OUT_NORMAL 1"
    std::vector<std::string> snippets; ///< e.g. "common/fullscreen.glsl", prepended to every stage in order
    std::string geometryFile;          ///< optional, e.g. "outline/outline.geom"; empty: no geometry stage
    /** Set: a compute program of this one file (e.g. "post/neighbour_pairs.comp"), the vertex, geometry and
     *  fragment files empty; empty: a draw program. */
    std::string computeFile;
};

/** Where a library's shaders come from. */
struct ShaderFolder {
    std::filesystem::path path;                  ///< empty: none of `searched` exists
    std::string origin;                          ///< "INKGRAPH_SHADER_DIR", "installed", "source tree" or "given"
    std::vector<std::filesystem::path> searched; ///< the folders looked at, in order
};

class ShaderLibrary {
public:
    /** INKGRAPH_SHADER_DIR from the environment if set (taken as it is, even when missing); else the first existing
     *  folder of installedCandidates(installedShaderFolder()) (gl/BinaryLocation.h: `<bin>/../share/inkgraph/shaders`,
     *  then `<bin>/../../share/inkgraph/shaders`, <bin> the folder of the executable or library holding this code);
     *  else, only for a binary in the build tree, the source tree's shaders/. Looked up on each call. */
    static ShaderFolder findShaderFolder();
    /** findShaderFolder().path: empty when no folder was found. */
    static std::filesystem::path defaultDirectory();

    /** The shaders of findShaderFolder(). Reads nothing yet: a missing folder is reported by the first build() with
     *  the folders searched, so plans compile without shaders. */
    ShaderLibrary();
    /** The shaders in `directory`. */
    explicit ShaderLibrary(std::filesystem::path directory);

    /** Compiles and links; throws ShaderSourceError for a file that cannot be read and for a stage that does not
     * compile or a program that does not link, naming the files, the defines and the folder, and quoting the GLSL
     * info log (its first kMaxQuotedLogBytes). With keepPrograms(true), a program of the same files, defines and
     * snippets as an earlier one is that program again (the label does not matter), so the stills of a batch compile
     * each program once. */
    GlProgram build(const ProgramDesc& desc);

    /** Keep every program built from now on until the library is destroyed (which must then happen while the GL
     *  context is still current). Off by default: a library outliving its context must own no GL objects. */
    void keepPrograms(bool keep) { mKeepPrograms = keep; }

    /** Programs compiled and linked, and builds answered with a kept program, since construction. */
    std::size_t compiledCount() const { return mCompiled; }
    std::size_t reusedCount() const { return mReused; }

    const std::filesystem::path& directory() const { return mFolder.path; }
    const ShaderFolder& folder() const { return mFolder; }

    /** The most of a GLSL info log an error quotes: the first errors say what is wrong, and a shader full of them
     *  would log kilobytes. */
    static constexpr std::size_t kMaxQuotedLogBytes = 1000;

private:
    const std::string& source(const std::string& relativePath);
    /** What to do about a shader folder that is not this inkgraph's, by where the folder came from. */
    std::string folderAdvice() const;
    GLuint compileStage(const ProgramDesc& desc, GLenum stage, const std::string& file);
    GlProgram compileAndLink(const ProgramDesc& desc);
    GlProgram compileAndLinkCompute(const ProgramDesc& desc);

    ShaderFolder mFolder;
    std::map<std::string, std::string> mSources;
    bool mKeepPrograms = false;
    std::map<std::string, GlProgram> mPrograms; ///< by programKey(): files, defines, snippets
    std::size_t mCompiled = 0;
    std::size_t mReused = 0;
};

} // namespace inkgraph
