#pragma once
/** @file A glTF file and the files it names, around tinygltf's parse: the checks of the JSON before tinygltf sees it
 *  (nesting depth; the `indices` of Draco primitives dropped), the external URIs a SAX pass collects, tinygltf's file
 *  callbacks (buffers only beside the model, regular files only, charged to the budget; images answered with a
 *  placeholder and never read at load time), its image callback (data: URIs kept encoded), the file's images in its
 *  order, shade-map paths, and the files a model names without loading it (referencedFiles()). Internal to the glTF
 *  reader. */

#include "scene/formats/FormatReaders.h"

#include <tiny_gltf.h>

#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace inkgraph::detail {

/** The JSON text of a .gltf file or of a GLB's JSON chunk (empty when the GLB is too short to have one). */
std::string_view jsonOf(std::string_view content, bool binary);

/** What tinygltf is given in place of a file it cannot take as written. */
struct TinygltfInput {
    /** The file with "indices" removed from every KHR_draco_mesh_compression primitive (tinygltf built without Draco
     *  refuses an indices accessor without a buffer view), EXT_meshopt_compression's placeholder buffers stubbed
     *  (stubMeshoptPlaceholders()) and integers written as whole numbers (3.0) written as integers, which tinygltf
     *  takes for absent; nothing when none applies. */
    std::optional<std::string> rewritten;
    std::vector<std::size_t> meshoptPlaceholders; ///< the buffers stubbed
    std::vector<Warning> warnings;                ///< what judgeValueShapes() said of the file
};

/** The file as tinygltf can take it: TinygltfInput. A place where glTF wants an integer holding something else (3.5,
 *  "3") is refused naming it, outside extensions and extras; so are the shapes judgeGlbHeader() and
 *  judgeValueShapes() refuse, whose warnings come with the input. */
TinygltfInput forTinygltf(const std::string& path, std::string_view content, bool binary);

/** Refuses JSON nested deeper than tinygltf's recursive parser can take, before tinygltf sees the file. */
void rejectDeepJson(const std::string& path, std::string_view content, bool binary);

/** The external (non-data:) URIs of the top-level "buffers" and "images" arrays, as written. */
struct ExternalUris {
    std::vector<std::string> bufferUris;
    std::vector<std::string> imageUris;
    /** data: URIs of images whose media type tinygltf does not decode (image/webp): it takes them for file names, so
     *  the file callbacks answer them as images (a placeholder) and sceneImages() decodes them. */
    std::vector<std::string> imageDataUris;
};

/** Why tinygltf could not decode a buffer's data: URI ("Failed to decode 'uri'", or "File not found" for one it took
 *  for a file name), said in the file's terms: a URI that is not base64, of a media type other than
 *  application/octet-stream and application/gltf-buffer, or a `byteLength` other than the bytes it holds
 * (`buffers[0].byteLength is 296, but its data: URI holds 288 bytes`); nothing when every data: buffer is sound. Parses
 * the whole JSON: for the error path. */
std::optional<std::string> dataUriBufferProblem(std::string_view json);

/** externalUris() by a SAX pass over `json`: what it collected before a syntax error still counts. */
ExternalUris externalUris(std::string_view json);

/** The path tinygltf asks its callbacks for first: the model's folder joined with the URI decoded its way (a '+' read
 *  as a space, a '%' always as the start of a byte). */
std::string tinygltfPathBesideModel(const std::string& baseDirectory, std::string_view uri);

/** The file a buffer's or image's URI names: the URI's path as RFC 3986 decodes it (only "%XX", and not "%00"); an
 *  absolute path, a file:// URI or a Windows share by its last name alone, beside the model; found as fileBeside()
 *  finds an OBJ's texture (as written, else with '\' as '/', else the file of its name beside the
 *  model, as a path of the exporting machine is shipped). */
std::string pathBesideModel(const std::string& baseDirectory, std::string_view uri);

/** A material's shade map path, resolved against the glTF file's folder and lexically normalised. */
std::string shadeMapBesideModel(const std::string& modelPath, const std::string& named);

/** What tinygltf's file callbacks work with: the load's budget, the external files the JSON names, and the record of
 *  what was opened (LoadReport::inputFiles). */
struct ExternalFiles {
    MeshBudget& budget;
    std::set<std::string> bufferPaths; ///< as tinygltf asks for them (tinygltfPathBesideModel())
    std::set<std::string> imagePaths;  ///< the same
    std::vector<std::string> opened;
    /** The file each buffer path tinygltf asks for stands for (pathBesideModel()): tinygltf decodes URIs its own way,
     *  and "model+lod0.bin" reaches the callbacks as "model lod0.bin". */
    std::map<std::string, std::string> fileOf;
    std::map<std::string, std::string> uriOf; ///< the first buffer URI that reached each asked path

    /** Records the buffer's or image's `uri` of a model in `baseDirectory`. For a buffer that tinygltf asks for by
     *  the same name as an earlier URI of another file ("a+b.bin" and "a%20b.bin": both "a b.bin"), that earlier
     *  URI: tinygltf cannot read both, and the caller refuses the file. */
    std::optional<std::string> name(const std::string& baseDirectory, std::string_view uri, bool image);
    /** The file tinygltf means by `path`. */
    const std::string& fileAskedAs(const std::string& path) const;
};

/** tinygltf's FsCallbacks::FileExists over an ExternalFiles (`user`). */
bool externalFileExists(const std::string& path, void* user);

/** tinygltf's FsCallbacks::ReadWholeFile over an ExternalFiles (`user`). */
bool readExternalFile(std::vector<unsigned char>* out, std::string* error, const std::string& path, void* user);

/** The encoded bytes of the images given as data: URIs, by glTF image index, kept by keepEncodedImage(). */
struct DataUriImages {
    MeshBudget& budget;
    std::vector<std::shared_ptr<const std::vector<unsigned char>>> bytes;
};

/** tinygltf's image loader over a DataUriImages (`user`): images stay encoded. */
bool keepEncodedImage(tinygltf::Image* image, int imageIndex, std::string* error, std::string* warning, int, int,
                      const unsigned char* bytes, int size, void* user);

/** The file's images in its order (Scene::images): embedded ones with their encoded bytes (charged to the budget),
 *  external ones with their path beside the model, not read here. */
std::vector<SceneImage> sceneImages(const std::string& path, const tinygltf::Model& model,
                                    const std::string& baseDirectory, const DataUriImages& dataUriImages,
                                    MeshBudget& budget);

/** The files a glTF (or GLB: `content` may stop after the JSON chunk) names: external buffers and images, and the
 *  shade maps of its materials. Best effort, nothing thrown. */
std::vector<std::string> gltfReferencedFiles(const std::string& path, std::string_view content);

/** gltfReferencedFiles() of a GLB (or VRM) file, reading its JSON chunk alone. */
std::vector<std::string> glbReferencedFiles(const std::string& path);

} // namespace inkgraph::detail
