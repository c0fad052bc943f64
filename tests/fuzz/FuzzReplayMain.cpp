// Replays inputs through a fuzz target without libFuzzer: the ctest side of tests/fuzz. Every file under the given
// files or folders is one input. Exits 1 when no input was found (a test that ran nothing must not pass); a failing
// input aborts (an escaped exception) or is reported by a sanitizer in the sanitized build.
#include "render/BackgroundThreads.h"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

std::vector<std::uint8_t> fileBytes(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

} // namespace

int main(int argc, char** argv) {
    std::vector<std::filesystem::path> inputs;
    for (int i = 1; i < argc; ++i) {
        const std::filesystem::path root(argv[i]);
        if (std::filesystem::is_directory(root)) {
            for (const auto& entry : std::filesystem::recursive_directory_iterator(root))
                if (entry.is_regular_file()) inputs.push_back(entry.path());
        } else if (std::filesystem::is_regular_file(root)) {
            inputs.push_back(root);
        } else {
            std::cerr << "fuzz replay: '" << root.string() << "' is neither a file nor a folder\n";
            return 1;
        }
    }
    if (inputs.empty()) {
        std::cerr << "fuzz replay: no inputs\n";
        return 1;
    }
    for (const std::filesystem::path& input : inputs) {
        std::cerr << "fuzz replay: " << input.string() << "\n";
        const std::vector<std::uint8_t> bytes = fileBytes(input);
        LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
    }
    std::cout << "fuzz replay: " << inputs.size() << " inputs, none failed\n";
    inkgraph::finishProcess();
    return 0;
}
