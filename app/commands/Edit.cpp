// `candela edit [scene.json]`: the interactive editor, or, without a display, the editor's
// screenshots of the scene rendered offscreen.
#include <cstdio>
#include <filesystem>
#include <string>

#include "app/commands/Commands.h"
#include "calculation/Interreflection.h"
#include "calculation/InterreflectionWorker.h"
#include "renderer/Renderer.h"
#include "renderer/ShaderLibrary.h"
#include "renderer/context/GlContext.h"
#include "report/Screenshot.h"
#include "scene/SceneIo.h"
#include "ui/Editor.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

namespace {

constexpr int kHeadlessWidth = 960;   ///< Offscreen screenshot width, pixels.
constexpr int kHeadlessHeight = 540;  ///< Offscreen screenshot height, pixels.
constexpr int kHeadlessMaxSpp = 64;   ///< Samples per pixel for progressive techniques.

/// Renders the scene offscreen with its own techniques until converged (at most 64 spp) and
/// writes the screenshot files the editor's Screenshot button would.
int renderScreenshotsOffscreen(const ui::EditorOptions& options) {
    Scene scene = loadScene(options.scenePath);
    ProtectedInputs inputs(scene.inputFiles());  // no screenshot file may replace one
    auto context = createOffscreenContext();
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    RenderSettings settings;
    settings.width = kHeadlessWidth;
    settings.height = kHeadlessHeight;
    settings.samplesPerFrame = 8;
    settings.maxSamples = kHeadlessMaxSpp;
    if (scene.camera.exposure > 0.0) settings.exposure = float(scene.camera.exposure);
    renderer.setSettings(settings);
    renderer.update(scene, kChangeAll);
    // The interreflected light, as the editor's worker converges to it: what the window shows.
    InterreflectionOptions io;
    io.directSpp = InterreflectionWorker::kFineSpp;
    Interreflection ir(scene, io);
    std::string light = "direct light only: no surface reflects onto another";
    if (ir.mesh().reflects() && ir.compute() && ir.hasInterreflection()) {
        std::vector<glm::vec3> v;
        for (const glm::dvec3& e : ir.indirectAtVertices()) v.push_back(glm::vec3(e));
        renderer.setIndirect(std::make_shared<RadiosityMesh>(ir.mesh()), std::move(v));
        light = "direct and interreflected light (" + std::to_string(ir.mesh().patches.size()) +
                " patches)";
    }

    PassTotals passes;
    // Guard against a plan that never reports convergence: 64 spp at 1 spp per frame at most.
    for (int frame = 0; frame < 4 * kHeadlessMaxSpp; ++frame) {
        renderer.renderFrame();
        passes.add(renderer.stats());
        if (renderer.converged()) break;
    }
    ScreenshotFiles files = writeScreenshot(options.screenshotDir, scene, renderer, passes);
    std::printf("rendered %s offscreen (%dx%d, %d spp%s), %s\n", options.scenePath.c_str(),
                kHeadlessWidth, kHeadlessHeight, renderer.stats().samplesPerPixel,
                renderer.plan().progressive() ? "" : ", exact techniques", light.c_str());
    std::printf("wrote %s\nwrote %s\nwrote %s\n", files.png.c_str(), files.exr.c_str(),
                files.json.c_str());
    return 0;
}

/// Refuses, before any window opens, a layout file that is the scene or a file it reads (the
/// editor writes it every frame). The screenshots, sheets, reports and autosaves are checked as
/// they are written (the editor protects the scene's files for its whole life).
void checkOutputs(const ui::EditorOptions& options) {
    if (options.layoutFile.empty()) return;
    ProtectedInputs inputs({options.scenePath});
    try {
        inputs.add(loadScene(options.scenePath).inputFiles());
    } catch (const InputError&) {
        // The editor opens with the error shown; the scene file alone is protected here.
    }
    checkNotAnInput(options.layoutFile.string(), "--layout-file", "the editor");
}

}  // namespace

int cmdEdit(const Args& args) {
    ui::EditorOptions options;
    std::string screenshotDir = options.screenshotDir.string(), layoutFile;
    CommandLine cli("edit");
    cli.argument("scene.json", options.scenePath,
                 "the scene to open (default: resources/scenes/demo.json of the source tree)",
                 false);
    cli.option("--size", "WxH", "the window's size, screen pixels (1280x800)",
               [&options](const std::string& v) { parseSize(v, options.width, options.height); });
    cli.output("--screenshot-dir", screenshotDir, "DIR",
               "where the Screenshot button writes shot-NNN.png, .exr and .json, and where they "
               "go without a display (candela-screenshots, in the current folder)");
    cli.output(
        "--layout-file", layoutFile, "FILE",
        "after every frame, write the window's layout as JSON: window, viewport, Screenshot "
        "button, widgets and luminaire positions in window pixels (for tests; default: none)");
    cli.option("--autosave-seconds", "S", "how often unsaved edits are autosaved, seconds (60)",
               [&options](const std::string& v) {
                   options.autosaveSeconds = parseInt("--autosave-seconds", v, 1, 1 << 20);
               });
    cli.integer("--quit-after-frames", options.quitAfterFrames, 1, 1 << 30, "N",
                "close the editor after N frames (for tests; default: run until closed)");
    if (!cli.parse(args)) return 0;
    options.screenshotDir = screenshotDir;
    options.layoutFile = layoutFile;
    if (options.scenePath.empty())
        options.scenePath = std::string(CANDELA_SOURCE_DIR) + "/resources/scenes/demo.json";
    checkOutputs(options);

    if (!displayAvailable()) {
        std::printf(
            "candela edit: no display found (DISPLAY and WAYLAND_DISPLAY are unset); "
            "rendering the scene's screenshots offscreen into %s/ instead\n",
            options.screenshotDir.string().c_str());
        return renderScreenshotsOffscreen(options);
    }
    std::unique_ptr<ui::Editor> editor;
    try {
        editor = std::make_unique<ui::Editor>(options);
    } catch (const RuntimeError& e) {
        std::fprintf(stderr, "candela edit: cannot open the editor window: %s\n", e.what());
        std::printf(
            "candela edit: no usable display found; rendering the scene's screenshots "
            "offscreen into %s/ instead\n",
            options.screenshotDir.string().c_str());
        return renderScreenshotsOffscreen(options);
    }
    return editor->run();
}

}  // namespace candela
