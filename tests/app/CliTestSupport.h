#pragma once
/** @file The `inkgraph` executable run as a user runs it, in a fresh folder per test (tests/app). */

#include "tests/support/TestFolder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace inkgraph::test {

namespace fs = std::filesystem;

struct CliRun {
    int exitCode = -1;
    std::string out;
    std::string err;
    double peakMib = 0.0; ///< the largest resident set of the run's processes (the shell and the executable)
};

/** Runs `command` through /bin/sh as std::system does, and returns its wait status and the peak resident set of it and
 *  the processes it waited for (wait4's rusage of this one child, not of every child the test has had). */
inline int runShell(const std::string& command, double& peakMib) {
    const pid_t child = fork();
    if (child == 0) {
        execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
        _exit(127);
    }
    int status = -1;
    rusage usage{};
    if (child < 0 || wait4(child, &status, 0, &usage) != child) return -1;
    peakMib = double(usage.ru_maxrss) / 1024.0;
    return status;
}

inline std::string readText(const fs::path& path) {
    std::ifstream file(path);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

/** `path` in single quotes, for the shell. */
inline std::string shellQuoted(const fs::path& path) {
    // Appended rather than "'" + path + "'": GCC 12 warns falsely (-Wrestrict, bug 105329) on that inlined.
    std::string text = "'";
    text += path.string();
    text += "'";
    return text;
}

class Cli : public TestFolder {
protected:
    /** Runs the executable through the shell; `environment` is prefixed ("A=1 B=2"). */
    CliRun run(const std::string& arguments, const std::string& environment = "") {
        const fs::path outFile = directory / "stdout.txt";
        const fs::path errFile = directory / "stderr.txt";
        const std::string command = "cd '" + directory.string() + "' && env LP_NUM_THREADS=1 " + environment + " '" +
                                    INKGRAPH_EXECUTABLE + "' " + arguments + " > '" + outFile.string() + "' 2> '" +
                                    errFile.string() + "' < /dev/null";
        CliRun result;
        const int status = runShell(command, result.peakMib);
        result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        result.out = readText(outFile);
        result.err = readText(errFile);
        fs::remove(outFile);
        fs::remove(errFile);
        return result;
    }

    /** Files in the test folder other than the given ones, to prove nothing half-written was left. */
    std::vector<std::string> listFiles(const fs::path& folder) {
        std::vector<std::string> names;
        for (const auto& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename().string());
        std::sort(names.begin(), names.end());
        return names;
    }

    /** Everything under `folder` (links not followed): each relative path with its kind and, for files, every byte
     *  (for links, the target). Equal snapshots: nothing was added, removed or changed. FIFOs are never opened. */
    static std::map<std::string, std::string> snapshot(const fs::path& folder) {
        std::map<std::string, std::string> entries;
        for (auto it = fs::recursive_directory_iterator(folder); it != fs::recursive_directory_iterator(); ++it) {
            const std::string name = fs::relative(it->path(), folder).string();
            const fs::file_status status = it->symlink_status();
            if (fs::is_symlink(status))
                entries[name] = "link to " + fs::read_symlink(it->path()).string();
            else if (fs::is_regular_file(status))
                entries[name] = "file: " + readText(it->path());
            else if (fs::is_directory(status))
                entries[name] = "folder";
            else
                entries[name] = "special";
        }
        return entries;
    }

    /** A bundled model's path, quoted for the shell. */
    static std::string model(const std::string& name) {
        return shellQuoted(fs::path(INKGRAPH_SOURCE_ROOT) / "models" / name);
    }
};

} // namespace inkgraph::test
