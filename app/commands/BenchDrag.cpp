// `candela bench --drag [SCENE] --out DIR`: how live the editor stays while a luminaire is
// dragged, and how soon the image is right again after the user lets go (issue 7, "live while
// moving"). For each luminaire of the scene in turn (by default the demo room with one luminaire
// of each kind, resources/scenes/editor-room.json, at 960x540):
//  - drag: it moves along a circle in its horizontal plane, one step per frame, rendered with the
//    editor's preview settings (renderer/LivePreview.h), and for comparison with the full
//    settings; the wall time of each frame, GPU finished, gives frames per second;
//  - release: the editor's full renderer (apart from the preview's) had the luminaire where it
//    was grabbed, refined; it is let go at its place and the full settings refine (16 samples
//    per pass), only the moved luminaire (each luminaire keeps its own accumulation), and, for
//    comparison, everything; after every pass the tone-mapped image is compared with a
//    reference (the same techniques at --reference-spp, another seed) and the clock, stopped
//    while comparing, gives the seconds until the mean Delta E falls below 1.
// Every image is tone-mapped against the reference's mean luminance, so Delta E measures noise
// and bias, not a change of exposure. Writes drag.csv, release.csv, summary.txt and plot.png.
// clang-format off
#include "renderer/gl/GlFunctions.h"
// clang-format on
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include "app/commands/BenchHarness.h"
#include "app/commands/BenchUtil.h"
#include "app/commands/Commands.h"
#include "renderer/ImageFile.h"
#include "renderer/LivePreview.h"
#include "renderer/Renderer.h"
#include "scene/SceneIo.h"
#include "shaders/shared/Constants.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

constexpr double kTargetDeltaE = 1.0;  ///< The issue's "right again": mean Delta E below this.
constexpr double kDragRadius = 0.4;    ///< Radius of the drag's circle, metres.

double seconds(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
}

struct DragRow {
    std::string luminaire, mode;  ///< mode: "preview" or "full"
    int frames = 0;
    double meanMs = 0.0, p95Ms = 0.0, worstMs = 0.0;
    std::map<std::string, double> passMs;  ///< Mean GPU time per frame of each pass
    double fps() const { return meanMs > 0.0 ? 1000.0 / meanMs : 0.0; }
};

struct ReleasePoint {
    double seconds = 0.0;  ///< Since release, rendering only
    int spp = 0;
    double deltaE = 0.0, rmse = 0.0;
};

/// Renders `frames` frames while luminaire `index` of `scene` moves around its circle, showing
/// `shown` (the scene itself, or its preview scene kept in step); the luminaire is back at its
/// place afterwards.
DragRow drag(Renderer& renderer, Scene& scene, Scene& shown, size_t index,
             const RenderSettings& settings, int frames, const std::string& mode) {
    Luminaire& lum = *scene.luminaires[index];
    glm::dvec3 home = lum.pose.position;
    renderer.setSettings(settings);
    renderer.update(shown, kChangeAll);
    renderer.renderFrame();  // the first frame after the switch (shadow maps of every luminaire)
    glFinish();
    std::vector<double> ms;
    std::map<std::string, double> passMs;
    for (int f = 1; f <= frames; ++f) {
        double a = 2.0 * gpu::kPi * f / frames;
        lum.pose.position = home + kDragRadius * glm::dvec3(std::sin(a), 0.0, 1.0 - std::cos(a));
        auto start = Clock::now();
        if (&shown != &scene) syncPreviewScene(shown, scene);
        renderer.update(shown, kChangeLuminaires);
        renderer.renderFrame();
        glFinish();
        ms.push_back(1000.0 * seconds(start, Clock::now()));
        for (const auto& p : renderer.stats().passes) passMs[p.name] += p.gpuMs / frames;
    }
    lum.pose.position = home;
    if (&shown != &scene) syncPreviewScene(shown, scene);
    DragRow row;
    row.luminaire = lum.name;
    row.mode = mode;
    row.frames = frames;
    row.passMs = passMs;
    for (double m : ms) row.meanMs += m / double(ms.size());
    std::vector<double> sorted = ms;
    std::sort(sorted.begin(), sorted.end());
    row.p95Ms = sorted[std::min(sorted.size() - 1, size_t(0.95 * double(sorted.size())))];
    row.worstMs = sorted.back();
    return row;
}

/// The reference every image is compared with: the scene's own techniques, converged, with
/// another seed; tone-mapped against its own mean luminance, which `full` takes too.
struct DragReference {
    std::vector<float> linear;
    std::vector<unsigned char> display;
};

DragReference renderReference(Renderer& renderer, const Scene& scene, RenderSettings& full,
                              int referenceSpp, const fs::path& out) {
    std::fprintf(stderr, "bench: reference, %d spp at %dx%d\n", referenceSpp, full.width,
                 full.height);
    RenderSettings settings = withBudget(full, referenceSpp, 977, 16);
    DragReference ref;
    ref.linear = renderShot(renderer, scene, settings).linear;
    full.fixedAverage = settings.fixedAverage = float(meanLuminance(ref.linear));
    renderer.setSettings(settings);
    renderer.renderFrame();  // converged: tone-maps again with the fixed average
    ref.display = renderer.readDisplay();
    writeImage8((out / "reference.png").string(), full.width, full.height, ref.display);
    return ref;
}

/// What the luminaires' drags and releases share.
struct DragRun {
    const DragOptions& options;
    Scene& scene;
    Scene& shown;            ///< The preview scene, kept in step with `scene`.
    Renderer& renderer;      ///< The preview's.
    Renderer& fullRenderer;  ///< The editor's full renderer, apart from the preview's.
    RenderSettings full, preview;
    DragReference reference;
    std::vector<DragRow> drags{};  ///< Preview and full settings, per luminaire.
    CsvFile release{"luminaire,refines,seconds,spp,mean_delta_e,rel_rmse"};
    std::vector<double> releaseTimes{};  ///< Seconds to Delta E < 1 (NaN: never), per luminaire.
    std::vector<double> restartTimes{};  ///< The same when everything restarts.
    std::vector<double> finalDeltaE{};   ///< Delta E when the moved luminaire's refinement stopped.
    bool first = true;                   ///< fullRenderer has not seen the scene yet.
};

/// Luminaire `index` dragged with the preview's settings and with the full ones.
void measureDrags(DragRun& run, size_t index) {
    // Compile every variant before timing anything.
    run.renderer.setSettings(run.preview);
    run.renderer.update(run.shown, kChangeAll);
    run.renderer.renderFrame();
    run.drags.push_back(drag(run.renderer, run.scene, run.shown, index, run.preview,
                             run.options.frames, "preview"));
    run.drags.push_back(drag(run.renderer, run.scene, run.scene, index, run.full,
                             std::max(4, run.options.frames / 6), "full"));
    for (const DragRow* r : {&run.drags[run.drags.size() - 2], &run.drags.back()})
        std::fprintf(stderr,
                     "bench: drag %-16s %-8s %5.1f fps (mean %.1f ms, 95th percentile %.1f ms)\n",
                     r->luminaire.c_str(), r->mode.c_str(), r->fps(), r->meanMs, r->p95Ms);
    for (const auto& [pass, ms] : run.drags[run.drags.size() - 2].passMs)
        std::fprintf(stderr, "bench:   preview pass %-40s %7.2f ms\n", pass.c_str(), ms);
}

/// Release, as in the editor: the full renderer (its own, apart from the preview's) shows the
/// luminaire where it was grabbed, a quarter round its circle, refined to the editor's 256 spp
/// (untimed: the user was looking at it); the preview renders the drag; the luminaire is let go
/// at its place. Then the full renderer refines only the moved luminaire, every other one keeping
/// its accumulation, or (`everything`) everything from scratch (what the editor did before
/// per-luminaire accumulation), pass by pass until Delta E < 1, convergence or the timeout.
/// Returns the seconds of rendering to Delta E < 1 (NaN: never); `last` is the last pass.
double measureRelease(DragRun& run, size_t index, bool everything, ReleasePoint& last) {
    Luminaire& moved = *run.scene.luminaires[index];
    const char* how = everything ? "everything" : "moved only";
    glm::dvec3 home = moved.pose.position;
    moved.pose.position = home + kDragRadius * glm::dvec3(1.0, 0.0, 1.0);
    run.fullRenderer.setSettings(run.full);
    run.fullRenderer.update(run.scene, run.first ? kChangeAll : kChangeLuminaires);
    run.first = false;
    do run.fullRenderer.renderFrame();
    while (!run.fullRenderer.converged());
    moved.pose.position = home;
    drag(run.renderer, run.scene, run.shown, index, run.preview, 4, "preview");
    run.fullRenderer.update(run.scene,
                            everything ? kChangeAll & ~kChangeGeometry : kChangeLuminaires);
    double rendering = 0.0, reached = std::nan("");
    while (rendering < run.options.timeout) {
        auto start = Clock::now();
        run.fullRenderer.renderFrame();
        glFinish();
        rendering += seconds(start, Clock::now());
        ReleasePoint p{rendering, run.fullRenderer.stats().samplesPerPixel,
                       meanDeltaE(run.fullRenderer.readDisplay(), run.reference.display),
                       relRmse(run.fullRenderer.readLinear(), run.reference.linear)};
        run.release.row('"' + moved.name + '"', how, p.seconds, p.spp, p.deltaE, p.rmse);
        last = p;
        if (std::isnan(reached) && p.deltaE < kTargetDeltaE) reached = p.seconds;
        if (!std::isnan(reached) || run.fullRenderer.converged()) break;
    }
    std::fprintf(
        stderr, "bench: release %-16s (%s refines) Delta E < %.0f after %s (Delta E %.2f)\n",
        moved.name.c_str(), how, kTargetDeltaE,
        std::isnan(reached) ? "never" : (std::to_string(reached) + " s").c_str(), last.deltaE);
    return reached;
}

void addSummary(BenchSummary& summary, const DragRun& run, const std::string& context) {
    const DragOptions& o = run.options;
    const RenderSettings& p = run.preview;
    summary.add("scene: %s at %dx%d\ncontext: %s\n", o.scenePath.c_str(), o.width, o.height,
                context.c_str());
    summary.add(
        "preview while dragging: %dx%d, %d spp per frame, techniques %s, %d shadow map(s) of %d^2\n"
        "full: %dx%d, %d spp per frame up to %d, each luminaire's own technique\n"
        "reference: own techniques at %d spp, another seed\n",
        p.width, p.height, p.samplesPerFrame, p.techniqueOverride.c_str(), p.shadowMaps.count,
        p.shadowMaps.resolution, o.width, o.height, run.full.samplesPerFrame, run.full.maxSamples,
        o.referenceSpp);
    auto secondsText = [](double t) {
        return std::isnan(t) ? std::string("never (timeout or converged first)")
                             : std::to_string(t).substr(0, 5) + " s";
    };
    for (size_t i = 0; i + 1 < run.drags.size(); i += 2) {
        const DragRow& pr = run.drags[i];
        const DragRow& f = run.drags[i + 1];
        double release = run.releaseTimes[i / 2], restart = run.restartTimes[i / 2];
        summary.add(
            "%-16s dragging %5.1f fps (95th percentile frame %.1f ms; full settings %.1f fps, %s "
            "slower); "
            "after release Delta E < 1 in %s refining it alone (Delta E at the end %.2f), %s "
            "refining "
            "everything (%s longer)\n",
            pr.luminaire.c_str(), pr.fps(), pr.p95Ms, f.fps(),
            formatRatio(f.meanMs / pr.meanMs).c_str(), secondsText(release).c_str(),
            run.finalDeltaE[i / 2], secondsText(restart).c_str(),
            formatRatio(restart / release).c_str());
    }
}

void writeDragCsv(const fs::path& path, const std::vector<DragRow>& drags) {
    CsvFile csv("luminaire,mode,frames,mean_ms,p95_ms,worst_ms,fps");
    for (const DragRow& r : drags)
        csv.row('"' + r.luminaire + '"', r.mode, r.frames, r.meanMs, r.p95Ms, r.worstMs, r.fps());
    csv.write(path);
}

/// Delta E after release against rendering time, a line per luminaire and way of refining.
void plotRelease(const fs::path& out, const Scene& scene) {
    std::string body =
        "set logscale y\nset grid\n"
        "set xlabel 'seconds after release (rendering only)'\n"
        "set ylabel 'mean Delta E against the reference'\n"
        "set key top right\nset arrow from graph 0, first 1 to graph 1, first 1 nohead dt 2\nplot ";
    for (size_t i = 0; i < scene.luminaires.size(); ++i)
        for (const std::string how : {"moved only", "everything"}) {
            const std::string& name = scene.luminaires[i]->name;
            body += (i || how == "everything" ? ", " : "") +
                    std::string("'release.csv' using (strcol(1) eq '") + name +
                    "' && strcol(2) eq '" + how + "' ? $3 : 1/0):5 with linespoints title '" +
                    name + " (" + how + ")'";
        }
    writePlot(out, 900, 420, body + "\n", "plot.png");
}

}  // namespace

int benchDrag(const DragOptions& o) {
    BenchFolder folder(o.out);  // whole or not at all: committed at the end
    const fs::path& out = folder.path();
    Scene scene = loadScene(o.scenePath);
    ProtectedInputs inputs(scene.inputFiles());
    if (scene.luminaires.empty())
        throw InputError(o.scenePath + ": bench --drag needs a scene with luminaires");
    BenchGpu gpu;
    // The editor's settings (ui/Editor.cpp): 16 samples per pass up to 256.
    RenderSettings full;
    full.width = o.width;
    full.height = o.height;
    full.samplesPerFrame = o.samplesPerFrame;
    full.maxSamples = 256;
    DragReference reference = renderReference(gpu.renderer, scene, full, o.referenceSpp, out);
    RenderSettings preview = previewSettings(full, o.policy);
    std::fprintf(
        stderr, "bench: preview %dx%d, %d spp per frame, techniques %s, %d shadow map(s) of %d^2\n",
        preview.width, preview.height, preview.samplesPerFrame, preview.techniqueOverride.c_str(),
        preview.shadowMaps.count, preview.shadowMaps.resolution);

    Scene shownWhileDragging = previewScene(scene);
    Renderer fullRenderer(gpu.shaders);
    fullRenderer.setExactTimes(true);
    DragRun run{o,    scene,   shownWhileDragging,  gpu.renderer, fullRenderer,
                full, preview, std::move(reference)};
    for (size_t i = 0; i < scene.luminaires.size(); ++i) {
        measureDrags(run, i);
        ReleasePoint last;
        run.releaseTimes.push_back(measureRelease(run, i, false, last));
        run.finalDeltaE.push_back(last.deltaE);
        run.restartTimes.push_back(measureRelease(run, i, true, last));
    }
    writeDragCsv(out / "drag.csv", run.drags);
    run.release.write(out / "release.csv");
    BenchSummary summary;
    summary.light(
        "direct light with shadows, as the editor's viewport draws it while a luminaire moves; "
        "no interreflected light");
    addSummary(summary, run, gpu.context->description());
    summary.write(out);
    plotRelease(out, scene);
    folder.commit();
    return 0;
}

}  // namespace candela
