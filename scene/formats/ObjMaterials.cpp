/** @file Wavefront material libraries (.mtl), for readObj(): per `newmtl`, the diffuse colour (Kd) and its map
 *  (map_Kd with its options), the dissolve (d, or Tr = 1 - d), the emission (Ke) and its map (map_Ke) and a cut-out
 *  map_d. Everything else
 *  (Ka, Ks, Ns, illum, bump, reflection) shapes a photoreal look that a toon render does not use, so it is skipped.
 *  Bad lines are warnings, not refusals: a library that travels with a model is often half-broken, and the model is
 *  still worth drawing. */

#include "scene/formats/FormatReaders.h"
#include "scene/formats/ShaderValues.h"
#include "scene/formats/TextTokens.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <system_error>

namespace inkgraph::detail {

namespace {

/** MTL keywords are lower- or mixed-case depending on the exporter ("map_Kd", "map_kd"); compared ignoring case. */
bool sameKeyword(std::string_view a, std::string_view b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
           });
}

/** File text in quotes, shortened (excerptForMessage()). */
std::string quotedExcerpt(std::string_view text) {
    std::string out = "'";
    out += excerptForMessage(text);
    out += '\'';
    return out;
}

/** A finite number filling the whole token (an explicit '+' allowed), else nothing. */
std::optional<double> numberOf(std::string_view token) {
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    double value = 0.0;
    const auto [next, error] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (token.empty() || error != std::errc() || next != token.data() + token.size() || !std::isfinite(value)) {
        return std::nullopt;
    }
    return value;
}

/** A `map_*` statement: its options and the file it names. */
struct MapStatement {
    std::string file; ///< as written, spaces kept
    TextureSampler sampler;
    glm::mat3 transform{1.0f};
};

/** Reads `[options] file`; on a problem returns nothing and says why in `problem`. The options (MTL spec, "Texture
 *  map statements") are skipped except -clamp (the sampler's wraps) and -s/-o (the texture transform). */
std::optional<MapStatement> parseMapStatement(std::string_view rest, std::string& problem) {
    const std::vector<std::string_view> tokens = tokensOf(rest);
    MapStatement map;
    glm::dvec2 scale{1.0}, offset{0.0};
    std::size_t at = 0;
    while (at < tokens.size() && tokens[at].size() > 1 && tokens[at].front() == '-') {
        const std::string_view option = tokens[at++];
        std::size_t fixedArguments = 0;
        if (sameKeyword(option, "-s") || sameKeyword(option, "-o") || sameKeyword(option, "-t")) {
            // One to three numbers (u [v [w]]); a texture has no w, and -t (turbulence) is not drawn.
            glm::dvec3 values = sameKeyword(option, "-s") ? glm::dvec3(1.0) : glm::dvec3(0.0);
            std::size_t count = 0;
            while (count < 3 && at < tokens.size() && numberOf(tokens[at]))
                values[int(count++)] = *numberOf(tokens[at++]);
            if (count == 0) {
                problem = "option '" + excerptForMessage(option) + "' without a number";
                return std::nullopt;
            }
            if (sameKeyword(option, "-s")) scale = glm::dvec2(values);
            if (sameKeyword(option, "-o")) offset = glm::dvec2(values);
            continue;
        }
        if (sameKeyword(option, "-clamp")) {
            if (at == tokens.size() || !(sameKeyword(tokens[at], "on") || sameKeyword(tokens[at], "off"))) {
                problem = "option '-clamp' without 'on' or 'off'";
                return std::nullopt;
            }
            const TextureWrap wrap = sameKeyword(tokens[at++], "on") ? TextureWrap::ClampToEdge : TextureWrap::Repeat;
            map.sampler.wrapS = map.sampler.wrapT = wrap;
            continue;
        }
        for (std::string_view known : {"-blendu", "-blendv", "-cc", "-bm", "-boost", "-texres", "-imfchan", "-type"}) {
            if (sameKeyword(option, known)) fixedArguments = 1;
        }
        if (sameKeyword(option, "-mm")) fixedArguments = 2;
        if (fixedArguments == 0) {
            problem = "unknown option '" + excerptForMessage(option) + "'";
            return std::nullopt;
        }
        if (tokens.size() - at < fixedArguments) {
            problem = "option '" + excerptForMessage(option) + "' without its value";
            return std::nullopt;
        }
        at += fixedArguments;
    }
    if (at == tokens.size()) {
        problem = "names no file";
        return std::nullopt;
    }
    // The rest of the line is the name: exporters write names with spaces unquoted.
    const std::string_view line = trimmed(rest);
    map.file.assign(tokens[at].data(), std::size_t(line.data() + line.size() - tokens[at].data()));
    // OBJ looks up (u s + o, v s + o) with v pointing up; in the glTF convention the mesh stores (u, 1 - v), so the
    // same lookup is v' = s v + (1 - s - o): a scale and a translation in KHR_texture_transform's matrix.
    glm::dmat3 transform(1.0);
    transform[0][0] = scale.x;
    transform[1][1] = scale.y;
    transform[2][0] = offset.x;
    transform[2][1] = 1.0 - scale.y - offset.y;
    std::string transformProblem;
    const std::optional<glm::mat3> forShaders = shaderTextureTransform(transform, map.sampler, transformProblem);
    if (!forShaders) {
        problem = "options -s/-o: " + transformProblem;
        return std::nullopt;
    }
    map.transform = *forShaders;
    return map;
}

/** `map_Kd skin.png # diffuse`: a comment after the name, as some exporters write it. A name may hold " #" itself
 *  (`hash #1.png`), so it is kept whole when a file of exactly that name lies beside the library; else the name ends
 *  before the first of at most four " #" whose part before names a file (fileBeside()), or before the first " #"
 *  when none does (the file is then missing under its own name). Only the exact name counts for the whole:
 *  fileBeside()'s last-name fallback found `green.png` for `red.png # was textures/green.png`. */
std::string withoutTrailingComment(const std::filesystem::path& folder, const std::string& name,
                                   const std::filesystem::path& modelFolder) {
    constexpr int kCommentStartsTried = 4; // each try looks at the disk: a line of " #"s must not take minutes
    std::error_code error;
    if (name.find('#') == std::string::npos || std::filesystem::is_regular_file(folder / name, error)) return name;
    std::optional<std::string> beforeFirstComment;
    int tried = 0;
    for (std::size_t hash = name.find('#'); hash != std::string::npos && tried < kCommentStartsTried;
         hash = name.find('#', hash + 1)) {
        if (hash == 0 || !isBlank(name[hash - 1])) continue;
        ++tried;
        const std::string before(trimmed(std::string_view(name).substr(0, hash)));
        if (before.empty()) break;
        if (!beforeFirstComment) beforeFirstComment = before;
        if (std::filesystem::is_regular_file(fileBeside(folder, before, modelFolder), error)) return before;
    }
    return beforeFirstComment.value_or(name);
}

/** A Ke this close to white (in every channel, after clamping to [0, 1]) is white: 1 - 1/512, under half an 8-bit
 *  step below 1. */
constexpr float kWhiteEmission = 1.0f - 1.0f / 512.0f;

/** What one `newmtl` block said, turned into a Material when the block ends. At namespace scope: clang (14) cannot
 *  default-construct a nested class with member initializers inside its enclosing class (std::optional::emplace()). */
struct PendingMaterial {
    Material material;
    std::size_t line = 0;
    std::optional<double> dissolve;     ///< d
    std::optional<double> transparency; ///< Tr
    bool diffuseColourGiven = false;    ///< a Kd line was read
    bool emissionGiven = false;         ///< a Ke line was read
    std::size_t emissionLine = 0;
    std::optional<MapStatement> diffuseMap;
    std::size_t diffuseMapLine = 0;
    std::optional<MapStatement> emissiveMap;
    std::size_t emissiveMapLine = 0;
    std::optional<MapStatement> dissolveMap;
    std::size_t dissolveMapLine = 0;
};

class MtlReader {
public:
    MtlReader(const std::string& path, const std::filesystem::path& modelFolder, ObjMaterials& materials,
              std::vector<Warning>& warnings)
        : mPath(path), mFolder(std::filesystem::path(path).parent_path()), mModelFolder(modelFolder),
          mMaterials(materials), mWarnings(warnings) {}

    void read(std::string_view content) {
        content = withoutByteOrderMark(content);
        for (std::size_t start = 0; start < content.size();) {
            std::size_t end = content.find('\n', start);
            if (end == std::string_view::npos) end = content.size();
            ++mLine;
            readLine(trimmed(content.substr(start, end - start)));
            start = end + 1;
        }
        finishMaterial();
    }

private:
    /** A statement of the library that cannot be read: the warning names the library's file. */
    void warn(const std::string& problem, WarningKind kind = WarningKind::MaterialStatementIgnored) {
        mWarnings.push_back(
            makeWarning(kind, "material library '" + mPath + "' line " + std::to_string(mLine) + ": " + problem, mPath,
                        mCurrent ? mCurrent->material.name : std::string()));
    }

    void readLine(std::string_view line) {
        if (line.empty() || line.front() == '#') return;
        const std::size_t keywordEnd =
            std::min(line.size(), std::size_t(std::find_if(line.begin(), line.end(), isBlank) - line.begin()));
        const std::string_view keyword = line.substr(0, keywordEnd);
        const std::string_view rest = trimmed(line.substr(keywordEnd));
        if (sameKeyword(keyword, "newmtl")) {
            finishMaterial();
            if (rest.empty()) {
                warn("'newmtl' without a name; its statements are ignored");
                return;
            }
            mCurrent.emplace();
            mCurrent->material.name = std::string(rest);
            mCurrent->line = mLine;
            return;
        }
        const bool used = sameKeyword(keyword, "Kd") || sameKeyword(keyword, "Ke") || sameKeyword(keyword, "d") ||
                          sameKeyword(keyword, "Tr") || sameKeyword(keyword, "map_Kd") ||
                          sameKeyword(keyword, "map_Ke") || sameKeyword(keyword, "map_d");
        if (!used) return; // Ka, Ks, Ns, illum, bump, ...: not part of a toon render's surface
        if (!mCurrent) {
            warn(quotedExcerpt(keyword) + " before any 'newmtl'; ignored");
            return;
        }
        const bool mapStatement = keyword.size() > 4 && sameKeyword(keyword.substr(0, 4), "map_");
        // A comment after the values (`Kd 0.8 0.8 0.8 # grey`, as some exporters write); numbers hold no '#'. A map's
        // file name may, so a map's comment is told from its name when the file is looked up (mapPath()).
        const std::string_view values = mapStatement ? rest : trimmed(rest.substr(0, rest.find('#')));
        if (sameKeyword(keyword, "Kd")) {
            if (const auto colour = readColour(keyword, values)) {
                mCurrent->material.baseColorFactor = glm::vec4(*colour, mCurrent->material.baseColorFactor.a);
                mCurrent->diffuseColourGiven = true;
            }
        } else if (sameKeyword(keyword, "Ke")) {
            if (const auto colour = readColour(keyword, values)) {
                mCurrent->material.emissiveFactor = *colour;
                mCurrent->emissionGiven = true;
                mCurrent->emissionLine = mLine;
            }
        } else if (sameKeyword(keyword, "d") || sameKeyword(keyword, "Tr")) {
            std::vector<std::string_view> tokens = tokensOf(values);
            if (!tokens.empty() && sameKeyword(tokens.front(), "-halo")) tokens.erase(tokens.begin()); // not drawn
            const std::optional<double> value = tokens.size() == 1 ? numberOf(tokens.front()) : std::nullopt;
            if (!value) {
                warn("cannot read '" + excerptForMessage(keyword) + "' value '" + excerptForMessage(values) +
                     "'; ignored");
                return;
            }
            std::vector<Warning> problems;
            (sameKeyword(keyword, "d") ? mCurrent->dissolve : mCurrent->transparency) =
                shaderValue(*value, kUnitRange, quotedExcerpt(keyword), problems);
            for (const Warning& problem : problems) warn(problem.message, WarningKind::ValueOutOfRange);
        } else {
            std::string problem;
            std::optional<MapStatement> map = parseMapStatement(rest, problem);
            if (!map) {
                warn(quotedExcerpt(keyword) + " " + problem + "; ignored");
                return;
            }
            if (sameKeyword(keyword, "map_Kd")) {
                mCurrent->diffuseMap = std::move(map);
                mCurrent->diffuseMapLine = mLine;
            } else if (sameKeyword(keyword, "map_Ke")) {
                mCurrent->emissiveMap = std::move(map);
                mCurrent->emissiveMapLine = mLine;
            } else {
                mCurrent->dissolveMap = std::move(map);
                mCurrent->dissolveMapLine = mLine;
            }
        }
    }

    /** `Kd r g b` or `Kd r` (grey). MTL colours carry no colour space; like most renderers, they are taken as
     *  linear as written, clamped to [0, 1] (the range of glTF's factors) with a value-out-of-range warning, as d
     *  and glTF's factors are (Kd -1 -1 -1 and Kd 1e300 0 0 were clamped without a word). */
    std::optional<glm::vec3> readColour(std::string_view keyword, std::string_view rest) {
        const std::vector<std::string_view> tokens = tokensOf(rest);
        if (!tokens.empty() && (sameKeyword(tokens.front(), "spectral") || sameKeyword(tokens.front(), "xyz"))) {
            warn(quotedExcerpt(std::string(keyword) + " " + std::string(tokens.front())) +
                 " colours are not supported; ignored");
            return std::nullopt;
        }
        glm::dvec3 colour(0.0);
        bool readable = tokens.size() == 1 || tokens.size() == 3;
        std::vector<double> values;
        for (std::size_t i = 0; readable && i < tokens.size(); ++i) {
            const std::optional<double> value = numberOf(tokens[i]);
            readable = value.has_value();
            if (readable) values.push_back(*value);
        }
        if (!readable) {
            warn("cannot read '" + excerptForMessage(keyword) + "' colour '" + excerptForMessage(rest) +
                 "' (1 or 3 numbers); ignored");
            return std::nullopt;
        }
        std::vector<Warning> problems;
        for (std::size_t i = 0; i < values.size(); ++i)
            colour[int(i)] = shaderValue(values[i], kUnitRange, quotedExcerpt(keyword), problems);
        for (const Warning& problem : problems) warn(problem.message, WarningKind::ValueOutOfRange);
        if (tokens.size() == 1) colour = glm::dvec3(colour.x);
        return glm::vec3(colour);
    }

    /** The image of a map, appended to the materials' images once per file; -1 when the file is missing (a
     *  warning: the material is drawn without it). Every file named is recorded, found or not. */
    int imageOf(const MapStatement& map, std::string_view keyword, std::size_t line) {
        const std::string path = fileBeside(mFolder, map.file, mModelFolder);
        if (std::ranges::find(mMaterials.namedFiles, path) == mMaterials.namedFiles.end()) {
            mMaterials.namedFiles.push_back(path);
        }
        const auto known = std::ranges::find(mMaterials.images, path, &SceneImage::path);
        if (known != mMaterials.images.end()) return int(known - mMaterials.images.begin());
        std::error_code error;
        // A FIFO or device would block when decoded: only regular files are images.
        if (!std::filesystem::is_regular_file(path, error)) {
            const std::string why = whyFileIsMissing(path).value_or("is missing or not a regular file");
            mWarnings.push_back(makeWarning(WarningKind::TextureMissing,
                                            "material library '" + mPath + "' line " + std::to_string(line) + ": " +
                                                std::string(keyword) + " '" + excerptForMessage(map.file) + "': '" +
                                                excerptForMessage(path) + "' " + why + "; material '" +
                                                excerptForMessage(mCurrent->material.name) + "' is drawn without it",
                                            path, mCurrent->material.name));
            if (std::ranges::find(mMaterials.missingImages, path, &SceneImage::path) == mMaterials.missingImages.end())
                mMaterials.missingImages.push_back(SceneImage{map.file, path, {}, nullptr});
            return -1;
        }
        SceneImage image;
        image.name = map.file;
        image.path = path;
        mMaterials.images.push_back(std::move(image));
        return int(mMaterials.images.size() - 1);
    }

    void finishMaterial() {
        if (!mCurrent) return;
        PendingMaterial& pending = *mCurrent;
        Material& material = pending.material;
        // d is the standard; Tr (= 1 - d) is what some exporters write instead. When both appear, d decides.
        const double alpha = pending.dissolve       ? *pending.dissolve
                             : pending.transparency ? 1.0 - *pending.transparency
                                                    : 1.0;
        material.baseColorFactor.a = float(alpha);
        if (alpha < 1.0) material.alphaMode = AlphaMode::Blend;
        if (alpha < kLeastVisibleAlpha) {
            // Said, not changed: exporters disagree on Tr (some write it as opacity), and d 0 may be meant. Under
            // half a level of 8-bit colour the faces change no pixel (whyMaterialDrawsNothing()).
            const std::string written = pending.dissolve ? "d " + formatNumber(alpha)
                                                         : "Tr " + formatNumber(*pending.transparency) +
                                                               ", read as d " + formatNumber(alpha) +
                                                               "; some exporters write Tr as opacity, 'd 1' draws it";
            mWarnings.push_back(makeWarning(WarningKind::MaterialInvisible,
                                            "material library '" + mPath + "' line " + std::to_string(pending.line) +
                                                ": material '" + excerptForMessage(material.name) +
                                                "' is fully transparent (" + written + "): its faces are not drawn",
                                            mPath, material.name));
        }
        for (std::optional<MapStatement>* map : {&pending.diffuseMap, &pending.emissiveMap, &pending.dissolveMap})
            if (*map) (*map)->file = withoutTrailingComment(mFolder, (*map)->file, mModelFolder);
        const glm::vec4 colourAsWritten = material.baseColorFactor;
        if (pending.diffuseMap && (!pending.diffuseColourGiven || glm::vec3(colourAsWritten) == glm::vec3(0.0f))) {
            // No Kd to multiply the image by: drawn as the image is, not darkened by the 0.8 grey of a bare material.
            // `Kd 0 0 0` beside a map_Kd would draw it black by the MTL rule (Kd times the map); exporters write it
            // for "the map decides", and Blender's importer lets the map replace it, so the map is drawn as it is.
            material.baseColorFactor = glm::vec4(glm::vec3(1.0f), material.baseColorFactor.a);
            material.baseColorFactorWithoutTexture = colourAsWritten; // drawn if the map cannot be (SceneMaterials)
        }
        if (pending.diffuseMap) {
            material.baseColorTexture.image = imageOf(*pending.diffuseMap, "map_Kd", pending.diffuseMapLine);
            material.baseColorTexture.sampler = pending.diffuseMap->sampler;
            material.baseColorTexture.transform = pending.diffuseMap->transform;
            // A missing map decides nothing: the Kd as written (or the bare grey) is drawn, not white.
            if (!material.baseColorTexture.present()) {
                material.baseColorFactor = colourAsWritten;
                material.baseColorFactorWithoutTexture.reset();
            }
        }
        const bool whiteEmission = glm::all(glm::greaterThanEqual(material.emissiveFactor, glm::vec3(kWhiteEmission)));
        if (pending.emissiveMap) {
            // The map times Ke (the MTL rule); without a Ke it is drawn as it is, as a map_Kd without Kd. A missing
            // map takes the emission with it: Ke (often 1 1 1 beside a map) alone would draw the material white.
            if (!pending.emissionGiven) material.emissiveFactor = glm::vec3(1.0f);
            material.emissiveTexture.image = imageOf(*pending.emissiveMap, "map_Ke", pending.emissiveMapLine);
            material.emissiveTexture.sampler = pending.emissiveMap->sampler;
            material.emissiveTexture.transform = pending.emissiveMap->transform;
            if (!material.emissiveTexture.present()) material.emissiveFactor = glm::vec3(0.0f);
        } else if (whiteEmission) {
            // A white emission hides every colour and map under it. Tools that keep an emission colour and its
            // strength apart write `Ke 1 1 1` for a white colour at strength 0 (Blender's Principled BSDF since 4.0,
            // scans exported as "Kd 0, Ke 1, map_Kd"), and Blender's importer sets the colour alone, at strength 0
            // unless a map_Ke is given: so it is read as no emission, and said. A Ke below white is drawn.
            material.emissiveFactor = glm::vec3(0.0f);
            mWarnings.push_back(makeWarning(
                WarningKind::WhiteEmissionIgnored,
                "material library '" + mPath + "' line " + std::to_string(pending.emissionLine) + ": material '" +
                    excerptForMessage(material.name) +
                    "': a white 'Ke' without a map_Ke is read as no emission, as Blender's importer reads it "
                    "(exporters write a white emission colour of strength 0 so); the material is drawn with its " +
                    (pending.diffuseMap ? "map_Kd" : "Kd") + ", not white",
                mPath, material.name));
        }
        if (pending.dissolveMap) {
            // A cut-out is drawn from the base colour texture's alpha: map_d naming the map_Kd image (a PNG with an
            // alpha channel, as exporters write it) is that. A separate mask image has no place in the material.
            const std::string maskPath = fileBeside(mFolder, pending.dissolveMap->file, mModelFolder);
            if (std::ranges::find(mMaterials.namedFiles, maskPath) == mMaterials.namedFiles.end()) {
                mMaterials.namedFiles.push_back(maskPath);
            }
            const bool sameImage =
                material.textured() && mMaterials.images[std::size_t(material.baseColorTexture.image)].path == maskPath;
            if (sameImage) {
                if (material.alphaMode == AlphaMode::Opaque) {
                    material.alphaMode = AlphaMode::Mask;
                    material.alphaCutoff = 0.5f;
                }
            } else {
                mWarnings.push_back(makeWarning(WarningKind::MaskIgnored,
                                                "material library '" + mPath + "' line " +
                                                    std::to_string(pending.dissolveMapLine) + ": map_d '" +
                                                    excerptForMessage(pending.dissolveMap->file) +
                                                    "' is not the material's map_Kd image; only the map_Kd image's "
                                                    "own alpha can cut out, so it is ignored",
                                                mPath, material.name));
            }
        }
        if (!mMaterials.byName.try_emplace(material.name, material).second) {
            mWarnings.push_back(makeWarning(WarningKind::MaterialRedefined,
                                            "material library '" + mPath + "' line " + std::to_string(pending.line) +
                                                ": material '" + excerptForMessage(material.name) +
                                                "' is defined again; the first definition is kept",
                                            mPath, material.name));
        }
        mCurrent.reset();
    }

    const std::string& mPath;
    std::filesystem::path mFolder;
    std::filesystem::path mModelFolder; ///< the OBJ's, where a texture is looked for too
    ObjMaterials& mMaterials;
    std::vector<Warning>& mWarnings;
    std::size_t mLine = 0;
    std::optional<PendingMaterial> mCurrent;
};

/** Entries of one folder a case-blind lookup reads at most, and of all the folders it remembers. */
constexpr std::size_t kMaxEntriesPerFolder = 100000;
constexpr std::size_t kMaxEntriesRemembered = 200000;

std::string asciiLower(std::string text) {
    for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

/** The entries of `folder` whose names differ from `wanted` in ASCII case alone (or not at all), sorted; `error` when
 *  the folder cannot be read. A folder's names are read once and remembered while its modification time stays (a
 *  model naming a thousand textures by the wrong case, in a folder of thousands, would read it a thousand times), for
 *  every thread of a batch. */
struct CaseBlindEntries {
    std::vector<std::string> names;
    std::error_code error;
};
CaseBlindEntries entriesIgnoringCase(const std::filesystem::path& folder, const std::string& wanted) {
    struct Listing {
        std::filesystem::file_time_type modified;
        std::multimap<std::string, std::string> byLowerName;
    };
    static std::mutex mutex;
    static std::map<std::string, Listing> listings;
    static std::size_t entriesRemembered = 0;
    const std::filesystem::path directory = folder.empty() ? std::filesystem::path(".") : folder;
    CaseBlindEntries found;
    std::error_code& error = found.error;
    const std::filesystem::file_time_type modified = std::filesystem::last_write_time(directory, error);
    if (error) return found;
    const std::lock_guard lock(mutex);
    auto listing = listings.find(directory.string());
    if (listing == listings.end() || listing->second.modified != modified) {
        Listing read{modified, {}};
        std::size_t entries = 0;
        for (std::filesystem::directory_iterator entry(directory, error), end;
             !error && entry != end && entries < kMaxEntriesPerFolder; entry.increment(error), ++entries) {
            const std::string name = entry->path().filename().string();
            read.byLowerName.emplace(asciiLower(name), name);
        }
        if (error) return found;
        if (listing != listings.end()) {
            entriesRemembered -= listing->second.byLowerName.size();
            listings.erase(listing);
        }
        if (entriesRemembered + read.byLowerName.size() > kMaxEntriesRemembered) {
            listings.clear();
            entriesRemembered = 0;
        }
        entriesRemembered += read.byLowerName.size();
        listing = listings.emplace(directory.string(), std::move(read)).first;
    }
    const auto [first, last] = listing->second.byLowerName.equal_range(asciiLower(wanted));
    for (auto entry = first; entry != last; ++entry) found.names.push_back(entry->second);
    std::ranges::sort(found.names);
    return found;
}

/** `relative` below `folder` with each name that does not exist as written matched to the one entry of its folder
 *  that differs from it in ASCII case alone, as Windows file systems find "Textures/Skin.PNG" for textures/skin.png;
 *  nothing when a name matches no entry, or several ("skin.png" and "SKIN.png" both: whyFileIsMissing() says so). */
std::optional<std::string> caseBlindPath(const std::filesystem::path& folder, const std::filesystem::path& relative) {
    std::filesystem::path found = folder;
    for (const std::filesystem::path& part : relative) {
        std::error_code error;
        if (part == "." || part == ".." || std::filesystem::exists(found / part, error)) {
            found /= part;
            continue;
        }
        const CaseBlindEntries match = entriesIgnoringCase(found, part.string());
        if (match.names.size() != 1) return std::nullopt;
        found /= match.names.front();
    }
    return found.string();
}

} // namespace

std::string fileBeside(const std::filesystem::path& folder, const std::string& name,
                       const std::optional<std::filesystem::path>& modelFolder) {
    const auto resolve = [&](const std::string& written) {
        const std::filesystem::path named{written};
        return (named.is_absolute() ? named : folder / named).string();
    };
    const auto exists = [](const std::string& path) {
        std::error_code error;
        return std::filesystem::exists(path, error);
    };
    if (name.find('\0') != std::string::npos) {
        // The system would read the name up to its NUL, another file: kept whole, it is missing and said so.
        std::string shown = name;
        for (std::size_t at = shown.find('\0'); at != std::string::npos; at = shown.find('\0', at))
            shown.replace(at, 1, "\\0");
        return resolve(shown);
    }
    const std::string asWritten = resolve(name);
    if (exists(asWritten)) return asWritten;
    std::string slashed = name;
    std::replace(slashed.begin(), slashed.end(), '\\', '/');
    if (slashed.size() >= 2 && slashed.front() == '"' && slashed.back() == '"')
        slashed = slashed.substr(1, slashed.size() - 2);
    // "\\server\share\skin.png" names another machine's folder, not "//server/share" here.
    const bool otherMachine = name.rfind("\\\\", 0) == 0;
    if (slashed != name && !otherMachine && exists(resolve(slashed))) return resolve(slashed);
    // A path into the exporting machine's folders ("C:\Users\me\tex\skin.png", "/home/artist/skin.png"), or into a
    // folder the model was not shipped with: models travel with their textures beside them (beside the library, or
    // beside the model when the library lies in a folder of its own).
    const std::filesystem::path slashedPath{slashed};
    const bool relative = !slashed.empty() && !slashedPath.is_absolute();
    const std::size_t slash = slashed.rfind('/');
    const std::string lastName = slash == std::string::npos ? slashed : slashed.substr(slash + 1);
    std::vector<std::filesystem::path> folders{folder};
    if (modelFolder && modelFolder->lexically_normal() != folder.lexically_normal()) folders.push_back(*modelFolder);
    // Beside the model by its last name alone: the library's relative path ("../tex/skin.png") leads from the
    // library's folder, not from the model's.
    for (const std::filesystem::path& besideFolder : folders) {
        if (!lastName.empty() && (slash != std::string::npos || besideFolder != folder) &&
            exists((besideFolder / lastName).string()))
            return (besideFolder / lastName).string();
    }
    // A name written on Windows, whose file systems ignore case ("Skin.PNG" for skin.png): the file that differs in
    // case alone, where the path leads or beside the library or the model.
    if (relative && !otherMachine) {
        if (const auto found = caseBlindPath(folder, slashedPath)) return *found;
    }
    for (const std::filesystem::path& besideFolder : folders) {
        if (!lastName.empty()) {
            if (const auto found = caseBlindPath(besideFolder, lastName)) return *found;
        }
    }
    return slashed != name && name.find('\\') != std::string::npos ? resolve(slashed) : asWritten;
}

std::optional<std::string> whyFileIsMissing(const std::string& path) {
    // Walked from the top, so the folder named is the first that stops the lookup: the one that cannot be read, or
    // the one whose names differ from the path's in case alone.
    const std::filesystem::path whole{path};
    std::filesystem::path folder = whole.root_path();
    for (const std::filesystem::path& part : whole.relative_path()) {
        const std::filesystem::path next = folder / part;
        std::error_code error;
        const std::filesystem::file_status status = std::filesystem::status(next, error);
        const std::string shownFolder = "'" + excerptForMessage(folder.empty() ? "." : folder.string()) + "'";
        if (error == std::errc::permission_denied || error == std::errc::operation_not_permitted)
            return "cannot be looked for: the folder " + shownFolder + " cannot be read (" + error.message() + ")";
        if (error && error != std::errc::no_such_file_or_directory) return std::nullopt; // a file for a folder, ...
        if (std::filesystem::exists(status)) {
            folder = next;
            continue;
        }
        if (part == "." || part == "..") return std::nullopt;
        const CaseBlindEntries entries = entriesIgnoringCase(folder, part.string());
        if (entries.error)
            return "cannot be looked for: the folder " + shownFolder + " cannot be read (" + entries.error.message() +
                   ")";
        if (entries.names.size() < 2) return std::nullopt;
        // Named in full up to four ("tex.png", "Tex.PNG", ...: a name has few case variants in one folder).
        constexpr std::size_t kNamed = 4;
        std::string names;
        const std::size_t shown = std::min(entries.names.size(), kNamed);
        for (std::size_t i = 0; i < shown; ++i) {
            if (i > 0) names += i + 1 == shown && shown == entries.names.size() ? " and " : ", ";
            names += "'" + excerptForMessage(entries.names[i]) + "'";
        }
        if (shown < entries.names.size()) names += " and " + std::to_string(entries.names.size() - shown) + " more";
        return "cannot be found: the folder " + shownFolder + " holds " + names +
               ", which differ from its name in case alone: rename the one meant to '" +
               excerptForMessage(part.string()) + "'";
    }
    return std::nullopt;
}

void readMtl(const std::string& path, std::string_view content, ObjMaterials& materials, std::vector<Warning>& warnings,
             const std::filesystem::path& modelFolder) {
    MtlReader(path, modelFolder, materials, warnings).read(content);
}

std::vector<std::string> mtlReferencedFiles(const std::string& path, std::string_view content,
                                            const std::filesystem::path& modelFolder) {
    const std::filesystem::path folder = std::filesystem::path(path).parent_path();
    std::vector<std::string> files;
    content = withoutByteOrderMark(content);
    for (std::size_t start = 0; start < content.size();) {
        std::size_t end = content.find('\n', start);
        if (end == std::string_view::npos) end = content.size();
        const std::string_view line = trimmed(content.substr(start, end - start));
        start = end + 1;
        const std::vector<std::string_view> tokens = tokensOf(line);
        if (tokens.empty() || !(sameKeyword(tokens.front(), "map_Kd") || sameKeyword(tokens.front(), "map_Ke") ||
                                sameKeyword(tokens.front(), "map_d"))) {
            continue;
        }
        std::string problem;
        if (const auto map = parseMapStatement(line.substr(tokens.front().size()), problem)) {
            const std::string file =
                fileBeside(folder, withoutTrailingComment(folder, map->file, modelFolder), modelFolder);
            if (std::ranges::find(files, file) == files.end()) files.push_back(file);
        }
    }
    return files;
}

} // namespace inkgraph::detail
