// The PNG encoder's settings against each other (issue 38): every picture named on the command line is decoded once,
// then encoded in memory, over and over, with each zlib level, strategy, memory level and row filter asked for, and
// inkgraph's own encoder (codecs/PngCodec.cpp) last. Prints CPU milliseconds per picture (the median of the rounds;
// this thread's CPU time, which other processes on a shared host do not inflate) and the pictures' total bytes.
//
//     ./build/bench/inkgraph_png_sweep [--rounds N] [--memory-levels 5,8] PICTURE.png...
//
// libpng is driven directly here, with the settings writeRows() in codecs/PngCodec.cpp leaves fixed.
#include "codecs/PngCodec.h"

#include <png.h>
#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

struct Picture {
    std::string name;
    png_uint_32 width = 0;
    png_uint_32 height = 0;
    std::vector<unsigned char> rgba;
    std::vector<const unsigned char*> rows;
};

Picture decodeRgba(const std::string& path) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&image, path.c_str()))
        throw std::runtime_error("decodeRgba(): cannot read '" + path + "': " + image.message);
    image.format = PNG_FORMAT_RGBA;
    Picture picture;
    picture.name = path;
    picture.width = image.width;
    picture.height = image.height;
    picture.rgba.resize(PNG_IMAGE_SIZE(image));
    if (!png_image_finish_read(&image, nullptr, picture.rgba.data(), 0, nullptr))
        throw std::runtime_error("decodeRgba(): cannot decode '" + path + "': " + image.message);
    for (png_uint_32 row = 0; row < picture.height; ++row)
        picture.rows.push_back(&picture.rgba[std::size_t(row) * picture.width * 4]);
    return picture;
}

double threadCpuMs() {
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return double(now.tv_sec) * 1e3 + double(now.tv_nsec) / 1e6;
}

struct Settings {
    int level;
    int strategy;
    int memoryLevel;
    int filters;
};

void appendBytes(png_structp png, png_bytep data, std::size_t length) {
    auto* bytes = static_cast<std::vector<unsigned char>*>(png_get_io_ptr(png));
    bytes->insert(bytes->end(), data, data + length);
}

void flushNothing(png_structp) {}

/** libpng's errors end the sweep here: an exception must not unwind libpng's C frames, and nothing is left to undo. */
[[noreturn]] void onError(png_structp, png_const_charp reason) {
    std::fprintf(stderr, "encodeWith(): libpng: %s\n", reason);
    std::exit(1);
}

std::size_t encodeWith(const Picture& picture, const Settings& settings) {
    std::vector<unsigned char> bytes;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, onError, nullptr);
    png_infop info = png_create_info_struct(png);
    png_set_write_fn(png, &bytes, appendBytes, flushNothing);
    png_set_IHDR(png, info, picture.width, picture.height, 8, PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_ABSOLUTE);
    png_set_compression_level(png, settings.level);
    png_set_compression_strategy(png, settings.strategy);
    png_set_compression_mem_level(png, settings.memoryLevel);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, settings.filters);
    png_write_info(png, info);
    png_write_image(png, const_cast<png_bytepp>(picture.rows.data()));
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return bytes.size();
}

template <typename Encode>
void report(const std::string& label, const std::vector<Picture>& pictures, int rounds, Encode encode) {
    std::vector<double> msPerPicture;
    std::size_t bytes = 0;
    for (int round = 0; round < rounds; ++round) {
        bytes = 0;
        const double start = threadCpuMs();
        for (const Picture& picture : pictures) bytes += encode(picture);
        msPerPicture.push_back((threadCpuMs() - start) / double(pictures.size()));
    }
    std::nth_element(msPerPicture.begin(), msPerPicture.begin() + rounds / 2, msPerPicture.end());
    std::printf("| %s | %.2f | %zu |\n", label.c_str(), msPerPicture[std::size_t(rounds / 2)], bytes);
    std::fflush(stdout);
}

std::vector<int> listOfInts(const std::string& text) {
    std::vector<int> values;
    for (std::size_t start = 0; start < text.size();) {
        const std::size_t comma = std::min(text.find(',', start), text.size());
        values.push_back(std::stoi(text.substr(start, comma - start)));
        start = comma + 1;
    }
    return values;
}

} // namespace

int main(int argc, char** argv) {
    int rounds = 5;
    std::vector<int> memoryLevels = {8, 5};
    std::vector<Picture> pictures;
    try {
        for (int arg = 1; arg < argc; ++arg) {
            const std::string text = argv[arg];
            if (text == "--rounds" && arg + 1 < argc)
                rounds = std::max(1, std::stoi(argv[++arg]));
            else if (text == "--memory-levels" && arg + 1 < argc)
                memoryLevels = listOfInts(argv[++arg]);
            else
                pictures.push_back(decodeRgba(text));
        }
        if (pictures.empty()) {
            std::fprintf(stderr, "usage: %s [--rounds N] [--memory-levels 5,8] PICTURE.png...\n", argv[0]);
            return 2;
        }
        struct Named {
            const char* name;
            int value;
        };
        const Named strategies[] = {{"default", Z_DEFAULT_STRATEGY}, {"rle", Z_RLE}, {"filtered", Z_FILTERED}};
        const Named filters[] = {
            {"none", PNG_FILTER_NONE}, {"sub", PNG_FILTER_SUB}, {"up", PNG_FILTER_UP}, {"paeth", PNG_FILTER_PAETH}};
        std::printf("%zu pictures, median of %d rounds\n\n| zlib level / strategy / memory level / filter | CPU ms "
                    "per picture | bytes |\n|---|---|---|\n",
                    pictures.size(), rounds);
        for (const int memoryLevel : memoryLevels)
            for (int level = 1; level <= 3; ++level)
                for (const Named& strategy : strategies)
                    for (const Named& filter : filters)
                        report(std::to_string(level) + " / " + strategy.name + " / " + std::to_string(memoryLevel) +
                                   " / " + filter.name,
                               pictures, rounds, [&](const Picture& picture) {
                                   return encodeWith(picture, {level, strategy.value, memoryLevel, filter.value});
                               });
        report("3 / default / 8 / every filter (libpng picks per row)", pictures, rounds, [](const Picture& picture) {
            return encodeWith(picture, {3, Z_DEFAULT_STRATEGY, 8, PNG_ALL_FILTERS});
        });
        report("0 (stored) / default / 8 / none", pictures, rounds, [](const Picture& picture) {
            return encodeWith(picture, {0, Z_DEFAULT_STRATEGY, 8, PNG_FILTER_NONE});
        });
        report("inkgraph's encodePngRows()", pictures, rounds, [](const Picture& picture) {
            return inkgraph::encodePngRows(picture.width, picture.height, 4, picture.rows.data()).size();
        });
    } catch (const std::exception& error) {
        std::fprintf(stderr, "%s\n", error.what());
        return 1;
    }
    return 0;
}
