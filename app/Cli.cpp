#include "app/Cli.h"

#include "render/Messages.h"

#include "app/BatchRun.h"
#include "app/CommandLineDocs.h"
#include "app/DatasetCheck.h"
#include "app/GeneratedDocs.h"
#include "render/ImageFiles.h"
#include "app/Render.h"
#include "flags/StyleFile.h"
#include "render/TemporaryFiles.h"
#include "app/Version.h"
#include "gl/GraphExecutor.h"
#include "gl/HeadlessContext.h"
#include "gl/ShaderLibrary.h"
#include "scene/Scene.h"

#include <opencv2/core.hpp>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <stdexcept>

namespace inkgraph {

namespace {

/** The command whose first name is `name`. */
const CommandInfo& commandNamed(const std::string& name) {
    for (const CommandInfo& command : commands())
        if (command.names.front() == name) return command;
    throw std::logic_error("commandNamed(): no command '" + name + "'");
}

/** "line-types, dump-files". */
std::string docSectionNames() {
    std::string names;
    for (const std::string& section : generatedDocSections()) names += (names.empty() ? "" : ", ") + section;
    return names;
}

/** `inkgraph help [TOPIC]`. */
int runHelpCommand(const std::vector<std::string>& arguments, std::ostream& out, std::ostream& err) {
    const std::string topic = arguments.size() > 1 ? arguments[1] : "";
    // Hidden: README.md's generated sections (app/GeneratedDocs.h), for scripts/update-docs.sh.
    if (topic == "--docs") {
        if (arguments.size() != 3) {
            err << "inkgraph: help --docs takes one section (" << docSectionNames() << ")\n";
            return kExitUsage;
        }
        try {
            out << generatedDocSection(arguments[2]);
        } catch (const std::invalid_argument&) {
            err << "inkgraph: no generated section '" << arguments[2] << "' (" << docSectionNames() << ")\n";
            return kExitUsage;
        }
        return kExitOk;
    }
    if (arguments.size() > 2) {
        err << "inkgraph: help takes one topic, got '" << arguments[1] << "' and '" << arguments[2] << "'\n";
        return kExitUsage;
    }
    if (topic.empty())
        out << mainHelp();
    else if (topic == "render")
        out << renderHelp();
    else if (topic == "check-dataset")
        out << checkDatasetHelp();
    else if (topic == "--man")
        out << manPage();
    else if (topic == "--bash-completion")
        out << bashCompletion();
    else {
        std::string topics;
        for (const std::string& word : commandNamed("help").words) topics += (topics.empty() ? "" : ", ") + word;
        err << "inkgraph: no help on '" << topic << "' (topics: " << topics << ")\n";
        return kExitUsage;
    }
    return kExitOk;
}

/** `inkgraph --version [--verbose]`. */
int runVersionCommand(const std::vector<std::string>& arguments, std::ostream& out, std::ostream& err) {
    if (arguments.size() == 1) {
        out << versionLine() << "\n";
        return kExitOk;
    }
    if (arguments.size() == 2 && arguments[1] == "--verbose") return writeVerboseVersion(out);
    std::string given;
    for (std::size_t i = 1; i < arguments.size(); ++i) given += (given.empty() ? "" : " ") + arguments[i];
    err << "inkgraph: --version takes only --verbose, got '" << given << "'\n";
    return kExitUsage;
}

int runRenderCommand(const std::vector<std::string>& arguments, std::ostream& out, std::ostream& err) {
    try {
        std::error_code noFolder;
        (void)std::filesystem::current_path(noFolder);
        if (noFolder)
            throw FileError("runCommandLine(): the working folder cannot be found (" + noFolder.message() +
                            "; was it deleted?); run inkgraph from an existing folder");
        const SourcedArguments expanded = expandStyleFile(arguments);
        const RenderOptions options = parseRenderOptions(expanded.arguments, expanded.origins);
        if (options.help) {
            out << renderHelp();
            return kExitOk;
        }
        return renderBatch(options, std::cin, out, err, arguments, expanded.arguments);
    } catch (...) {
        const ErrorReport report = reportOf(std::current_exception());
        err << "inkgraph: " << report.message << "\n";
        if (report.showsHelpHint) err << "(see: inkgraph help render)\n";
        return report.exitCode;
    }
}

} // namespace

const std::vector<CommandInfo>& commands() {
    // runCommandLine() dispatches on these names; runHelpCommand() takes its topics from help's words.
    static const std::vector<CommandInfo> kCommands = {
        {{"render"}, "MODEL... -o OUT.png [options]", "render a still of each model (see: inkgraph help render)", {}},
        {{"check-dataset"},
         "DIR",
         "verify a data set made with render --dataset DIR: every still's files\n"
         "there and whole, no unfinished run; exit 0 whole, 1 not (see: inkgraph\n"
         "check-dataset --help)",
         {"--help"}},
        {{"--version"},
         "[--verbose]",
         "print the version and the git commit; --verbose adds the shader folder\n"
         "in use, the EGL and OpenGL driver (it makes a context) and the libraries'\n"
         "versions, and exits with 4 when there is no context or no shader folder",
         {"--verbose"}},
        {{"help", "--help", "-h"},
         "[render | check-dataset | --man | --bash-completion]",
         "this text; render: every flag of inkgraph render; check-dataset: what\n"
         "it checks; --man: the man page (roff); --bash-completion: the bash\n"
         "completion script",
         {"render", "check-dataset", "--man", "--bash-completion"}},
    };
    return kCommands;
}

std::string mainHelp() {
    constexpr std::size_t kHelpColumn = 47;
    std::string text = std::string("inkgraph - ") + kProgramSummary + "\n\nUsage:\n";
    for (const CommandInfo& command : commands()) {
        std::string usage = "  inkgraph " + command.names.front() + " " + command.arguments;
        usage = usage.size() + 1 > kHelpColumn ? usage + "\n" + std::string(kHelpColumn, ' ')
                                               : usage + std::string(kHelpColumn - usage.size(), ' ');
        for (char c : command.help) usage += c == '\n' ? "\n" + std::string(kHelpColumn, ' ') : std::string(1, c);
        text += usage + "\n";
    }
    return text;
}

int runCommandLine(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
    std::vector<std::string> arguments(argv + std::min(argc, 1), argv + argc);
    if (arguments.empty()) {
        err << mainHelp();
        return kExitUsage;
    }
    const auto named = [&arguments](const std::string& command) {
        const std::vector<std::string>& names = commandNamed(command).names;
        return std::find(names.begin(), names.end(), arguments[0]) != names.end();
    };
    int exitCode = kExitOk;
    if (named("render")) {
        arguments.erase(arguments.begin());
        removeTemporariesOnSignals();
        exitCode = runRenderCommand(arguments, out, err);
    } else if (named("check-dataset")) {
        exitCode = runCheckDatasetCommand({arguments.begin() + 1, arguments.end()}, out, err);
    } else if (named("--version")) {
        exitCode = runVersionCommand(arguments, out, err);
    } else if (named("help")) {
        exitCode = runHelpCommand(arguments, out, err);
    } else {
        err << "inkgraph: unknown command '" << arguments[0] << "' (try: inkgraph --help)\n";
        return kExitUsage;
    }
    // Output that cannot be written (--help > /dev/full, a closed pipe) is a failed run, not a silent one.
    try {
        requireStandardOutputWritten(out);
    } catch (const FileError& error) {
        if (exitCode == kExitOk) err << "inkgraph: " << error.what() << "\n";
        return exitCode == kExitOk ? kExitOutput : exitCode;
    }
    return exitCode;
}

} // namespace inkgraph
