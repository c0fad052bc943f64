#pragma once
/** @file Image and text files, each written under a temporary name in the target folder and renamed into place, so a
 *  failed run never leaves a half-written file.
 *  Images are cv::Mat with row 0 at the top and channels in RGBA order (not OpenCV's BGR). The format follows the
 *  extension: PNG, which nearly every run writes, is encoded and decoded in the process by libpng (render/PngFiles.h);
 *  every other format (EXR, TIFF, JPEG, ...) and imageFilePixelType() go through OpenImageIO, a module loaded only
 *  when a run needs it (render/ImageIoModule.h), because loading it costs ~0.2 s. */

#include <opencv2/core.hpp>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph {

/** Writing or reading a file failed; the message names the file and the reason. */
class FileError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/** Whether reading or writing `path` goes through the OpenImageIO module: every extension but .png (in any case). */
bool usesImageIoModule(const std::filesystem::path& path);

/** Starts loading the OpenImageIO module on a background thread (see render/ImageIoModule.h), so its ~0.2 s of
 *  dynamic linking overlaps other work. Only for a run that will use it (usesImageIoModule()): the load is never
 *  undone. Optional: every function below that needs the module loads it on first use anyway. */
void preloadImageIo();

/** The module in this process, for --stats: "not loaded" (nothing needed it), "loading", "loaded" or "failed to
 *  load". Never starts a load. */
std::string imageIoModuleState();

/** Loads the OpenImageIO module (waiting for a load already started) and names it: "2.4.7 (module
 *  '/usr/lib/inkgraph/libinkgraph_imageio.so')", OpenImageIO's version first. Throws FileError naming every place
 * looked at when it cannot be loaded. For `inkgraph --version --verbose`. */
std::string imageIoLibrary();

/** Waits until a load that preloadImageIo() (or a first use) started has finished, successfully or not; returns at
 *  once when none was started. After it the loader thread has ended: render/BackgroundThreads.h. */
void finishImageIoPreload();

/** Writes CV_8UC1/CV_8UC4 as 8-bit sRGB and CV_32FC1/CV_32FC4 as float32 (EXR keeps float; PNG would quantise, so
 *  float images must go to .exr or .tif, and a PNG refuses them); an 8-bit picture written as EXR is converted to
 *  linear float. The format follows the extension. The place must be a regular file or a new name
 *  (requireOutputPlace(), render/OutputPlace.h: a device or a FIFO is refused, never replaced). Encoded in memory,
 *  written under a temporary name, synced, renamed into place. */
void writeImage(const std::filesystem::path& path, const cv::Mat& image);

/** `image` encoded in memory in the format of `finalPath`'s extension (as writeImage() writes it); thread-safe, so
 *  a batch encodes one still's picture while the next renders. Throws FileError naming `finalPath`. */
std::vector<unsigned char> encodeImageFile(const std::filesystem::path& finalPath, const cv::Mat& image);

/** Encodes `image` in the format of `finalPath`'s extension and writes it to `destination` (a new file, created
 *  exclusively, synced to disk); errors name `finalPath`. For callers that rename later (app/OutputFiles). */
void writeImageTo(const std::filesystem::path& destination, const std::filesystem::path& finalPath,
                  const cv::Mat& image);

/** Writes all `byteCount` bytes to an open file, continuing short writes and retrying EINTR. Returns 0, or the errno
 *  of the failure (EIO for a write that wrote nothing): the caller names the file. */
int writeWhole(int descriptor, const void* data, std::size_t byteCount);

/** Writes bytes to a new file (O_EXCL), checking every write, then fsync and close; on failure removes it and throws
 *  FileError naming `shownName`. */
void writeBytes(const std::filesystem::path& destination, const void* data, std::size_t byteCount,
                const std::string& shownName);

/** The most pixels readImage() accepts unless told otherwise: the largest picture inkgraph writes. */
inline constexpr std::size_t kDefaultMaxReadPixels = std::size_t(16384) * 16384;

/** Reads a PNG (libpng) or any image OpenImageIO knows into CV_8UCn (8-bit files) or CV_32FCn (everything else; a
 *  16-bit PNG is scaled to [0, 1]). Images whose header declares more than `maxPixels` pixels are refused (FileError)
 *  before anything is allocated. */
cv::Mat readImage(const std::filesystem::path& path, std::size_t maxPixels = kDefaultMaxReadPixels);

/** The bytes of a file from outside (a shade map, a style file): a regular file of at most `maxBytes`, judged
 *  before anything is read, so a FIFO, a device or a huge file is refused at once. Throws FileError starting with
 *  `who` and naming the file. */
std::string readInputBytes(const std::filesystem::path& path, std::uintmax_t maxBytes, const std::string& who);

/** readImage() for a PNG from outside (a user's shade map): a file of at most `maxFileBytes`, reduced to its critical
 *  chunks (app/PngChunks.h) and decoded from memory by libpng alone, whatever the content. Throws FileError starting
 *  with `who` (the flag that names the file, as readInputBytes()) and naming the file. */
cv::Mat readPngImage(const std::filesystem::path& path, std::size_t maxPixels, std::size_t maxFileBytes,
                     const std::string& who = "readPngImage()");

/** The pixel type stored in the file itself, e.g. "uint8", "half", "float" (readImage converts, this does not).
 *  Through OpenImageIO for every format: only tests and tools ask. */
std::string imageFilePixelType(const std::filesystem::path& path);

/** Writes text under a temporary name and renames it into place; the place as writeImage() takes it. */
void writeTextFile(const std::filesystem::path& path, const std::string& text);

/** 0 when a file can be created in `folder`, else the errno of trying. A probe file is the only reliable test of
 *  writability (permissions, read-only mounts, ACLs). */
int creationErrorIn(const std::filesystem::path& folder);

/** A short sibling of `path`, unique to this process: "final.png" -> ".inkgraph-<host>-1234-0.tmp"
 * (render/TemporaryFiles.h temporaryTag()). */
std::filesystem::path temporarySibling(const std::filesystem::path& path);

} // namespace inkgraph
