// A program of its own that renders with the installed library: find_package(inkgraph) and inkgraph::inkgraph are all
// it needs (CMakeLists.txt). Usage: inkgraph-consumer MODEL OUT_DIR
//   OUT_DIR/picture.png      the still: cel shading, silhouette, contour and suggestive contours, seen from the left
//   OUT_DIR/contour.png      the contour layer alone, white on black (a mask)
//   OUT_DIR/normal.exr       the view-space normals, float32
// and one line per buffer on the standard output: its name, size, channels and type.
#include <inkgraph/inkgraph.h>

#include <filesystem>
#include <iostream>

namespace ig = inkgraph::api;

int main(int argc, char** argv) {
    if (argc != 3) {
        std::cerr << "usage: " << argv[0] << " MODEL OUT_DIR\n";
        return 2;
    }
    const std::filesystem::path outDir = argv[2];
    try {
        std::cout << "inkgraph " << ig::version() << " (" << ig::gitCommit() << ")\n";
        const ig::Scene scene = ig::Scene::load(argv[1]);
        std::cout << "loaded '" << scene.path() << "': " << scene.triangleCount() << " triangles\n";

        ig::Look look = ig::Look::fromArguments({"--shading", "cel", "--lines", "silhouette,contour,suggestive"});
        look.set("--contour-width", "1.5");
        ig::Frame frame;
        frame.width = 512;
        frame.height = 384;
        frame.camera = {"--orbit", "-40,10"};

        ig::Renderer renderer; // one GL context, kept for every render of this renderer
        const ig::Still still = renderer.render(scene, look, frame, {"lines.contour", "normal", "depth"});
        std::cout << "rendered in " << still.milliseconds() << " ms on " << renderer.glDescription() << "\n";

        std::filesystem::create_directories(outDir);
        still.write((outDir / "picture.png").string());
        still.buffer("lines.contour").write((outDir / "contour.png").string());
        still.buffer("normal").write((outDir / "normal.exr").string());
        for (const std::string& name : still.bufferNames()) {
            const ig::Image& image = still.buffer(name);
            std::cout << name << ": " << image.width << "x" << image.height << "x" << image.channels << " "
                      << (image.type == ig::Image::Type::Float32 ? "float32" : "uint8") << "\n";
        }
        return 0;
    } catch (const ig::Error& error) {
        std::cerr << "inkgraph-consumer: " << error.what() << "\n";
        return error.exitCode();
    }
}
