#pragma once
/** @file A fresh, empty folder for each test, for tests that read and write real files. No GL. */

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include <unistd.h>

namespace inkgraph::test {

/** Fixture base: `directory` is created empty before each test, named by the suite, the test and the process (so
 *  parallel ctest runs never share one), and removed after it, unless the test failed: then it is kept to look at. */
class TestFolder : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        // A parameterized test's names hold '/' ("Case/Suite", "Test/case"): one folder, not a tree of them.
        std::string name =
            "inkgraph-" + std::string(info->test_suite_name()) + "-" + info->name() + "-" + std::to_string(::getpid());
        std::replace(name.begin(), name.end(), '/', '.');
        directory = std::filesystem::temp_directory_path() / name;
        std::filesystem::remove_all(directory);
        std::filesystem::create_directories(directory);
    }
    void TearDown() override {
        if (!HasFailure()) std::filesystem::remove_all(directory);
    }

    std::filesystem::path directory;
};

} // namespace inkgraph::test
