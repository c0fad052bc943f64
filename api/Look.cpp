#include "api/Internal.h"

#include "flags/FlagTable.h"

#include <algorithm>

namespace inkgraph::api {
namespace {

/** The flags of the Camera section that pose the scene as it loads: SceneOptions, not a Frame's. */
bool posesScene(const Flag& flag) {
    const std::string& name = flag.names.back();
    return name == "--animation" || name == "--time";
}

bool takes(FlagOwner owner, const Flag& flag) {
    if (owner == FlagOwner::Look) return flag.section == HelpSection::Look || flag.section == HelpSection::Lines;
    return flag.section == HelpSection::Camera && !posesScene(flag);
}

/** Where the library takes what `flag` sets, for the refusal of a flag given in the wrong place. */
std::string whereInLibrary(const Flag& flag) {
    const std::string& name = flag.names.back();
    switch (flag.section) {
    case HelpSection::Look:
    case HelpSection::Lines: return "give it to the Look";
    case HelpSection::Camera:
        return posesScene(flag) ? "it poses the scene as it loads: SceneOptions, given to Scene::load()"
                                : "give it in Frame::camera";
    case HelpSection::Output:
        return name == "--size" ? "give Frame::width and height"
                                : "the library returns images: Still::buffer(), Still::write(), Image::write()";
    case HelpSection::Batch: return "render each Scene in a loop";
    case HelpSection::System:
        return name == "--memory-limit" ? "give SceneOptions::memoryLimitBytes to Scene::load()"
                                        : "give it to the Renderer's constructor";
    }
    return "";
}

/** parseRenderFlags() with the Look's own refusals first. */
RenderOptions parseLook(const SourcedArguments& arguments) {
    refuseOtherFlags(arguments, FlagOwner::Look);
    return parseRenderFlags(arguments.arguments, arguments.origins);
}

} // namespace

void refuseOtherFlags(const SourcedArguments& arguments, FlagOwner owner) {
    const std::vector<std::string>& items = arguments.arguments;
    for (std::size_t i = 0; i < items.size(); ++i) {
        const Flag* flag = findFlag(items[i]);
        if (flag == nullptr || !flag->apply) return;
        if (!takes(owner, *flag)) {
            const std::string origin = arguments.origins.empty() ? "" : arguments.origins[i];
            throw UsageError((origin.empty() ? "" : origin + ": ") + "'" + items[i] + "' is not a " +
                             (owner == FlagOwner::Look ? "look" : "camera") + " flag (" + whereInLibrary(*flag) + ")");
        }
        if (!flag->valueName.empty()) ++i;
    }
}

Look::Look() = default;

Look Look::fromArguments(const std::vector<std::string>& arguments) {
    return translated("Look::fromArguments()", [&] {
        // A --style file's settings go first, as on the command line; its messages name the file and line.
        const SourcedArguments expanded = expandStyleFile(arguments);
        parseLook(expanded);
        Look look;
        look.mArguments = expanded.arguments;
        return look;
    });
}

Look Look::fromStyleFile(const std::string& path) {
    return translated("Look::fromStyleFile()", [&] {
        const SourcedArguments expanded = expandStyleFile({"--style", path});
        parseLook(expanded);
        Look look;
        look.mArguments = expanded.arguments;
        return look;
    });
}

Look& Look::set(const std::string& flag, const std::string& value) {
    translated("Look::set()", [&] {
        const Flag* entry = findFlag(flag);
        std::vector<std::string> arguments = {flag};
        // An unknown flag keeps its value, so the parser names the flag as unknown rather than refusing the value.
        if ((entry != nullptr && !entry->valueName.empty()) || (entry == nullptr && !value.empty()))
            arguments.push_back(value);
        else if (!value.empty())
            throw UsageError(flag + ": takes no value, got '" + value + "'");
        const SourcedArguments expanded = expandStyleFile(arguments);
        refuseOtherFlags(expanded, FlagOwner::Look);
        // The flag's own checks; the rules between flags wait for the whole look (render()).
        parseRenderFlags(expanded.arguments, expanded.origins, FlagChecks::Values);
        mArguments.insert(mArguments.end(), expanded.arguments.begin(), expanded.arguments.end());
    });
    return *this;
}

} // namespace inkgraph::api
