#pragma once
/** @file A material's image decoded to 8-bit RGBA by stb_image (Debian's libstb), only when a pass that runs samples
 *  it: the loader keeps images encoded (Material.h SceneImage). No GL. */

#include "scene/Material.h"

#include <cstddef>
#include <string>
#include <vector>

namespace inkgraph {

struct DecodedImage {
    int width = 0;
    int height = 0;
    std::vector<unsigned char>
        rgba; ///< width x height x 4 bytes, rows top to bottom, sRGB-encoded colour, linear alpha
};

/** The bytes a decoded image of this size takes with its mipmap chain (4/3 of the base level), the amount charged to
 *  the memory limit. */
std::size_t decodedImageBytes(int width, int height);

/** Decodes `image` (embedded bytes, or its file read now). Its size is read from the header before anything is
 *  decoded, and an image whose decodedImageBytes() exceeds `byteLimit` is refused. Throws SceneError
 *  "decodeSceneImage(): '<model>' image '<name>': <problem>" for an unreadable file, a corrupt or unsupported
 *  encoding (stb_image's reason quoted) or the limit. */
DecodedImage decodeSceneImage(const SceneImage& image, const std::string& modelPath, std::size_t byteLimit);

} // namespace inkgraph
