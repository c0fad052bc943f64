#include "api/Internal.h"

#include "flags/FlagTable.h"
#include "passes/lines/LineTypes.h"
#include "scene/MessageText.h"

#include <algorithm>

namespace inkgraph::api {
inline namespace INKGRAPH_ABI_NAMESPACE {
namespace {

bool takes(FlagOwner owner, const Flag& flag) {
    if (owner == FlagOwner::Look) return flag.section == HelpSection::Look || flag.section == HelpSection::Lines;
    return flag.section == HelpSection::Camera || flag.names.back() == "--size";
}

/** Where the library takes what `flag` sets, for the refusal of a flag given in the wrong place. */
std::string whereInLibrary(const Flag& flag) {
    const std::string& name = flag.names.back();
    switch (flag.section) {
    case HelpSection::Look:
    case HelpSection::Lines: return "give it to the Look";
    case HelpSection::Camera: return "give it to the Frame";
    case HelpSection::Output:
        return name == "--size" ? "give Frame::width and height"
                                : "the library returns images: Still::buffer(), Still::write(), Image::write()";
    case HelpSection::Batch: return "render each Scene in a loop";
    case HelpSection::Views:
        return "sampleViews() (Python: sample_views()) draws the views: put each one's orbit() in a Frame";
    case HelpSection::System:
        if (name == "--memory-limit") return "give SceneOptions::memoryLimitBytes to Scene::load()";
        if (name == "--weld-distance") return "give SceneOptions::weldDistance to Scene::load()";
        if (name == "--strict") return "give SceneOptions::strict to Scene::load()";
        return "give it to the Renderer's constructor";
    }
    return "";
}

/** The flag an argument names, or null for a value or an unknown flag. */
const Flag* flagOf(const std::string& argument) {
    const Flag* flag = findFlag(argument);
    return flag != nullptr && flag->apply ? flag : nullptr;
}

/** The look of `expanded` flags, checked as the command line checks them: each value, then the rules between them
 *  (the Look's own refusals first). */
Look::Impl lookOf(SourcedArguments expanded) {
    refuseOtherFlags(expanded, FlagOwner::Look);
    Look::Impl impl;
    if (expanded.origins.empty()) expanded.origins.assign(expanded.arguments.size(), "");
    impl.parsed = parseRenderFlags(expanded.arguments, expanded.origins);
    impl.arguments = std::move(expanded.arguments);
    impl.origins = std::move(expanded.origins);
    return impl;
}

/** The line parameter named `name` (any line type's), or UsageError naming the ones there are. */
const LineParameter& lineParameterNamed(const std::string& name) {
    std::string names;
    for (const LineParameter* parameter : lineParameters()) {
        if (parameter->name == name) return *parameter;
        names += (names.empty() ? "" : ", ") + parameter->name;
    }
    throw UsageError("no line parameter '" + detail::excerptForMessage(name) + "' (there are: " + names + ")");
}

/** A look's state, or Error(Usage) for a Look moved from: its state went with the move, and using it crashed. */
template <class ImplPointer>
auto& stateOf(ImplPointer& impl) {
    if (!impl) throw lookMovedFrom();
    return *impl;
}

} // namespace

void refuseOtherFlags(const SourcedArguments& arguments, FlagOwner owner) {
    const std::vector<std::string>& items = arguments.arguments;
    for (std::size_t i = 0; i < items.size(); ++i) {
        const Flag* flag = flagOf(items[i]);
        if (flag == nullptr) return;
        if (!takes(owner, *flag)) {
            const std::string origin = arguments.origins.empty() ? "" : arguments.origins[i];
            throw UsageError((origin.empty() ? "" : origin + ": ") + "'" + items[i] + "' is not a " +
                             (owner == FlagOwner::Look ? "look" : "frame") + " flag (" + whereInLibrary(*flag) + ")");
        }
        if (!flag->valueName.empty()) ++i;
    }
}

std::vector<std::string> Look::Impl::givenFlags() const {
    std::vector<std::string> given;
    for (std::size_t i = 0; i < arguments.size(); ++i) {
        const Flag* flag = flagOf(arguments[i]);
        if (flag == nullptr) continue;
        given.push_back(flag->names.back());
        if (!flag->valueName.empty()) ++i;
    }
    return given;
}

Look::Look() : mImpl(std::make_unique<Impl>()) { mImpl->parsed = parseRenderFlags({}); }
Look::~Look() = default;
Look::Look(const Look& other) : mImpl(std::make_unique<Impl>(stateOf(other.mImpl))) {}
Look& Look::operator=(const Look& other) {
    if (this != &other) mImpl = std::make_unique<Impl>(stateOf(other.mImpl));
    return *this;
}
Look::Look(Look&&) noexcept = default;
Look& Look::operator=(Look&&) noexcept = default;

Look Look::fromArguments(const std::vector<std::string>& arguments) {
    return translated("Look::fromArguments()", [&] {
        // A --style file's settings go first, as on the command line; its messages name the file and line.
        Look look;
        *look.mImpl = lookOf(expandStyleFile(arguments));
        return look;
    });
}

Look Look::fromStyleFile(const std::string& path) {
    return translated("Look::fromStyleFile()", [&] {
        Look look;
        *look.mImpl = lookOf(expandStyleFile({"--style", path}));
        return look;
    });
}

namespace {

/** `message` with each of `texts` it quotes shortened to its start (excerptForMessage()): the library takes strings
 *  of any length, and a value of megabytes made a message of megabytes. */
std::string withLongTextsShortened(std::string message, std::initializer_list<std::string_view> texts) {
    for (const std::string_view text : texts) {
        if (text.size() <= detail::kMessageExcerptChars) continue;
        const std::string excerpt = detail::excerptForMessage(text);
        for (std::size_t at = message.find(text); at != std::string::npos; at = message.find(text, at + excerpt.size()))
            message.replace(at, text.size(), excerpt);
    }
    return message;
}

} // namespace

Look& Look::set(const std::string& flag, const std::string& value) {
    try {
        translated("Look::set()", [&] {
            const Flag* entry = findFlag(flag);
            std::vector<std::string> arguments = {flag};
            // An unknown flag keeps its value, so the parser names the flag as unknown rather than refusing the value.
            if ((entry != nullptr && !entry->valueName.empty()) || (entry == nullptr && !value.empty()))
                arguments.push_back(value);
            else if (!value.empty())
                throw UsageError(flag + ": takes no value, got '" + value + "'");
            SourcedArguments added = expandStyleFile(arguments);
            refuseOtherFlags(added, FlagOwner::Look);
            if (added.origins.empty()) added.origins.assign(added.arguments.size(), "");
            // The flags set again lose their earlier values; the new ones' values are checked as the parse goes.
            Impl next = stateOf(mImpl);
            for (std::size_t i = 0; i < added.arguments.size(); ++i) {
                const Flag* replaced = flagOf(added.arguments[i]);
                if (replaced == nullptr) continue;
                for (std::size_t j = 0; j < next.arguments.size();) {
                    const Flag* existing = flagOf(next.arguments[j]);
                    const std::size_t span = existing != nullptr && !existing->valueName.empty() ? 2 : 1;
                    if (existing == replaced) {
                        next.arguments.erase(next.arguments.begin() + long(j), next.arguments.begin() + long(j + span));
                        next.origins.erase(next.origins.begin() + long(j), next.origins.begin() + long(j + span));
                    } else {
                        j += span;
                    }
                }
                if (!replaced->valueName.empty()) ++i;
            }
            next.arguments.insert(next.arguments.end(), added.arguments.begin(), added.arguments.end());
            next.origins.insert(next.origins.end(), added.origins.begin(), added.origins.end());
            next.parsed = parseRenderFlags(next.arguments, next.origins, FlagChecks::Values);
            stateOf(mImpl) = std::move(next);
        });
    } catch (const Error& error) {
        throw Error(error.kind(), withLongTextsShortened(error.what(), {flag, value}));
    }
    return *this;
}

std::vector<std::string> Look::arguments() const { return stateOf(mImpl).arguments; }

namespace {

/** Sets one flag for a typed setter: its messages name the setter first. */
void setFlag(Look& look, const std::string& setter, const std::string& flag, const std::string& value) {
    try {
        look.set(flag, value);
    } catch (const Error& error) {
        const std::string prefix = "Look::set(): ";
        const std::string message = error.what();
        throw Error(error.kind(),
                    setter + ": " + (message.rfind(prefix, 0) == 0 ? message.substr(prefix.size()) : message));
    }
}

} // namespace

Shading Look::shading() const { return static_cast<Shading>(stateOf(mImpl).parsed.look.shading); }
Look& Look::setShading(Shading shading) {
    setFlag(*this, "Look::setShading()", "--shading", nameOf(shading));
    return *this;
}

double Look::shininess() const { return stateOf(mImpl).parsed.look.shininess; }
Look& Look::setShininess(double exponent) {
    setFlag(*this, "Look::setShininess()", "--shininess", exactText(exponent));
    return *this;
}

std::optional<int> Look::bands() const { return stateOf(mImpl).parsed.look.bands; }
Look& Look::setBands(int bands) {
    setFlag(*this, "Look::setBands()", "--bands", std::to_string(bands));
    return *this;
}

std::string Look::shadeMap() const { return stateOf(mImpl).parsed.look.shadeMapPath; }
Look& Look::setShadeMap(const std::string& path) {
    setFlag(*this, "Look::setShadeMap()", "--shademap", path);
    return *this;
}

std::string Look::outlineWidthMap() const { return stateOf(mImpl).parsed.look.outlineWidthMap.text(); }
Look& Look::setOutlineWidthMap(const std::string& source) {
    setFlag(*this, "Look::setOutlineWidthMap()", "--outline-width-map", source);
    return *this;
}

ViewVector Look::viewVector() const { return static_cast<ViewVector>(stateOf(mImpl).parsed.look.viewVector); }
Look& Look::setViewVector(ViewVector mode) {
    setFlag(*this, "Look::setViewVector()", "--view-vector", nameOf(mode));
    return *this;
}

FaceOrientation Look::faceOrientation() const {
    return static_cast<FaceOrientation>(stateOf(mImpl).parsed.look.faceOrientation);
}
Look& Look::setFaceOrientation(FaceOrientation method) {
    setFlag(*this, "Look::setFaceOrientation()", "--face-orientation", nameOf(method));
    return *this;
}

int Look::frontRule() const { return stateOf(mImpl).parsed.look.frontRule; }
Look& Look::setFrontRule(int rule) {
    setFlag(*this, "Look::setFrontRule()", "--front-rule", std::to_string(rule));
    return *this;
}

std::optional<Vec3> Look::light() const {
    const std::optional<glm::dvec3>& light = stateOf(mImpl).parsed.look.towardLight;
    if (!light) return std::nullopt;
    return Vec3{light->x, light->y, light->z};
}
Look& Look::setLight(const Vec3& towardLight) {
    setFlag(*this, "Look::setLight()", "--light", vectorText(towardLight));
    return *this;
}

std::optional<Color> Look::ambient() const {
    const std::optional<glm::dvec3>& ambient = stateOf(mImpl).parsed.look.ambient;
    if (!ambient) return std::nullopt;
    return Color{ambient->r, ambient->g, ambient->b, 1.0};
}
Look& Look::setAmbient(const Color& linearRgb) {
    if (linearRgb.a != 1.0)
        throw Error(Error::Kind::Usage,
                    "Look::setAmbient(): a light has no alpha: alpha must be 1, got " + exactText(linearRgb.a));
    setFlag(*this, "Look::setAmbient()", "--ambient",
            exactText(linearRgb.r) + "," + exactText(linearRgb.g) + "," + exactText(linearRgb.b));
    return *this;
}

Color Look::paper() const {
    const glm::dvec3& paper = stateOf(mImpl).parsed.look.background;
    return {paper.r, paper.g, paper.b, 1.0};
}
Look& Look::setPaper(const Color& color) {
    if (color.a != 1.0)
        throw Error(Error::Kind::Usage,
                    "Look::setPaper(): the paper is opaque: alpha must be 1, got " + exactText(color.a));
    setFlag(*this, "Look::setPaper()", "--background",
            exactText(color.r) + "," + exactText(color.g) + "," + exactText(color.b));
    return *this;
}

int Look::supersample() const { return stateOf(mImpl).parsed.look.supersample; }
Look& Look::setSupersample(int factor) {
    setFlag(*this, "Look::setSupersample()", "--supersample", std::to_string(factor));
    return *this;
}

int Look::msaa() const { return stateOf(mImpl).parsed.look.msaa; }
Look& Look::setMsaa(int samples) {
    setFlag(*this, "Look::setMsaa()", "--msaa", std::to_string(samples));
    return *this;
}

Precision Look::gbufferPrecision() const { return static_cast<Precision>(stateOf(mImpl).parsed.look.gbufferPrecision); }
Look& Look::setGbufferPrecision(Precision precision) {
    setFlag(*this, "Look::setGbufferPrecision()", "--gbuffer-precision", nameOf(precision));
    return *this;
}

std::vector<LineType> Look::lines() const {
    std::vector<LineType> types;
    for (const std::string& name : stateOf(mImpl).parsed.look.lines) types.push_back(lineTypeNamed(name));
    return types;
}
Look& Look::setLines(const std::vector<LineType>& types) {
    std::string list;
    for (LineType type : types) {
        if (!list.empty()) list += ",";
        list += nameOf(type);
    }
    setFlag(*this, "Look::setLines()", "--lines", list.empty() ? "none" : list);
    return *this;
}

LineStyle Look::lineStyle(LineType type) const {
    const inkgraph::LineStyle style = stateOf(mImpl).parsed.look.styleOf(nameOf(type));
    return {style.widthPixels, {style.color.r, style.color.g, style.color.b, style.color.a}};
}
Look& Look::setLineStyle(LineType type, const LineStyle& style) {
    // Only what changes is given, so a style set whole does not give a flag that the rules would find without effect.
    // Set on a copy, so a refused colour does not leave the width set: all or nothing.
    const LineStyle current = lineStyle(type);
    const std::string name = nameOf(type);
    Look next(*this);
    if (style.width != current.width)
        setFlag(next, "Look::setLineStyle()", "--" + name + "-width", exactText(style.width));
    const Color& color = style.color;
    if (color.r != current.color.r || color.g != current.color.g || color.b != current.color.b ||
        color.a != current.color.a)
        setFlag(next, "Look::setLineStyle()", "--" + name + "-color", colorText(color));
    *this = std::move(next);
    return *this;
}

std::vector<std::string> Look::lineParameterNames(LineType type) {
    const inkgraph::LineType* info = findLineType(nameOf(type));
    std::vector<std::string> names;
    if (info != nullptr)
        for (const LineParameter* parameter : info->parameters) names.push_back(parameter->name);
    return names;
}

double Look::lineParameter(const std::string& name) const {
    return translated("Look::lineParameter()", [&] {
        const LineParameter& parameter = lineParameterNamed(name);
        if (parameter.isChoice()) throw UsageError("'" + name + "' is a choice: read it with lineChoice()");
        const std::optional<double> value = stateOf(mImpl).parsed.look.lineParameters.numberIfSet(parameter);
        if (!value) throw UsageError("'" + name + "' has no default and was not set");
        return *value;
    });
}

std::string Look::lineChoice(const std::string& name) const {
    return translated("Look::lineChoice()", [&] {
        const LineParameter& parameter = lineParameterNamed(name);
        if (!parameter.isChoice()) throw UsageError("'" + name + "' is a number: read it with lineParameter()");
        return stateOf(mImpl).parsed.look.lineParameters.choice(parameter);
    });
}

Look& Look::setLineParameter(const std::string& name, double value) {
    translated("Look::setLineParameter()", [&] {
        if (lineParameterNamed(name).isChoice())
            throw UsageError("'" + name + "' is a choice: set it with setLineChoice()");
    });
    setFlag(*this, "Look::setLineParameter()", "--" + name, exactText(value));
    return *this;
}

Look& Look::setLineChoice(const std::string& name, const std::string& value) {
    translated("Look::setLineChoice()", [&] {
        if (!lineParameterNamed(name).isChoice())
            throw UsageError("'" + name + "' is a number: set it with setLineParameter()");
    });
    setFlag(*this, "Look::setLineChoice()", "--" + name, value);
    return *this;
}

StrokeSettings Look::strokes() const {
    const StrokeStyle& strokes = stateOf(mImpl).parsed.look.strokes;
    return {strokes.minLength,     strokes.weightByDepth, strokes.weightByStrength, strokes.taperEnds,
            strokes.mergeOverlaps, strokes.hiddenDashOn,  strokes.hiddenDashOff};
}
Look& Look::setStrokes(const StrokeSettings& strokes) {
    // As setLineStyle(): only the flags whose value changes are given, on a copy (all or nothing).
    const StrokeSettings current = this->strokes();
    Look next(*this);
    if (strokes.minLength != current.minLength)
        setFlag(next, "Look::setStrokes()", "--min-stroke-length", exactText(strokes.minLength));
    if (strokes.weightByDepth != current.weightByDepth || strokes.weightByStrength != current.weightByStrength ||
        strokes.taperEnds != current.taperEnds) {
        std::string weights;
        if (strokes.weightByDepth) weights += "depth";
        if (strokes.weightByStrength) weights += std::string(weights.empty() ? "" : ",") + "strength";
        if (strokes.taperEnds) weights += std::string(weights.empty() ? "" : ",") + "taper";
        setFlag(next, "Look::setStrokes()", "--line-weight", weights.empty() ? "none" : weights);
    }
    if (strokes.mergeOverlaps != current.mergeOverlaps)
        setFlag(next, "Look::setStrokes()", "--overlapping-lines", strokes.mergeOverlaps ? "merge" : "draw");
    if (strokes.hiddenDashOn != current.hiddenDashOn || strokes.hiddenDashOff != current.hiddenDashOff)
        setFlag(next, "Look::setStrokes()", "--hidden-dash",
                exactText(strokes.hiddenDashOn) + "," + exactText(strokes.hiddenDashOff));
    *this = std::move(next);
    return *this;
}

} // namespace INKGRAPH_ABI_NAMESPACE
} // namespace inkgraph::api
