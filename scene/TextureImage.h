#pragma once
/** @file A material's image decoded to 8-bit RGBA, only when a pass that runs samples it: the loader keeps images
 *  encoded (Material.h SceneImage). PNG through libpng and JPEG through libjpeg-turbo (codecs/), each row by row into
 *  the one RGBA buffer, WebP (EXT_texture_webp) through libwebp into it; the other formats stb_image reads (BMP, TGA,
 *  GIF, PSD, HDR, PIC) through stb;
 *  PNM, which stb does not read safely, is refused. No GL. */

#include "scene/Material.h"
#include "scene/Scene.h"

#include <cstddef>
#include <memory>
#include <string>
#include <utility>

namespace inkgraph {

/** The image formats decodeSceneImage() reads, for messages and help texts: "PNG, JPEG, WebP, BMP, TGA, GIF, PSD, HDR
 *  or PIC". */
inline constexpr const char* kTextureFormatNames = "PNG, JPEG, WebP, BMP, TGA, GIF, PSD, HDR or PIC";

struct DecodedImage {
    int width = 0;
    int height = 0;
    /** width x height x 4 bytes, rows top to bottom, sRGB-encoded colour and linear alpha: the decoder's own buffer,
     *  kept rather than copied (a 8192^2 texture is 256 MiB). */
    std::shared_ptr<const unsigned char> rgba;
};

/** decodeSceneImage()'s error for an image that cannot be used whatever the limits: its file is missing, or its bytes
 *  are corrupt, truncated, empty or of an unsupported format. A renderer draws the material without it and warns
 *  (--strict makes that an error); an image refused by the memory limit is a plain SceneError. */
class ImageUnusableError : public SceneError {
public:
    enum class Reason { Missing, Undecodable };
    ImageUnusableError(const std::string& message, std::string problem, Reason reason)
        : SceneError(message), mProblem(std::move(problem)), mReason(reason) {}
    /** What is wrong, without the function, model and image the message starts with. */
    const std::string& problem() const { return mProblem; }
    Reason reason() const { return mReason; }

private:
    std::string mProblem;
    Reason mReason;
};

/** What one texture costs at its peak, charged to the memory limit: the decoded pixels (4 bytes each) while they are
 *  uploaded, plus the GL copy with its mipmap chain (4/3 of them; llvmpipe keeps it in process memory). */
std::size_t decodedImageBytes(int width, int height);

/** Decodes `image` (embedded bytes, or its file read now). An external file must be a regular file no larger than
 *  `byteLimit`; the image's size is read from its header before anything is decoded, and an image whose
 *  decodedImageBytes(), plus what its decoder allocates of its own (a progressive JPEG's coefficients, stb's
 *  whole-image buffers), exceed `byteLimit` is refused. A PNG's data is inflated only as far as its header's pixels
 *  reach, however far it would inflate. `index` (its place in Scene::images) and its name label it in
 *  messages. Throws SceneError "decodeSceneImage(): '<model>' image 2 'skin': <problem>" for a file that is missing,
 * not a regular file, too large or unreadable, a corrupt, truncated or unsupported encoding (the decoder's reason
 * quoted) or the limit. */
DecodedImage decodeSceneImage(const SceneImage& image, std::size_t index, const std::string& modelPath,
                              std::size_t byteLimit);

/** What decoding every image the scene's materials name (textureRefsOf(), each image once) would take at its peak,
 *  without decoding any: each image's size read from its header (embedded bytes, or the first bytes of its file),
 *  charged decodedImageBytes() plus what stb_image allocates of its own for the formats it decodes, as
 *  decodeSceneImage() charges them. An image whose header cannot be read (missing, corrupt) counts nothing: it is not
 *  decoded either. For the run's memory estimate (render/MemoryBudget.h), so a batch can be sized before it runs. */
std::size_t estimatedTextureBytes(const Scene& scene);

} // namespace inkgraph
