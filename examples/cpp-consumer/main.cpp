// A program of its own that renders with the installed inkgraph library (README.md), through typed calls only: it
// loads the model given on the command line and renders it from 8 orbits around it (azimuth 0, 45, ..., 315 degrees,
// 10 degrees above the horizontal), SIZE x SIZE pixels (512 unless given), MToon shading with the silhouette and the
// contour. For each view NN it writes into OUT_DIR
//   picture-NN.png   the still
//   camera-NN.json   the camera it was drawn with: size, vertical fov, where the view came from, eye, target, up,
//                    near, far, OpenGL's view and projection matrices and OpenCV's intrinsics K and extrinsics [R|t]
//                    (rows; the keys of `inkgraph render --dump`'s manifest.json camera)
// and prints one line per view (its contour pixels, the pixels the model covers) and every warning with its code.
#include <inkgraph/inkgraph.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <locale>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace ig = inkgraph::api;

namespace {

// A few lines of JSON by hand, so that the program needs nothing but the library.

std::string jsonNumber(double value) {
    if (!std::isfinite(value)) return "null"; // JSON has no inf or nan
    std::ostringstream text;
    text.imbue(std::locale::classic()); // a decimal point whatever the user's locale
    text << std::setprecision(std::numeric_limits<double>::max_digits10) << value;
    return text.str();
}

std::string jsonString(const std::string& value) {
    std::string text = "\"";
    for (const char c : value) {
        if (c == '"' || c == '\\') {
            text += '\\';
            text += c;
        } else if (static_cast<unsigned char>(c) < 0x20) {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned>(c));
            text += escaped;
        } else {
            text += c; // UTF-8 passes through
        }
    }
    return text + "\"";
}

std::string jsonVector(const ig::Vec3& v) {
    return "[" + jsonNumber(v.x) + ", " + jsonNumber(v.y) + ", " + jsonNumber(v.z) + "]";
}

template <std::size_t Rows, std::size_t Columns>
std::string jsonRows(const std::array<std::array<double, Columns>, Rows>& matrix) {
    std::string text = "[";
    for (std::size_t row = 0; row < Rows; ++row) {
        text += row == 0 ? "[" : ", [";
        for (std::size_t column = 0; column < Columns; ++column)
            text += (column == 0 ? "" : ", ") + jsonNumber(matrix[row][column]);
        text += "]";
    }
    return text + "]";
}

std::string sourceName(ig::CameraSource source) {
    switch (source) {
    case ig::CameraSource::File: return "file";
    case ig::CameraSource::Auto: return "auto";
    case ig::CameraSource::Orbit: return "orbit";
    case ig::CameraSource::Eye: return "eye";
    }
    return "unknown";
}

std::string cameraJson(const ig::StillCamera& camera, const std::string& model, const std::string& picture,
                       const ig::Orbit& orbit) {
    const std::vector<std::pair<std::string, std::string>> fields = {
        {"model", jsonString(model)},
        {"picture", jsonString(picture)},
        {"azimuth_degrees", jsonNumber(orbit.azimuth)},
        {"elevation_degrees", jsonNumber(orbit.elevation)},
        {"width", std::to_string(camera.width)},
        {"height", std::to_string(camera.height)},
        {"fov_y_degrees", jsonNumber(camera.fovY)},
        {"source", jsonString(sourceName(camera.source))},
        {"eye", jsonVector(camera.eye)},
        {"target", jsonVector(camera.target)},
        {"up", jsonVector(camera.up)},
        {"near", jsonNumber(camera.near)},
        {"far", jsonNumber(camera.far)},
        {"view_matrix", jsonRows(camera.view)},
        {"projection_matrix", jsonRows(camera.projection)},
        {"intrinsics", jsonRows(camera.intrinsics)},
        {"extrinsics", jsonRows(camera.extrinsics)},
    };
    std::string text = "{\n";
    for (std::size_t i = 0; i < fields.size(); ++i)
        text += "  " + jsonString(fields[i].first) + ": " + fields[i].second + (i + 1 < fields.size() ? ",\n" : "\n");
    return text + "}\n";
}

void writeText(const std::filesystem::path& path, const std::string& text) {
    std::ofstream file(path, std::ios::binary);
    file << text;
    file.close();
    if (!file) throw std::runtime_error("cannot write '" + path.string() + "'");
}

/** Pixels of a line layer with ink (coverage above 0). Rows are rowBytes() apart. */
std::size_t inkedPixels(const ig::Image& layer) {
    std::size_t count = 0;
    for (int row = 0; row < layer.height(); ++row) {
        const std::uint8_t* pixel = layer.data() + std::size_t(row) * layer.rowBytes();
        for (int column = 0; column < layer.width(); ++column) count += pixel[column] != 0 ? 1 : 0;
    }
    return count;
}

/** Pixels of the depth buffer the model covers (its view depth is 0 elsewhere). */
std::size_t coveredPixels(const ig::Image& depth) {
    std::size_t count = 0;
    for (int row = 0; row < depth.height(); ++row) {
        const float* pixel = depth.floats() + std::size_t(row) * depth.rowBytes() / sizeof(float);
        for (int column = 0; column < depth.width(); ++column) count += pixel[column] > 0.0f ? 1 : 0;
    }
    return count;
}

void printWarnings(const std::vector<ig::Warning>& warnings) {
    for (const ig::Warning& warning : warnings)
        std::cout << "warning [" << warning.code << "] " << warning.message << "\n";
}

std::string twoDigits(int n) { return (n < 10 ? "0" : "") + std::to_string(n); }

} // namespace

int main(int argc, char** argv) {
    if (argc != 3 && argc != 4) {
        std::cerr << "usage: " << argv[0] << " MODEL OUT_DIR [SIZE]\n";
        return 2;
    }
    const std::filesystem::path outDir = argv[2];
    try {
        const int size = argc == 4 ? std::stoi(argv[3]) : 512;
        std::cout << "inkgraph " << ig::version() << " (git " << ig::gitCommit() << "), built against "
                  << INKGRAPH_VERSION_MAJOR << "." << INKGRAPH_VERSION_MINOR << "." << INKGRAPH_VERSION_PATCH << "\n";
        const ig::Scene scene = ig::Scene::load(argv[1]);
        std::cout << "loaded '" << scene.path() << "': " << scene.triangleCount() << " triangles, " << scene.meshCount()
                  << " meshes\n";
        printWarnings(scene.warnings());

        // The look, typed: each setter checks its value at once (Error(Usage) with the flag's own message).
        ig::Look look;
        look.setShading(ig::Shading::MToon).setLines({ig::LineType::Silhouette, ig::LineType::Contour});
        look.setLineStyle(ig::LineType::Contour, ig::LineStyle{1.5, ig::Color{0.1, 0.1, 0.1, 1.0}});

        ig::Frame frame;
        frame.width = frame.height = size;

        // The pictures go into one buffer of ours, reused for every view: each still's picture() views it, so each
        // is written before the next render draws over it.
        const std::size_t rowBytes = std::size_t(size) * 4;
        std::vector<std::uint8_t> pixels(rowBytes * std::size_t(size));

        std::filesystem::create_directories(outDir);
        ig::Renderer renderer; // one GL context, kept for every render of this renderer
        for (int view = 0; view < 8; ++view) {
            frame.orbit = ig::Orbit{45.0 * view, 10.0, std::nullopt}; // the auto-framing distance
            const ig::Still still =
                renderer.renderInto(pixels.data(), rowBytes, scene, look, frame, {"lines.contour", "depth"});
            if (view == 0) std::cout << "rendered on " << renderer.glDescription() << "\n";

            const std::string picture = "picture-" + twoDigits(view) + ".png";
            const std::string camera = "camera-" + twoDigits(view) + ".json";
            still.write((outDir / picture).string());
            writeText(outDir / camera, cameraJson(still.camera(), scene.path(), picture, *frame.orbit));
            std::cout << picture << ", " << camera << ": azimuth " << frame.orbit->azimuth << ", "
                      << still.picture().width() << "x" << still.picture().height() << ", contour "
                      << inkedPixels(still.buffer("lines.contour")) << " pixels, covered "
                      << coveredPixels(still.buffer("depth")) << " pixels\n";
            printWarnings(still.warnings());
        }
        return 0;
    } catch (const ig::Error& error) {
        std::cerr << "inkgraph-consumer: " << error.what() << "\n";
        return error.exitCode();
    } catch (const std::exception& error) { // a SIZE that is not a number, a camera file not written
        std::cerr << "inkgraph-consumer: " << error.what() << "\n";
        return 1;
    }
}
