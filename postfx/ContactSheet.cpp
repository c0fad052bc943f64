#include "postfx/ContactSheet.h"
#include "postfx/SizeText.h"

#include <opencv2/core/check.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kTitleFontScale = 0.6;      // ~14 px from cap top to baseline
constexpr double kLabelFontScale = 0.45;     // ~10 px
constexpr double kCaptionFontScale = 0.4;    // ~9 px
constexpr double kMinFontScale = 0.3;        // ~7 px: below this Hershey simplex is unreadable, so longer text is cut
constexpr int kTitleBaseline = 22;           // in the title bar: 8 px above the caps, 4 below the descenders
constexpr int kLabelBaseline = 14;           // below the picture
constexpr int kCaptionBaseline = 30;         // below the picture; descenders end at ~34 of kCaptionHeight's 36
constexpr std::size_t kMaxShownChars = 1024; // cut before measuring: 4096 px hold ~700 characters at the smallest scale

bool isFloatDepth(int depth) { return depth == CV_32F || depth == CV_16F; }

/** Empty when `image` suits `content`; otherwise what is wrong, worded to follow "image " or "tile 'name' ". */
std::string contentProblem(const cv::Mat& image, TileContent content) {
    if (image.empty()) return "is empty";
    if (image.dims != 2) return "must be a 2-D image, got " + std::to_string(image.dims) + " dimensions";
    const int depth = image.depth();
    const int channels = image.channels();
    bool accepted = false;
    const char* wanted = "";
    switch (content) {
    case TileContent::Color:
        accepted = depth == CV_8U && (channels == 4 || channels == 3);
        wanted = "CV_8UC4 (or CV_8UC3)";
        break;
    case TileContent::Lines:
    case TileContent::Mask:
        accepted = image.type() == CV_8UC1;
        wanted = "CV_8UC1";
        break;
    case TileContent::UnitVector:
        accepted = isFloatDepth(depth) && (channels == 3 || channels == 4);
        wanted = "CV_32FC3 or CV_32FC4 (or CV_16F)";
        break;
    case TileContent::SignedScalar:
    case TileContent::Depth:
        accepted = isFloatDepth(depth) && channels == 1;
        wanted = "CV_32FC1 (or CV_16FC1)";
        break;
    case TileContent::Data:
        accepted = isFloatDepth(depth) && channels >= 1 && channels <= 4;
        wanted = "CV_32F with 1 to 4 channels (or CV_16F)";
        break;
    }
    if (accepted) return {};
    return std::string("must be ") + wanted + " for '" + tileContentName(content) + "', got " +
           cv::typeToString(image.type());
}

/** The picture's size inside `box`, aspect kept, at least 1 pixel a side. */
cv::Size fitSize(cv::Size image, cv::Size box) {
    const double scale =
        std::min(static_cast<double>(box.width) / image.width, static_cast<double>(box.height) / image.height);
    const auto side = [scale](int length, int limit) {
        return std::clamp(static_cast<int>(std::lround(length * scale)), 1, limit);
    };
    return {side(image.width, box.width), side(image.height, box.height)};
}

/** A buffer mapped to display values at its own size, before scaling. */
struct Display {
    cv::Mat color; ///< CV_8UC3 display values; for Color CV_16UC4: RGB premultiplied (c x a, 0..65025), a x 257
    cv::Mat bad;   ///< CV_8UC1, nonzero where a value is non-finite; empty when there is none
};

cv::Mat asFloat(const cv::Mat& image) {
    if (image.depth() == CV_32F) return image;
    cv::Mat converted;
    image.convertTo(converted, CV_32F); // CV_16F -> CV_32F is exact
    return converted;
}

uchar toByte(double value) { return cv::saturate_cast<uchar>(value); }

Display showColor(const cv::Mat& image) {
    Display display;
    display.color.create(image.size(), CV_16UC4);
    const int channels = image.channels();
    for (int row = 0; row < image.rows; ++row) {
        const uchar* in = image.ptr<uchar>(row);
        auto* out = display.color.ptr<cv::Vec<ushort, 4>>(row);
        // Colour tiles hold premultiplied colour (the shading, postfx/Composite.h; else opaque or empty pixels): the
        // display's colour x alpha (in 255ths) is the stored value x 255; an empty pixel's colour is none.
        for (int col = 0; col < image.cols; ++col, in += channels) {
            const int alpha = channels == 4 ? in[3] : 255;
            const int scale = alpha == 0 ? 0 : 255;
            out[col] = {static_cast<ushort>(in[0] * scale), static_cast<ushort>(in[1] * scale),
                        static_cast<ushort>(in[2] * scale), static_cast<ushort>(alpha * 257)};
        }
    }
    return display;
}

Display showGrey(const cv::Mat& image, bool inverted) {
    Display display;
    display.color.create(image.size(), CV_8UC3);
    for (int row = 0; row < image.rows; ++row) {
        const uchar* in = image.ptr<uchar>(row);
        auto* out = display.color.ptr<cv::Vec3b>(row);
        for (int col = 0; col < image.cols; ++col) {
            const uchar grey = inverted ? static_cast<uchar>(255 - in[col]) : in[col];
            out[col] = {grey, grey, grey};
        }
    }
    return display;
}

/** Runs `shade(values, out)` on every pixel whose channels are all finite; the others become bad. */
template <typename Shade>
Display showFloat(const cv::Mat& image, Shade shade) {
    const cv::Mat data = asFloat(image);
    const int channels = data.channels();
    Display display;
    display.color.create(data.size(), CV_8UC3);
    cv::Mat bad(data.size(), CV_8UC1, cv::Scalar(0));
    bool anyBad = false;
    for (int row = 0; row < data.rows; ++row) {
        const float* in = data.ptr<float>(row);
        auto* out = display.color.ptr<cv::Vec3b>(row);
        uchar* badRow = bad.ptr<uchar>(row);
        for (int col = 0; col < data.cols; ++col, in += channels) {
            bool finite = true;
            for (int channel = 0; channel < channels; ++channel) finite = finite && std::isfinite(in[channel]);
            if (finite) finite = shade(in, out[col]);
            if (!finite) {
                out[col] = {0, 0, 0};
                badRow[col] = 255;
                anyBad = true;
            }
        }
    }
    if (anyBad) display.bad = bad;
    return display;
}

cv::Vec3b rgb(const cv::Vec4b& color) { return {color[0], color[1], color[2]}; }

Display showUnitVector(const cv::Mat& image) {
    const bool hasAlpha = image.channels() == 4;
    return showFloat(image, [hasAlpha](const float* value, cv::Vec3b& out) {
        if (hasAlpha && !(value[3] > 0.0f)) {
            out = rgb(TilePalette::kVectorBackground);
            return true;
        }
        for (int channel = 0; channel < 3; ++channel)
            out[channel] = toByte(127.5 + 127.5 * std::clamp(static_cast<double>(value[channel]), -1.0, 1.0));
        return true;
    });
}

Display showSignedScalar(const cv::Mat& image) {
    return showFloat(image, [](const float* value, cv::Vec3b& out) {
        const double t = std::clamp(static_cast<double>(value[0]), -1.0, 1.0);
        // Linear from white at 0 to pure blue at -1 and pure red at +1: the sign reads at a glance, and the scale is
        // fixed so two pictures of n.v compare.
        if (t < 0.0) {
            const uchar fade = toByte(255.0 * (1.0 + t));
            out = {fade, fade, 255};
        } else {
            const uchar fade = toByte(255.0 * (1.0 - t));
            out = {255, fade, fade};
        }
        return true;
    });
}

Display showDepth(const cv::Mat& image) {
    const cv::Mat data = asFloat(image);
    double nearest = std::numeric_limits<double>::infinity();
    double farthest = -std::numeric_limits<double>::infinity();
    for (int row = 0; row < data.rows; ++row) {
        const float* in = data.ptr<float>(row);
        for (int col = 0; col < data.cols; ++col)
            if (std::isfinite(in[col]) && in[col] > 0.0f) {
                nearest = std::min(nearest, static_cast<double>(in[col]));
                farthest = std::max(farthest, static_cast<double>(in[col]));
            }
    }
    const double range = farthest - nearest; // <= 0 when one depth (or none) is covered: all nearest
    return showFloat(data, [nearest, range](const float* value, cv::Vec3b& out) {
        if (value[0] < 0.0f) return false; // depth is positive: a negative one is a convention mix-up, shown as bad
        if (value[0] == 0.0f) {
            out = rgb(TilePalette::kDepthBackground);
            return true;
        }
        const double t = range > 0.0 ? (value[0] - nearest) / range : 0.0;
        const uchar grey = toByte(TilePalette::kDepthNear - t * (TilePalette::kDepthNear - TilePalette::kDepthFar));
        out = {grey, grey, grey};
        return true;
    });
}

Display showData(const cv::Mat& image) {
    const cv::Mat data = asFloat(image);
    const int channels = data.channels();
    const int shown = std::min(channels, 3);
    double low[3], high[3];
    for (int channel = 0; channel < 3; ++channel) {
        low[channel] = std::numeric_limits<double>::infinity();
        high[channel] = -std::numeric_limits<double>::infinity();
    }
    for (int row = 0; row < data.rows; ++row) {
        const float* in = data.ptr<float>(row);
        for (int col = 0; col < data.cols; ++col, in += channels)
            for (int channel = 0; channel < shown; ++channel)
                if (std::isfinite(in[channel])) {
                    low[channel] = std::min(low[channel], static_cast<double>(in[channel]));
                    high[channel] = std::max(high[channel], static_cast<double>(in[channel]));
                }
    }
    return showFloat(data, [&low, &high, shown](const float* value, cv::Vec3b& out) {
        uchar level[3] = {0, 0, 0};
        for (int channel = 0; channel < shown; ++channel) {
            const double range = high[channel] - low[channel]; // in double: float max - float min stays finite
            level[channel] = range > 0.0 ? toByte(255.0 * (value[channel] - low[channel]) / range)
                                         : static_cast<uchar>(TilePalette::kDataFlat);
        }
        out = shown == 1 ? cv::Vec3b(level[0], level[0], level[0]) : cv::Vec3b(level[0], level[1], level[2]);
        return true;
    });
}

Display showContent(const cv::Mat& image, TileContent content) {
    switch (content) {
    case TileContent::Color: return showColor(image);
    case TileContent::Lines: return showGrey(image, true);
    case TileContent::Mask: return showGrey(image, false);
    case TileContent::UnitVector: return showUnitVector(image);
    case TileContent::SignedScalar: return showSignedScalar(image);
    case TileContent::Depth: return showDepth(image);
    case TileContent::Data: return showData(image);
    }
    throw std::logic_error("tileImage(): unknown TileContent");
}

/** Marks every picture pixel that a bad source pixel overlaps, so one NaN is never averaged away. */
cv::Mat scaleBad(const cv::Mat& bad, cv::Size fit) {
    cv::Mat scaled(fit, CV_8UC1, cv::Scalar(0));
    const std::int64_t cols = bad.cols, rows = bad.rows;
    for (std::int64_t row = 0; row < rows; ++row) {
        const uchar* in = bad.ptr<uchar>(static_cast<int>(row));
        // Source pixel [row, row + 1) covers picture rows [row x h / rows, (row + 1) x h / rows), in integers.
        const std::int64_t firstRow = row * fit.height / rows;
        const std::int64_t lastRow = std::max(firstRow, ((row + 1) * fit.height + rows - 1) / rows - 1);
        for (std::int64_t col = 0; col < cols; ++col) {
            if (in[col] == 0) continue;
            const std::int64_t firstCol = col * fit.width / cols;
            const std::int64_t lastCol = std::max(firstCol, ((col + 1) * fit.width + cols - 1) / cols - 1);
            scaled(cv::Range(static_cast<int>(firstRow), static_cast<int>(lastRow) + 1),
                   cv::Range(static_cast<int>(firstCol), static_cast<int>(lastCol) + 1))
                .setTo(255);
        }
    }
    return scaled;
}

/** tileImage() for an image already checked against its content. */
cv::Mat renderTile(const cv::Mat& image, TileContent content, cv::Size size) {
    const Display display = showContent(image, content);
    const cv::Size fit = fitSize(image.size(), size);
    const bool shrinking = fit.width < image.cols || fit.height < image.rows;
    cv::Mat color = display.color;
    if (fit != image.size())
        cv::resize(display.color, color, fit, 0.0, 0.0, shrinking ? cv::INTER_AREA : cv::INTER_NEAREST);
    const cv::Mat bad = display.bad.empty() ? cv::Mat() : scaleBad(display.bad, fit);

    const cv::Vec4b& letterbox = TilePalette::kLetterbox;
    cv::Mat tile(size, CV_8UC4, cv::Scalar(letterbox[0], letterbox[1], letterbox[2], letterbox[3]));
    const cv::Point origin((size.width - fit.width) / 2, (size.height - fit.height) / 2);
    for (int row = 0; row < fit.height; ++row) {
        auto* out = tile.ptr<cv::Vec4b>(origin.y + row) + origin.x;
        const uchar* badRow = bad.empty() ? nullptr : bad.ptr<uchar>(row);
        if (content == TileContent::Color) {
            // "over" the checker in sRGB values, as compositeFinal() blends the premultiplied shading over the paper:
            // colour + checker x (1 - a).
            const auto* in = color.ptr<cv::Vec<ushort, 4>>(row);
            for (int col = 0; col < fit.width; ++col) {
                const bool light = (row / TilePalette::kCheckerSquare + col / TilePalette::kCheckerSquare) % 2 == 0;
                const cv::Vec4b& checker = light ? TilePalette::kCheckerLight : TilePalette::kCheckerDark;
                const float transparency = 1.0f - in[col][3] / 65535.0f;
                for (int channel = 0; channel < 3; ++channel)
                    out[col][channel] =
                        cv::saturate_cast<uchar>(in[col][channel] / 255.0f + checker[channel] * transparency);
                out[col][3] = 255;
            }
        } else {
            const auto* in = color.ptr<cv::Vec3b>(row);
            for (int col = 0; col < fit.width; ++col) out[col] = {in[col][0], in[col][1], in[col][2], 255};
        }
        if (badRow)
            for (int col = 0; col < fit.width; ++col)
                if (badRow[col] != 0) out[col] = TilePalette::kBad;
    }
    return tile;
}

/** Where everything goes on the sheet. */
struct SheetGeometry {
    int columns = 1;
    int rows = 1;
    int tileHeight = 1;
    int titleHeight = 0;
    cv::Size size;
};

SheetGeometry sheetGeometry(const char* who, std::int64_t tileCount, cv::Size first, const ContactSheetLayout& layout) {
    const std::string prefix = std::string(who) + ": ";
    if (tileCount < 1) throw std::invalid_argument(prefix + "no tiles");
    if (first.width <= 0 || first.height <= 0)
        throw std::invalid_argument(prefix + "the first tile's size must be positive, got " + sizeText(first));
    if (layout.tileWidth < ContactSheetLayout::kMinTileWidth || layout.tileWidth > ContactSheetLayout::kMaxTileWidth)
        throw std::invalid_argument(
            prefix + "'tileWidth' must be " + std::to_string(ContactSheetLayout::kMinTileWidth) + " to " +
            std::to_string(ContactSheetLayout::kMaxTileWidth) + ", got " + std::to_string(layout.tileWidth));
    if (layout.columns < 0)
        throw std::invalid_argument(prefix + "'columns' must be 0 (automatic) or positive, got " +
                                    std::to_string(layout.columns));
    std::int64_t columns = layout.columns;
    if (columns == 0)
        while (columns * columns < tileCount) ++columns; // ceil(sqrt(n)) without floating point
    columns = std::min(columns, tileCount);
    const std::int64_t rows = (tileCount + columns - 1) / columns;
    const std::int64_t tileHeight =
        std::clamp<std::int64_t>(std::llround(static_cast<double>(layout.tileWidth) * first.height / first.width), 1,
                                 std::int64_t(ContactSheetLayout::kMaxTileAspect) * layout.tileWidth);
    const std::int64_t titleHeight = layout.title.empty() ? 0 : ContactSheetLayout::kTitleBarHeight;
    constexpr std::int64_t spacing = ContactSheetLayout::kSpacing;
    const std::int64_t width = spacing + columns * (layout.tileWidth + spacing);
    const std::int64_t height =
        titleHeight + spacing + rows * (tileHeight + ContactSheetLayout::kCaptionHeight + spacing);
    if (width > ContactSheetLayout::kMaxSide || height > ContactSheetLayout::kMaxSide)
        throw std::invalid_argument(prefix + "the sheet would be " + std::to_string(width) + "x" +
                                    std::to_string(height) + " pixels (" + std::to_string(tileCount) + " tiles, " +
                                    std::to_string(columns) + " columns, tiles " + std::to_string(layout.tileWidth) +
                                    "x" + std::to_string(tileHeight) + "); at most " +
                                    std::to_string(ContactSheetLayout::kMaxSide) + " a side");
    SheetGeometry geometry;
    geometry.columns = static_cast<int>(columns);
    geometry.rows = static_cast<int>(rows);
    geometry.tileHeight = static_cast<int>(tileHeight);
    geometry.titleHeight = static_cast<int>(titleHeight);
    geometry.size = {static_cast<int>(width), static_cast<int>(height)};
    return geometry;
}

int textWidth(const std::string& text, double scale) {
    int baseline = 0;
    return cv::getTextSize(text, kFont, scale, 1, &baseline).width;
}

/** One line of text with its baseline's left end at `origin` in `area` (a view into the sheet, which clips), shrunk
 *  to `maxWidth` pixels, and below kMinFontScale cut with "...". */
void drawLine(cv::Mat& area, std::string text, cv::Point origin, int maxWidth, double fontScale,
              const cv::Scalar& ink) {
    if (text.empty() || maxWidth <= 0) return;
    if (text.size() > kMaxShownChars) text.resize(kMaxShownChars);
    double scale = fontScale;
    const int fullWidth = textWidth(text, scale);
    if (fullWidth > maxWidth) scale = std::max(kMinFontScale, fontScale * maxWidth / fullWidth);
    if (textWidth(text, scale) > maxWidth) {
        const std::string ellipsis = "...";
        while (!text.empty() && textWidth(text + ellipsis, scale) > maxWidth) text.pop_back();
        text += ellipsis;
    }
    // getTextSize() rounds: make sure the line really fits.
    while (textWidth(text, scale) > maxWidth && scale > 0.05) scale *= 0.95;
    cv::putText(area, text, origin, kFont, scale, ink, 1, cv::LINE_AA);
}

cv::Scalar opaque(const cv::Vec4b& color) { return {double(color[0]), double(color[1]), double(color[2]), 255.0}; }

} // namespace

const char* tileContentName(TileContent content) {
    switch (content) {
    case TileContent::Color: return "Color";
    case TileContent::Lines: return "Lines";
    case TileContent::Mask: return "Mask";
    case TileContent::UnitVector: return "UnitVector";
    case TileContent::SignedScalar: return "SignedScalar";
    case TileContent::Depth: return "Depth";
    case TileContent::Data: return "Data";
    }
    return "unknown";
}

std::string describeImage(const cv::Mat& image) {
    if (image.empty()) return "empty";
    static const char* const kChannelNames[] = {"r", "rg", "rgb", "rgba"};
    const int channels = image.channels();
    std::string text = channels <= 4 ? std::string(kChannelNames[channels - 1]) : std::string("c");
    if (channels > 4) text.append(std::to_string(channels)).append("x");
    switch (image.depth()) {
    case CV_8U: text += "8"; break;
    case CV_8S: text += "8s"; break;
    case CV_16U: text += "16"; break;
    case CV_16S: text += "16s"; break;
    case CV_32S: text += "32s"; break;
    case CV_32F: text += "32f"; break;
    case CV_64F: text += "64f"; break;
    case CV_16F: text += "16f"; break;
    default: text += "?"; break;
    }
    if (image.dims == 2) return text + " " + sizeText(image.size());
    std::string shape;
    for (int axis = 0; axis < image.dims; ++axis) {
        if (axis > 0) shape += 'x';
        shape += std::to_string(image.size[axis]);
    }
    return text + " " + shape;
}

cv::Mat tileImage(const cv::Mat& image, TileContent content, cv::Size size) {
    if (size.width < 1 || size.height < 1 || size.width > ContactSheetLayout::kMaxSide ||
        size.height > ContactSheetLayout::kMaxSide)
        throw std::invalid_argument("tileImage(): size must be 1 to " + std::to_string(ContactSheetLayout::kMaxSide) +
                                    " a side, got " + sizeText(size));
    const std::string problem = contentProblem(image, content);
    if (!problem.empty()) throw std::invalid_argument("tileImage(): image " + problem);
    return renderTile(image, content, size);
}

cv::Size contactSheetSize(int tileCount, cv::Size firstImageSize, const ContactSheetLayout& layout) {
    return sheetGeometry("contactSheetSize()", tileCount, firstImageSize, layout).size;
}

cv::Mat composeContactSheet(const std::vector<ContactTile>& tiles, const ContactSheetLayout& layout) {
    const char* const who = "composeContactSheet()";
    if (tiles.empty()) throw std::invalid_argument(std::string(who) + ": no tiles");
    for (const ContactTile& tile : tiles) {
        const std::string problem = contentProblem(tile.image, tile.content);
        if (!problem.empty()) throw std::invalid_argument(std::string(who) + ": tile '" + tile.label + "' " + problem);
    }
    const SheetGeometry geometry =
        sheetGeometry(who, static_cast<std::int64_t>(tiles.size()), tiles.front().image.size(), layout);

    const cv::Scalar ink = opaque(layout.ink);
    cv::Mat sheet(geometry.size, CV_8UC4, opaque(layout.paper));
    constexpr int spacing = ContactSheetLayout::kSpacing;
    if (geometry.titleHeight > 0) {
        cv::Mat bar = sheet(cv::Rect(0, 0, sheet.cols, geometry.titleHeight));
        drawLine(bar, layout.title, {spacing, kTitleBaseline}, sheet.cols - 2 * spacing, kTitleFontScale, ink);
    }
    const cv::Size tileSize(layout.tileWidth, geometry.tileHeight);
    for (std::size_t index = 0; index < tiles.size(); ++index) {
        const int column = static_cast<int>(index % static_cast<std::size_t>(geometry.columns));
        const int row = static_cast<int>(index / static_cast<std::size_t>(geometry.columns));
        const cv::Point cell(spacing + column * (layout.tileWidth + spacing),
                             geometry.titleHeight + spacing +
                                 row * (geometry.tileHeight + ContactSheetLayout::kCaptionHeight + spacing));
        const ContactTile& tile = tiles[index];
        renderTile(tile.image, tile.content, tileSize).copyTo(sheet(cv::Rect(cell, tileSize)));
        // The text area is a view of exactly the cell's width, so nothing can spill into the next cell.
        cv::Mat text =
            sheet(cv::Rect(cell.x, cell.y + geometry.tileHeight, layout.tileWidth, ContactSheetLayout::kCaptionHeight));
        drawLine(text, tile.label, {1, kLabelBaseline}, layout.tileWidth - 2, kLabelFontScale, ink);
        drawLine(text, tile.caption, {1, kCaptionBaseline}, layout.tileWidth - 2, kCaptionFontScale, ink);
    }
    return sheet;
}

} // namespace inkgraph
