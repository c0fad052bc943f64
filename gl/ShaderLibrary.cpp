#include "gl/ShaderLibrary.h"

#include "gl/BinaryLocation.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace inkgraph {
namespace {

std::string joinDefines(const std::vector<std::string>& defines) {
    std::string joined;
    for (const std::string& define : defines) joined += (joined.empty() ? "" : ", ") + define;
    return joined.empty() ? "none" : joined;
}

/** The info log of a shader or program, through the matching pair of GL getters. */
template <class GetInteger, class GetLog>
std::string infoLog(GLuint object, GetInteger getInteger, GetLog getLog) {
    GLint length = 0;
    getInteger(object, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    GLsizei written = 0;
    getLog(object, length, &written, log.data());
    log.resize(static_cast<std::size_t>(std::max(written, 0)));
    return log;
}

/** `log` as an error quotes it: whole lines up to ShaderLibrary::kMaxQuotedLogBytes, then how much was left out. */
std::string quotedLog(std::string log) {
    while (!log.empty() && (log.back() == '\n' || log.back() == '\0' || log.back() == ' ')) log.pop_back();
    if (log.empty()) return "(the GLSL compiler gave no log)";
    if (log.size() <= ShaderLibrary::kMaxQuotedLogBytes) return log;
    std::size_t kept = log.rfind('\n', ShaderLibrary::kMaxQuotedLogBytes);
    if (kept == std::string::npos || kept == 0) kept = ShaderLibrary::kMaxQuotedLogBytes;
    return log.substr(0, kept) + "\n... (" + std::to_string(log.size() - kept) + " more bytes of the log)";
}

/** How to read a compile log's "N:LINE" when the stage has snippets before it (compileStage() numbers them). */
std::string snippetsLegend(const std::vector<std::string>& snippets) {
    std::string legend;
    for (std::size_t i = 0; i < snippets.size(); ++i)
        legend += (i == 0 ? "" : ", ") + std::to_string(i + 1) + " '" + snippets[i] + "'";
    return legend.empty() ? "" : "; the log's 0:LINE is a line of that file, N:LINE one of snippet N: " + legend;
}

const char* stageDefine(GLenum stage) {
    switch (stage) {
    case GL_VERTEX_SHADER: return "#define INKGRAPH_VERTEX_STAGE 1\n";
    case GL_GEOMETRY_SHADER: return "#define INKGRAPH_GEOMETRY_STAGE 1\n";
    case GL_FRAGMENT_SHADER: return "#define INKGRAPH_FRAGMENT_STAGE 1\n";
    case GL_COMPUTE_SHADER: return "#define INKGRAPH_COMPUTE_STAGE 1\n";
    }
    throw std::logic_error("stageDefine(): unknown shader stage");
}

} // namespace

ShaderFolder ShaderLibrary::findShaderFolder() {
    ShaderFolder folder;
    if (const char* fromEnvironment = std::getenv("INKGRAPH_SHADER_DIR"); fromEnvironment && *fromEnvironment) {
        folder.path = fromEnvironment;
        folder.origin = "INKGRAPH_SHADER_DIR";
        folder.searched = {folder.path};
        return folder;
    }
    const auto firstExisting = [&folder](const std::vector<std::filesystem::path>& candidates, const char* origin) {
        for (const std::filesystem::path& candidate : candidates) {
            folder.searched.push_back(candidate);
            std::error_code error;
            if (std::filesystem::is_directory(candidate, error)) {
                folder.path = candidate;
                folder.origin = origin;
                return true;
            }
        }
        return false;
    };
    if (firstExisting(installedCandidates(installedShaderFolder()), "installed")) return folder;
    // Named only here, and only ever read by a binary of the build tree: an installed program that lost its shaders
    // must say so rather than quietly run on the source tree it was built from.
    if (runsFromBuildTree()) firstExisting({INKGRAPH_SOURCE_SHADER_DIR}, "source tree");
    return folder;
}

std::filesystem::path ShaderLibrary::defaultDirectory() { return findShaderFolder().path; }

ShaderLibrary::ShaderLibrary() : mFolder(findShaderFolder()) {}

ShaderLibrary::ShaderLibrary(std::filesystem::path directory) {
    mFolder.path = std::move(directory);
    mFolder.origin = "given";
    mFolder.searched = {mFolder.path};
}

const std::string& ShaderLibrary::source(const std::string& relativePath) {
    auto found = mSources.find(relativePath);
    if (found != mSources.end()) return found->second;
    if (mFolder.path.empty()) {
        std::string searched;
        for (const std::filesystem::path& folder : mFolder.searched)
            searched += (searched.empty() ? "'" : ", '") + folder.string() + "'";
        throw ShaderSourceError("ShaderLibrary::source(): cannot read shader '" + relativePath +
                                "': no shader folder found (searched " + (searched.empty() ? "nothing" : searched) +
                                "); reinstall inkgraph, or set INKGRAPH_SHADER_DIR to its shaders/ folder");
    }
    const std::filesystem::path path = mFolder.path / relativePath;
    std::ifstream file(path, std::ios::binary);
    if (!file)
        throw ShaderSourceError("ShaderLibrary::source(): cannot read shader '" + path.string() + "'" + folderAdvice());
    std::ostringstream text;
    text << file.rdbuf();
    return mSources.emplace(relativePath, text.str()).first->second;
}

std::string ShaderLibrary::folderAdvice() const {
    if (mFolder.origin == "INKGRAPH_SHADER_DIR")
        return "; INKGRAPH_SHADER_DIR is '" + mFolder.path.string() +
               "' (set it to inkgraph's shaders/ folder, or unset it to use the installed one)";
    return " (the " + mFolder.origin + " shader folder '" + mFolder.path.string() +
           "' does not match this inkgraph; set INKGRAPH_SHADER_DIR to inkgraph's shaders/ folder)";
}

GLuint ShaderLibrary::compileStage(const ProgramDesc& desc, GLenum stage, const std::string& file) {
    std::string text = "#version 450 core\n";
    // Snippets may hold stage-specific code (e.g. the fullscreen-triangle vertex function).
    text += stageDefine(stage);
    for (const std::string& define : desc.defines) text += "#define " + define + "\n";
    // Each file its own source-string number, so the compiler's "N:LINE" points into the file itself: 0 the stage
    // file, N the N-th snippet (snippetsLegend() says so in an error).
    for (std::size_t i = 0; i < desc.snippets.size(); ++i)
        text += "#line 1 " + std::to_string(i + 1) + "\n" + source(desc.snippets[i]) + "\n";
    text += "#line 1 0\n" + source(file);

    GlHandle<ShaderDeleter> shader(glCreateShader(stage));
    const char* pointer = text.c_str();
    glShaderSource(shader.id(), 1, &pointer, nullptr);
    glCompileShader(shader.id());
    GLint compiled = GL_FALSE;
    glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &compiled);
    if (compiled != GL_TRUE) {
        const std::string log = infoLog(shader.id(), glGetShaderiv, glGetShaderInfoLog);
        throw ShaderSourceError("ShaderLibrary::build(): shader '" + (mFolder.path / file).string() +
                                "' does not compile (program '" + desc.label +
                                "', defines: " + joinDefines(desc.defines) + snippetsLegend(desc.snippets) + ")" +
                                folderAdvice() + ". The GLSL log:\n" + quotedLog(log));
    }
    return shader.release();
}

GlProgram ShaderLibrary::build(const ProgramDesc& desc) {
    if (!mKeepPrograms) return compileAndLink(desc);
    // Everything that goes into the source text; '\n' cannot occur in a file name or a define.
    std::string key = desc.vertexFile + "\n" + desc.geometryFile + "\n" + desc.fragmentFile + "\n" + desc.computeFile;
    for (const std::string& define : desc.defines) key += "\nD" + define;
    for (const std::string& snippet : desc.snippets) key += "\nS" + snippet;
    if (auto kept = mPrograms.find(key); kept != mPrograms.end()) {
        ++mReused;
        return kept->second;
    }
    return mPrograms.emplace(key, compileAndLink(desc)).first->second;
}

GlProgram ShaderLibrary::compileAndLink(const ProgramDesc& desc) {
    if (!desc.computeFile.empty()) return compileAndLinkCompute(desc);
    const bool hasGeometry = !desc.geometryFile.empty();
    GlHandle<ShaderDeleter> vertex(compileStage(desc, GL_VERTEX_SHADER, desc.vertexFile));
    GlHandle<ShaderDeleter> geometry;
    if (hasGeometry) geometry = GlHandle<ShaderDeleter>(compileStage(desc, GL_GEOMETRY_SHADER, desc.geometryFile));
    GlHandle<ShaderDeleter> fragment(compileStage(desc, GL_FRAGMENT_SHADER, desc.fragmentFile));
    GlProgram program(glCreateProgram(), desc.label);
    glAttachShader(program.id(), vertex.id());
    if (hasGeometry) glAttachShader(program.id(), geometry.id());
    glAttachShader(program.id(), fragment.id());
    glLinkProgram(program.id());
    glDetachShader(program.id(), vertex.id());
    if (hasGeometry) glDetachShader(program.id(), geometry.id());
    glDetachShader(program.id(), fragment.id());
    GLint linked = GL_FALSE;
    glGetProgramiv(program.id(), GL_LINK_STATUS, &linked);
    if (linked != GL_TRUE) {
        const std::string log = infoLog(program.id(), glGetProgramiv, glGetProgramInfoLog);
        const auto quoted = [this](const std::string& file) { return "'" + (mFolder.path / file).string() + "'"; };
        const std::string stages = quoted(desc.vertexFile) + " + " +
                                   (hasGeometry ? quoted(desc.geometryFile) + " + " : "") + quoted(desc.fragmentFile);
        throw ShaderSourceError("ShaderLibrary::build(): the shaders " + stages + " do not link (program '" +
                                desc.label + "', defines: " + joinDefines(desc.defines) + ")" + folderAdvice() +
                                ". The GLSL log:\n" + quotedLog(log));
    }
    ++mCompiled;
    return program;
}

GlProgram ShaderLibrary::compileAndLinkCompute(const ProgramDesc& desc) {
    if (!desc.vertexFile.empty() || !desc.geometryFile.empty() || !desc.fragmentFile.empty())
        throw std::invalid_argument("ShaderLibrary::build(): program '" + desc.label +
                                    "' names a compute file and draw stages; a program is one or the other");
    GlHandle<ShaderDeleter> compute(compileStage(desc, GL_COMPUTE_SHADER, desc.computeFile));
    GlProgram program(glCreateProgram(), desc.label);
    glAttachShader(program.id(), compute.id());
    glLinkProgram(program.id());
    glDetachShader(program.id(), compute.id());
    GLint linked = GL_FALSE;
    glGetProgramiv(program.id(), GL_LINK_STATUS, &linked);
    if (linked != GL_TRUE) {
        const std::string log = infoLog(program.id(), glGetProgramiv, glGetProgramInfoLog);
        throw ShaderSourceError("ShaderLibrary::build(): the shader '" + (mFolder.path / desc.computeFile).string() +
                                "' does not link (program '" + desc.label + "', defines: " + joinDefines(desc.defines) +
                                ")" + folderAdvice() + ". The GLSL log:\n" + quotedLog(log));
    }
    ++mCompiled;
    return program;
}

} // namespace inkgraph
