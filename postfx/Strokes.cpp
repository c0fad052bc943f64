#include "postfx/Strokes.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace inkgraph {
namespace {

/** The token strength of a stroke pixel with no point of its own (bridging a gap): it seeds nothing, and a stroke's
 *  opacity leaves it out. */
constexpr float kBridgeStrength = 1e-3f;

} // namespace

namespace {

constexpr double kDegrees = 3.14159265358979323846 / 180.0;
constexpr int kNone = -1;

/** A traced chain of one layer, at the data resolution. */
struct Branch {
    int layer = 0;
    std::vector<cv::Point2d> positions;
    std::vector<cv::Point> pixels; ///< in the layer's skeleton
    std::vector<float> strengths;
    double length = 0.0;
    bool loop = false; ///< closed with no end: a path of its own
};

/** One end of an open branch: side 0 is its first vertex, side 1 its last. */
struct End {
    std::size_t branch = 0;
    int side = 0;
    cv::Point2d position;
    cv::Point2d outward; ///< unit, pointing out of the branch past its end; zero for a lone pixel
    int partner = kNone; ///< the end it continues into
};

double lengthAlong(const std::vector<cv::Point2d>& points, bool closed) {
    double length = 0.0;
    for (std::size_t index = 1; index < points.size(); ++index) length += cv::norm(points[index] - points[index - 1]);
    if (closed && points.size() > 1) length += cv::norm(points.front() - points.back());
    return length;
}

/** The skeleton pixel a point belongs to: the one it rounds to when that is on, else the nearest on pixel around
 *  it (a kernel marks one pixel of a pair and places the point at the crossing between them, up to a pixel away);
 *  (-1, -1) when none is. */
cv::Point pixelOfPoint(const cv::Mat& mask, const cv::Point2f& position) {
    const double x = position.x, y = position.y;
    const double roundedCol = std::floor(x + 0.5), roundedRow = std::floor(y + 0.5);
    if (!(roundedCol >= -1 && roundedRow >= -1 && roundedCol <= mask.cols && roundedRow <= mask.rows)) return {-1, -1};
    const int col = int(roundedCol), row = int(roundedRow);
    auto on = [&](int c, int r) { return c >= 0 && r >= 0 && c < mask.cols && r < mask.rows && mask.at<uchar>(r, c); };
    if (on(col, row)) return {col, row};
    cv::Point best(-1, -1);
    double nearest = 0.0;
    for (int dr = -1; dr <= 1; ++dr)
        for (int dc = -1; dc <= 1; ++dc) {
            if (!on(col + dc, row + dr)) continue;
            const double distance = std::hypot(col + dc - x, row + dr - y);
            if (best.x < 0 || distance < nearest) {
                best = {col + dc, row + dr};
                nearest = distance;
            }
        }
    return best;
}

/** A float per pixel of `mask`: 0 on its set pixels, left unwritten elsewhere. The per-pixel maps below are read and
 *  written on a skeleton's own pixels only, so the rest (most of the frame: 4 MB a layer at 1024x1024) is never
 *  cleared. 32 mask bytes at a time: skeleton masks are mostly empty. */
cv::Mat1f zeroOnSetPixels(const cv::Mat& mask) {
    cv::Mat1f values(mask.size());
    for (int row = 0; row < mask.rows; ++row) {
        const uchar* set = mask.ptr<uchar>(row);
        float* value = values[row];
        int col = 0;
        for (; col + 32 <= mask.cols; col += 32) {
            std::uint64_t words[4];
            std::memcpy(words, set + col, sizeof words);
            if ((words[0] | words[1] | words[2] | words[3]) == 0) continue;
            for (int offset = col; offset < col + 32; ++offset)
                if (set[offset]) value[offset] = 0.0f;
        }
        for (; col < mask.cols; ++col)
            if (set[col]) value[col] = 0.0f;
    }
    return values;
}

/** The largest strength of the points belonging to each pixel of the skeleton (0 where none does), on the skeleton's
 *  pixels only (zeroOnSetPixels()): pixelOfPoint() and the traced chains never leave them. */
cv::Mat1f pixelStrengths(const LineSkeleton& skeleton) {
    cv::Mat1f strengths = zeroOnSetPixels(skeleton.mask);
    for (const LinePoint& point : skeleton.points) {
        const cv::Point pixel = pixelOfPoint(skeleton.mask, point.position);
        if (pixel.x < 0) continue;
        float& strength = strengths(pixel);
        strength = std::max(strength, point.strength);
    }
    return strengths;
}

/** Unit vector from the vertex `reach` back along the chain to its end (`fromStart` picks which end). */
cv::Point2d outwardAt(const std::vector<cv::Point2d>& points, bool fromStart, double reach) {
    const std::size_t count = points.size();
    const cv::Point2d end = fromStart ? points.front() : points.back();
    cv::Point2d inner = end;
    double travelled = 0.0;
    for (std::size_t step = 1; step < count; ++step) {
        const cv::Point2d& previous = fromStart ? points[step - 1] : points[count - step];
        inner = fromStart ? points[step] : points[count - 1 - step];
        travelled += cv::norm(inner - previous);
        if (travelled >= reach) break;
    }
    const cv::Point2d direction = end - inner;
    const double length = cv::norm(direction);
    return length > 1e-9 ? direction / length : cv::Point2d(0.0, 0.0);
}

double angleBetween(const cv::Point2d& a, const cv::Point2d& b) { return std::acos(std::clamp(a.dot(b), -1.0, 1.0)); }

void checkInputs(const std::vector<StrokeLayer>& layers, const StrokeSettings& settings) {
    cv::Size dataSize;
    for (std::size_t index = 0; index < layers.size(); ++index) {
        const StrokeLayer& layer = layers[index];
        const std::string name = "chainStrokes(): 'layers' [" + std::to_string(index) + "]";
        if (!layer.skeleton || layer.skeleton->mask.empty() || layer.skeleton->mask.type() != CV_8UC1)
            throw std::invalid_argument(name + " has no CV_8UC1 skeleton mask");
        if (layer.scale < 1) throw std::invalid_argument(name + " 'scale' must be at least 1");
        const cv::Size size(layer.skeleton->mask.cols * layer.scale, layer.skeleton->mask.rows * layer.scale);
        if (index == 0) dataSize = size;
        if (size != dataSize) throw std::invalid_argument(name + " is not at the first layer's data size");
        if (!std::isfinite(layer.minLengthPixels) || layer.minLengthPixels < 0.0)
            throw std::invalid_argument(name + " 'minLengthPixels' must be finite and >= 0");
        if (!(layer.seedStrength >= 0.0f && layer.seedStrength <= 1.0f))
            throw std::invalid_argument(name + " 'seedStrength' must lie in [0, 1]");
        if (!std::isfinite(layer.joinAllowancePixels) || layer.joinAllowancePixels < 0.0)
            throw std::invalid_argument(name + " 'joinAllowancePixels' must be finite and >= 0");
    }
    auto checkLength = [](double value, const char* field) {
        if (!std::isfinite(value) || value < 0.0)
            throw std::invalid_argument(std::string("chainStrokes(): 'settings.") + field +
                                        "' must be finite and >= 0");
    };
    checkLength(settings.joinRadiusPixels, "joinRadiusPixels");
    checkLength(settings.directionPixels, "directionPixels");
    checkLength(settings.absorbPixels, "absorbPixels");
    checkLength(settings.joinAngleDegrees, "joinAngleDegrees");
    if (settings.joinAngleDegrees > 180.0)
        throw std::invalid_argument("chainStrokes(): 'settings.joinAngleDegrees' must be at most 180");
}

std::vector<Branch> traceBranches(const std::vector<StrokeLayer>& layers) {
    std::vector<Branch> branches;
    for (std::size_t layerIndex = 0; layerIndex < layers.size(); ++layerIndex) {
        const StrokeLayer& layer = layers[layerIndex];
        const cv::Mat1f strengths = pixelStrengths(*layer.skeleton);
        const double scale = layer.scale;
        for (PixelChain& chain : tracePixelChains(*layer.skeleton)) {
            Branch branch;
            branch.layer = int(layerIndex);
            branch.pixels = std::move(chain.pixels);
            for (const cv::Point2d& position : chain.positions)
                branch.positions.push_back((position + cv::Point2d(0.5, 0.5)) * scale - cv::Point2d(0.5, 0.5));
            for (const cv::Point& pixel : branch.pixels) branch.strengths.push_back(strengths(pixel));
            if (chain.closed && chain.anchored) {
                // A loop back to its junction: an open chain whose two ends meet there, so they may join.
                branch.positions.push_back(branch.positions.front());
                branch.pixels.push_back(branch.pixels.front());
                branch.strengths.push_back(branch.strengths.front());
            }
            branch.loop = chain.closed && !chain.anchored;
            branch.length = lengthAlong(branch.positions, branch.loop);
            branches.push_back(std::move(branch));
        }
    }
    return branches;
}

std::vector<End> endsOf(const std::vector<Branch>& branches, double reach) {
    std::vector<End> ends;
    for (std::size_t index = 0; index < branches.size(); ++index) {
        const Branch& branch = branches[index];
        if (branch.loop) continue;
        for (int side = 0; side < 2; ++side) {
            End end;
            end.branch = index;
            end.side = side;
            end.position = side == 0 ? branch.positions.front() : branch.positions.back();
            end.outward = outwardAt(branch.positions, side == 0, reach);
            ends.push_back(end);
        }
    }
    return ends;
}

/** Step 2 of the file comment: pairs ends that continue one another, the best candidates first. */
void joinEnds(std::vector<End>& ends, const std::vector<Branch>& branches, const std::vector<StrokeLayer>& layers,
              const StrokeSettings& settings) {
    const auto allowanceOf = [&](const End& end) {
        return layers[std::size_t(branches[end.branch].layer)].joinAllowancePixels;
    };
    double widestAllowance = 0.0;
    for (const StrokeLayer& layer : layers) widestAllowance = std::max(widestAllowance, layer.joinAllowancePixels);
    const double maxTurn = settings.joinAngleDegrees * kDegrees;
    const double cell = std::max(settings.joinRadiusPixels + 2.0 * widestAllowance, 1.0);
    auto key = [&](const cv::Point2d& p) {
        return (std::int64_t(std::floor(p.x / cell)) << 32) ^ (std::int64_t(std::floor(p.y / cell)) & 0xffffffff);
    };
    std::unordered_map<std::int64_t, std::vector<int>> grid;
    for (std::size_t index = 0; index < ends.size(); ++index) grid[key(ends[index].position)].push_back(int(index));

    struct Candidate {
        double cost;
        int a, b;
    };
    std::vector<Candidate> candidates;
    for (std::size_t index = 0; index < ends.size(); ++index) {
        const End& a = ends[index];
        const std::int64_t col = std::int64_t(std::floor(a.position.x / cell));
        const std::int64_t row = std::int64_t(std::floor(a.position.y / cell));
        for (std::int64_t dr = -1; dr <= 1; ++dr)
            for (std::int64_t dc = -1; dc <= 1; ++dc) {
                const auto found = grid.find(((col + dc) << 32) ^ ((row + dr) & 0xffffffff));
                if (found == grid.end()) continue;
                for (const int other : found->second) {
                    if (other <= int(index)) continue;
                    const End& b = ends[std::size_t(other)];
                    const double radius = settings.joinRadiusPixels + allowanceOf(a) + allowanceOf(b);
                    const cv::Point2d gap = b.position - a.position;
                    const double distance = cv::norm(gap);
                    if (distance > radius) continue;
                    if (a.branch == b.branch && branches[a.branch].length <= 2.0 * radius) continue;
                    const bool aLone = a.outward == cv::Point2d(), bLone = b.outward == cv::Point2d();
                    if (aLone || bLone) {
                        // After every true continuation: a lone pixel has no direction to judge.
                        candidates.push_back(
                            {(aLone && bLone ? 4.0 : 2.0) + distance / std::max(radius, 1e-9), int(index), other});
                        continue;
                    }
                    const double turn = angleBetween(a.outward, -b.outward);
                    if (turn > maxTurn) continue;
                    if (distance > 0.75) {
                        const cv::Point2d across = gap / distance;
                        if (angleBetween(a.outward, across) > maxTurn || angleBetween(across, -b.outward) > maxTurn)
                            continue;
                    }
                    candidates.push_back(
                        {turn / std::max(maxTurn, 1e-9) + distance / std::max(radius, 1e-9), int(index), other});
                }
            }
    }
    std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
        return x.cost != y.cost ? x.cost < y.cost : (x.a != y.a ? x.a < y.a : x.b < y.b);
    });
    for (const Candidate& candidate : candidates) {
        End& a = ends[std::size_t(candidate.a)];
        End& b = ends[std::size_t(candidate.b)];
        if (a.partner != kNone || b.partner != kNone) continue;
        a.partner = candidate.b;
        b.partner = candidate.a;
    }
}

/** One branch as walked along a path. */
struct PathStep {
    std::size_t branch;
    bool forward;
};

/** Step 3: the paths the joined ends make, open ones from their free ends, then the cycles. */
std::vector<std::pair<std::vector<PathStep>, bool>> pathsOf(const std::vector<End>& ends,
                                                            const std::vector<Branch>& branches) {
    std::vector<int> endOf(branches.size() * 2, kNone); // branch * 2 + side -> end index
    for (std::size_t index = 0; index < ends.size(); ++index)
        endOf[ends[index].branch * 2 + std::size_t(ends[index].side)] = int(index);
    std::vector<char> visited(branches.size(), 0);
    std::vector<std::pair<std::vector<PathStep>, bool>> paths;

    auto walk = [&](int start) {
        std::vector<PathStep> steps;
        bool closed = false;
        int current = start;
        for (;;) {
            const End& entry = ends[std::size_t(current)];
            visited[entry.branch] = 1;
            steps.push_back({entry.branch, entry.side == 0});
            const int exit = endOf[entry.branch * 2 + std::size_t(1 - entry.side)];
            const int next = ends[std::size_t(exit)].partner;
            if (next == kNone) break;
            if (next == start) {
                closed = true;
                break;
            }
            if (visited[ends[std::size_t(next)].branch]) break;
            current = next;
        }
        paths.emplace_back(std::move(steps), closed);
    };
    for (std::size_t index = 0; index < ends.size(); ++index)
        if (ends[index].partner == kNone && !visited[ends[index].branch]) walk(int(index));
    for (std::size_t index = 0; index < ends.size(); ++index)
        if (!visited[ends[index].branch] && ends[index].side == 0) walk(int(index));
    for (std::size_t index = 0; index < branches.size(); ++index)
        if (branches[index].loop) paths.push_back({{{index, true}}, true});
    return paths;
}

/** A stroke's length and strengths, from its points. */
void measureStroke(Stroke& stroke) {
    std::vector<cv::Point2d> positions;
    double strengthSum = 0.0;
    stroke.peakStrength = 0.0f;
    for (const LinePoint& point : stroke.points) {
        positions.emplace_back(point.position.x, point.position.y);
        strengthSum += point.strength;
        stroke.peakStrength = std::max(stroke.peakStrength, point.strength);
    }
    stroke.lengthPixels = lengthAlong(positions, stroke.closed);
    stroke.meanStrength = stroke.points.empty() ? 0.0f : float(strengthSum / double(stroke.points.size()));
}

void finishStroke(Stroke& stroke, std::vector<Stroke>& strokes) {
    if (stroke.points.empty()) return;
    measureStroke(stroke);
    strokes.push_back(std::move(stroke));
}

/** Appends `tail`'s points to `head`, the shared point once. */
void appendStroke(Stroke& head, const Stroke& tail) {
    std::size_t first = 0;
    if (!head.points.empty() && !tail.points.empty() && head.points.back().position == tail.points.front().position)
        first = 1;
    head.points.insert(head.points.end(), tail.points.begin() + std::ptrdiff_t(first), tail.points.end());
    head.pixels.insert(head.pixels.end(), tail.pixels.begin() + std::ptrdiff_t(first), tail.pixels.end());
}

/** Step 3's fragments: a run of one layer shorter than `limit` between runs of others (a pixel or two of crease
 *  where a contour runs on) joins its longer neighbour, drawn from its traced positions in that neighbour's type;
 *  neighbours of one layer that then meet become one stroke. Returns how many runs were absorbed. */
std::size_t absorbFragments(std::vector<Stroke>& runs, double limit) {
    std::size_t absorbed = 0;
    while (runs.size() > 1) {
        std::size_t shortest = 0;
        for (std::size_t index = 1; index < runs.size(); ++index)
            if (runs[index].lengthPixels < runs[shortest].lengthPixels) shortest = index;
        if (runs[shortest].lengthPixels >= limit) break;
        std::size_t into = shortest == 0 ? 1 : shortest - 1;
        if (shortest > 0 && shortest + 1 < runs.size() &&
            runs[shortest + 1].lengthPixels > runs[shortest - 1].lengthPixels)
            into = shortest + 1;
        Stroke piece = std::move(runs[shortest]);
        std::fill(piece.pixels.begin(), piece.pixels.end(), cv::Point(-1, -1));
        piece.layer = runs[into].layer;
        if (into < shortest) {
            appendStroke(runs[into], piece);
        } else {
            appendStroke(piece, runs[into]);
            runs[into].points = std::move(piece.points);
            runs[into].pixels = std::move(piece.pixels);
        }
        runs.erase(runs.begin() + std::ptrdiff_t(shortest));
        ++absorbed;
        // Runs of one layer that now meet are one stroke.
        for (std::size_t index = 1; index < runs.size();) {
            if (runs[index].layer != runs[index - 1].layer) {
                ++index;
                continue;
            }
            appendStroke(runs[index - 1], runs[index]);
            runs.erase(runs.begin() + std::ptrdiff_t(index));
        }
        for (Stroke& run : runs) measureStroke(run);
    }
    return absorbed;
}

} // namespace

std::size_t Strokes::keptStrokes() const {
    return std::size_t(std::count_if(strokes.begin(), strokes.end(), [](const Stroke& s) { return s.kept; }));
}

std::size_t Strokes::droppedShort() const {
    return std::size_t(
        std::count_if(strokes.begin(), strokes.end(), [&](const Stroke& s) { return !chains[s.chain].longEnough; }));
}

std::size_t Strokes::droppedWeak() const {
    return std::size_t(std::count_if(strokes.begin(), strokes.end(), [&](const Stroke& s) {
        return chains[s.chain].longEnough && !chains[s.chain].seeded;
    }));
}

Strokes chainStrokes(const std::vector<StrokeLayer>& layers, const StrokeSettings& settings) {
    checkInputs(layers, settings);
    Strokes result;
    const std::vector<Branch> branches = traceBranches(layers);
    std::vector<End> ends = endsOf(branches, settings.directionPixels);
    joinEnds(ends, branches, layers, settings);

    for (const auto& [steps, closed] : pathsOf(ends, branches)) {
        const std::size_t chainIndex = result.chains.size();
        StrokeChain chain;
        chain.closed = closed;
        std::vector<Stroke> runs;
        Stroke stroke;
        stroke.layer = kNone;
        cv::Point2d last;
        float lastStrength = 0.0f;
        for (const PathStep& step : steps) {
            const Branch& branch = branches[step.branch];
            chain.lengthPixels += branch.length;
            const std::size_t count = branch.positions.size();
            std::size_t first = 0;
            if (stroke.layer != kNone) {
                const cv::Point2d entry = step.forward ? branch.positions.front() : branch.positions.back();
                const double gap = cv::norm(entry - last);
                chain.lengthPixels += gap;
                if (branch.layer != stroke.layer) {
                    ++result.crossTypeJoins;
                    finishStroke(stroke, runs);
                    stroke = {};
                    stroke.layer = kNone;
                } else if (gap < 1e-6) {
                    ++result.junctionJoins;
                    first = 1; // the shared junction pixel, once
                } else {
                    ++result.gapJoins;
                    // Bridging points every half pixel, strictly between the two ends.
                    const int pieces = int(std::ceil(gap / 0.5));
                    const float entryStrength = step.forward ? branch.strengths.front() : branch.strengths.back();
                    for (int piece = 1; piece < pieces; ++piece) {
                        const double t = double(piece) / pieces;
                        const cv::Point2d position = last + (entry - last) * t;
                        const float strength =
                            std::max(lastStrength + float(t) * (entryStrength - lastStrength), 1e-3f);
                        stroke.points.push_back({cv::Point2f(position), strength});
                        stroke.pixels.emplace_back(-1, -1);
                    }
                }
            }
            if (stroke.layer == kNone) {
                stroke.layer = branch.layer;
                stroke.chain = chainIndex;
            }
            for (std::size_t k = first; k < count; ++k) {
                const std::size_t index = step.forward ? k : count - 1 - k;
                // A pixel with no point of its own (strength 0) keeps a token strength, so every stroke point is a
                // valid LinePoint; it seeds nothing.
                const float strength = std::max(branch.strengths[index], kBridgeStrength);
                stroke.points.push_back({cv::Point2f(branch.positions[index]), strength});
                stroke.pixels.push_back(branch.pixels[index]);
            }
            last = stroke.points.empty() ? last : cv::Point2d(stroke.points.back().position);
            lastStrength = stroke.points.empty() ? 0.0f : stroke.points.back().strength;
        }
        finishStroke(stroke, runs);
        result.absorbedFragments += absorbFragments(runs, settings.absorbPixels);
        if (closed) {
            const Branch& firstBranch = branches[steps.front().branch];
            const cv::Point2d start =
                steps.front().forward ? firstBranch.positions.front() : firstBranch.positions.back();
            const double gap = cv::norm(start - last);
            if (steps.size() > 1 || !firstBranch.loop) chain.lengthPixels += gap;
            if (runs.size() == 1) {
                Stroke& loop = runs.front();
                loop.closed = true;
                // The closing junction pixel is the first point already.
                if (loop.points.size() > 1 && loop.points.back().position == loop.points.front().position) {
                    loop.points.pop_back();
                    loop.pixels.pop_back();
                }
                measureStroke(loop);
            }
        }
        for (Stroke& run : runs) result.strokes.push_back(std::move(run));
        result.chains.push_back(chain);
    }

    // Step 4: the rules, per chain.
    for (StrokeChain& chain : result.chains) {
        chain.longEnough = true;
        chain.seeded = false;
    }
    for (const Stroke& stroke : result.strokes) {
        StrokeChain& chain = result.chains[stroke.chain];
        const StrokeLayer& layer = layers[std::size_t(stroke.layer)];
        if (chain.lengthPixels < layer.minLengthPixels) chain.longEnough = false;
        if (layer.seedStrength <= 0.0f || stroke.peakStrength >= layer.seedStrength) chain.seeded = true;
    }
    for (Stroke& stroke : result.strokes) stroke.kept = result.chains[stroke.chain].kept();
    return result;
}

double strokeSpanBiasPixels(double heightPixels) { return strokeSpanBiasPixels(heightPixels, 1.0); }

double strokeSpanBiasPixels(double heightPixels, double samplePixels) {
    if (!std::isfinite(heightPixels) || heightPixels <= 0.0)
        throw std::invalid_argument("strokeSpanBiasPixels(): 'heightPixels' must be finite and > 0, got " +
                                    std::to_string(heightPixels));
    if (!std::isfinite(samplePixels) || samplePixels <= 0.0)
        throw std::invalid_argument("strokeSpanBiasPixels(): 'samplePixels' must be finite and > 0, got " +
                                    std::to_string(samplePixels));
    return std::max(0.0, heightPixels / kLengthReferenceRows - samplePixels);
}

double strokeJoinAllowancePixels(double heightPixels, double samplePixels) {
    return 0.5 * (strokeSpanBiasPixels(heightPixels) - strokeSpanBiasPixels(heightPixels, samplePixels));
}

double strokeLengthLimitPixels(double share, double heightPixels) {
    return strokeLengthLimitPixels(share, heightPixels, 1.0);
}

double strokeLengthLimitPixels(double share, double heightPixels, double samplePixels) {
    if (!std::isfinite(share) || share < 0.0)
        throw std::invalid_argument("strokeLengthLimitPixels(): 'share' must be finite and >= 0, got " +
                                    std::to_string(share));
    if (!std::isfinite(heightPixels) || heightPixels <= 0.0)
        throw std::invalid_argument("strokeLengthLimitPixels(): 'heightPixels' must be finite and > 0, got " +
                                    std::to_string(heightPixels));
    if (share == 0.0) return 0.0;
    return share * heightPixels + strokeSpanBiasPixels(heightPixels, samplePixels);
}

StrokeSettings strokeSettingsFor(double outputRows, int supersample) {
    if (!std::isfinite(outputRows) || outputRows <= 0.0)
        throw std::invalid_argument("strokeSettingsFor(): 'outputRows' must be finite and > 0, got " +
                                    std::to_string(outputRows));
    if (supersample < 1)
        throw std::invalid_argument("strokeSettingsFor(): 'supersample' must be >= 1, got " +
                                    std::to_string(supersample));
    const double scaledRadius = std::max(2.0, kJoinRadiusAt1024 * outputRows / kLengthReferenceRows) * supersample;
    StrokeSettings settings;
    settings.joinRadiusPixels = scaledRadius - strokeSpanBiasPixels(outputRows * supersample);
    settings.directionPixels = 2.0 * scaledRadius;
    settings.absorbPixels = 2.0 * scaledRadius;
    return settings;
}

StrokesNearLimits strokesNearLimits(const Strokes& strokes, const std::vector<StrokeLayer>& layers, double share) {
    if (!std::isfinite(share) || share < 0.0 || share >= 1.0)
        throw std::invalid_argument("strokesNearLimits(): 'share' must be finite and in [0, 1), got " +
                                    std::to_string(share));
    // Per chain, the strongest peak over its layer's seed strength; infinite once a stroke's layer always seeds.
    std::vector<double> seedRatio(strokes.chains.size(), 0.0);
    for (const Stroke& stroke : strokes.strokes) {
        if (stroke.layer < 0 || std::size_t(stroke.layer) >= layers.size())
            throw std::invalid_argument("strokesNearLimits(): stroke layer " + std::to_string(stroke.layer) +
                                        " is not in 'layers' (" + std::to_string(layers.size()) + ")");
        const float seed = layers[std::size_t(stroke.layer)].seedStrength;
        double& ratio = seedRatio[stroke.chain];
        ratio = std::max(ratio, seed > 0.0f ? double(stroke.peakStrength) / double(seed)
                                            : std::numeric_limits<double>::infinity());
    }
    StrokesNearLimits near{std::vector<std::size_t>(layers.size(), 0), std::vector<std::size_t>(layers.size(), 0)};
    for (const Stroke& stroke : strokes.strokes) {
        const StrokeLayer& layer = layers[std::size_t(stroke.layer)];
        const double limit = layer.minLengthPixels;
        if (limit > 0.0 && std::abs(strokes.chains[stroke.chain].lengthPixels - limit) <= share * limit)
            ++near.length[std::size_t(stroke.layer)];
        if (layer.seedStrength > 0.0f && std::abs(seedRatio[stroke.chain] - 1.0) <= share)
            ++near.seed[std::size_t(stroke.layer)];
    }
    return near;
}

void mergeOverlaps(Strokes& strokes, const std::vector<StrokeLayer>& layers, const std::vector<double>& halfWidths) {
    if (halfWidths.size() != layers.size())
        throw std::invalid_argument("mergeOverlaps(): 'halfWidths' must hold one width per layer");
    if (layers.empty()) return;
    const cv::Size dataSize(layers[0].skeleton->mask.cols * layers[0].scale,
                            layers[0].skeleton->mask.rows * layers[0].scale);
    // 0 on the pixels earlier layers draw along, for the distance transform.
    cv::Mat notDrawn(dataSize, CV_8UC1, cv::Scalar(255));
    auto pixelOf = [&](const LinePoint& point) {
        return cv::Point(std::clamp(int(std::lround(point.position.x)), 0, dataSize.width - 1),
                         std::clamp(int(std::lround(point.position.y)), 0, dataSize.height - 1));
    };
    double earlierHalfWidth = 0.0;
    for (std::size_t layer = 0; layer < layers.size(); ++layer) {
        if (layer > 0) {
            cv::Mat distance;
            cv::distanceTransform(notDrawn, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
            const double reach = halfWidths[layer] + earlierHalfWidth;
            for (Stroke& stroke : strokes.strokes) {
                if (stroke.layer != int(layer) || !stroke.kept) continue;
                // A stroke mostly along an earlier type's is that line drawn again: it gives way whole. Deciding per
                // stroke, not per point, leaves no scattered pieces where the two lines part by about the reach.
                std::size_t covered = 0;
                for (const LinePoint& point : stroke.points) covered += distance.at<float>(pixelOf(point)) <= reach;
                if (2 * covered >= stroke.points.size()) {
                    stroke.kept = false;
                    strokes.overlapsMerged += 1;
                }
            }
        }
        for (const Stroke& stroke : strokes.strokes)
            if (stroke.layer == int(layer) && stroke.kept)
                for (const LinePoint& point : stroke.points) notDrawn.at<uchar>(pixelOf(point)) = 0;
        earlierHalfWidth = std::max(earlierHalfWidth, halfWidths[layer]);
    }
}

void weighStrokes(Strokes& strokes, const LineWeightSettings& weight, const cv::Mat& depth, cv::Size dataSize) {
    if (!weight.any()) return;
    const bool byDepth = weight.farWidth != 1.0;
    if (byDepth && (depth.type() != CV_32FC1 || depth.size() != dataSize))
        throw std::invalid_argument("weighStrokes(): 'depth' must be CV_32FC1 at the data size");
    auto depthAt = [&](const cv::Point2f& position) {
        const int col = int(std::lround(std::clamp(position.x, 0.0f, float(depth.cols - 1))));
        const int row = int(std::lround(std::clamp(position.y, 0.0f, float(depth.rows - 1))));
        float nearest = depth.at<float>(row, col);
        if (nearest > 0.0f) return double(nearest);
        // Lines beside the model (silhouettes, outlines) take the nearest surface next to them.
        for (int dr = -3; dr <= 3; ++dr)
            for (int dc = -3; dc <= 3; ++dc) {
                const int r = row + dr, c = col + dc;
                if (r < 0 || c < 0 || r >= depth.rows || c >= depth.cols) continue;
                const float z = depth.at<float>(r, c);
                if (z > 0.0f && (nearest <= 0.0f || z < nearest)) nearest = z;
            }
        return nearest > 0.0f ? double(nearest) : weight.farDepth;
    };
    const double depthSpan = weight.farDepth - weight.nearDepth;
    for (Stroke& stroke : strokes.strokes) {
        if (!stroke.kept) continue;
        // Arc length to each point, for the taper.
        std::vector<double> along(stroke.points.size(), 0.0);
        for (std::size_t index = 1; index < stroke.points.size(); ++index)
            along[index] =
                along[index - 1] + cv::norm(stroke.points[index].position - stroke.points[index - 1].position);
        const double taper = stroke.closed ? 0.0 : std::min(weight.taperPixels, 0.5 * stroke.lengthPixels);
        for (std::size_t index = 0; index < stroke.points.size(); ++index) {
            LinePoint& point = stroke.points[index];
            double share = point.width; // a band of varying width's own (StrokesPass), else 1
            if (byDepth) {
                const double t = depthSpan > 0.0
                                     ? std::clamp((depthAt(point.position) - weight.nearDepth) / depthSpan, 0.0, 1.0)
                                     : 0.0;
                share *= 1.0 + (weight.farWidth - 1.0) * t;
            }
            share *= 1.0 - weight.strengthShare + weight.strengthShare * point.strength;
            if (taper > 0.0) {
                const double fromEnd = std::min(along[index], stroke.lengthPixels - along[index]) / taper;
                if (fromEnd < 1.0) share *= weight.taperStart + (1.0 - weight.taperStart) * std::max(fromEnd, 0.0);
            }
            point.width = float(std::clamp(share, 0.02, 1.0));
        }
    }
}

LineSkeleton keptSkeleton(const Strokes& strokes, const std::vector<StrokeLayer>& layers, int layer) {
    const StrokeLayer& source = layers.at(std::size_t(layer));
    const cv::Mat& mask = source.skeleton->mask;
    const cv::Size dataSize(mask.cols * source.scale, mask.rows * source.scale);
    LineSkeleton kept;
    kept.mask = cv::Mat::zeros(dataSize, CV_8UC1);
    auto mark = [&](const cv::Point2f& position) {
        const double col = std::floor(double(position.x) + 0.5), row = std::floor(double(position.y) + 0.5);
        if (col >= 0 && row >= 0 && col < dataSize.width && row < dataSize.height)
            kept.mask.at<uchar>(int(row), int(col)) = 255;
    };
    // Written and read on the skeleton's pixels only (zeroOnSetPixels()): a stroke's own pixels are its layer's, and
    // pixelOfPoint() gives set pixels.
    cv::Mat1f widthAt = source.scale == 1 ? zeroOnSetPixels(mask) : cv::Mat1f();
    // A coarser layer's traced positions lie `scale` data pixels apart: the points between two of them, at most a
    // data pixel apart, as a layer found at the data size has them.
    auto fillBetween = [&](const LinePoint& from, const LinePoint& to) {
        const cv::Point2f step = to.position - from.position;
        const int parts = int(std::ceil(std::hypot(double(step.x), double(step.y))));
        for (int part = 1; part < parts; ++part) {
            const float t = float(part) / float(parts);
            LinePoint between = from;
            between.position = from.position + step * t;
            between.strength = from.strength + (to.strength - from.strength) * t;
            between.width = from.width + (to.width - from.width) * t;
            kept.points.push_back(between);
            mark(between.position);
        }
    };
    for (const Stroke& stroke : strokes.strokes) {
        if (!stroke.kept || stroke.layer != layer) continue;
        for (std::size_t index = 0; index < stroke.points.size(); ++index) {
            const cv::Point& pixel = stroke.pixels[index];
            if (source.scale == 1 && pixel.x >= 0) {
                if (mask.at<uchar>(pixel) == 0) continue; // never read back: see above
                float& width = widthAt(pixel);
                width = std::max(width, stroke.points[index].width);
            } else {
                // Bridging points, and a coarser layer's traced positions, are drawn as they are.
                if (source.scale > 1 && index > 0) fillBetween(stroke.points[index - 1], stroke.points[index]);
                kept.points.push_back(stroke.points[index]);
                mark(stroke.points[index].position);
            }
        }
        if (source.scale > 1 && stroke.closed && stroke.points.size() > 1)
            fillBetween(stroke.points.back(), stroke.points.front());
    }
    if (source.scale == 1) {
        for (const LinePoint& point : source.skeleton->points) {
            const cv::Point pixel = pixelOfPoint(mask, point.position);
            if (pixel.x < 0) continue;
            const float width = widthAt(pixel);
            if (width <= 0.0f) continue;
            LinePoint drawn = point;
            drawn.width = width;
            kept.points.push_back(drawn);
            kept.mask.at<uchar>(pixel) = 255;
        }
    }
    return kept;
}

namespace {

/** Adds to `kept` (indices into `stroke`'s points, ascending, the simplified polyline's) the points where the width
 *  leaves its straight interpolation between kept neighbours (by arc length) by more than `tolerancePixels` on either
 *  side of the line: half the width's change, at `widthPixels` data pixels per width share. Ramer-Douglas-Peucker on
 *  the width profile, so a straight stroke keeps its taper. A closed stroke's last span runs back to its first point.
 */
std::vector<std::size_t> keepWidthProfile(const Stroke& stroke, std::vector<std::size_t> kept, bool closed,
                                          double tolerancePixels, double widthPixels) {
    const std::size_t count = stroke.points.size();
    if (kept.empty() || count < 3) return kept;
    // Arc length along the stroke, one entry more for a closed stroke's way back to its start.
    std::vector<double> along(count + 1, 0.0);
    for (std::size_t index = 1; index <= count; ++index) {
        const cv::Point2f step = stroke.points[index % count].position - stroke.points[index - 1].position;
        along[index] = along[index - 1] + std::hypot(double(step.x), double(step.y));
    }
    const auto arcAt = [&](std::size_t index) {
        return index <= count ? along[index] : along[count] + along[index - count];
    };
    const auto widthAt = [&](std::size_t index) { return double(stroke.points[index % count].width); };
    std::vector<char> keep(count, 0);
    for (const std::size_t index : kept) keep[index] = 1;
    std::vector<std::pair<std::size_t, std::size_t>> spans;
    for (std::size_t k = 0; k + 1 < kept.size(); ++k) spans.emplace_back(kept[k], kept[k + 1]);
    if (closed) spans.emplace_back(kept.back(), count + kept.front());
    while (!spans.empty()) {
        const auto [from, to] = spans.back();
        spans.pop_back();
        const double length = arcAt(to) - arcAt(from);
        std::size_t farthest = 0;
        double deviation = 0.0;
        for (std::size_t index = from + 1; index < to; ++index) {
            const double t = length > 0.0 ? (arcAt(index) - arcAt(from)) / length : 0.0;
            const double straight = widthAt(from) + t * (widthAt(to) - widthAt(from));
            const double off = 0.5 * std::abs(widthAt(index) - straight) * widthPixels;
            if (off > deviation) deviation = off, farthest = index;
        }
        // Within the tolerance, but never more than an eighth of the full width (a 3 px taper is all within a
        // tolerance of 2 px, and kept no width at all); at tolerance 0 a float's rounding is no change of width.
        if (deviation <= std::max(std::min(tolerancePixels, 0.125 * widthPixels), 1e-4)) continue;
        keep[farthest % count] = 1;
        spans.emplace_back(from, farthest);
        spans.emplace_back(farthest, to);
    }
    kept.clear();
    for (std::size_t index = 0; index < count; ++index)
        if (keep[index]) kept.push_back(index);
    return kept;
}

} // namespace

std::vector<Polyline> strokePolylines(const Strokes& strokes, int layer, double tolerancePixels,
                                      std::vector<std::vector<float>>* widths, double widthPixels) {
    std::vector<Polyline> polylines;
    if (widths) widths->clear();
    for (const Stroke& stroke : strokes.strokes) {
        if (!stroke.kept || stroke.layer != layer) continue;
        Polyline full;
        full.closed = stroke.closed && stroke.points.size() > 2;
        for (const LinePoint& point : stroke.points) full.points.push_back(point.position);
        Polyline simplified = simplifyPolyline(full, tolerancePixels, true);
        if (widths) {
            // The simplified vertices are some of the stroke's own, in order: match them up, then keep the points
            // the width profile needs.
            std::vector<std::size_t> kept;
            std::size_t next = 0;
            for (const cv::Point2f& vertex : simplified.points) {
                while (next + 1 < full.points.size() && full.points[next] != vertex) ++next;
                kept.push_back(next);
            }
            kept = keepWidthProfile(stroke, std::move(kept), simplified.closed, tolerancePixels, widthPixels);
            simplified.points.clear();
            std::vector<float> vertexWidths;
            for (const std::size_t index : kept) {
                simplified.points.push_back(full.points[index]);
                vertexWidths.push_back(stroke.points[index].width);
            }
            widths->push_back(std::move(vertexWidths));
        }
        polylines.push_back(std::move(simplified));
    }
    return polylines;
}

std::vector<float> strokeOpacities(const Strokes& strokes, int layer) {
    std::vector<float> opacities;
    for (const Stroke& stroke : strokes.strokes) {
        if (!stroke.kept || stroke.layer != layer) continue;
        double sum = 0.0;
        std::size_t count = 0;
        for (const LinePoint& point : stroke.points)
            if (point.strength > kBridgeStrength) sum += point.strength, ++count;
        opacities.push_back(count > 0 ? float(sum / double(count)) : 1.0f);
    }
    return opacities;
}

} // namespace inkgraph
