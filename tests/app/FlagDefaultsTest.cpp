// A default a help text states is the code's default: giving the flag that value changes nothing. The help writes
// most defaults from the code (flags/FlagTable.cpp); this catches one typed by hand that drifted, in any flag, line
// parameter or shading model, and a choice word that no longer names its value as the code names it.
#include "flags/FlagTable.h"
#include "flags/Options.h"
#include "passes/PostStage.h"
#include "passes/lines/LineTypes.h"
#include "scene/Camera.h"
#include "scene/mesh/FaceOrientation.h"
#include "scene/mesh/Procedural.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace inkgraph {
namespace {

/** What the options mean for a still, with every default resolved: a flag given its default must leave this as it
 *  was. Parameters and line styles are compared by their effective values, the field of view as the camera resolves
 *  it for a model without a camera of its own. */
std::string effectiveSettings(const RenderOptions& options) {
    std::ostringstream out;
    out.precision(17);
    const Look& look = options.look;
    out << "size " << options.width << "x" << options.height << "\nsvg-tolerance " << options.svgTolerance << "\ntime "
        << options.animationTime << "\nauto camera " << options.autoCamera << "\nshading " << int(look.shading)
        << "\nshininess " << look.shininess << "\nbands " << look.bands.value_or(0) << "\nview vector "
        << int(look.viewVector) << "\nface orientation " << int(look.faceOrientation) << "\nfront rule "
        << look.frontRule << "\nsupersample " << look.supersample << "\nmsaa " << look.msaa << "\nprecision "
        << int(look.gbufferPrecision) << "\npost stage " << int(look.postStage) << "\nbackground " << look.background.r
        << "," << look.background.g << "," << look.background.b << "\nambient " << look.ambient.has_value()
        << "\nwidth map " << int(look.outlineWidthMap.source) << "\nstrokes " << look.strokes.minLength << " "
        << look.strokes.weightByDepth << look.strokes.weightByStrength << look.strokes.taperEnds
        << look.strokes.mergeOverlaps << " " << look.strokes.hiddenDashOn << "," << look.strokes.hiddenDashOff
        << "\nlines";
    for (const std::string& type : look.lines) out << " " << type;
    out << "\nhidden lines";
    for (const std::string& type : options.hiddenLineTypes) out << " " << type;
    for (const LineType& type : lineTypes()) {
        const LineStyle style = look.styleOf(type.name);
        out << "\n"
            << type.name << " " << style.widthPixels << " " << style.color.r << "," << style.color.g << ","
            << style.color.b << "," << style.color.a;
    }
    for (const LineParameter* parameter : lineParameters()) {
        out << "\n" << parameter->name << " ";
        if (parameter->isChoice())
            out << look.lineParameters.choice(*parameter);
        else if (const std::optional<double> value = look.lineParameters.numberIfSet(*parameter))
            out << *value;
    }
    const ViewSampling& views = options.viewSampling;
    out << "\nviews " << views.seed << " " << views.elevationMean << "," << views.elevationDeviation << ","
        << views.elevationLow << "," << views.elevationHigh << " " << views.distanceJitter << " "
        << views.lightJitterDegrees << "\njobs " << options.jobs << " draw threads " << options.drawThreads << "\negl "
        << options.eglPlatform << " readback " << options.readback << "\nweld " << options.weldTolerance;
    static const Scene scene = makeScene(makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 16, 8));
    out << "\nfov " << resolveCamera(cameraRequestOf(options), scene).fovYDegrees << "\n";
    return out.str();
}

/** The defaults `help` states: "(default V", ", default V", "; default V" (V up to a space, ';', ':' or ')', or a
 *  comma and a space), and "WORD (default)" where WORD is one of `choices`. "default:" introduces a description, and
 *  "the default X" speaks of something else; neither states a value. */
std::vector<std::string> statedDefaults(std::string help, const std::vector<std::string>& choices) {
    std::replace(help.begin(), help.end(), '\n', ' ');
    std::vector<std::string> values;
    static const std::regex kValue(R"((?:^|\(|[,;.] )default ([^\s;:),]+(?:,[^\s;:),]+)*))");
    for (std::sregex_iterator it(help.begin(), help.end(), kValue), end; it != end; ++it) values.push_back((*it)[1]);
    static const std::regex kWord(R"(([^\s|(,]+) \(default\))");
    for (std::sregex_iterator it(help.begin(), help.end(), kWord), end; it != end; ++it)
        if (std::find(choices.begin(), choices.end(), (*it)[1].str()) != choices.end()) values.push_back((*it)[1]);
    return values;
}

/** The flag whose apply() a help entry's stated defaults are tried with: itself, or for a pattern entry
 *  ("--TYPE-width PX") that flag of the first line type. */
const Flag* flagToTry(const Flag& entry) {
    if (entry.apply) return &entry;
    const std::string pattern = entry.helpLabel.substr(0, entry.helpLabel.find(' '));
    if (pattern.rfind("--TYPE-", 0) != 0) return nullptr;
    return findFlag("--" + lineTypes().front().name + "-" + pattern.substr(7));
}

TEST(FlagDefaults, EveryDefaultAHelpTextStatesIsTheCodesDefault) {
    const std::string unchanged = effectiveSettings(RenderOptions{});
    std::set<std::string> checked;
    for (const Flag& entry : renderFlags()) {
        if (entry.help.empty()) continue;
        const std::string name = entry.names.empty() ? entry.helpLabel : entry.names.back();
        // --ambient states two defaults, one for each family of models (ShadingModelTraits::defaultAmbient, from
        // which the help writes both); given, one value stands for both.
        if (name == "--ambient") continue;
        const Flag* tried = flagToTry(entry);
        for (const std::string& value : statedDefaults(entry.help, tried ? tried->choices : entry.choices)) {
            ASSERT_NE(tried, nullptr) << name << " states a default (" << value << ") but takes no value to try it";
            RenderOptions options;
            ASSERT_NO_THROW(tried->apply(value, options)) << name << "'s stated default '" << value << "'";
            EXPECT_EQ(effectiveSettings(options), unchanged)
                << name << "'s help states the default '" << value << "', but giving it changes the settings";
            checked.insert(name);
        }
    }
    // The scan reads what the help writers write: these must be among the flags it checked.
    for (const char* flag : {"--size",
                             "--svg-tolerance",
                             "--time",
                             "--fov",
                             "--camera",
                             "--shading",
                             "--shininess",
                             "--view-vector",
                             "--face-orientation",
                             "--front-rule",
                             "--background",
                             "--msaa",
                             "--lines",
                             "--TYPE-width PX",
                             "--TYPE-color R,G,B[,A]",
                             "--crease-angle",
                             "--depth-jump",
                             "--suggestive-stencil",
                             "--supersample",
                             "--min-stroke-length",
                             "--line-weight",
                             "--overlapping-lines",
                             "--hidden-lines",
                             "--hidden-dash",
                             "--gbuffer-precision",
                             "--draw-threads",
                             "--seed",
                             "--view-elevation",
                             "--view-distance-jitter",
                             "--light-jitter",
                             "--egl-platform",
                             "--readback",
                             "--post-stage",
                             "--weld-distance"})
        EXPECT_TRUE(checked.count(flag)) << flag << ": no stated default found in its help";
}

TEST(FlagDefaults, TheScanFindsADefaultThatDrifted) {
    EXPECT_EQ(statedDefaults("width in pixels (default 3), constant", {}), std::vector<std::string>{"3"});
    EXPECT_EQ(statedDefaults("dashes (default 6,4; each 1 to 4096", {}), std::vector<std::string>{"6,4"});
    EXPECT_EQ(statedDefaults("(1 to 8,\ndefault 1) and", {}), std::vector<std::string>{"1"});
    EXPECT_EQ(statedDefaults("exact (default) | constant", {"exact", "constant"}), std::vector<std::string>{"exact"});
    EXPECT_TRUE(statedDefaults("(default: the cores), the default view is 0,14", {}).empty());
    RenderOptions drifted;
    findFlag("--shininess")->apply("33", drifted);
    EXPECT_NE(effectiveSettings(drifted), effectiveSettings(RenderOptions{}));
}

TEST(FlagChoices, NameTheirValuesAsTheCodeNamesThem) {
    for (const std::string& word : findFlag("--view-vector")->choices) {
        RenderOptions options;
        findFlag("--view-vector")->apply(word, options);
        EXPECT_EQ(viewVectorModeName(options.look.viewVector), word);
    }
    for (const std::string& word : findFlag("--face-orientation")->choices) {
        RenderOptions options;
        findFlag("--face-orientation")->apply(word, options);
        EXPECT_EQ(faceOrientationMethodName(options.look.faceOrientation), word);
    }
    for (const std::string& word : findFlag("--post-stage")->choices) {
        RenderOptions options;
        findFlag("--post-stage")->apply(word, options);
        EXPECT_EQ(std::string(postStageDeviceName(options.look.postStage)), word);
    }
}

} // namespace
} // namespace inkgraph
