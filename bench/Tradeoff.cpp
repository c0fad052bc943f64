#include "bench/Tradeoff.h"

#include "bench/Median.h"

#include "render/StillRenderer.h"
#include "passes/StillGraph.h"
#include "passes/lines/LineLayerPass.h"
#include "passes/lines/types/SuggestiveLines.h"

#include <nlohmann/json.hpp>
#include "gl/GraphExecutor.h"
#include "gl/HeadlessContext.h"
#include "gl/TexturePool.h"
#include "graph/GraphCompiler.h"
#include "passes/lines/LineTypes.h"
#include "scene/Camera.h"
#include "scene/mesh/Procedural.h"
#include "tests/support/AnalyticLines.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <functional>
#include <cmath>
#include <iomanip>
#include <map>
#include <memory>
#include <ostream>
#include <sstream>
#include <stdexcept>

namespace inkgraph::bench {
namespace {

constexpr double kTorusRing = 1.0;
constexpr double kTorusTube = 0.4;
constexpr double kTorusDistance = 5.0;
constexpr double kTorusElevationDegrees = 30.0;
constexpr double kSphereDistance = 4.0;
constexpr double kFovDegrees = 35.0;

/** Where a scene is seen from: the GL camera's request and the analytic camera of the ground truth, which agree. */
struct View {
    glm::dvec3 eye;
    glm::dvec3 up;
    int size;

    test::SyntheticCamera analytic() const {
        test::SyntheticCamera camera;
        camera.width = camera.height = size;
        camera.eye = eye;
        camera.target = glm::dvec3(0.0);
        camera.up = up;
        camera.fovYDegrees = kFovDegrees;
        return camera;
    }
    CameraRequest request() const {
        CameraRequest camera;
        camera.eye = eye;
        camera.target = glm::dvec3(0.0);
        camera.up = up;
        camera.fovYDegrees = kFovDegrees;
        camera.width = camera.height = size;
        return camera;
    }
};

View torusView(int size) {
    const double elevation = glm::radians(kTorusElevationDegrees);
    return {{0.0, -kTorusDistance * std::cos(elevation), kTorusDistance * std::sin(elevation)}, {0.0, 0.0, 1.0}, size};
}

View sphereView(int size) { return {{0.0, 0.0, kSphereDistance}, {0.0, 1.0, 0.0}, size}; }

/** One still of `look` from `view`, set up as the renderer sets it up, run warm. */
class WarmRender {
public:
    WarmRender(const Scene& scene, const View& view, Look look, const std::vector<std::string>& requested)
        : mScene(scene), mLook(std::move(look)), mSize(view.size) {
        mSphere = computeBoundingSphere(mScene);
        mFrame = frameParamsOf(mLook, mScene, resolveCamera(view.request(), mScene), mSphere);
        mGpuScene = makeSceneImport(mScene, mFrame.worldOrigin, mFrame, mLook);
        mGraph = buildStillGraph({mLook, mShaders, mScene, mSphere, *mGpuScene, mFrame, std::nullopt});
        std::vector<std::string> resources = {mGraph.finalResource};
        resources.insert(resources.end(), requested.begin(), requested.end());
        // The skeletons stay in the store for linePoints().
        for (const std::string& type : mLook.lines)
            if (mGraph.lineLayer(type) != nullptr) resources.push_back(type + ".skeleton");
        mPlan = compile(mGraph.view(), resources);
    }

    /** Runs once; returns each pass's execute() + prepare() milliseconds by name. */
    std::map<std::string, double> run() {
        ExecuteOptions execute;
        execute.frameWidth = mSize;
        execute.frameHeight = mSize;
        std::map<std::string, double> milliseconds;
        for (const PassTiming& timing : mExecutor.run(mPlan, mGraph.mutableView(), execute))
            milliseconds[timing.pass] = timing.milliseconds + timing.prepareMilliseconds;
        return milliseconds;
    }

    const Look& look() const { return mLook; }
    const StillGraph& graph() const { return mGraph; }
    const BoundingSphere& sphere() const { return mSphere; }
    ResourceStore& store() { return mExecutor.store(); }

private:
    const Scene& mScene;
    Look mLook;
    int mSize;
    BoundingSphere mSphere;
    FrameParams mFrame;
    ShaderLibrary mShaders;
    std::unique_ptr<GpuScene> mGpuScene;
    StillGraph mGraph;
    TexturePool mPool;
    GraphExecutor mExecutor{mPool};
    Plan mPlan;
};

struct Timings {
    double frame = 0.0;
    double method = 0.0;
    double setup = 0.0; ///< one-off derived data of the first (warm-up) run: the object-space curvature
};

/** One untimed warm-up (shader variants compile on the first draw, curvature is derived), then `repetitions` timed
 *  runs. */
Timings timeRuns(WarmRender& render, const std::vector<std::string>& methodPasses, int repetitions) {
    auto total = [](const std::map<std::string, double>& times) {
        double sum = 0.0;
        for (const auto& [pass, ms] : times) sum += ms;
        return sum;
    };
    render.run();
    double setup = 0.0;
    if (const LineLayerPass* object = render.graph().lineLayer("suggestive-object")) {
        nlohmann::ordered_json report;
        object->describe(report);
        setup = report.value("curvature_ms", 0.0);
    }
    std::vector<double> frames, methods;
    for (int i = 0; i < repetitions; ++i) {
        const std::map<std::string, double> times = render.run();
        frames.push_back(total(times));
        double method = 0.0;
        for (const std::string& pass : methodPasses)
            if (auto found = times.find(pass); found != times.end()) method += found->second;
        methods.push_back(method);
    }
    return {median(frames), median(methods), setup};
}

/** The points a line layer found, in output pixels. */
std::vector<cv::Point2d> linePoints(const WarmRender& render, const std::string& type) {
    return outputPixelPositions(const_cast<WarmRender&>(render).store().object<LineSkeleton>(type + ".skeleton"),
                                render.look().supersample);
}

/** Pixels where the shading changes between 4-neighbours that both lie on the model: the band boundaries. */
cv::Mat bandBoundaries(const cv::Mat& shade, const cv::Mat& coverage) {
    cv::Mat boundaries = cv::Mat::zeros(shade.size(), CV_8UC1);
    for (int row = 0; row + 1 < shade.rows; ++row) {
        for (int col = 0; col + 1 < shade.cols; ++col) {
            if (!coverage.at<uchar>(row, col)) continue;
            const cv::Vec4b here = shade.at<cv::Vec4b>(row, col);
            for (const cv::Point next : {cv::Point(col + 1, row), cv::Point(col, row + 1)}) {
                if (!coverage.at<uchar>(next)) continue;
                const cv::Vec4b there = shade.at<cv::Vec4b>(next);
                if (here[0] != there[0] || here[1] != there[1] || here[2] != there[2])
                    boundaries.at<uchar>(row, col) = 255;
            }
        }
    }
    return boundaries;
}

/** Only the lines of `type`, no shading. */
Look linesOnly(const std::string& type) {
    Look look;
    look.shading = ShadingModel::None;
    look.lines = {type};
    return look;
}

const LineParameter& stencilParameter() {
    for (const LineParameter* parameter : findLineType("suggestive")->parameters)
        if (parameter->name == "suggestive-stencil") return *parameter;
    throw std::logic_error("stencilParameter(): the suggestive type has no 'suggestive-stencil'");
}

void halfPrecision(Look& look) { look.gbufferPrecision = GBufferPrecision::Float16; }
void fivePointStencil(Look& look) { look.lineParameters.set(stencilParameter(), std::string("5")); }

/** The suggestive stencil's points (3 or 5) of a look. */
std::string stencilPoints(const Look& look) { return look.lineParameters.choice(stencilParameter()); }

std::string thousands(std::size_t triangles) {
    return triangles >= 1000 ? std::to_string((triangles + 500) / 1000) + "k" : std::to_string(triangles);
}

class Sweep {
public:
    Sweep(const TradeoffConfig& config, std::ostream& progress) : mConfig(config), mProgress(progress) {}

    std::vector<TradeoffRow> run() {
        static HeadlessContext context; // one per process, shared by every row
        const int base = mConfig.quick ? 256 : 1024;
        const std::vector<int> sizes = mConfig.quick ? std::vector<int>{128, 256} : std::vector<int>{512, 1024, 2048};
        const std::vector<int> supersamples = mConfig.quick ? std::vector<int>{2} : std::vector<int>{2, 4};
        const Scene torus = makeScene(
            makeTorus(float(kTorusRing), float(kTorusTube), mConfig.quick ? 256 : 512, mConfig.quick ? 128 : 256));

        for (const char* type : {"contour", "suggestive"}) {
            if (!runs(type)) continue;
            for (int size : sizes) lineRow(torus, type, size);
            for (int supersample : supersamples)
                lineRow(torus, type, base, [&](Look& look) { look.supersample = supersample; });
            lineRow(torus, type, base, halfPrecision);
        }
        // The contour's kernel as a compute shader (--post-stage gpu): the same lines to 1e-3 px, another cost.
        if (runs("contour")) {
            const auto gpu = [](Look& look) { look.postStage = PostStageDevice::Gpu; };
            for (int size : sizes) lineRow(torus, "contour", size, gpu);
            for (int supersample : supersamples)
                lineRow(torus, "contour", base, [&](Look& look) {
                    gpu(look);
                    look.supersample = supersample;
                });
        }
        if (!mConfig.onlyMethod.empty()) return std::move(mRows);
        lineRow(torus, "suggestive", base, fivePointStencil);
        lineRow(torus, "suggestive", base, [&](Look& look) {
            halfPrecision(look);
            fivePointStencil(look);
        });
        for (const double threshold : {0.0, 0.05})
            lineRow(torus, "suggestive", base,
                    [&](Look& look) { look.lineParameters.set(line_parameters::kSuggestiveThreshold, threshold); });

        // Object space: the accuracy follows the mesh, so the torus at three tessellations; curvature is derived on
        // the first frame (setup) and reused.
        const std::vector<int> objectSegments =
            mConfig.quick ? std::vector<int>{64, 256} : std::vector<int>{64, 256, 512};
        for (int segments : objectSegments) {
            const Scene mesh = segments == (mConfig.quick ? 256 : 512)
                                   ? torus
                                   : makeScene(makeTorus(float(kTorusRing), float(kTorusTube), segments, segments / 2));
            lineRow(mesh, "suggestive-object", base);
        }
        lineRow(torus, "suggestive-object", base, [](Look& look) { look.supersample = 2; });

        const std::vector<int> sphereSegments =
            mConfig.quick ? std::vector<int>{32, 128} : std::vector<int>{32, 128, 512};
        for (int segments : sphereSegments) {
            const Scene sphere = makeScene(makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, segments, segments / 2));
            for (const char* type : {"contour", "mesh-silhouette"}) sphereRow(sphere, type, base, segments);
        }

        shadingRows(torus, base);
        return std::move(mRows);
    }

private:
    bool runs(const std::string& method) const { return mConfig.onlyMethod.empty() || mConfig.onlyMethod == method; }

    /** Ground truth for the torus at `size`: the contours, or the suggestive contours at `threshold`. */
    const std::vector<LinePolyline>& torusTruth(const std::string& type, int size, double threshold,
                                                double featureSize) {
        const std::string key = type + " " + std::to_string(size) + " " + std::to_string(threshold);
        auto found = mTruth.find(key);
        if (found != mTruth.end()) return found->second;
        const test::SyntheticCamera camera = torusView(size).analytic();
        std::vector<LinePolyline> truth;
        if (type == "contour") {
            truth = test::torusContours(camera, glm::dvec3(0.0), kTorusRing, kTorusTube);
        } else {
            test::AnalyticSuggestiveSettings settings;
            settings.featureSize = featureSize;
            settings.threshold = threshold;
            truth = test::torusSuggestiveContours(camera, glm::dvec3(0.0), kTorusRing, kTorusTube, settings);
        }
        return mTruth.emplace(key, std::move(truth)).first->second;
    }

    void lineRow(const Scene& scene, const std::string& type, int size, const std::function<void(Look&)>& adjust = {}) {
        Look look = linesOnly(type);
        if (adjust) adjust(look);
        WarmRender render(scene, torusView(size), look, {});
        const Timings timings = timeRuns(render, {"gbuffer", type}, mConfig.repetitions);
        const double threshold = look.lineParameters.number(line_parameters::kSuggestiveThreshold);
        const double featureSize = kSuggestiveFeatureSizeFraction * render.sphere().radius;
        const std::vector<cv::Point2d> points = linePoints(render, type);
        const std::vector<LinePolyline>& truth = torusTruth(type == "contour" ? "contour" : "suggestive", size,
                                                            type == "contour" ? 0.0 : threshold, featureSize);

        TradeoffRow row;
        row.method = type;
        std::ostringstream setting;
        setting << size << " S" << look.supersample;
        if (type == "suggestive-object")
            setting << " T" << threshold << " " << thousands(scene.triangleCount()) << " tris";
        else
            setting << (look.gbufferPrecision == GBufferPrecision::Float16 ? " half" : " float");
        if (type == "suggestive") setting << " " << stencilPoints(look) << "-point T" << threshold;
        if (look.postStage == PostStageDevice::Gpu) setting << " gpu";
        row.setting = setting.str();
        row.scene = "torus " + thousands(scene.triangleCount());
        finish(row, size, look.supersample, scene.triangleCount(), timings, points, truth);
    }

    void sphereRow(const Scene& scene, const std::string& type, int size, int segments) {
        WarmRender render(scene, sphereView(size), linesOnly(type), {});
        const Timings timings =
            timeRuns(render, {type == "contour" ? "gbuffer" : "mesh-edges", type}, mConfig.repetitions);
        const std::vector<LinePolyline> truth =
            test::sphereSilhouette(sphereView(size).analytic(), glm::dvec3(0.0), 1.0);
        TradeoffRow row;
        row.method = type == "contour" ? "contour (sphere)" : type;
        row.setting = std::to_string(size) + " " + std::to_string(segments) + " segments";
        row.scene = "sphere " + std::to_string(segments);
        finish(row, size, 1, scene.triangleCount(), timings, linePoints(render, type), truth);
    }

    /** Comic shading's approximations against its exact mode: band boundaries scored as lines. */
    void shadingRows(const Scene& scene, int size) {
        struct Mode {
            ViewVectorMode viewVector;
            FaceOrientationMethod orientation;
        };
        using M = FaceOrientationMethod;
        const std::vector<Mode> modes = {{ViewVectorMode::Exact, M::Standard},
                                         {ViewVectorMode::Constant, M::Standard},
                                         {ViewVectorMode::Exact, M::DuringTriangles},
                                         {ViewVectorMode::Exact, M::DuringVertices},
                                         {ViewVectorMode::Exact, M::AfterVertices}};
        cv::Mat reference;
        for (const Mode& mode : modes) {
            Look look;
            look.shading = ShadingModel::Comic;
            look.viewVector = mode.viewVector;
            look.faceOrientation = mode.orientation;
            look.towardLight = glm::normalize(glm::dvec3(-0.4, 0.5, 0.77));
            WarmRender render(scene, torusView(size), look, {"shade.color", "gbuffer.coverage"});
            const Timings timings = timeRuns(render, {"shade"}, mConfig.repetitions);
            const cv::Mat boundaries =
                bandBoundaries(render.store().image("shade.color"), render.store().image("gbuffer.coverage"));
            if (reference.empty()) reference = boundaries.clone();
            TradeoffRow row;
            row.method = "comic";
            row.setting = viewVectorModeName(mode.viewVector) + " view, " + faceOrientationMethodName(mode.orientation);
            row.scene = "torus " + thousands(scene.triangleCount());
            row.size = size;
            row.triangles = scene.triangleCount();
            row.frameMilliseconds = timings.frame;
            row.methodMilliseconds = timings.method;
            row.accuracy = scoreLineMasks(boundaries, reference, mConfig.tolerancePixels);
            row.f1AtTwoPixels = scoreLineMasks(boundaries, reference, 2.0).f1;
            report(row);
        }
    }

    void finish(TradeoffRow& row, int size, int supersample, std::size_t triangles, const Timings& timings,
                const std::vector<cv::Point2d>& points, const std::vector<LinePolyline>& truth) {
        row.size = size;
        row.supersample = supersample;
        row.triangles = triangles;
        row.frameMilliseconds = timings.frame;
        row.methodMilliseconds = timings.method;
        row.setupMilliseconds = timings.setup;
        row.accuracy = scoreLinePoints(points, truth, mConfig.tolerancePixels);
        row.f1AtTwoPixels = scoreLinePoints(points, truth, 2.0).f1;
        report(row);
    }

    void report(const TradeoffRow& row) {
        mProgress << std::fixed << std::setprecision(3) << row.method << " | " << row.setting << " | " << row.scene
                  << ": " << std::setprecision(1) << row.frameMilliseconds << " ms, F1 " << std::setprecision(3)
                  << row.accuracy.f1 << " (P " << row.accuracy.precision << ", R " << row.accuracy.recall << ")"
                  << std::endl;
        mRows.push_back(row);
    }

    TradeoffConfig mConfig;
    std::ostream& mProgress;
    std::vector<TradeoffRow> mRows;
    std::map<std::string, std::vector<LinePolyline>> mTruth;
};

std::string fixed(double value, int digits) {
    std::ostringstream text;
    text << std::fixed << std::setprecision(digits) << value;
    return text.str();
}

} // namespace

std::vector<TradeoffRow> runTradeoffSweep(const TradeoffConfig& config, std::ostream& progress) {
    if (config.repetitions < 1)
        throw std::invalid_argument("runTradeoffSweep(): 'repetitions' must be at least 1, got " +
                                    std::to_string(config.repetitions));
    if (!(config.tolerancePixels > 0.0 && std::isfinite(config.tolerancePixels)))
        throw std::invalid_argument("runTradeoffSweep(): 'tolerancePixels' must be positive and finite");
    return Sweep(config, progress).run();
}

std::string tradeoffCsv(const std::vector<TradeoffRow>& rows) {
    std::ostringstream csv;
    csv << "method,setting,scene,size,supersample,triangles,frame_ms,method_ms,setup_ms,tolerance_px,precision,"
           "recall,f1,f1_at_2px,predicted,spurious,truth_length,pred_to_truth_p95,pred_to_truth_max,"
           "truth_to_pred_p95,truth_to_pred_max,chamfer_mean\n";
    csv << std::setprecision(9);
    for (const TradeoffRow& row : rows) {
        const LineAccuracy& a = row.accuracy;
        csv << row.method << ",\"" << row.setting << "\"," << row.scene << "," << row.size << "," << row.supersample
            << "," << row.triangles << "," << row.frameMilliseconds << "," << row.methodMilliseconds << ","
            << row.setupMilliseconds << "," << a.tolerancePixels << "," << a.precision << "," << a.recall << "," << a.f1
            << "," << row.f1AtTwoPixels << "," << a.predictedCount << "," << a.spuriousCount << "," << a.truthLength
            << "," << a.predictedToTruthP95 << "," << a.predictedToTruthMax << "," << a.truthToPredictedP95 << ","
            << a.truthToPredictedMax << "," << a.chamferMean << "\n";
    }
    return csv.str();
}

std::string tradeoffMarkdown(const std::vector<TradeoffRow>& rows, double tolerancePixels) {
    const std::string k = fixed(tolerancePixels, tolerancePixels == std::floor(tolerancePixels) ? 0 : 1);
    std::ostringstream table;
    table << "| method | setting | scene | frame ms | method ms | P@" << k << " | R@" << k << " | F1@" << k
          << " | F1@2 | p95 px (pred/truth) | max px (pred/truth) |\n";
    table << "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const TradeoffRow& row : rows) {
        const LineAccuracy& a = row.accuracy;
        table << "| " << row.method << " | " << row.setting << " | " << row.scene << " | "
              << fixed(row.frameMilliseconds, 1) << " | " << fixed(row.methodMilliseconds, 1)
              << (row.setupMilliseconds > 1.0 ? " (+" + fixed(row.setupMilliseconds, 0) + " first)" : "") << " | "
              << fixed(a.precision, 3) << " | " << fixed(a.recall, 3) << " | " << fixed(a.f1, 3) << " | "
              << fixed(row.f1AtTwoPixels, 3) << " | " << fixed(a.predictedToTruthP95, 2) << " / "
              << fixed(a.truthToPredictedP95, 2) << " | " << fixed(a.predictedToTruthMax, 2) << " / "
              << fixed(a.truthToPredictedMax, 2) << " |\n";
    }
    return table.str();
}

namespace {

/** One panel of the plot: one method's rows, milliseconds (log) across, F1 up, each point labelled. */
void drawPanel(cv::Mat& plot, const cv::Rect& area, const std::string& method, const std::vector<TradeoffRow>& rows,
               const cv::Scalar& colour) {
    const int font = cv::FONT_HERSHEY_SIMPLEX;
    const cv::Scalar black(0, 0, 0), grey(205, 205, 205), faint(235, 235, 235);
    const cv::Rect frame(area.x + 60, area.y + 30, area.width - 80, area.height - 75);
    double lowestMs = rows.front().frameMilliseconds, highestMs = lowestMs, lowestF1 = 1.0;
    for (const TradeoffRow& row : rows) {
        lowestMs = std::min(lowestMs, row.frameMilliseconds);
        highestMs = std::max(highestMs, row.frameMilliseconds);
        lowestF1 = std::min(lowestF1, row.accuracy.f1);
    }
    // Whole decades across; F1 from the 0.05 step below the lowest point, so small differences show.
    const double firstDecade = std::floor(std::log10(std::max(lowestMs, 1e-3)));
    const double lastDecade = std::max(firstDecade + 1.0, std::ceil(std::log10(std::max(highestMs, 1e-3))));
    const double floorF1 = std::max(0.0, std::floor(lowestF1 * 20.0 - 0.5) / 20.0);
    const double f1Step = 1.0 - floorF1 > 0.3 ? 0.1 : 0.05;
    const auto x = [&](double ms) {
        const double t = (std::log10(std::max(ms, 1e-3)) - firstDecade) / (lastDecade - firstDecade);
        return frame.x + int(std::lround(t * frame.width));
    };
    const auto y = [&](double f1) { return frame.y + int(std::lround((1.0 - f1) / (1.0 - floorF1) * frame.height)); };
    for (double decade = firstDecade; decade <= lastDecade; decade += 1.0) {
        for (int step = 1; step < 10 && decade + std::log10(step) <= lastDecade + 1e-9; ++step) {
            const int px = x(std::pow(10.0, decade) * step);
            cv::line(plot, {px, frame.y}, {px, frame.br().y}, step == 1 ? grey : faint);
        }
        cv::putText(plot, fixed(std::pow(10.0, decade), decade < 0 ? int(-decade) : 0),
                    {x(std::pow(10.0, decade)) - 10, frame.br().y + 18}, font, 0.45, black, 1, cv::LINE_AA);
    }
    for (double f1 = 1.0; f1 >= floorF1 - 1e-9; f1 -= f1Step) {
        cv::line(plot, {frame.x, y(f1)}, {frame.br().x, y(f1)}, grey);
        cv::putText(plot, fixed(f1, 2), {frame.x - 45, y(f1) + 5}, font, 0.45, black, 1, cv::LINE_AA);
    }
    cv::rectangle(plot, frame, black);
    cv::putText(plot, method, {frame.x, area.y + 20}, font, 0.65, colour, 2, cv::LINE_AA);
    cv::putText(plot, "frame ms", {frame.x + frame.width / 2 - 30, frame.br().y + 38}, font, 0.45, black, 1,
                cv::LINE_AA);

    // Labels go right of their point, moved down past labels already placed so none overlap.
    std::vector<cv::Rect> placed;
    for (const TradeoffRow& row : rows) {
        const cv::Point at(x(row.frameMilliseconds), y(row.accuracy.f1));
        cv::circle(plot, at, 5, colour, cv::FILLED, cv::LINE_AA);
        int baseline = 0;
        const cv::Size text = cv::getTextSize(row.setting, font, 0.38, 1, &baseline);
        cv::Rect box(at.x + 8, at.y - text.height / 2, text.width, text.height + 3);
        if (box.br().x > area.br().x) box.x = at.x - 8 - text.width; // near the right edge: label on the left
        for (int tries = 0; tries < 40; ++tries) {
            const bool overlaps = std::any_of(placed.begin(), placed.end(),
                                              [&](const cv::Rect& other) { return (other & box).area() > 0; });
            if (!overlaps) break;
            box.y += text.height + 3;
        }
        placed.push_back(box);
        if (std::abs(box.y + box.height / 2 - at.y) > box.height)
            cv::line(plot, at, {box.x < at.x ? box.br().x : box.x, box.y + box.height / 2}, faint, 1, cv::LINE_AA);
        cv::putText(plot, row.setting, {box.x, box.y + text.height}, font, 0.38, black, 1, cv::LINE_AA);
    }
}

} // namespace

cv::Mat tradeoffPlot(const std::vector<TradeoffRow>& rows, double tolerancePixels) {
    // One panel per method (its own F1 range), three across.
    std::vector<std::string> methods;
    for (const TradeoffRow& row : rows)
        if (std::find(methods.begin(), methods.end(), row.method) == methods.end()) methods.push_back(row.method);
    constexpr int kPanelWidth = 620;
    constexpr int kPanelHeight = 440;
    constexpr int kTitleHeight = 40;
    const int columns = std::max<int>(1, std::min<int>(3, int(methods.size())));
    const int panelRows = std::max<int>(1, int((methods.size() + 2) / 3));
    cv::Mat plot(kTitleHeight + panelRows * kPanelHeight, columns * kPanelWidth, CV_8UC3, cv::Scalar(255, 255, 255));
    cv::putText(plot,
                "F1 at " + fixed(tolerancePixels, 1) +
                    " px against analytic lines (comic: band boundaries against exact shading) vs frame ms, warm",
                {20, 27}, cv::FONT_HERSHEY_SIMPLEX, 0.65, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    const std::vector<cv::Scalar> palette = {{200, 90, 20},  {30, 30, 220}, {40, 150, 40}, {180, 40, 180},
                                             {20, 130, 220}, {120, 120, 0}, {90, 90, 90},  {0, 160, 160}};
    for (std::size_t i = 0; i < methods.size(); ++i) {
        std::vector<TradeoffRow> methodRows;
        for (const TradeoffRow& row : rows)
            if (row.method == methods[i]) methodRows.push_back(row);
        const cv::Rect area(int(i % 3) * kPanelWidth, kTitleHeight + int(i / 3) * kPanelHeight, kPanelWidth,
                            kPanelHeight);
        drawPanel(plot, area, methods[i], methodRows, palette[i % palette.size()]);
    }
    return plot;
}

} // namespace inkgraph::bench
