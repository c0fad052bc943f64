#include "postfx/SvgLines.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <set>
#include <stdexcept>
#include <string>

namespace inkgraph {
namespace {

/** Appends `value` rounded to `decimals` places, without trailing zeros or a trailing point, and never "-0".
 *  Locale-free (std::to_chars), so a C library locale with a decimal comma cannot break the document. */
void appendNumber(std::string& out, double value, int decimals) {
    char buffer[64];
    const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, decimals);
    if (error != std::errc()) throw std::logic_error("svgDocument(): appendNumber() buffer too small");
    char* last = end;
    if (std::find(buffer, end, '.') != end) {
        while (last[-1] == '0') --last;
        if (last[-1] == '.') --last;
    }
    const bool negativeZero = last - buffer == 2 && buffer[0] == '-' && buffer[1] == '0';
    if (negativeZero)
        out += '0';
    else
        out.append(buffer, last);
}

std::string formatNumber(double value, int decimals) {
    std::string text;
    appendNumber(text, value, decimals);
    return text;
}

std::string layerName(std::size_t index) { return "'layers' [" + std::to_string(index) + "]"; }

/** #rrggbb of display channels in [0, 1], checked. */
std::string hexColor(const std::array<double, 4>& color, const std::string& name) {
    static constexpr char kDigits[] = "0123456789abcdef";
    for (std::size_t channel = 0; channel < 4; ++channel)
        if (!std::isfinite(color[channel]) || color[channel] < 0.0 || color[channel] > 1.0)
            throw std::invalid_argument("svgDocument(): " + name + " channel " + std::to_string(channel) +
                                        " must be finite and in [0, 1], got " + std::to_string(color[channel]));
    std::string text = "#";
    for (std::size_t channel = 0; channel < 3; ++channel) {
        const int byte = static_cast<int>(std::lround(color[channel] * 255.0));
        text += kDigits[byte >> 4];
        text += kDigits[byte & 15];
    }
    return text;
}

bool isIdCharacter(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_' ||
           c == '.';
}

/** The length of the well-formed UTF-8 sequence at `at` that XML 1.0 allows, or 0. */
std::size_t validUtf8Length(const std::string& text, std::size_t at) {
    const auto byte = [&](std::size_t index) { return static_cast<unsigned char>(text[index]); };
    const unsigned lead = byte(at);
    std::size_t length = 0;
    std::uint32_t code = 0;
    if (lead < 0x80) return 1;
    if (lead >= 0xC2 && lead <= 0xDF)
        length = 2, code = lead & 0x1Fu;
    else if (lead >= 0xE0 && lead <= 0xEF)
        length = 3, code = lead & 0x0Fu;
    else if (lead >= 0xF0 && lead <= 0xF4)
        length = 4, code = lead & 0x07u;
    else
        return 0;
    if (at + length > text.size()) return 0;
    for (std::size_t index = 1; index < length; ++index) {
        if ((byte(at + index) & 0xC0u) != 0x80u) return 0;
        code = (code << 6) | (byte(at + index) & 0x3Fu);
    }
    const bool overlong = (length == 3 && code < 0x800) || (length == 4 && code < 0x10000);
    const bool surrogate = code >= 0xD800 && code <= 0xDFFF;
    const bool notCharacter = code == 0xFFFE || code == 0xFFFF || code > 0x10FFFF;
    return overlong || surrogate || notCharacter ? 0 : length;
}

/** Text content for XML 1.0: markup characters escaped, what XML cannot hold replaced by '?'. */
std::string escapeXml(const std::string& text) {
    std::string escaped;
    escaped.reserve(text.size());
    for (std::size_t at = 0; at < text.size();) {
        const char c = text[at];
        switch (c) {
        case '&':
            escaped += "&amp;";
            ++at;
            continue;
        case '<':
            escaped += "&lt;";
            ++at;
            continue;
        case '>':
            escaped += "&gt;";
            ++at;
            continue;
        case '"':
            escaped += "&quot;";
            ++at;
            continue;
        case '\'':
            escaped += "&apos;";
            ++at;
            continue;
        default: break;
        }
        const auto byte = static_cast<unsigned char>(c);
        if (byte < 0x20 && c != '\t' && c != '\n' && c != '\r') {
            escaped += '?';
            ++at;
            continue;
        }
        const std::size_t length = validUtf8Length(text, at);
        if (length == 0) {
            escaped += '?';
            ++at;
            continue;
        }
        escaped.append(text, at, length);
        at += length;
    }
    return escaped;
}

void checkLayer(const SvgLineLayer& layer, std::size_t index, std::set<std::string>& types) {
    const std::string name = layerName(index);
    if (layer.type.empty()) throw std::invalid_argument("svgDocument(): " + name + " 'type' must not be empty");
    for (const char c : layer.type)
        if (!isIdCharacter(c))
            throw std::invalid_argument("svgDocument(): " + name + " 'type' '" + layer.type +
                                        "' may hold only A-Z, a-z, 0-9, '-', '_' and '.' (it becomes an XML id)");
    if (!types.insert(layer.type).second)
        throw std::invalid_argument("svgDocument(): " + name + " 'type' '" + layer.type +
                                    "' repeats an earlier layer's (group ids must be unique)");
    if (layer.supersample < 1)
        throw std::invalid_argument("svgDocument(): " + name + " 'supersample' must be >= 1, got " +
                                    std::to_string(layer.supersample));
    if (!std::isfinite(layer.widthPixels) || layer.widthPixels <= 0.0)
        throw std::invalid_argument("svgDocument(): " + name + " 'widthPixels' must be finite and > 0, got " +
                                    std::to_string(layer.widthPixels));
    for (std::size_t line = 0; line < layer.polylines.size(); ++line)
        for (const cv::Point2f& point : layer.polylines[line].points)
            if (!std::isfinite(point.x) || !std::isfinite(point.y))
                throw std::invalid_argument("svgDocument(): " + name + " 'polylines' [" + std::to_string(line) +
                                            "] has a non-finite coordinate");
    if (!layer.opacities.empty() && layer.opacities.size() != layer.polylines.size())
        throw std::invalid_argument("svgDocument(): " + name + " 'opacities' must be empty or one per polyline");
    for (const double opacity : layer.opacities)
        if (!(opacity > 0.0 && opacity <= 1.0))
            throw std::invalid_argument("svgDocument(): " + name + " 'opacities' must lie in (0, 1], got " +
                                        std::to_string(opacity));
    if (!layer.widths.empty() && layer.widths.size() != layer.polylines.size())
        throw std::invalid_argument("svgDocument(): " + name + " 'widths' must be empty or one per polyline");
    for (std::size_t line = 0; line < layer.widths.size(); ++line) {
        if (layer.widths[line].size() != layer.polylines[line].points.size())
            throw std::invalid_argument("svgDocument(): " + name + " 'widths' [" + std::to_string(line) +
                                        "] must hold one width per vertex");
        for (const double width : layer.widths[line])
            if (!std::isfinite(width) || width <= 0.0)
                throw std::invalid_argument("svgDocument(): " + name + " 'widths' [" + std::to_string(line) +
                                            "] must be finite and > 0");
    }
}

void appendPath(std::string& out, const Polyline& polyline, double scale, const std::string& opacity) {
    if (polyline.points.empty()) return;
    auto appendPoint = [&](const char* command, const cv::Point2f& point) {
        out += command;
        appendNumber(out, (double(point.x) + 0.5) * scale, 2);
        out += ' ';
        appendNumber(out, (double(point.y) + 0.5) * scale, 2);
    };
    out += "    <path " + opacity + "d=\"";
    appendPoint("M ", polyline.points.front());
    if (polyline.points.size() == 1) {
        appendPoint(" L ", polyline.points.front()); // zero length: round caps draw a dot
    } else {
        for (std::size_t index = 1; index < polyline.points.size(); ++index) appendPoint(" L ", polyline.points[index]);
        if (polyline.closed) out += " Z";
    }
    out += "\"/>\n";
}

/** A polyline of varying width as a filled outline: the left side forward, a round cap, the right side back, a round
 *  cap. Vertex normals are the mean of the two segments' (mitred joins, good for the gentle turns of strokes). */
void appendWeightedPath(std::string& out, const Polyline& polyline, const std::vector<double>& widths, double scale,
                        const std::string& fill) {
    const std::size_t count = polyline.points.size();
    if (count == 0) return;
    std::vector<cv::Point2d> points;
    for (const cv::Point2f& point : polyline.points)
        points.emplace_back((double(point.x) + 0.5) * scale, (double(point.y) + 0.5) * scale);
    auto appendXY = [&](const cv::Point2d& point) {
        appendNumber(out, point.x, 2);
        out += ' ';
        appendNumber(out, point.y, 2);
    };
    auto appendArc = [&](double radius, const cv::Point2d& to) {
        out += " A ";
        appendNumber(out, radius, 2);
        out += ' ';
        appendNumber(out, radius, 2);
        // Sweep 0, toward decreasing angle (y down): from the left side (+normal, the normal being the direction
        // turned by +90 degrees) the arc passes the end ahead of the line, a cap that bulges out of it.
        out += " 0 0 0 ";
        appendXY(to);
    };
    out += "    <path " + fill + " d=\"";
    if (count == 1) { // a dot: a circle of the width
        const double radius = 0.5 * widths[0];
        out += "M ";
        appendXY(points[0] - cv::Point2d(radius, 0.0));
        appendArc(radius, points[0] + cv::Point2d(radius, 0.0));
        appendArc(radius, points[0] - cv::Point2d(radius, 0.0));
        out += " Z\"/>\n";
        return;
    }
    const bool closed = polyline.closed && count > 2;
    auto segmentNormal = [&](std::size_t from, std::size_t to) {
        const cv::Point2d along = points[to] - points[from];
        const double length = cv::norm(along);
        return length > 0.0 ? cv::Point2d(-along.y, along.x) / length : cv::Point2d(0.0, 0.0);
    };
    std::vector<cv::Point2d> left(count), right(count);
    for (std::size_t index = 0; index < count; ++index) {
        cv::Point2d normal(0.0, 0.0);
        if (index > 0 || closed) normal += segmentNormal(index > 0 ? index - 1 : count - 1, index);
        if (index + 1 < count || closed) normal += segmentNormal(index, (index + 1) % count);
        const double length = cv::norm(normal);
        normal = length > 0.0 ? normal / length : cv::Point2d(0.0, 0.0);
        left[index] = points[index] + normal * (0.5 * widths[index]);
        right[index] = points[index] - normal * (0.5 * widths[index]);
    }
    out += "M ";
    appendXY(left[0]);
    for (std::size_t index = 1; index < count; ++index) {
        out += " L ";
        appendXY(left[index]);
    }
    if (closed) {
        // A ring: the outer side, then the inner side the other way round, so the nonzero rule leaves a hole.
        out += " Z M ";
        appendXY(right[count - 1]);
        for (std::size_t index = count - 1; index-- > 0;) {
            out += " L ";
            appendXY(right[index]);
        }
        out += " Z\"/>\n";
        return;
    }
    appendArc(0.5 * widths[count - 1], right[count - 1]);
    for (std::size_t index = count - 1; index-- > 0;) {
        out += " L ";
        appendXY(right[index]);
    }
    appendArc(0.5 * widths[0], left[0]);
    out += " Z\"/>\n";
}

} // namespace

std::string svgDocument(int width, int height, const std::vector<SvgLineLayer>& layers,
                        const SvgDocumentOptions& options) {
    if (width < 1 || height < 1)
        throw std::invalid_argument("svgDocument(): 'width' and 'height' must be >= 1, got " + std::to_string(width) +
                                    "x" + std::to_string(height));
    std::set<std::string> types;
    for (std::size_t index = 0; index < layers.size(); ++index) checkLayer(layers[index], index, types);
    const std::string backgroundColor =
        options.background ? hexColor(*options.background, "'options.background'") : std::string();

    const std::string widthText = std::to_string(width), heightText = std::to_string(height);
    std::string out;
    out += "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n";
    out += "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\""
           " version=\"1.1\" width=\"" +
           widthText + "\" height=\"" + heightText + "\" viewBox=\"0 0 " + widthText + " " + heightText + "\">\n";
    out += "  <title>" + escapeXml(options.title) + "</title>\n";
    if (options.background)
        out += "  <rect id=\"background\" x=\"0\" y=\"0\" width=\"" + widthText + "\" height=\"" + heightText +
               "\" fill=\"" + backgroundColor + "\" fill-opacity=\"" + formatNumber((*options.background)[3], 3) +
               "\"/>\n";
    for (std::size_t index = 0; index < layers.size(); ++index) {
        const SvgLineLayer& layer = layers[index];
        out += "  <g id=\"lines-" + layer.type + "\" inkscape:groupmode=\"layer\" inkscape:label=\"" + layer.type +
               "\" opacity=\"" + formatNumber(layer.color[3], 3) + "\" fill=\"none\" stroke=\"" +
               hexColor(layer.color, layerName(index) + " 'color'") + "\" stroke-width=\"" +
               formatNumber(layer.widthPixels, 3) + "\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n";
        const double scale = 1.0 / layer.supersample;
        const std::string fill =
            "fill=\"" + hexColor(layer.color, layerName(index) + " 'color'") + "\" stroke=\"none\"";
        for (std::size_t line = 0; line < layer.polylines.size(); ++line) {
            // Opacities are written to 3 decimals, so one that rounds to 1 is left out.
            const double opacity = layer.opacities.empty() ? 1.0 : layer.opacities[line];
            const std::string opacityText = formatNumber(opacity, 3);
            const bool faded = opacityText != "1";
            if (layer.widths.empty())
                appendPath(out, layer.polylines[line], scale,
                           faded ? "stroke-opacity=\"" + opacityText + "\" " : std::string());
            else
                appendWeightedPath(out, layer.polylines[line], layer.widths[line], scale,
                                   faded ? fill + " fill-opacity=\"" + opacityText + "\"" : fill);
        }
        out += "  </g>\n";
    }
    out += "</svg>\n";
    return out;
}

} // namespace inkgraph
