// The one table of warning codes (scene/Warning.h): every kind has its row, in order, each code once, in kebab case,
// with a one-line meaning; a warning made of a kind carries that row's code.
#include "scene/Warning.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace inkgraph {
namespace {

bool isKebabCase(std::string_view code) {
    if (code.empty() || code.front() == '-' || code.back() == '-') return false;
    for (std::size_t i = 0; i < code.size(); ++i) {
        const char c = code[i];
        const bool letterOrDigit = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
        if (!letterOrDigit && !(c == '-' && code[i - 1] != '-')) return false;
    }
    return true;
}

TEST(WarningCodes, EveryKindHasOneRowInOrderWithAUniqueKebabCaseCodeAndAMeaning) {
    const std::vector<WarningCode>& codes = warningCodes();
    ASSERT_EQ(codes.size(), std::size_t(WarningKind::Count)) << "a WarningKind without its row in warningCodes()";
    std::set<std::string_view> seen;
    for (std::size_t i = 0; i < codes.size(); ++i) {
        const WarningCode& row = codes[i];
        EXPECT_EQ(std::size_t(row.kind), i) << "row " << i << " '" << row.code << "' is out of WarningKind's order";
        EXPECT_TRUE(isKebabCase(row.code)) << "'" << row.code << "'";
        EXPECT_TRUE(seen.insert(row.code).second) << "'" << row.code << "' is in the table twice";
        EXPECT_FALSE(row.meaning.empty()) << row.code;
        EXPECT_EQ(row.meaning.find('\n'), std::string_view::npos) << row.code << ": one line";
        EXPECT_EQ(row.meaning.find('|'), std::string_view::npos) << row.code << ": a Markdown table cell";
    }
}

TEST(WarningCodes, AWarningOfAKindCarriesItsCode) {
    for (const WarningCode& row : warningCodes()) {
        const Warning warning = makeWarning(row.kind, "message", "model.gltf", "mesh 'a'");
        EXPECT_EQ(warning.code, row.code);
        EXPECT_EQ(warningCode(row.kind), row.code);
        EXPECT_EQ(warning.message, "message");
        EXPECT_EQ(warning.file, "model.gltf");
        EXPECT_EQ(warning.item, "mesh 'a'");
    }
    EXPECT_EQ(makeWarning(WarningKind::TextureMissing, "m").code, "texture-missing");
    EXPECT_THROW(warningCode(WarningKind::Count), std::logic_error);
}

} // namespace
} // namespace inkgraph
