// `candela bench --environment sky|MAP.hdr|MAP.exr --out DIR`: what accuracy costs in time for
// the environment techniques (Lu et al. 2013), on a fixed scene (a ground, a matte box and a
// glossy box, so shadow rays and the Phong lobe both run) and view. Three parts, one run:
//  1. Error against samples and GPU time for each technique (relative RMSE of linear luminance
//     and mean CIE76 Delta E of the tone-mapped images against a converged reference), and the
//     samples uniform-faces needs to match balanced (the paper: 60 against 180);
//  2. Per-frame cost of a changing map at 128^2 and 256^2 faces: the table rebuild (Algorithm 1)
//     and the sample pools against the shading pass, with the sun moving every frame;
//  3. Temporal stability while the sun moves slowly (the metric is defined in part 3 below).
// Writes bench.csv, rebuild.csv, temporal.csv, summary.txt, the images and plots.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/commands/BenchHarness.h"
#include "app/commands/BenchUtil.h"
#include "app/commands/Commands.h"
#include "luminaires/environment/Environment.h"
#include "scene/SceneIo.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

namespace fs = std::filesystem;

namespace {

/// The bench's sky: a clear noon-ish sun 35 degrees up (its disc a few texels of a 1024-wide
/// map, some 1e4 times the sky's luminance), the moving map of parts 2 and 3 in any case.
SkyParams benchSky() {
    SkyParams sky;
    sky.sunElevationDeg = 35.0;
    sky.sunAzimuthDeg = 120.0;
    sky.width = 1024;
    return sky;
}

/// The sky of the bench with the sun at `azimuthDeg`.
std::shared_ptr<const EnvironmentMap> skyAt(SkyParams sky, double azimuthDeg) {
    sky.sunAzimuthDeg = azimuthDeg;
    return makeSkyMap(sky);
}

/// The bench scene around `source` (the sky or a map file): a 20 m ground, a matte 1 m box and
/// a glossy one (Phong exponent from roughness 0.3), seen from 5 m.
Scene benchScene(const std::string& source, const SkyParams& sky, const fs::path& outDir) {
    nlohmann::json doc = nlohmann::json::parse(R"({"geometry": [
        {"plane": {"center": [0, 0, 0], "normal": [0, 1, 0], "size": [20, 20]}, "albedo": [0.5, 0.5, 0.5]},
        {"box": {"center": [-0.7, 0.5, 0], "size": [1, 1, 1], "rotate_y_deg": 20}, "albedo": [0.7, 0.6, 0.5]},
        {"box": {"center": [0.9, 0.4, 0.6], "size": [0.8, 0.8, 0.8], "rotate_y_deg": -15},
         "albedo": [0.1, 0.2, 0.4], "specular": [0.5, 0.5, 0.5], "roughness": 0.3}],
      "camera": {"position": [3.2, 2.4, 4.2], "target": [0, 0.4, 0], "fov_deg": 50}})");
    doc["environment"] = source == "sky"
                             ? nlohmann::json{{"sky",
                                               {{"sun_elevation_deg", sky.sunElevationDeg},
                                                {"sun_azimuth_deg", sky.sunAzimuthDeg},
                                                {"resolution", sky.width}}}}
                             : nlohmann::json{{"file", fs::absolute(source).generic_string()}};
    // Kept beside the results, so `candela render` can reproduce any image.
    writeFileAtomically((outDir / "bench_scene.json").string(), doc.dump(2) + "\n");
    return parseScene(doc, (outDir / "bench_scene.json").string());
}

/// Part 1 compares the paper's techniques (Lu et al. 2013: balanced against uniform faces), the
/// balance heuristic and a global CDF, in that order, with Havran et al. 2005 as the
/// deterministic baseline: a chosen list, not the whole table (which has the CPU reference and
/// the variants of part 3).
Sweep environmentSweep(const EnvironmentOptions& o) {
    Sweep sweep;
    sweep.slot = TechniqueSlot::Environment;
    // balanced-mis: unbiased, and the most robust on the glossy box.
    sweep.reference = "balanced-mis";
    sweep.referenceSpp = o.referenceSpp;
    sweep.progressive = {"balanced", "uniform-faces", "balanced-mis", "global-cdf"};
    sweep.deterministic = {"havran2005"};
    sweep.spp = o.spp;
    // Each point is the mean squared error of `repeats` images with independent seeds: the
    // balanced techniques share one pool of light samples per face among all pixels of a frame,
    // so part of a frame's error is common to every pixel and one image's rmse varies much
    // from seed to seed (their spread goes in the CSV).
    sweep.repeats = o.repeats;
    sweep.timedPasses = "shade:environment";
    return sweep;
}

void addErrorSummary(BenchSummary& summary, const std::vector<BenchRow>& rows,
                     const EnvironmentOptions& o, double refNoise) {
    summary.add(
        "\n1. error against samples (reference: balanced-mis, %d spp, own noise %.5f removed in "
        "quadrature; each error the root mean square over %d images of independent seeds)\n",
        o.referenceSpp, refNoise, o.repeats);
    for (int spp : o.spp) {
        BenchRow balanced = rowAt(rows, "balanced", spp);
        double eb = balanced.rmse, em = rowAt(rows, "balanced-mis", spp).rmse;
        double needU = atError(rows, "uniform-faces", eb, false);
        double needUm = atError(rows, "uniform-faces", em, false);
        double timeU = atError(rows, "uniform-faces", eb, true);
        summary.add(
            "%5d spp: rel. RMSE balanced %.4f, uniform-faces %.4f, balanced-mis %.4f, global-cdf "
            "%.4f; uniform-faces needs %s the samples of balanced (%s of balanced-mis) and %s its "
            "time\n",
            spp, eb, rowAt(rows, "uniform-faces", spp).rmse, em,
            rowAt(rows, "global-cdf", spp).rmse, formatRatio(needU / spp).c_str(),
            formatRatio(needUm / spp).c_str(), formatRatio(timeU / balanced.shadeMs).c_str());
    }
    for (const BenchRow& r : rows)
        if (r.technique == "havran2005")
            summary.add(
                "havran2005 (256 lights, deterministic): rel. RMSE %.4f, Delta E %.3f in %.2f ms\n",
                r.rmse, r.deltaE, r.shadeMs);
}

double median(std::vector<double> v) {
    if (v.empty()) return std::nan("");
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

/// Part 2 at one face size and sample count: 8 frames (after one that compiles and warms up),
/// each with the sun 0.5 degrees further, so Algorithm 1 runs every frame. Rows go to `csv`.
void rebuildFrames(Renderer& renderer, Scene& scene, RenderSettings s, const SkyParams& sky,
                   int faceSize, int spp, CsvFile& csv, BenchSummary& summary) {
    s.environmentFaceSize = faceSize;
    s.environmentTechnique = "balanced";
    s.samplesPerFrame = spp;
    s.maxSamples = 0;
    renderer.setSettings(s);
    std::vector<double> cdf, samples, shade, cpu;
    for (int frame = -1; frame < 8; ++frame) {
        auto start = std::chrono::steady_clock::now();
        scene.environmentMap = skyAt(sky, sky.sunAzimuthDeg + 0.5 * (frame + 2));  // rebuilt
        renderer.update(scene, kChangeEnvironment);
        renderer.renderFrame();
        double wall =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        const std::vector<PassTiming>& passes = renderer.stats().passes;
        double c = gpuMs(passes, "env:cdf"), smp = gpuMs(passes, "env:samples");
        double sh = gpuMs(passes, "shade:environment");
        if (frame < 0) continue;
        cdf.push_back(c), samples.push_back(smp), shade.push_back(sh), cpu.push_back(wall);
        csv.row(faceSize, spp, c, smp, sh, wall);
    }
    std::string line = formatText(
        "  %3d^2 faces, %2d spp/frame: tables %.2f ms + sample pools %.2f ms against "
        "shading %.2f ms (tables %.0f %% of shading); whole frame incl. sky on the CPU "
        "and upload %.0f ms wall\n",
        faceSize, spp, median(cdf), median(samples), median(shade),
        100.0 * median(cdf) / median(shade), median(cpu));
    summary.addText(line);
    std::fprintf(stderr, "bench: %s", line.c_str());
}

/// Part 2: the sun moves every frame, so every frame gets a new map.
void measureRebuild(Renderer& renderer, Scene& scene, const RenderSettings& settings,
                    const SkyParams& sky, BenchSummary& summary, const fs::path& out) {
    summary.addText(
        "\n2. per frame with the sun moving (a new map every frame), medians of 8 frames\n");
    CsvFile csv("face_size,spp,cdf_ms,samples_ms,shade_ms,upload_and_sky_ms");
    for (int faceSize : {128, 256})
        for (int spp : {16, 64})
            rebuildFrames(renderer, scene, settings, sky, faceSize, spp, csv, summary);
    csv.write(out / "rebuild.csv");
}

std::vector<double> luminances(const std::vector<float>& rgb) {
    std::vector<double> y(rgb.size() / 3);
    for (size_t i = 0; i < y.size(); ++i) y[i] = luma(&rgb[3 * i]);
    return y;
}

/// One case of part 3: what renders each frame, and whether its seed changes.
struct TemporalCase {
    const char* name;
    const char* technique;
    bool freshSeed;
};

/// The context of part 3's renders.
struct Temporal {
    Renderer& renderer;
    Scene& scene;
    RenderSettings settings;  ///< 128^2 faces
    SkyParams sky;
    const EnvironmentOptions& options;
};

/// Luminance of the image with the sun `offsetDeg` further, `spp` samples of `technique`.
std::vector<double> temporalFrame(Temporal& t, double offsetDeg, const char* technique, int spp,
                                  uint32_t seed) {
    t.scene.environmentMap = skyAt(t.sky, t.sky.sunAzimuthDeg + offsetDeg);
    RenderSettings s =
        withBudget(withTechnique(t.settings, TechniqueSlot::Environment, technique), spp, seed, 64);
    return luminances(renderShot(t.renderer, t.scene, s).linear);
}

/// The true change per step: converged images of the first and last frame (the same seed for
/// both), their relative RMS difference divided by the number of steps.
void addConvergedChange(Temporal& t, double step, BenchSummary& summary) {
    int frames = t.options.temporalFrames;
    std::vector<double> first =
        temporalFrame(t, 0.0, "balanced-mis", t.options.referenceSpp / 4, 77);
    std::vector<double> last =
        temporalFrame(t, step * (frames - 1), "balanced-mis", t.options.referenceSpp / 4, 77);
    double num = 0, den = 0;
    for (size_t i = 0; i < first.size(); ++i)
        num += (last[i] - first[i]) * (last[i] - first[i]), den += first[i] * first[i];
    summary.add(
        "  sun step %.3f deg/frame; change of converged images per step %.5f (an upper bound: "
        "their own "
        "decorrelation included)\n",
        step, std::sqrt(num / den) / (frames - 1));
}

/// The flicker of one case at one sun step: a row per frame pair in `csv`, a summary line.
void measureFlicker(Temporal& t, double step, const TemporalCase& c, CsvFile& csv,
                    BenchSummary& summary) {
    std::vector<double> prev, deltas;
    double sumD2 = 0, sumI2 = 0, sumI = 0;
    for (int frame = 0; frame < t.options.temporalFrames; ++frame) {
        auto y = temporalFrame(t, step * frame, c.technique, t.options.temporalSpp,
                               c.freshSeed ? uint32_t(101 + frame) : 101u);
        if (!prev.empty()) {
            double d2 = 0, i2 = 0;
            for (size_t i = 0; i < y.size(); ++i) {
                double d = y[i] - prev[i];
                d2 += d * d, i2 += prev[i] * prev[i], sumI += prev[i];
                deltas.push_back(std::abs(d));
            }
            sumD2 += d2, sumI2 += i2;
            csv.row(step, std::string(c.technique) + (c.freshSeed ? "-fresh-seed" : ""), frame,
                    std::sqrt(d2 / i2));
        }
        prev = std::move(y);
    }
    double meanI = sumI / double(deltas.size());
    size_t k = size_t(0.999 * double(deltas.size()));
    std::nth_element(deltas.begin(), deltas.begin() + long(k), deltas.end());
    std::string line =
        formatText("    %-48s flicker %.5f, 99.9th percentile step %.4f of the mean\n", c.name,
                   std::sqrt(sumD2 / sumI2), deltas[k] / meanI);
    summary.addText(line);
    std::fprintf(stderr, "bench: step %.3f: %s", step, line.c_str());
}

/// Part 3. The sun moves by a fixed step a frame (0.01 degrees is the real sun's motion in
/// about 2 s) for `temporalFrames` frames of temporalSpp samples, every frame a new map and a
/// new accumulation. Metric: the flicker of static pixels, sqrt(sum_t,p (I_t+1(p) - I_t(p))^2 /
/// sum_t,p I_t(p)^2) over luminance, and its tail, the 99.9th percentile of
/// |I_t+1(p) - I_t(p)| / mean_p I over all pixel steps.
void measureTemporal(Temporal& t, BenchSummary& summary, const fs::path& out) {
    summary.add(
        "\n3. temporal stability: the sun moving a fixed step per frame, %d frames of %d spp, "
        "128^2 faces\n",
        t.options.temporalFrames, t.options.temporalSpp);
    // The fractional and integer sample counts, a fixed against a fresh seed, uniform faces and
    // Havran's filtered lights: the comparisons part 3 is about.
    const TemporalCase cases[] = {
        {"balanced (fractional N_f, same seed)", "balanced", false},
        {"balanced-integer (N_f rounded, same seed)", "balanced-integer", false},
        {"balanced (fractional N_f, new seed per frame)", "balanced", true},
        {"uniform-faces (same seed)", "uniform-faces", false},
        {"havran2005 (filtered lights)", "havran2005", false}};
    CsvFile csv("sun_step_deg,case,frame,flicker_step");
    for (double step : {0.001, 0.01, 0.05}) {
        addConvergedChange(t, step, summary);
        for (const TemporalCase& c : cases) measureFlicker(t, step, c, csv, summary);
    }
    csv.write(out / "temporal.csv");
}

void plotResults(const fs::path& out) {
    writePlot(
        out, 1350, 420,
        "set logscale xy\nset grid\nset key bottom left\nset multiplot layout 1,3\n"
        "set xlabel 'samples per pixel'\nset ylabel 'rel. RMSE (luminance, ref. noise removed)'\n" +
            sweepPlot("balanced uniform-faces balanced-mis global-cdf", 2, 4) +
            "set xlabel 'GPU time of the shading pass (ms)'\n" +
            sweepPlot("balanced uniform-faces balanced-mis global-cdf havran2005", 3, 4) +
            "unset logscale\nset logscale y\nset xlabel 'frame (sun +0.01 deg each)'\n"
            "set ylabel 'frame-to-frame change (rel. RMS)'\nset key top right\n"
            "plot for [t in 'balanced balanced-integer balanced-fresh-seed uniform-faces "
            "havran2005'] "
            "'temporal.csv' using (strcol(2) eq t && $1 == 0.01 ? $3 : 1/0):4 with linespoints "
            "title t.' "
            "(0.01 deg/frame)'\nunset multiplot\n",
        "error_vs_time.png");
}

}  // namespace

int benchEnvironment(const EnvironmentOptions& o) {
    BenchFolder folder(o.out);  // whole or not at all: committed at the end
    const fs::path& out = folder.path();
    SkyParams sky = benchSky();
    ProtectedInputs
        inputs;  // the map (MAP.hdr|MAP.exr): bench_scene.json and every image must miss it
    if (o.source != "sky") inputs.add(o.source);
    // Before any work: none of the files with fixed names may be the map (each image of the
    // sweep is checked as it is written).
    for (const char* name :
         {"bench_scene.json", "reference.png", "reference.exr", "bench.csv", "rebuild.csv",
          "temporal.csv", "error_vs_time.png", "summary.txt", "plot.gp"})
        checkNotAnInput((fs::path(o.out) / name).string(), "--out");
    Scene scene = benchScene(o.source, sky, out);
    BenchGpu gpu;
    RenderSettings settings;
    settings.width = o.width;
    settings.height = o.height;
    BenchSummary summary;
    summary.light(
        "the environment's direct light with shadows (shadow rays); no interreflected light");
    summary.add("environment: %s (%dx%d lat-long), scene %s, %dx%d pixels\ncontext: %s\n",
                o.source == "sky" ? "procedural sky, sun 35 deg up" : o.source.c_str(),
                scene.environmentMap->width(), scene.environmentMap->height(),
                (fs::path(o.out) / "bench_scene.json").c_str(), o.width, o.height,
                gpu.context->description().c_str());

    Sweep sweep = environmentSweep(o);
    Reference ref = renderReference(gpu.renderer, scene, settings, sweep, out);
    std::vector<BenchRow> rows = runSweep(gpu.renderer, scene, settings, sweep, ref, out);
    writeBenchCsv((out / "bench.csv").string(), rows);
    addErrorSummary(summary, rows, o, ref.noise);

    measureRebuild(gpu.renderer, scene, settings, sky, summary, out);
    RenderSettings temporalSettings = settings;
    temporalSettings.environmentFaceSize = 128;
    Temporal temporal{gpu.renderer, scene, temporalSettings, sky, o};
    measureTemporal(temporal, summary, out);

    summary.write(out);
    plotResults(out);
    folder.commit();
    std::printf("wrote %s/bench.csv, rebuild.csv, temporal.csv and images\n", o.out.c_str());
    return 0;
}

}  // namespace candela
