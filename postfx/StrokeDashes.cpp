#include "postfx/StrokeDashes.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace inkgraph {
namespace {

LinePoint pointBetween(const LinePoint& a, const LinePoint& b, double t) {
    LinePoint point;
    point.position = a.position + (b.position - a.position) * float(t);
    point.strength = float(double(a.strength) + (double(b.strength) - double(a.strength)) * t);
    point.width = float(double(a.width) + (double(b.width) - double(a.width)) * t);
    return point;
}

double distance(const LinePoint& a, const LinePoint& b) {
    return std::hypot(double(b.position.x) - double(a.position.x), double(b.position.y) - double(a.position.y));
}

/** A dash's length and strengths, from its points (open). */
void measureDash(Stroke& dash) {
    dash.lengthPixels = 0.0;
    double strengthSum = 0.0;
    dash.peakStrength = 0.0f;
    for (std::size_t index = 0; index < dash.points.size(); ++index) {
        if (index > 0) dash.lengthPixels += distance(dash.points[index - 1], dash.points[index]);
        strengthSum += dash.points[index].strength;
        dash.peakStrength = std::max(dash.peakStrength, dash.points[index].strength);
    }
    dash.meanStrength = dash.points.empty() ? 0.0f : float(strengthSum / double(dash.points.size()));
}

/** The dashes of one stroke, in order along it. */
std::vector<Stroke> dashesOf(const Stroke& stroke, const DashPattern& pattern) {
    const double period = pattern.onPixels + pattern.offPixels;
    const std::size_t count = stroke.points.size();
    const bool closed = stroke.closed && count > 2;
    // The pattern's state at arc length s: drawn when s mod period < on.
    const auto drawnAt = [&](double s) { return std::fmod(s, period) < pattern.onPixels; };

    std::vector<Stroke> dashes;
    Stroke dash;
    dash.layer = stroke.layer;
    dash.chain = stroke.chain;
    dash.kept = true;
    const Stroke blank = dash;
    bool drawing = true; // s = 0 lies in the first dash
    dash.points.push_back(stroke.points[0]);
    dash.pixels.push_back(stroke.pixels[0]);
    const auto endDash = [&] {
        if (!dash.points.empty()) dashes.push_back(std::move(dash));
        dash = blank;
    };

    double s = 0.0;
    const std::size_t segments = closed ? count : count - 1;
    for (std::size_t segment = 0; segment < segments; ++segment) {
        const std::size_t to = (segment + 1) % count;
        const LinePoint& a = stroke.points[segment];
        const LinePoint& b = stroke.points[to];
        const double length = distance(a, b);
        const double end = s + length;
        // The pattern's boundaries strictly inside the segment, in order: k x period (a dash begins) and
        // k x period + on (it ends).
        for (double k = std::floor(s / period); k * period < end; k += 1.0) {
            for (const double boundary : {k * period, k * period + pattern.onPixels}) {
                if (!(boundary > s && boundary < end)) continue;
                const bool begins = boundary == k * period;
                if (begins == drawing) continue;
                const LinePoint cut = pointBetween(a, b, (boundary - s) / length);
                if (begins) {
                    dash.points.push_back(cut);
                    dash.pixels.emplace_back(-1, -1);
                } else {
                    dash.points.push_back(cut);
                    dash.pixels.emplace_back(-1, -1);
                    endDash();
                }
                drawing = begins;
            }
        }
        // The segment's end point; a boundary exactly on it ends or begins a dash with it.
        const bool drawnThere = drawnAt(end);
        if (drawing || drawnThere) {
            dash.points.push_back(b);
            dash.pixels.push_back(closed && to == 0 ? stroke.pixels[0] : stroke.pixels[to]);
        }
        if (drawing && !drawnThere) endDash();
        drawing = drawnThere;
        s = end;
    }
    if (!dash.points.empty()) {
        if (closed && drawing && !dashes.empty()) {
            // Round the seam: the last dash runs on into the first (both hold the first point: once).
            Stroke& first = dashes.front();
            dash.points.insert(dash.points.end(), first.points.begin() + 1, first.points.end());
            dash.pixels.insert(dash.pixels.end(), first.pixels.begin() + 1, first.pixels.end());
            first = std::move(dash);
        } else {
            dashes.push_back(std::move(dash));
        }
    }
    // A dash that begins on the stroke's very last point has no length: not drawn.
    dashes.erase(
        std::remove_if(dashes.begin(), dashes.end(), [](const Stroke& piece) { return piece.points.size() < 2; }),
        dashes.end());
    for (Stroke& piece : dashes) measureDash(piece);
    return dashes;
}

} // namespace

std::size_t dashStrokes(Strokes& strokes, int layer, const DashPattern& pattern) {
    if (!(std::isfinite(pattern.onPixels) && pattern.onPixels > 0.0 && std::isfinite(pattern.offPixels) &&
          pattern.offPixels >= 0.0))
        throw std::invalid_argument(
            "dashStrokes(): 'pattern' needs a dash above 0 and a gap of 0 or more pixels, got " +
            std::to_string(pattern.onPixels) + "," + std::to_string(pattern.offPixels));
    if (pattern.solid()) return 0;
    std::vector<Stroke> result;
    result.reserve(strokes.strokes.size());
    std::size_t made = 0;
    for (Stroke& stroke : strokes.strokes) {
        if (stroke.layer != layer || !stroke.kept || stroke.points.empty()) {
            result.push_back(std::move(stroke));
            continue;
        }
        if (stroke.lengthPixels <= pattern.onPixels) {
            ++made; // drawn whole: a dash of its own, as the picture and the SVG show it
            result.push_back(std::move(stroke));
            continue;
        }
        std::vector<Stroke> dashes = dashesOf(stroke, pattern);
        made += dashes.size();
        for (Stroke& dash : dashes) result.push_back(std::move(dash));
    }
    strokes.strokes = std::move(result);
    return made;
}

} // namespace inkgraph
