// The man page and the bash completion (app/CommandLineDocs.h) against the flag table they are generated from: every
// flag in both, the page read by groff without a warning, the script run by a real bash, whose completion function
// is asked as the shell asks it (COMP_WORDS, COMP_CWORD) and must answer from the table. Needs bash and groff.
#include "app/Cli.h"
#include "app/CommandLineDocs.h"
#include "app/DatasetCheck.h"
#include "flags/FlagTable.h"
#include "flags/Options.h"
#include "passes/lines/LineTypes.h"
#include "tests/support/TestFolder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>

namespace inkgraph {
namespace {

namespace fs = std::filesystem;

struct Shell {
    int exitCode = -1;
    std::string output; ///< standard output and standard error together
};

/** Runs `command` with /bin/sh, capturing both outputs. */
Shell runShell(const std::string& command) {
    Shell result;
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (pipe == nullptr) return result;
    char buffer[4096];
    std::size_t count = 0;
    while ((count = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) result.output.append(buffer, count);
    const int status = pclose(pipe);
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

std::string quoted(const std::string& text) {
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

/** The man page's way of writing `text` in bold: minus signs escaped. */
std::string manBold(const std::string& text) {
    std::string escaped;
    for (char c : text) escaped += c == '-' ? std::string("\\-") : std::string(1, c);
    return "\\fB" + escaped + "\\fR";
}

class CommandLineDocs : public test::TestFolder {
protected:
    void SetUp() override {
        TestFolder::SetUp();
        completion = directory / "inkgraph-completion.bash";
        std::ofstream(completion) << bashCompletion();
    }

    /** What bash's completion of `inkgraph` offers for `line` (the word under the cursor last, "" for a new word),
     *  run in `folder`: the shell's own arrays set as readline sets them, then the function the script registered
     *  with `complete`. */
    std::set<std::string> complete(const std::vector<std::string>& line, const fs::path& folder = {}) {
        std::string array;
        for (const std::string& word : line) array += " " + quoted(word);
        const std::string script = "source " + quoted(completion.string()) +
                                   " && function=$(complete -p inkgraph | sed -E 's/.*-F ([^ ]+).*/\\1/')" +
                                   " && COMP_WORDS=(inkgraph" + array +
                                   ") && COMP_CWORD=" + std::to_string(line.size()) + " && \"$function\" inkgraph" +
                                   " && printf '%s\\n' \"${COMPREPLY[@]}\"";
        const fs::path where = folder.empty() ? directory : folder;
        const Shell shell = runShell("cd " + quoted(where.string()) + " && bash -c " + quoted(script));
        EXPECT_EQ(shell.exitCode, 0) << shell.output;
        std::set<std::string> offered;
        std::istringstream stream(shell.output);
        for (std::string entry; std::getline(stream, entry);)
            if (!entry.empty()) offered.insert(entry);
        return offered;
    }

    fs::path completion;
};

std::vector<std::string> everyFlagName() {
    std::vector<std::string> names;
    for (const Flag& entry : renderFlags())
        for (const std::string& name : entry.names) names.push_back(name);
    return names;
}

TEST_F(CommandLineDocs, EveryRenderFlagIsInTheManPageAndTheCompletion) {
    const std::string page = manPage();
    const std::string script = bashCompletion();
    const std::vector<std::string> names = everyFlagName();
    ASSERT_GT(names.size(), 60u);
    for (const std::string& name : names) {
        EXPECT_NE(page.find(manBold(name)), std::string::npos) << name << " is not in the man page";
        EXPECT_NE(script.find(" " + name + " "), std::string::npos) << name << " is not in the completion script";
    }
    // And the shell offers each of them for its own name.
    std::string loop;
    for (const std::string& name : names) loop += " " + quoted(name);
    const std::string shellScript = "source " + quoted(completion.string()) + " && for flag in" + loop +
                                    "; do COMP_WORDS=(inkgraph render \"$flag\"); COMP_CWORD=2; _inkgraph;"
                                    " printf '%s\\n' \"${COMPREPLY[@]}\" | grep -qx -- \"$flag\" ||"
                                    " echo \"not offered: $flag\"; done";
    const Shell shell = runShell("cd " + quoted(directory.string()) + " && bash -c " + quoted(shellScript));
    EXPECT_EQ(shell.exitCode, 0);
    EXPECT_EQ(shell.output, "");
}

TEST_F(CommandLineDocs, ManPageHasItsSectionsAndGroffReadsItWithoutAWarning) {
    const std::string page = manPage();
    for (const char* section :
         {".SH NAME\n", ".SH SYNOPSIS\n", ".SH DESCRIPTION\n", ".SH COMMANDS\n", ".SH \"RENDER OPTIONS\"\n",
          ".SH \"EXIT STATUS\"\n", ".SH ENVIRONMENT\n", ".SH FILES\n", ".SH \"SEE ALSO\"\n"})
        EXPECT_NE(page.find(section), std::string::npos) << section;
    EXPECT_NE(page.find("\n.TH INKGRAPH 1 "), std::string::npos);
    for (HelpSection section : helpSections()) {
        std::string title;
        for (char c : std::string(helpSectionTitle(section)))
            title += c == '"' ? std::string("\\(dq") : std::string(1, c);
        std::string escaped;
        for (char c : title) escaped += c == '-' ? std::string("\\-") : std::string(1, c);
        EXPECT_NE(page.find(".SS \"" + escaped + "\""), std::string::npos) << escaped;
    }
    for (const ExitCodeMeaning& exit : exitCodeMeanings())
        EXPECT_NE(page.find(".TP\n" + manBold(std::to_string(exit.code)) + "\n" + exit.meaning), std::string::npos)
            << exit.code;
    for (const CommandInfo& command : commands())
        for (const std::string& name : command.names) EXPECT_NE(page.find(manBold(name)), std::string::npos) << name;
    EXPECT_TRUE(std::all_of(page.begin(), page.end(), [](char c) { return (unsigned char)c < 0x80; }))
        << "characters beyond ASCII are written as groff escapes";

    const fs::path file = directory / "inkgraph.1";
    std::ofstream(file) << page;
    const Shell groff = runShell("groff -ww -z -man " + quoted(file.string()));
    EXPECT_EQ(groff.exitCode, 0) << groff.output;
    EXPECT_EQ(groff.output, "") << "groff warns";
    // As a reader sees it: the flags as typed (hyphen-minus, not hyphens), the escapes decoded.
    const Shell text = runShell("groff -man -Tutf8 -P-cbou " + quoted(file.string()));
    EXPECT_EQ(text.exitCode, 0) << text.output;
    EXPECT_NE(text.output.find("-o, --output FILE"), std::string::npos);
    EXPECT_NE(text.output.find("--shading MODE"), std::string::npos);
    EXPECT_NE(text.output.find("Winnemöller"), std::string::npos);
}

TEST_F(CommandLineDocs, CompletionScriptIsValidBash) {
    const Shell syntax = runShell("bash -n " + quoted(completion.string()));
    EXPECT_EQ(syntax.exitCode, 0) << syntax.output;
    EXPECT_EQ(syntax.output, "");
}

TEST_F(CommandLineDocs, CompletesFlagsByPrefix) {
    std::set<std::string> expected;
    for (const std::string& name : everyFlagName())
        if (name.rfind("--shad", 0) == 0) expected.insert(name);
    EXPECT_EQ(expected, (std::set<std::string>{"--shading", "--shademap"}));
    EXPECT_EQ(complete({"render", "--shad"}), expected);
    EXPECT_EQ(complete({"render", "model.obj", "-o", "x.png", "--shad"}), expected);
    const std::set<std::string> all = complete({"render", "-"});
    EXPECT_EQ(all.size(), everyFlagName().size() + 1) << "every flag and --help";
    EXPECT_TRUE(all.count("--help"));
}

TEST_F(CommandLineDocs, CompletesTheValuesOfFlagsWithAFixedSet) {
    std::size_t flagsWithChoices = 0;
    for (const Flag& entry : renderFlags()) {
        if (entry.choices.empty()) continue;
        ++flagsWithChoices;
        const std::set<std::string> choices(entry.choices.begin(), entry.choices.end());
        EXPECT_EQ(complete({"render", entry.names.back(), ""}), choices) << entry.names.back();
    }
    EXPECT_GE(flagsWithChoices, 8u);
    // A line parameter of words offers them: --suggestive-stencil's 3 and 5 were offered nothing.
    for (const LineParameter* parameter : lineParameters()) {
        if (!parameter->isChoice()) continue;
        const std::set<std::string> words(parameter->choices.begin(), parameter->choices.end());
        EXPECT_EQ(complete({"render", "--" + parameter->name, ""}), words) << parameter->name;
    }
    // --shading c: the models starting with c, from the table.
    const Flag* shading = findFlag("--shading");
    std::set<std::string> startingWithC;
    for (const std::string& choice : shading->choices)
        if (choice[0] == 'c') startingWithC.insert(choice);
    EXPECT_TRUE(startingWithC.count("cel") && startingWithC.count("comic"));
    EXPECT_EQ(complete({"render", "--shading", "c"}), startingWithC);
    // A comma list completes its last item, keeping the ones before.
    const Flag* lines = findFlag("--lines");
    std::set<std::string> afterComma;
    for (const std::string& choice : lines->choices)
        if (choice[0] == 'c') afterComma.insert("silhouette," + choice);
    EXPECT_TRUE(afterComma.count("silhouette,contour"));
    EXPECT_EQ(complete({"render", "--lines", "silhouette,c"}), afterComma);
    // A value with no fixed set and no file: nothing to offer (not the folder's files).
    std::ofstream(directory / "model.obj") << "v 0 0 0\n";
    EXPECT_EQ(complete({"render", "--size", ""}), std::set<std::string>{});
}

TEST_F(CommandLineDocs, CompletesFilesForModelsAndPathFlags) {
    const fs::path folder = directory / "files";
    fs::create_directories(folder / "renders");
    for (const char* name : {"bunny.obj", "stats.json", "style.txt"}) std::ofstream(folder / name) << "x\n";
    EXPECT_EQ(complete({"render", ""}, folder),
              (std::set<std::string>{"bunny.obj", "stats.json", "style.txt", "renders"}));
    EXPECT_EQ(complete({"render", "b"}, folder), std::set<std::string>{"bunny.obj"});
    EXPECT_EQ(complete({"render", "bunny.obj", "--stats", ""}, folder),
              (std::set<std::string>{"stats.json", "renders"}))
        << "FILE.json: only .json files, and folders to descend into";
    EXPECT_EQ(complete({"render", "bunny.obj", "--dump", ""}, folder), std::set<std::string>{"renders"});
    EXPECT_EQ(complete({"render", "bunny.obj", "--style", "s"}, folder),
              (std::set<std::string>{"stats.json", "style.txt"}));
    EXPECT_EQ(complete({"render", "bunny.obj", "--shademap", "st"}, folder),
              (std::set<std::string>{"stats.json", "style.txt"}));
}

TEST_F(CommandLineDocs, CompletesTheCommandsAndTheirWords) {
    std::set<std::string> names;
    for (const CommandInfo& command : commands())
        for (const std::string& name : command.names) names.insert(name);
    EXPECT_EQ(complete({""}), names);
    EXPECT_EQ(complete({"--v"}), std::set<std::string>{"--version"});
    EXPECT_EQ(complete({"--version", ""}), std::set<std::string>{"--verbose"});
    EXPECT_EQ(complete({"help", "--"}), (std::set<std::string>{"--man", "--bash-completion"}));
    EXPECT_EQ(complete({"help", "render", ""}), std::set<std::string>{});
}

TEST(CommandLineCommands, EveryCommandAndHelpTopicRuns) {
    for (const CommandInfo& command : commands()) {
        for (const std::string& name : command.names) {
            std::vector<const char*> argv = {"inkgraph", name.c_str()};
            if (name == "render" || name == "check-dataset") argv.push_back("--help");
            std::ostringstream out, err;
            EXPECT_EQ(runCommandLine(int(argv.size()), argv.data(), out, err), kExitOk) << name << ": " << err.str();
            EXPECT_FALSE(out.str().empty()) << name;
        }
    }
    const std::vector<std::pair<std::string, std::string>> topics = {{"render", renderHelp()},
                                                                     {"check-dataset", checkDatasetHelp()},
                                                                     {"--man", manPage()},
                                                                     {"--bash-completion", bashCompletion()}};
    for (const auto& [topic, text] : topics) {
        const char* argv[] = {"inkgraph", "help", topic.c_str()};
        std::ostringstream out, err;
        EXPECT_EQ(runCommandLine(3, argv, out, err), kExitOk) << topic;
        EXPECT_EQ(out.str(), text) << topic;
    }
    const char* badTopic[] = {"inkgraph", "help", "--nope"};
    std::ostringstream out, err;
    EXPECT_EQ(runCommandLine(3, badTopic, out, err), kExitUsage);
    EXPECT_NE(err.str().find("no help on '--nope' (topics: render, check-dataset, --man, --bash-completion)"),
              std::string::npos)
        << err.str();
    const char* badVersion[] = {"inkgraph", "--version", "--verbos"};
    EXPECT_EQ(runCommandLine(3, badVersion, out, err), kExitUsage);
    EXPECT_NE(err.str().find("--version takes only --verbose, got '--verbos'"), std::string::npos) << err.str();
    const char* extraVersion[] = {"inkgraph", "--version", "--verbose", "x"};
    EXPECT_EQ(runCommandLine(4, extraVersion, out, err), kExitUsage);
    EXPECT_NE(err.str().find("--version takes only --verbose, got '--verbose x'"), std::string::npos) << err.str();
}

TEST(CommandLineCommands, HelpListsEveryCommandAndExitCode) {
    const std::string help = mainHelp();
    for (const CommandInfo& command : commands())
        EXPECT_NE(help.find("inkgraph " + command.names.front() + " " + command.arguments), std::string::npos)
            << command.names.front();
    for (const std::string& line : [&help] {
             std::vector<std::string> lines;
             std::istringstream stream(help);
             for (std::string line; std::getline(stream, line);) lines.push_back(line);
             return lines;
         }())
        EXPECT_LE(line.size(), 120u) << line;
    const std::string render = renderHelp();
    for (const ExitCodeMeaning& exit : exitCodeMeanings())
        EXPECT_NE(render.find(std::to_string(exit.code) + " " + exit.meaning), std::string::npos) << exit.meaning;
}

TEST(FlagChoices, AreExactlyWhatTheParserTakes) {
    for (const Flag& entry : renderFlags()) {
        if (entry.choices.empty()) continue;
        const std::string& name = entry.names.back();
        for (const std::string& choice : entry.choices) {
            RenderOptions options;
            EXPECT_NO_THROW(entry.apply(choice, options)) << name << " " << choice;
        }
        RenderOptions options;
        EXPECT_THROW(entry.apply("not-a-choice", options), UsageError) << name;
        if (!entry.commaList) continue;
        // A list takes any of its choices together ("none" stands alone).
        std::string list;
        for (const std::string& choice : entry.choices)
            if (choice != "none") list += (list.empty() ? "" : ",") + choice;
        EXPECT_NO_THROW(entry.apply(list, options)) << name << " " << list;
    }
}

} // namespace
} // namespace inkgraph
