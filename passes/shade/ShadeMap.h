#pragma once
/** @file Shade maps (Lander's 1-D shade texture, Winnemoller & Bangay 2002's 2-D shade map) as CPU images. No GL
 *  here: the shading pass uploads them with nearest filtering, clamped to the edge.
 *
 *  Axes. Column = diffuse, left (dark) to right (lit). For cel (1-D, one row) the column axis is the half-Lambert
 *  term q = (n.l + 1)/2 of Qu, Chen & Zwicker; for comic (2-D) it is Lander's s = max(n.l, 0). Row = specular
 *  t = max(r.v, 0)^shininess for comic: the bottom row is t = 0, the top row t = 1 (as the map is drawn). Texel
 *  i = min(floor(u N), N - 1). Texels are sRGB colours multiplied with the material's base colour. */

#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace inkgraph {

/** The largest side of a shade map (a map needs no more texels than the screen has pixels across). */
inline constexpr int kMaxShadeMapSide = 4096;

struct ShadeMap {
    cv::Mat texels;     ///< CV_8UC4 sRGB, row 0 at the top; 1 row for a 1-D map
    std::string source; ///< "builtin:bands-5", or the file it came from

    bool isOneDimensional() const { return texels.rows == 1; }
};

/** N even bands over the half-Lambert axis, levels i/(N-1) (grey). N = 5 is Qu, Chen & Zwicker's cel default
 *  {0, .25, .5, .75, 1} with borders at q = .2, .4, .6, .8. The levels are linear light, stored as their sRGB
 *  codes (0.25 -> 137) like every 8-bit colour, so the decoded texel times the base colour gives the level.
 *  Throws std::invalid_argument unless 2 <= N <= 256. */
ShadeMap makeBandShadeMap(int bands);

/** The default comic map: two tones and a highlight (grey, so the material colour shows through). 32 x 32:
 *  shadow (linear 0.2) where s < 0.25, lit (0.6) elsewhere, highlight (1.0) in the top half, t >= 0.5. */
ShadeMap makeDefaultComicShadeMap();

/** Checks an image read from `source` (any channel count from 1 to 4, 8-bit) and converts it to a ShadeMap:
 *  grey -> rgb, alpha ignored (set to 255). Throws std::invalid_argument starting with `who` and naming `source`
 *  when it is empty, not 8-bit, has more than 4 channels, is larger than 4096 a side, or (with `requireOneRow`) has
 *  more than one row. */
ShadeMap shadeMapFromImage(const cv::Mat& image, const std::string& source, bool requireOneRow,
                           const std::string& who = "shadeMapFromImage()");

/** A 2-D map's rows grouped into bands of identical rows, with the specular term's band borders moved to the
 *  half squared distance x = |r - v|^2 / 2 = 1 - r.v, where the shader can test them without a log or exp:
 *  t = (r.v)^n >= j/R  <=>  x <= 1 - (j/R)^(1/n). Exact in double, and free of the cancellation of 1 - r.v near the
 *  highlight (x is computed from r - v). Most maps have a few bands (a highlight or two over the diffuse tones). */
struct SpecularRowBands {
    std::vector<int> firstRow; ///< per band, the map row where it starts, counted from the bottom (t = 0)
    std::vector<double> maxHalfSquaredDistance; ///< per band after the first: the band holds t when x <= this
                                                ///< (decreasing); > 2 (every x) for shininess 0, where t = 1
};
SpecularRowBands specularRowBands(const ShadeMap& map, double shininess);

} // namespace inkgraph
