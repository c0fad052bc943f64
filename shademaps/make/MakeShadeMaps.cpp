// Writes the bundled shade maps into a folder (the PNGs in shademaps/ come from this program):
//   inkgraph_make_shademaps OUT_DIR
// Each map is a function of the two shading terms, sampled at texel centres:
//   s in [0,1] across (diffuse: half-Lambert q for one-row cel maps, max(n.l, 0) for comic maps),
//   t in [0,1] up (specular max(r.v, 0)^n; the bottom row is t = 0).
// Colours are display sRGB in [0,1]; every map is multiplied with the material colour when used.
#include "render/ImageFiles.h"

#include <opencv2/core.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace {

using Color = std::array<double, 3>;
using MapFunction = std::function<Color(double s, double t, int column, int row)>;

struct MapSpec {
    std::string file;
    int width;
    int height;
    MapFunction color;
};

Color grey(double value) { return {value, value, value}; }

Color mix(const Color& a, const Color& b, double weight) {
    return {a[0] + (b[0] - a[0]) * weight, a[1] + (b[1] - a[1]) * weight, a[2] + (b[2] - a[2]) * weight};
}

/** A threshold in (0, 1) per texel from an integer hash: white noise, so neighbouring columns (which neighbouring
 *  pixels of a smooth surface index) switch independently, and the dots do not line up into the moire stripes an
 *  ordered (Bayer) pattern draws along the iso-lines of n.l. */
double noiseThreshold(int column, int row) {
    std::uint32_t hash = std::uint32_t(column) * 73856093u ^ std::uint32_t(row) * 19349663u;
    hash ^= hash >> 16;
    hash *= 0x7feb352du;
    hash ^= hash >> 15;
    hash *= 0x846ca68bu;
    hash ^= hash >> 16;
    return (double(hash & 0xffffffu) + 0.5) / double(1u << 24);
}

const std::vector<MapSpec>& mapSpecs() {
    static const std::vector<MapSpec> kSpecs = {
        // Lander's look with Winnemöller & Bangay 2002's addition: shadow and light tones, a hard white highlight.
        {"classic-two-tone.png", 128, 64,
         [](double s, double t, int, int) { return t > 0.5 && s > 0.3 ? grey(1.0) : grey(s > 0.3 ? 0.78 : 0.45); }},
        // Three diffuse bands and a highlight band.
        {"three-bands.png", 128, 64,
         [](double s, double t, int, int) {
             if (t > 0.6 && s > 0.2) return grey(1.0);
             return grey(s < 0.2 ? 0.32 : s < 0.6 ? 0.58 : 0.8);
         }},
        // Metal: dark and light stripes across the diffuse axis (reflected environment), a broad bright highlight.
        {"metallic.png", 128, 64,
         [](double s, double t, int, int) {
             const Color dark{0.22, 0.24, 0.3};
             const Color light{0.82, 0.86, 0.95};
             if (t > 0.25 && s > 0.1) return Color{1.0, 1.0, 1.0};
             const double stripe = std::floor(s * 5.0);
             return static_cast<int>(stripe) % 2 == 0 ? mix(dark, light, 0.15 + 0.12 * stripe) : mix(dark, light, 0.9);
         }},
        // Duo-tone, warm: violet shadows, warm light, pale highlight.
        {"duotone-warm.png", 128, 64,
         [](double s, double t, int, int) {
             if (t > 0.5 && s > 0.35) return Color{1.0, 0.97, 0.85};
             return s > 0.35 ? Color{1.0, 0.8, 0.55} : Color{0.42, 0.32, 0.62};
         }},
        // Duo-tone, cool: teal shadows, ice light.
        {"duotone-cool.png", 128, 64,
         [](double s, double t, int, int) {
             if (t > 0.5 && s > 0.35) return Color{1.0, 1.0, 1.0};
             return s > 0.35 ? Color{0.78, 0.92, 1.0} : Color{0.16, 0.36, 0.44};
         }},
        // Near-stippling (Winnemöller & Bangay 2002, Figure 9d): black dots on white, denser where darker, by random
        // thresholds on the tone; the highlight is clean paper. Wide, so the dots are small where n.l changes quickly.
        {"near-stippling.png", 1024, 64,
         [](double s, double t, int column, int row) {
             if (t > 0.5) return grey(1.0);
             const double tone = 0.1 + 0.9 * s;
             return grey(tone > noiseThreshold(column, row) ? 1.0 : 0.08);
         }},
        // Rim-like: the terminator glows (a bright band where the light grazes), then shadow, then the lit tone.
        {"rim-like.png", 128, 64,
         [](double s, double t, int, int) {
             if (t > 0.6 && s > 0.3) return grey(1.0);
             if (s < 0.06) return Color{1.0, 0.92, 0.75};
             return s < 0.35 ? Color{0.28, 0.25, 0.35} : Color{0.72, 0.7, 0.78};
         }},
        // Noir: black shadows, white light, no highlight band (the specular axis changes nothing).
        {"noir.png", 128, 64, [](double s, double, int, int) { return grey(s > 0.25 ? 0.95 : 0.06); }},
        // Soft diffuse with a banded highlight: the specular term alone is stylised (Winnemöller & Bangay 2002,
        // Figure 6b/6c).
        {"soft-highlight.png", 128, 64,
         [](double s, double t, int, int) {
             if (t > 0.7) return grey(1.0);
             if (t > 0.3) return grey(0.92);
             return grey(0.3 + 0.55 * s);
         }},
        // A one-row cel map: two bands on the half-Lambert axis (borders at n.l = 0), for --shading cel.
        {"cel-two-band.png", 64, 1, [](double s, double, int, int) { return grey(s > 0.5 ? 1.0 : 0.55); }},
    };
    return kSpecs;
}

cv::Mat renderMap(const MapSpec& spec) {
    cv::Mat image(spec.height, spec.width, CV_8UC4);
    for (int row = 0; row < spec.height; ++row) {
        for (int column = 0; column < spec.width; ++column) {
            const double s = (column + 0.5) / spec.width;
            const double t = spec.height == 1 ? 0.0 : (spec.height - 1 - row + 0.5) / spec.height; // bottom: t=0
            const Color color = spec.color(s, t, column, row);
            auto& pixel = image.at<cv::Vec4b>(row, column);
            for (int channel = 0; channel < 3; ++channel)
                pixel[channel] = cv::saturate_cast<uchar>(color[channel] * 255.0 + 0.5);
            pixel[3] = 255;
        }
    }
    return image;
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s OUT_DIR\n", argv[0]);
        return 2;
    }
    try {
        const std::filesystem::path folder = argv[1];
        std::filesystem::create_directories(folder);
        for (const MapSpec& spec : mapSpecs()) {
            inkgraph::writeImage(folder / spec.file, renderMap(spec));
            std::printf("%s %dx%d\n", spec.file.c_str(), spec.width, spec.height);
        }
    } catch (const std::exception& error) {
        std::fprintf(stderr, "%s: %s\n", argv[0], error.what());
        return 1;
    }
    return 0;
}
