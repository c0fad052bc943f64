#pragma once
/** @file The boundary between inkgraph and OpenImageIO. Debian's OpenImageIO links about 260 libraries, and the
 *  dynamic loader spends ~0.2 s resolving their symbols: more than rendering the default model takes. So the OIIO
 *  code lives in a module (libinkgraph_imageio.so) that render/ImageFiles loads with dlopen only for the formats libpng
 *  does not serve (EXR, TIFF, JPEG, ...; PNG is render/PngFiles.h, in the process): a run that writes only PNG never
 *  loads it, one that needs it loads it on a background thread while the scene loads. The boundary is plain: no
 *  exception crosses it, errors come back as text. */

#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace inkgraph {

struct ImageIoFunctions {
    int version;
    /** Encodes `image` in memory in the format of `formatPath`'s extension. The caller writes the bytes: OIIO's
     *  writers do not all report I/O errors (libpng's is ignored, libjpeg's exits the process), memory never fails. */
    bool (*encodeImage)(const std::string& formatPath, const cv::Mat& image, std::vector<unsigned char>& bytes,
                        std::string& error);
    /** Refuses, before allocating, images of more than `maxPixels` pixels, volume and deep images. */
    bool (*readImage)(const std::string& path, std::size_t maxPixels, cv::Mat& image, std::string& error);
    /** The file's own pixel type ("uint8", "half", "float", ...). */
    bool (*pixelType)(const std::string& path, std::string& type, std::string& error);
    /** "2.4.7": the OpenImageIO the module runs with (`inkgraph --version --verbose`). */
    const char* (*libraryVersion)();
};

inline constexpr int kImageIoVersion = 6;

/** The module's file name (app/CMakeLists.txt builds it so), in the build tree's top folder and installed in
 *  `${CMAKE_INSTALL_LIBDIR}/inkgraph/` (gl/BinaryLocation.h). */
inline constexpr const char* kImageIoModuleName = "libinkgraph_imageio.so";

} // namespace inkgraph

/** The module's only export. */
extern "C" const inkgraph::ImageIoFunctions* inkgraph_image_io_functions();
