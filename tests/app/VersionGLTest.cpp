// `inkgraph --version [--verbose]` and the generated man page and completion, through the real executable of the
// build tree. --verbose makes a GL context (llvmpipe in CI).
#include "CliTestSupport.h"

#include "render/BuildInfo.h"
#include "app/CommandLineDocs.h"

#include <gtest/gtest.h>

#include <map>
#include <regex>
#include <sstream>

namespace inkgraph {
namespace {

using test::Cli;
using test::CliRun;
using test::readText;
namespace fs = std::filesystem;

/** The "name: value" lines of --verbose after the first, by name. */
std::map<std::string, std::string> facts(const std::string& text) {
    std::map<std::string, std::string> result;
    std::istringstream stream(text);
    std::string line;
    std::getline(stream, line); // the version line
    while (std::getline(stream, line)) {
        const std::size_t colon = line.find(':');
        if (colon == std::string::npos) continue;
        const std::size_t value = line.find_first_not_of(' ', colon + 1);
        result[line.substr(0, colon)] = value == std::string::npos ? "" : line.substr(value);
    }
    return result;
}

TEST_F(Cli, VersionNamesTheVersionAndTheCommit) {
    const CliRun result = run("--version");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_EQ(result.out, std::string("inkgraph 0.2.0 (git ") + inkgraphGitCommit() + ")\n");
    EXPECT_TRUE(std::regex_match(std::string(inkgraphGitCommit()), std::regex("[0-9a-f]{7,40}|unknown")))
        << inkgraphGitCommit();
    EXPECT_EQ(result.err, "");
}

TEST_F(Cli, VerboseVersionTellsWhatTheProgramRunsOn) {
    const CliRun result = run("--version --verbose");
    ASSERT_EQ(result.exitCode, 0) << result.out << result.err;
    EXPECT_EQ(result.out.substr(0, result.out.find('\n')),
              std::string("inkgraph 0.2.0 (git ") + inkgraphGitCommit() + ")");
    const std::map<std::string, std::string> found = facts(result.out);
    EXPECT_EQ(found.at("binary"), fs::weakly_canonical(INKGRAPH_EXECUTABLE).string());
    // A binary of the build tree, with no installed shaders beside it, reads the source tree's.
    EXPECT_EQ(found.at("shaders"), (fs::path(INKGRAPH_SOURCE_ROOT) / "shaders").string() + " (source tree)");
    EXPECT_TRUE(std::regex_search(found.at("EGL"), std::regex(R"(^1\.[0-9]+, .+, (device|surfaceless) platform$)")))
        << found.at("EGL");
    EXPECT_NE(found.at("OpenGL").find("4."), std::string::npos) << found.at("OpenGL");
    EXPECT_TRUE(std::regex_match(found.at("OpenImageIO"), std::regex(R"([0-9]+\.[0-9]+\.[0-9]+ \(module '.+'\))")))
        << found.at("OpenImageIO");
    EXPECT_NE(found.at("OpenImageIO").find("'" + std::string(INKGRAPH_BINARY_ROOT) + "/libinkgraph_imageio.so'"),
              std::string::npos)
        << found.at("OpenImageIO");
    for (const char* library : {"OpenCV", "libpng", "zlib", "oneTBB", "tinygltf", "Draco", "meshoptimizer", "GLM",
                                "libepoxy", "nlohmann_json"}) {
        ASSERT_TRUE(found.count(library)) << library << " missing from:\n" << result.out;
        EXPECT_TRUE(std::regex_match(found.at(library), std::regex(R"([0-9]+(\.[0-9]+)+)")))
            << library << ": " << found.at(library);
    }
}

TEST_F(Cli, VerboseVersionNamesTheShaderFolderFromTheEnvironmentAndFailsWithoutOne) {
    fs::create_directories(directory / "my-shaders");
    const CliRun given = run("--version --verbose", "INKGRAPH_SHADER_DIR=" + (directory / "my-shaders").string());
    EXPECT_EQ(given.exitCode, 0) << given.out << given.err;
    EXPECT_EQ(facts(given.out).at("shaders"), (directory / "my-shaders").string() + " (INKGRAPH_SHADER_DIR)");
    const CliRun missing = run("--version --verbose", "INKGRAPH_SHADER_DIR=" + (directory / "none").string());
    EXPECT_EQ(missing.exitCode, 4) << missing.out << missing.err;
    EXPECT_EQ(facts(missing.out).at("shaders"),
              (directory / "none").string() + " (INKGRAPH_SHADER_DIR), which is not a folder");
}

TEST_F(Cli, TheBuildWritesTheManPageAndCompletionThatTheProgramPrints) {
    const fs::path share = fs::path(INKGRAPH_BINARY_ROOT) / "share";
    const CliRun man = run("help --man");
    ASSERT_EQ(man.exitCode, 0) << man.err;
    EXPECT_EQ(man.out, manPage());
    EXPECT_EQ(readText(share / "man" / "man1" / "inkgraph.1"), man.out);
    const CliRun completion = run("help --bash-completion");
    ASSERT_EQ(completion.exitCode, 0) << completion.err;
    EXPECT_EQ(completion.out, bashCompletion());
    EXPECT_EQ(readText(share / "bash-completion" / "completions" / "inkgraph"), completion.out);
}

TEST_F(Cli, HelpThatCannotBeWrittenFails) {
    const std::string command =
        "cd '" + directory.string() + "' && '" + INKGRAPH_EXECUTABLE + "' help --man > /dev/full 2> err.txt";
    const int status = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 5);
    EXPECT_NE(readText(directory / "err.txt").find("cannot write the standard output"), std::string::npos);
}

} // namespace
} // namespace inkgraph
