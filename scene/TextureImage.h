#pragma once
/** @file A material's image decoded to 8-bit RGBA by stb_image (Debian's libstb), only when a pass that runs samples
 *  it: the loader keeps images encoded (Material.h SceneImage). No GL. */

#include "scene/Material.h"

#include <cstddef>
#include <memory>
#include <string>

namespace inkgraph {

struct DecodedImage {
    int width = 0;
    int height = 0;
    /** width x height x 4 bytes, rows top to bottom, sRGB-encoded colour and linear alpha: stb_image's own buffer,
     *  kept rather than copied (a 8192^2 texture is 256 MiB). */
    std::shared_ptr<const unsigned char> rgba;
};

/** What one texture costs at its peak, charged to the memory limit: the decoded pixels (4 bytes each) while they are
 *  uploaded, plus the GL copy with its mipmap chain (4/3 of them; llvmpipe keeps it in process memory). */
std::size_t decodedImageBytes(int width, int height);

/** Decodes `image` (embedded bytes, or its file read now). An external file must be a regular file no larger than
 *  `byteLimit`; the image's size is read from its header before anything is decoded, and an image whose
 *  decodedImageBytes() exceed `byteLimit` is refused. `index` (its place in Scene::images) and its name label it in
 *  messages. Throws SceneError "decodeSceneImage(): '<model>' image 2 'skin': <problem>" for a file that is missing,
 * not a regular file, too large or unreadable, a corrupt or unsupported encoding (stb_image's reason quoted) or the
 * limit. */
DecodedImage decodeSceneImage(const SceneImage& image, std::size_t index, const std::string& modelPath,
                              std::size_t byteLimit);

} // namespace inkgraph
