// boundedMessage() (render/Messages.h): every message the user reads is at most 2000 bytes, whatever it quotes, and
// shows control characters instead of sending them to the terminal.
#include "render/Messages.h"
#include "scene/MessageText.h"

#include <gtest/gtest.h>

#include <string>

namespace inkgraph {
namespace {

TEST(Messages, ControlCharactersAreShownNotSent) {
    // A list line or a mesh name with a terminal's escape sequences (clear the screen, red, the bell) is shown as
    // text; line breaks and tabs, which messages use, stay; UTF-8 stays.
    EXPECT_EQ(boundedMessage("inkgraph: [1/1] 'x\x1b[2J\x1b[31mred\x07\x7f\r.obj' failed: caf\xc3\xa9\tok\n"),
              "inkgraph: [1/1] 'x\\x1b[2J\\x1b[31mred\\x07\\x7f\\x0d.obj' failed: caf\xc3\xa9\tok\n");
    EXPECT_EQ(printableText(std::string("a\0b", 3)), "a\\x00b");
}

TEST(Messages, AFileNameIsQuotedOnOneLine) {
    // A line break or a tab in a file's name split the progress line that named it (" -> 'o\tu\nt.png'"); a name is
    // shown on its line, every control character as its code, where a message's own line breaks stay.
    EXPECT_EQ(detail::quotedFileName("out/o\tu\nt\r\x1b[2J.png"), "'out/o\\x09u\\x0at\\x0d\\x1b[2J.png'");
    EXPECT_EQ(detail::quotedFileName(std::string("a\0b", 3)), "'a\\x00b'");
    EXPECT_EQ(detail::quotedFileName("caf\xc3\xa9 it's.obj"), "'caf\xc3\xa9 it's.obj'") << "UTF-8 and quotes stay";
    EXPECT_EQ(detail::excerptForMessage("mesh\nname"), "mesh\\x0aname") << "a name inside a model too";
    EXPECT_EQ(printableText("first\n  - second\tthird\x07"), "first\n  - second\tthird\\x07");
}

TEST(Messages, AMessageThatFitsIsUnchanged) {
    const std::string message = "loadScene(): 'model.obj': line 3: " + std::string(1500, 'x');
    EXPECT_EQ(boundedMessage(message), message);
}

TEST(Messages, ALongQuotedPathKeepsItsEndsAndSaysItsLength) {
    const std::string path = "/models/" + std::string(4980, 'p') + "/skin.png";
    const std::string bounded =
        boundedMessage("decodeSceneImage(): 'a.gltf' image 0: its file '" + path + "' cannot be found");
    EXPECT_LE(bounded.size(), kMessageByteLimit);
    EXPECT_EQ(bounded, "decodeSceneImage(): 'a.gltf' image 0: its file '/models/" + std::string(72, 'p') + "..." +
                           std::string(71, 'p') + "/skin.png (4997 bytes)' cannot be found");
}

TEST(Messages, ShortQuotesStayWholeAndTheRestIsCutAtTheLimit) {
    // No quoted run to shorten (the long run is not quoted): cut, saying how long the message was.
    const std::string message = "'short' " + std::string(5000, 'z');
    const std::string bounded = boundedMessage(message);
    EXPECT_LE(bounded.size(), kMessageByteLimit);
    EXPECT_EQ(bounded.rfind("'short' zzz", 0), 0u) << bounded.substr(0, 40);
    EXPECT_NE(bounded.find("(cut; the message had 5008 bytes)"), std::string::npos);
}

TEST(Messages, CutsNeverSplitAUtf8Character) {
    // 2-byte characters (é) from byte 1: any cut at an odd offset would split one.
    std::string quoted;
    for (int i = 0; i < 2000; ++i) quoted += "\xc3\xa9";
    const std::string bounded = boundedMessage("x'" + quoted + "'");
    ASSERT_LE(bounded.size(), kMessageByteLimit);
    const std::string inside = bounded.substr(2, bounded.find("...") - 2);
    EXPECT_EQ(inside.size() % 2, 0u);
    for (std::size_t i = 0; i < inside.size(); i += 2) EXPECT_EQ(inside.substr(i, 2), "\xc3\xa9");
}

} // namespace
} // namespace inkgraph
