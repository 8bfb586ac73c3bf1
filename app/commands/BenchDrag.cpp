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
#include <sstream>

#include "app/commands/BenchUtil.h"
#include "app/commands/Commands.h"
#include "renderer/ImageFile.h"
#include "renderer/LivePreview.h"
#include "renderer/Renderer.h"
#include "renderer/context/GlContext.h"
#include "scene/SceneIo.h"
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
DragRow drag(Renderer& renderer, Scene& scene, Scene& shown, size_t index, const RenderSettings& settings,
             int frames, const std::string& mode) {
    Luminaire& lum = *scene.luminaires[index];
    glm::dvec3 home = lum.pose.position;
    renderer.setSettings(settings);
    renderer.update(shown, kChangeAll);
    renderer.renderFrame();  // the first frame after the switch (shadow maps of every luminaire)
    glFinish();
    std::vector<double> ms;
    std::map<std::string, double> passMs;
    for (int f = 1; f <= frames; ++f) {
        double a = 2.0 * 3.14159265358979 * f / frames;
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

}  // namespace

int benchDrag(const Args& args) {
    std::string scenePath = std::string(CANDELA_SOURCE_DIR) + "/resources/scenes/editor-room.json";
    std::string outDir = "bench-drag";
    int width = 960, height = 540, frames = 60, refSpp = 1024;
    double timeout = 60.0;
    PreviewPolicy policy;
    int samplesPerFrame = 16;  // as the editor (ui/Editor.cpp)
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--drag") {
            if (i + 1 < args.size() && args[i + 1].rfind("--", 0) != 0) scenePath = args[++i];
        } else if (a == "--out") outDir = flagValue(args, i);
        else if (a == "--size") parseSize(flagValue(args, i), width, height);
        else if (a == "--frames") frames = parseInt(a, flagValue(args, i), 4, 100000);
        else if (a == "--reference-spp") refSpp = parseInt(a, flagValue(args, i), 16, 1 << 20);
        else if (a == "--preview-scale") policy.scale = float(parseNumberList(a, flagValue(args, i)).at(0));
        else if (a == "--preview-techniques") policy.techniques = flagValue(args, i);
        else if (a == "--preview-spp") policy.samplesPerFrame = parseInt(a, flagValue(args, i), 1, 1024);
        else if (a == "--samples-per-frame") samplesPerFrame = parseInt(a, flagValue(args, i), 1, 1024);
        else if (a == "--timeout") timeout = parseInt(a, flagValue(args, i), 1, 100000);
        else throw InputError("bench: unknown option " + a);
    }
    fs::create_directories(outDir);
    Scene scene = loadScene(scenePath);
    ProtectedInputs inputs(scene.inputFiles());
    if (scene.luminaires.empty()) throw InputError(scenePath + ": bench --drag needs a scene with luminaires");
    auto context = createOffscreenContext();
    ShaderLibrary shaders;
    Renderer renderer(shaders);

    // The editor's settings (ui/Editor.cpp): 16 samples per pass up to 256.
    RenderSettings full;
    full.width = width;
    full.height = height;
    full.samplesPerFrame = samplesPerFrame;
    full.maxSamples = 256;

    // The reference: the scene's own techniques, converged, with another seed.
    std::fprintf(stderr, "bench: reference, %d spp at %dx%d\n", refSpp, width, height);
    RenderSettings refSettings = full;
    refSettings.samplesPerFrame = 16;
    refSettings.maxSamples = refSpp;
    refSettings.seed = 977;
    renderer.setSettings(refSettings);
    renderer.update(scene, kChangeAll);
    do renderer.renderFrame();
    while (!renderer.converged());
    std::vector<float> refLinear = renderer.readLinear();
    double avg = meanLuminance(refLinear);
    full.fixedAverage = refSettings.fixedAverage = float(avg);
    renderer.setSettings(refSettings);
    renderer.renderFrame();  // converged: tone-maps again with the fixed average
    std::vector<unsigned char> refDisplay = renderer.readDisplay();
    writeImage8((fs::path(outDir) / "reference.png").string(), width, height, refDisplay);

    if (!(policy.scale > 0.f && policy.scale <= 1.f)) throw InputError("bench: --preview-scale must be in (0, 1]");
    RenderSettings preview = previewSettings(full, policy);
    std::fprintf(stderr, "bench: preview %dx%d, %d spp per frame, techniques %s, %d shadow map(s) of %d^2\n",
                 preview.width, preview.height, preview.samplesPerFrame, preview.techniqueOverride.c_str(),
                 preview.shadowMaps.count, preview.shadowMaps.resolution);

    Scene shownWhileDragging = previewScene(scene);
    std::vector<DragRow> drags;
    std::ostringstream releaseCsv;
    releaseCsv << "luminaire,refines,seconds,spp,mean_delta_e,rel_rmse\n";
    std::vector<std::pair<std::string, double>> releaseTimes;  // seconds to Delta E < 1 (NaN: never)
    std::vector<std::pair<std::string, double>> restartTimes;  // the same when everything restarts
    Renderer fullRenderer(shaders);  // the editor's full renderer, apart from the preview's
    bool first = true;
    std::vector<std::pair<std::string, double>> finalDeltaE;
    for (size_t i = 0; i < scene.luminaires.size(); ++i) {
        const std::string name = scene.luminaires[i]->name;
        // Compile every variant before timing anything.
        renderer.setSettings(preview);
        renderer.update(shownWhileDragging, kChangeAll);
        renderer.renderFrame();
        drags.push_back(drag(renderer, scene, shownWhileDragging, i, preview, frames, "preview"));
        drags.push_back(drag(renderer, scene, scene, i, full, std::max(4, frames / 6), "full"));
        for (const DragRow* r : {&drags[drags.size() - 2], &drags.back()})
            std::fprintf(stderr, "bench: drag %-16s %-8s %5.1f fps (mean %.1f ms, 95th percentile %.1f ms)\n",
                         name.c_str(), r->mode.c_str(), r->fps(), r->meanMs, r->p95Ms);
        for (const auto& [pass, ms] : drags[drags.size() - 2].passMs)
            std::fprintf(stderr, "bench:   preview pass %-40s %7.2f ms\n", pass.c_str(), ms);

        // Release, as in the editor: the full renderer (its own, apart from the preview's) shows
        // the luminaire where it was grabbed, a quarter round its circle, refined to the
        // editor's 256 spp (untimed: the user was looking at it); the preview renders the drag;
        // the luminaire is let go at its place. Then the full renderer refines (a) only the
        // moved luminaire, every other one keeping its accumulation, and (b) for comparison,
        // everything from scratch (what the editor did before per-luminaire accumulation).
        Luminaire& moved = *scene.luminaires[i];
        glm::dvec3 home = moved.pose.position;
        for (const char* how : {"moved only", "everything"}) {
            bool everything = std::string(how) == "everything";
            moved.pose.position = home + kDragRadius * glm::dvec3(1.0, 0.0, 1.0);
            fullRenderer.setSettings(full);
            fullRenderer.update(scene, first ? kChangeAll : kChangeLuminaires);
            first = false;
            do fullRenderer.renderFrame();
            while (!fullRenderer.converged());
            moved.pose.position = home;
            drag(renderer, scene, shownWhileDragging, i, preview, 4, "preview");
            fullRenderer.update(scene, everything ? kChangeAll & ~kChangeGeometry : kChangeLuminaires);
            double rendering = 0.0, reached = std::nan("");
            ReleasePoint last;
            while (rendering < timeout) {
                auto start = Clock::now();
                fullRenderer.renderFrame();
                glFinish();
                rendering += seconds(start, Clock::now());
                ReleasePoint p{rendering, fullRenderer.stats().samplesPerPixel,
                               meanDeltaE(fullRenderer.readDisplay(), refDisplay),
                               relRmse(fullRenderer.readLinear(), refLinear)};
                releaseCsv << '"' << name << "\"," << how << "," << p.seconds << "," << p.spp << "," << p.deltaE << ","
                           << p.rmse << "\n";
                last = p;
                if (std::isnan(reached) && p.deltaE < kTargetDeltaE) reached = p.seconds;
                if (!std::isnan(reached) || fullRenderer.converged()) break;
            }
            (everything ? restartTimes : releaseTimes).emplace_back(name, reached);
            if (!everything) finalDeltaE.emplace_back(name, last.deltaE);
            std::fprintf(stderr, "bench: release %-16s (%s refines) Delta E < %.0f after %s (Delta E %.2f)\n", name.c_str(),
                         how, kTargetDeltaE, std::isnan(reached) ? "never" : (std::to_string(reached) + " s").c_str(),
                         last.deltaE);
        }
    }

    std::ostringstream csv;
    csv << "luminaire,mode,frames,mean_ms,p95_ms,worst_ms,fps\n";
    for (const DragRow& r : drags)
        csv << '"' << r.luminaire << "\"," << r.mode << "," << r.frames << "," << r.meanMs << "," << r.p95Ms << ","
            << r.worstMs << "," << r.fps() << "\n";
    writeFileAtomically((fs::path(outDir) / "drag.csv").string(), csv.str());
    writeFileAtomically((fs::path(outDir) / "release.csv").string(), releaseCsv.str());

    std::ostringstream summary;
    char line[320];
    std::snprintf(line, sizeof line, "scene: %s at %dx%d\ncontext: %s\n", scenePath.c_str(), width, height,
                  context->description().c_str());
    summary << line;
    std::snprintf(line, sizeof line,
                  "preview while dragging: %dx%d, %d spp per frame, techniques %s, %d shadow map(s) of %d^2\n"
                  "full: %dx%d, %d spp per frame up to %d, each luminaire's own technique\n"
                  "reference: own techniques at %d spp, another seed\n",
                  preview.width, preview.height, preview.samplesPerFrame, preview.techniqueOverride.c_str(),
                  preview.shadowMaps.count, preview.shadowMaps.resolution, width, height, full.samplesPerFrame,
                  full.maxSamples, refSpp);
    summary << line;
    for (size_t i = 0; i + 1 < drags.size(); i += 2) {
        const DragRow& p = drags[i];
        const DragRow& f = drags[i + 1];
        double release = releaseTimes[i / 2].second, restart = restartTimes[i / 2].second;
        auto secondsText = [](double t) {
            return std::isnan(t) ? std::string("never (timeout or converged first)") : std::to_string(t).substr(0, 5) + " s";
        };
        std::snprintf(line, sizeof line,
                      "%-16s dragging %5.1f fps (95th percentile frame %.1f ms; full settings %.1f fps, %s slower); "
                      "after release Delta E < 1 in %s refining it alone (Delta E at the end %.2f), %s refining "
                      "everything (%s longer)\n",
                      p.luminaire.c_str(), p.fps(), p.p95Ms, f.fps(), formatRatio(f.meanMs / p.meanMs).c_str(),
                      secondsText(release).c_str(), finalDeltaE[i / 2].second, secondsText(restart).c_str(),
                      formatRatio(restart / release).c_str());
        summary << line;
    }
    writeFileAtomically((fs::path(outDir) / "summary.txt").string(), summary.str());
    std::fputs(summary.str().c_str(), stdout);

    std::ostringstream gp;
    gp << "set terminal pngcairo size 900,420 noenhanced\nset datafile separator ','\nset logscale y\nset grid\n"
           "set xlabel 'seconds after release (rendering only)'\nset ylabel 'mean Delta E against the reference'\n"
           "set key top right\nset arrow from graph 0, first 1 to graph 1, first 1 nohead dt 2\nplot ";
    for (size_t i = 0; i < scene.luminaires.size(); ++i)
        for (const char* how : {"moved only", "everything"})
            gp << (i || std::string(how) == "everything" ? ", " : "") << "'release.csv' using (strcol(1) eq '"
               << scene.luminaires[i]->name << "' && strcol(2) eq '" << how << "' ? $3 : 1/0):5 with linespoints title '"
               << scene.luminaires[i]->name << " (" << how << ")'";
    gp << "\n";
    writeFileAtomically((fs::path(outDir) / "plot.gp").string(), gp.str());
    runGnuplot(outDir, "plot.png");
    return 0;
}

}  // namespace candela
