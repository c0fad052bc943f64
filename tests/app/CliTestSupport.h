#pragma once
/** @file The `inkgraph` executable run as a user runs it, in a fresh folder per test (tests/app). */

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace inkgraph::test {

namespace fs = std::filesystem;

struct CliRun {
    int exitCode = -1;
    std::string out;
    std::string err;
};

inline std::string readText(const fs::path& path) {
    std::ifstream file(path);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

class Cli : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        directory = fs::temp_directory_path() /
                    ("inkgraph-cli-" + std::string(info->name()) + "-" + std::to_string(::getpid()));
        fs::remove_all(directory);
        fs::create_directories(directory);
    }
    void TearDown() override {
        if (!HasFailure()) fs::remove_all(directory);
    }

    /** Runs the executable through the shell; `environment` is prefixed ("A=1 B=2"). */
    CliRun run(const std::string& arguments, const std::string& environment = "") {
        const fs::path outFile = directory / "stdout.txt";
        const fs::path errFile = directory / "stderr.txt";
        const std::string command = "cd '" + directory.string() + "' && env LP_NUM_THREADS=1 " + environment + " '" +
                                    INKGRAPH_EXECUTABLE + "' " + arguments + " > '" + outFile.string() + "' 2> '" +
                                    errFile.string() + "' < /dev/null";
        const int status = std::system(command.c_str());
        CliRun result;
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

    static std::string model(const std::string& name) {
        // Appended rather than "'" + path + "'": GCC 12 warns falsely (-Wrestrict, bug 105329) on that inlined.
        std::string quoted = "'";
        quoted += (fs::path(INKGRAPH_SOURCE_ROOT) / "models" / name).string();
        quoted += "'";
        return quoted;
    }

    fs::path directory;
};

} // namespace inkgraph::test
