#include "graph/Resource.h"

#include "graph/Pass.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace inkgraph {
namespace {

TEST(GraphResourceTest, BytesPerPixel) {
    EXPECT_EQ(bytesPerPixel(Format::RGBA32F), 16);
    EXPECT_EQ(bytesPerPixel(Format::R32F), 4);
    EXPECT_EQ(bytesPerPixel(Format::RGBA8), 4);
    EXPECT_EQ(bytesPerPixel(Format::R8), 1);
    EXPECT_EQ(bytesPerPixel(Format::Depth32F), 4);
}

TEST(GraphResourceTest, FormatName) {
    EXPECT_EQ(formatName(Format::RGBA32F), "rgba32f");
    EXPECT_EQ(formatName(Format::R32F), "r32f");
    EXPECT_EQ(formatName(Format::RGBA8), "rgba8");
    EXPECT_EQ(formatName(Format::R8), "r8");
    EXPECT_EQ(formatName(Format::Depth32F), "depth32f");
    EXPECT_TRUE(isFloatFormat(Format::Depth32F)) << "read back as float32, dumped as EXR";
}

TEST(GraphResourceTest, TextureDescDefaultsAndEquality) {
    const TextureDesc desc;
    EXPECT_EQ(desc.format, Format::RGBA32F);
    EXPECT_EQ(desc.scale, 1);
    EXPECT_EQ(desc, (TextureDesc{Format::RGBA32F, 1}));
    EXPECT_NE(desc, (TextureDesc{Format::RGBA32F, 2}));
    EXPECT_NE(desc, (TextureDesc{Format::R8, 1}));
}

TEST(GraphResourceTest, ScaledSideIsTheFrameTimesScaleOverDivisor) {
    EXPECT_EQ(scaledSide(2048, 1, 1), 2048);
    EXPECT_EQ(scaledSide(1000, 2, 1), 2000);
    EXPECT_EQ(scaledSide(2048, 1, 2), 1024);
    EXPECT_EQ(scaledSide(3000, 1, 2), 1500);
    EXPECT_EQ(scaledSide(1500, 2, 3), 1000) << "supersampled, then sampled at a third";
    EXPECT_EQ(TextureDesc{}.divisor, 1);
    EXPECT_NE((TextureDesc{Format::R32F, 1, 1, 2}), (TextureDesc{Format::R32F, 1, 1, 1}));
    // A divisor that leaves part of a pixel would not cover the frame exactly: refused, naming both numbers.
    try {
        scaledSide(2049, 1, 2);
        FAIL() << "2049 / 2 accepted";
    } catch (const std::invalid_argument& error) {
        EXPECT_NE(std::string(error.what()).find("scaledSide(): a side of 2049 pixels"), std::string::npos)
            << error.what();
        EXPECT_NE(std::string(error.what()).find("divisor 2"), std::string::npos) << error.what();
    }
    EXPECT_THROW(scaledSide(100, 0, 1), std::invalid_argument);
    EXPECT_THROW(scaledSide(100, 1, 0), std::invalid_argument);
}

TEST(GraphResourceTest, SplitAWellFormedName) {
    const ResourceName name = ResourceName::split("gbuffer.normal");
    EXPECT_EQ(name.pass, "gbuffer");
    EXPECT_EQ(name.field, "normal");
    EXPECT_EQ(name.joined(), "gbuffer.normal");
}

TEST(GraphResourceTest, SplitWithoutExactlyOneDotGivesEmptyParts) {
    for (const char* bad : {"normal", "", "gbuffer.normal.x", "a..b"}) {
        SCOPED_TRACE(bad);
        const ResourceName name = ResourceName::split(bad);
        EXPECT_TRUE(name.pass.empty());
        EXPECT_TRUE(name.field.empty());
    }
}

TEST(GraphResourceTest, SplitKeepsEmptySidesOfTheDot) {
    const ResourceName leading = ResourceName::split(".normal");
    EXPECT_EQ(leading.pass, "");
    EXPECT_EQ(leading.field, "normal");
    const ResourceName trailing = ResourceName::split("gbuffer.");
    EXPECT_EQ(trailing.pass, "gbuffer");
    EXPECT_EQ(trailing.field, "");
}

TEST(GraphPassBuilderTest, RecordsReadsWritesAndSideEffect) {
    PassBuilder builder("cel");
    EXPECT_EQ(builder.passName(), "cel");
    EXPECT_FALSE(builder.hasSideEffect());

    builder.read("gbuffer.normal");
    builder.read("shademap.ramp");
    builder.write("color", {Format::RGBA8, 1});
    builder.write("mask", {Format::R8, 2}, Need::Optional);
    builder.markSideEffect();

    ASSERT_EQ(builder.reads().size(), 2u);
    EXPECT_EQ(builder.reads()[0].resource, "gbuffer.normal");
    EXPECT_EQ(builder.reads()[1].resource, "shademap.ramp");
    ASSERT_EQ(builder.writes().size(), 2u);
    EXPECT_EQ(builder.writes()[0].field, "color");
    EXPECT_EQ(builder.writes()[0].desc, (TextureDesc{Format::RGBA8, 1}));
    EXPECT_EQ(builder.writes()[0].need, Need::Required);
    EXPECT_EQ(builder.writes()[1].field, "mask");
    EXPECT_EQ(builder.writes()[1].desc.scale, 2);
    EXPECT_EQ(builder.writes()[1].need, Need::Optional);
    EXPECT_TRUE(builder.hasSideEffect());
}

TEST(GraphPassBuilderTest, MalformedWritesAreRecordedAsGivenNotThrown) {
    // compile() reports these together with every other problem, so declare() must not throw.
    PassBuilder builder("cel");
    EXPECT_NO_THROW(builder.write("hull.color", {}));
    EXPECT_NO_THROW(builder.write("", {}));
    ASSERT_EQ(builder.writes().size(), 2u);
    EXPECT_EQ(builder.writes()[0].field, "hull.color");
    EXPECT_EQ(builder.writes()[1].field, "");
}

} // namespace
} // namespace inkgraph
