#pragma once
/** @file A labelled contact sheet of intermediates: every buffer (G-buffer fields, n.v, depth, coverage, line masks,
 *  shading, the final picture) turned into a small 8-bit picture by what it holds, then laid out in a grid with its
 *  name and format under it, so one image shows a whole run. Pure functions over cv::Mat: no GL, no I/O, inputs never
 *  mutated. Images have row 0 at the top and channels in RGBA order; results are CV_8UC4 sRGB display values.
 *
 *  Float buffers are linear data, not colour: they are mapped to display values directly (no gamma curve), so equal
 *  steps in the data are equal steps in the 8-bit value. Any pixel with a non-finite value (NaN, +-Inf) in any channel
 *  of a float buffer is shown magenta, whatever the content, and stays visible when the picture is shrunk. */

#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace inkgraph {

/** What a buffer holds, which decides how it is shown. Accepted types: CV_32F, or CV_16F (converted exactly), where
 *  float is named below. */
enum class TileContent {
    /** CV_8UC4 sRGB RGBA with alpha = coverage (or CV_8UC3, opaque): shown over a light checker so coverage is seen. */
    Color,
    /** CV_8UC1 line coverage, 255 = full line: shown as black ink on white (255 - value in every channel). */
    Lines,
    /** CV_8UC1 such as coverage (0/255): shown as grey as it is. */
    Mask,
    /** Float 3 or 4 channels, components in [-1,1] (normal, view vector, w), alpha = coverage when there are 4: shown
     *  as 0.5 + 0.5 x per channel; pixels with alpha <= 0 are background, shown dark grey. */
    UnitVector,
    /** Float 1 channel in [-1,1] such as n.v: a diverging map on a fixed scale (blue -1, white 0, red +1, clamped), so
     *  pictures of different runs compare. */
    SignedScalar,
    /** Float 1 channel linear depth, > 0 on the model, 0 = background: normalised over the covered pixels' min..max,
     *  nearest white, farthest dark grey, background black; negative depth is shown as bad data (magenta). */
    Depth,
    /** Any other float image, 1-4 channels: each of the first three channels normalised over its own finite min..max
     *  into red, green, blue (1 channel: grey; 2: blue 0; a 4th channel is not shown). */
    Data,
};

/** The enumerator's name, e.g. "UnitVector", for messages. */
const char* tileContentName(TileContent content);

/** The display colours of tileImage(), RGBA. */
struct TilePalette {
    static inline const cv::Vec4b kLetterbox = cv::Vec4b(128, 128, 128, 255);    ///< around a picture of another aspect
    static inline const cv::Vec4b kBad = cv::Vec4b(255, 0, 255, 255);            ///< non-finite (and negative depth)
    static inline const cv::Vec4b kCheckerLight = cv::Vec4b(255, 255, 255, 255); ///< Color: checker behind it
    static inline const cv::Vec4b kCheckerDark = cv::Vec4b(204, 204, 204, 255);  ///< Color: the other squares
    static constexpr int kCheckerSquare = 8;                                     ///< Color: square side, tile pixels
    static inline const cv::Vec4b kVectorBackground = cv::Vec4b(64, 64, 64, 255); ///< UnitVector where alpha <= 0
    static inline const cv::Vec4b kDepthBackground = cv::Vec4b(0, 0, 0, 255);     ///< Depth where depth == 0
    static constexpr int kDepthNear = 255;                                        ///< Depth: nearest pixel's grey
    static constexpr int kDepthFar = 64;                                          ///< Depth: farthest pixel's grey
    static constexpr int kDataFlat = 128;                                         ///< Data: a channel of one value
};

/** A short description of a buffer for a caption, in the plan's format names: "rgba32f 1024x1024", "r8 512x512",
 *  "rg16f 64x32"; "empty" for an empty image. */
std::string describeImage(const cv::Mat& image);

/** One buffer on the sheet. */
struct ContactTile {
    std::string label;   ///< first line under the picture, e.g. "gbuffer.normal"
    std::string caption; ///< second line, e.g. "rgba32f 1024x1024" (describeImage())
    cv::Mat image;       ///< the buffer, of a type its content accepts
    TileContent content = TileContent::Data;
};

/** CV_8UC4, opaque, of exactly `size`: one buffer shown as its content says, scaled to fit `size` with its aspect
 *  kept and centred on TilePalette::kLetterbox. Shrinking averages areas (INTER_AREA), so a 1-pixel line shrunk 4x
 *  stays as a grey line instead of vanishing; enlarging repeats pixels (INTER_NEAREST) so data pixels stay sharp.
 *  The mapping to display values happens at the buffer's own size and the colours are then averaged; non-finite
 *  pixels are tracked apart, and a tile pixel that any of them touches is magenta. Color is blended over the checker
 *  in sRGB values (as compositeFinal() does), premultiplied by alpha before averaging so transparent pixels' colour
 *  does not bleed. Throws std::invalid_argument starting "tileImage():" for an empty image, a type the content does
 *  not accept, or a size outside 1..16384 a side. */
cv::Mat tileImage(const cv::Mat& image, TileContent content, cv::Size size);

/** How the sheet is laid out. The fixed measures are the k constants below, in sheet pixels. */
struct ContactSheetLayout {
    static constexpr int kSpacing = 8;         ///< outer margin and the gap between cells, both ways
    static constexpr int kTitleBarHeight = 32; ///< height of the title bar (only when `title` is not empty)
    static constexpr int kCaptionHeight = 36;  ///< below each picture: the label line, then the caption line
    static constexpr int kMinTileWidth = 32;
    static constexpr int kMaxTileWidth = 4096;
    /** A cell's picture is at most this many times as tall as it is wide: a taller first picture (a 16x512 still) is
     *  letterboxed into it, where the sheet of its aspect would have been over kMaxSide tall. */
    static constexpr int kMaxTileAspect = 4;
    static constexpr int kMaxSide = 16384; ///< the largest sheet, each side (the largest picture inkgraph writes)

    int tileWidth = 256;                             ///< picture width of every cell, kMinTileWidth..kMaxTileWidth
    int columns = 0;                                 ///< 0 = automatic: ceil(sqrt(tile count)); at most the tiles
    std::string title;                               ///< one header line, e.g. model and look; empty = no title bar
    cv::Vec4b paper = cv::Vec4b(236, 234, 228, 255); ///< RGBA behind everything; alpha ignored (sheet opaque)
    cv::Vec4b ink = cv::Vec4b(24, 24, 24, 255);      ///< RGBA of the text; its alpha is ignored
};

/** The size composeContactSheet() gives `tileCount` tiles whose first image is `firstImageSize`, without drawing
 *  anything, so a caller can check an output before any work:
 *  tileHeight = clamp(round(tileWidth x first rows / first cols), 1, kMaxTileAspect x tileWidth),
 *  rows = ceil(tileCount / columns),
 *  width = kSpacing + columns x (tileWidth + kSpacing),
 *  height = (title ? kTitleBarHeight : 0) + kSpacing + rows x (tileHeight + kCaptionHeight + kSpacing).
 *  Throws std::invalid_argument starting "contactSheetSize():" when tileCount < 1, the first size is not positive,
 *  tileWidth is outside kMinTileWidth..kMaxTileWidth, columns < 0, or a side would exceed kMaxSide. */
cv::Size contactSheetSize(int tileCount, cv::Size firstImageSize, const ContactSheetLayout& layout);

/** CV_8UC4 RGBA, opaque (see contactSheetSize() for its size): the title bar (title in ink on the paper), then the
 *  tiles row by row in the given order. Every cell is the tile's picture at tileWidth x tileHeight (tileImage(); the
 *  height follows the first tile's aspect up to kMaxTileAspect, other aspects are letterboxed), then its label and
 *  caption in ink on the paper, Hershey simplex anti-aliased, left-aligned, each line shrunk to fit the cell width
 *  and, below a readable size, cut with "..." (Hershey fonts draw ASCII only; other characters come out as '?').
 *  Every tile is checked before anything is drawn. Throws std::invalid_argument starting "composeContactSheet():"
 *  when there are no tiles, a tile is empty or of a type its content does not accept (naming the tile's label in
 *  quotes), or for the layout errors of contactSheetSize(). */
cv::Mat composeContactSheet(const std::vector<ContactTile>& tiles, const ContactSheetLayout& layout);

} // namespace inkgraph
