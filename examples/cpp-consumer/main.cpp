// A program of its own that renders with the installed inkgraph library (README.md): it loads the model given on the
// command line and writes into OUT_DIR
//   picture.png   the still: cel shading with silhouette, contours and suggestive contours, seen 40 degrees to the
//                 front view's left (--orbit -40,10)
//   contour.png   the contour layer alone, a mask (white on black)
//   normal.exr    the view-space normals, float32 RGBA (alpha: coverage)
// then prints one line per buffer: its name, size, channels, type and how many of its pixels are set.
#include <inkgraph/inkgraph.h>

#include <algorithm>
#include <filesystem>
#include <iostream>

namespace ig = inkgraph::api;

namespace {

/** Pixels with any channel not zero: ink in a line mask, the covered pixels in the normals. */
std::size_t setPixels(const ig::Image& image) {
    const std::size_t pixels = std::size_t(image.width) * std::size_t(image.height);
    const std::size_t stride = std::size_t(image.channels) * image.bytesPerChannel();
    std::size_t count = 0;
    for (std::size_t pixel = 0; pixel < pixels; ++pixel) {
        const std::uint8_t* first = image.bytes.data() + pixel * stride;
        count += std::any_of(first, first + stride, [](std::uint8_t byte) { return byte != 0; }) ? 1 : 0;
    }
    return count;
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::cerr << "usage: " << argv[0] << " MODEL OUT_DIR\n";
        return 2;
    }
    const std::filesystem::path outDir = argv[2];
    try {
        std::cout << "inkgraph " << ig::version() << " (git " << ig::gitCommit() << ")\n";
        const ig::Scene scene = ig::Scene::load(argv[1]);
        std::cout << "loaded '" << scene.path() << "': " << scene.triangleCount() << " triangles\n";

        // The look and the frame in the command line's words (inkgraph help render).
        ig::Look look = ig::Look::fromArguments({"--shading", "cel", "--lines", "silhouette,contour,suggestive"});
        look.set("--contour-width", "1.5");
        ig::Frame frame;
        frame.width = 512;
        frame.height = 384;
        frame.camera = {"--orbit", "-40,10"};

        ig::Renderer renderer; // one GL context, kept for every render of this renderer
        const ig::Still still = renderer.render(scene, look, frame, {"lines.contour", "normal"});
        std::cout << "rendered on " << renderer.glDescription() << "\n";

        std::filesystem::create_directories(outDir);
        still.write((outDir / "picture.png").string());
        still.buffer("lines.contour").write((outDir / "contour.png").string());
        still.buffer("normal").write((outDir / "normal.exr").string());
        for (const std::string& name : still.bufferNames()) {
            const ig::Image& image = still.buffer(name);
            std::cout << name << ": " << image.width << "x" << image.height << "x" << image.channels << " "
                      << (image.type == ig::Image::Type::Float32 ? "float32" : "uint8") << ", " << setPixels(image)
                      << " pixels set\n";
        }
        return 0;
    } catch (const ig::Error& error) {
        std::cerr << "inkgraph-consumer: " << error.what() << "\n";
        return error.exitCode();
    }
}
