#include "render/InputFiles.h"

#include "render/UsageError.h"

#include <sys/stat.h>

#include <system_error>

namespace inkgraph {
namespace fs = std::filesystem;

std::optional<FileIdentity> fileIdentity(const fs::path& path) {
    struct stat status {};
    if (::stat(path.c_str(), &status) != 0) return std::nullopt;
    return FileIdentity{status.st_dev, status.st_ino};
}

fs::path resolvedPath(const fs::path& path) {
    std::error_code error;
    fs::path result = fs::weakly_canonical(fs::absolute(path, error), error);
    return error ? fs::absolute(path).lexically_normal() : result;
}

bool isSameFile(const fs::path& first, const fs::path& second) {
    if (resolvedPath(first) == resolvedPath(second)) return true;
    const auto firstIdentity = fileIdentity(first);
    const auto secondIdentity = fileIdentity(second);
    return firstIdentity && secondIdentity && *firstIdentity == *secondIdentity;
}

void refuseInputAsOutput(const fs::path& output, const std::string& shownOutput, const std::vector<RunInput>& inputs) {
    for (const RunInput& input : inputs)
        if (isSameFile(input.path, output))
            throw UsageError(shownOutput + " is " + input.what + "; choose another file");
}

std::vector<RunInput> inputsFoundByLoading(const std::string& modelPath, const Scene& scene) {
    // Appended, not "'" + name: GCC 12 warns falsely (-Wrestrict, bug 105329) on that inlined.
    std::string model = "'";
    model.append(fs::path(modelPath).filename().string()).append("'");
    std::vector<RunInput> inputs;
    for (const std::string& file : scene.report.inputFiles)
        inputs.push_back({file, "a file the model " + model + " reads"});
    for (const Mesh& mesh : scene.meshes)
        if (!mesh.material.shadeMapPath.empty())
            inputs.push_back({mesh.material.shadeMapPath, "the shade map of mesh '" + mesh.name + "' of " + model});
    return inputs;
}

} // namespace inkgraph
