// The suggestive contours' one sampling at every size (passes/lines/types/SuggestiveLines.h): which divisor of the
// picture gives the kernel its field of at least 1024 rows.
#include "passes/lines/types/SuggestiveLines.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace inkgraph {
namespace {

TEST(SuggestiveField, IsThePicturesOwnUpTo2047Rows) {
    EXPECT_EQ(suggestiveFieldDivisor(512, 512), 1);
    EXPECT_EQ(suggestiveFieldDivisor(1024, 1024), 1);
    EXPECT_EQ(suggestiveFieldDivisor(1920, 1080), 1);
    EXPECT_EQ(suggestiveFieldDivisor(4000, 2047), 1) << "a divisor of 2 would leave 1023.5 rows";
}

TEST(SuggestiveField, IsTheLargestWholeDivisorThatKeeps1024Rows) {
    EXPECT_EQ(suggestiveFieldDivisor(2048, 2048), 2);
    EXPECT_EQ(suggestiveFieldDivisor(3000, 3000), 2) << "1500 rows: 3 would leave 1000";
    EXPECT_EQ(suggestiveFieldDivisor(3840, 2160), 2);
    EXPECT_EQ(suggestiveFieldDivisor(4096, 4096), 4);
    EXPECT_EQ(suggestiveFieldDivisor(6144, 3072), 3);
}

TEST(SuggestiveField, NeedsADivisorOfBothSides) {
    EXPECT_EQ(suggestiveFieldDivisor(2049, 2049), 1) << "no whole divisor: the picture's own G-buffer";
    EXPECT_EQ(suggestiveFieldDivisor(2047, 2048), 1) << "2 divides the rows but not the columns";
    EXPECT_EQ(suggestiveFieldDivisor(4095, 4096), 1) << "4 and 2 divide the rows but not the columns; 3 not the rows";
    EXPECT_EQ(suggestiveFieldDivisor(4098, 4096), 2) << "4 does not divide the columns, 2 does";
}

TEST(SuggestiveField, RefusesAnEmptyPicture) {
    EXPECT_THROW(suggestiveFieldDivisor(0, 2048), std::invalid_argument);
    EXPECT_THROW(suggestiveFieldDivisor(2048, -1), std::invalid_argument);
}

} // namespace
} // namespace inkgraph
