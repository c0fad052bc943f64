// The --dump folder's own undo (app/DumpFolder.h), without a render: what a failed run removes is only what it made,
// found where it now is, never a folder the user made at its name meanwhile.
#include "app/DumpFolder.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

namespace fs = std::filesystem;

class DumpFolderUndo : public ::testing::Test {
protected:
    void SetUp() override {
        fs::remove_all(root);
        fs::create_directories(root);
    }
    void TearDown() override { fs::remove_all(root); }

    const fs::path root = fs::temp_directory_path() / ("inkgraph-dump-folder-" + std::to_string(::getpid()));
};

TEST_F(DumpFolderUndo, AFailedRunRemovesTheFoldersItMadeAndNoneTheUserMadeAtTheirNames) {
    {
        const DumpFolder dump((root / "made" / "d").string()); // "made" and "d" are created by the check
        ASSERT_TRUE(fs::is_directory(root / "made" / "d"));
        // The user moves the run's folders away and makes a folder of their own at the name.
        fs::rename(root / "made", root / "moved");
        fs::create_directories(root / "made");
        std::ofstream(root / "moved" / "note.txt") << "the user's\n"; // keeps "moved" from being empty
    }                                                                 // the run fails: the dump is abandoned
    EXPECT_TRUE(fs::is_directory(root / "made")) << "the user's own folder was removed";
    EXPECT_FALSE(fs::exists(root / "moved" / "d")) << "the dump folder the run made was left where it was moved";
    EXPECT_TRUE(fs::exists(root / "moved" / "note.txt"));
    for (const auto& entry : fs::directory_iterator(root / "moved"))
        EXPECT_EQ(entry.path().filename().string().rfind(".inkgraph", 0), std::string::npos) << entry.path();
}

TEST_F(DumpFolderUndo, AFailedRunIntoANewFolderRemovesItAndItsStaging) {
    { const DumpFolder dump((root / "a" / "b" / "d").string()); }
    EXPECT_TRUE(fs::is_empty(root)) << "a folder the run made, or its staging folder, was left";
}

TEST_F(DumpFolderUndo, AnEarlierDumpThatLostAFileIsStillADumpButNotOneNamingAFolderOrHoldingAnother) {
    const fs::path dump = root / "d";
    fs::create_directories(dump);
    std::ofstream(dump / "manifest.json") << R"({"inkgraph":"0","files":[{"file":"depth.exr"},{"file":"final.png"}]})";
    std::ofstream(dump / "final.png") << "x";
    // depth.exr deleted since (or a copy that stopped short): replacing the rest loses nothing of the user's.
    EarlierDump earlier = readEarlierDump(dump);
    EXPECT_EQ(earlier.problem, "");
    EXPECT_EQ(earlier.files, std::vector<std::string>({"final.png", "manifest.json"}));
    fs::create_directories(dump / "depth.exr" / "precious");
    earlier = readEarlierDump(dump);
    EXPECT_EQ(earlier.problem, "its manifest.json names 'depth.exr', which is not a file in it");
    fs::remove_all(dump / "depth.exr");
    std::ofstream(dump / "notes.txt") << "mine";
    earlier = readEarlierDump(dump);
    EXPECT_EQ(earlier.problem, "it holds 'notes.txt', which its manifest.json does not name");
}

} // namespace
} // namespace inkgraph
