/** The files the run read that only loading the model revealed: its buffers and images, and the shade maps its
 *  materials name. No output may be one of them (OutputSet::refuseInputs). */
std::vector<RunInput> inputsFoundByLoading(const RenderOptions& options, const Scene& scene) {
    // Appended, not "'" + name: GCC 12 warns falsely (-Wrestrict, bug 105329) on that inlined.
    std::string model = "'";
    model.append(std::filesystem::path(options.modelPath).filename().string()).append("'");
    std::vector<RunInput> inputs;
    for (const std::string& file : scene.report.inputFiles)
        inputs.push_back({file, "a file the model " + model + " reads"});
    for (const Mesh& mesh : scene.meshes)
        if (!mesh.shadeMapPath.empty())
            inputs.push_back({mesh.shadeMapPath, "the shade map of mesh '" + mesh.name + "' of " + model});
    return inputs;
}

} // namespace

void requireStandardOutputWritten(std::ostream& out) {
    errno = 0;
    out.flush();
    if (!out || (&out == &std::cout && (std::fflush(stdout) != 0 || std::ferror(stdout))))
        throw FileError(std::string("renderStill(): cannot write the standard output") +
                        (errno ? std::string(": ") + std::strerror(errno) : ""));
}

std::size_t memoryLimitOf(const RenderOptions& options) {
    if (options.memoryLimitBytes) return *options.memoryLimitBytes;
    const long pages = ::sysconf(_SC_PHYS_PAGES);
    const long pageSize = ::sysconf(_SC_PAGE_SIZE);
    const std::size_t physical = pages > 0 && pageSize > 0 ? std::size_t(pages) * std::size_t(pageSize) : 0;
    return std::max<std::size_t>(physical / 2, std::size_t(1) << 30);
}

CameraRequest cameraRequestOf(const RenderOptions& options) {
    CameraRequest request;
    request.eye = options.eye;
    request.target = options.target;
    request.up = options.up;
    request.fovYDegrees = options.fovYDegrees;
    if (options.clipRange) {
        request.zNear = options.clipRange->x;
        request.zFar = options.clipRange->y;
    }
    request.width = options.width;
    request.height = options.height;
    return request;
}

StillRequest stillRequestOf(const RenderOptions& options) {
    StillRequest request;
    request.modelPath = options.modelPath;
    request.look = options.look;
    request.camera = cameraRequestOf(options);
    request.extraOutputs = options.extraOutputs;
    request.keepEveryBuffer = keepsEveryBuffer(options);
    request.keepSvgInputs = !options.svgPath.empty();
    request.memoryLimitBytes = memoryLimitOf(options);
    if (options.eglPlatform == "device") request.eglPlatform = EglPlatform::Device;
    if (options.eglPlatform == "surfaceless") request.eglPlatform = EglPlatform::Surfaceless;
    return request;
}

StillReport RenderSession::render(const RenderOptions& options, const StillBatchPosition* batch) {
    const auto processStart = std::chrono::steady_clock::now();
    const bool renders = rendersImages(options);
    // In a batch the progress line per still replaces the lines of one still.
    const bool talks = !options.quiet && batch == nullptr;
    const StillLog log{mLog, talks, options.quiet};
    // OpenImageIO's ~0.2 s of dynamic linking overlaps loading the model. (Not rendering: on llvmpipe, LLVM's symbol
    // look-ups wait for the dynamic loader's lock, so they would queue behind it.)
    if (renders) preloadImageIo();
    StillReport report;

    // Every output place is checked before any work; outputs are staged and put in place only at the end.
    OutputSet outputs(options);
    const std::unique_ptr<PreparedStill> still = mRenderer.prepare(stillRequestOf(options), log);
    report.triangles = still->scene.triangleCount();
    outputs.refuseInputs(inputsFoundByLoading(options, still->scene));

    const Plan& plan = still->plan;
    if (options.printPlan) {
        mOut << plan.describe();
        requireStandardOutputWritten(mOut); // before the commit: a run that fails puts no file in place
    }
    if (!options.graphvizPath.empty()) outputs.stageGraphviz(plan.graphviz());
    if (!renders) {
        outputs.commit();
        return report;
    }
    checkFrameBudget(plan, options, &still->scene);

    StillResult result = mRenderer.execute(*still, log);
    const auto writeStart = std::chrono::steady_clock::now();
    stageStillOutputs(options, *still, result, outputs);
    if (!options.statsPath.empty()) {
        StatsContext context{options, batch};
        context.writeMilliseconds = millisecondsSince(writeStart);
        context.estimatedPeakBytes = estimatePlanBytes(plan, options, &still->scene);
        context.totalMilliseconds = millisecondsSince(processStart);
        outputs.stageStats(statsText(context, mRenderer, *still, result));
    }
    outputs.commit();
    report.milliseconds = millisecondsSince(processStart);
    if (talks) {
        mLog << "inkgraph: rendered " << options.width << "x" << options.height << " in "
             << millisecondsSince(processStart) << " ms";
        if (!options.outputPath.empty()) mLog << " -> '" << options.outputPath << "'";
        mLog << "\n";
    }
    return report;
}

} // namespace inkgraph
