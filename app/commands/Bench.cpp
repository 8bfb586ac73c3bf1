// `candela bench --lightfield FILE.lf.json --out DIR`: what accuracy costs in time for the
// light-field techniques (Lu et al. 2015, Fig. 11 and 12). Each technique renders a fixed scene
// and view at increasing sample counts; every render is timed on the GPU (the shading pass's
// timer queries) and compared with a reference image: relative RMSE of linear luminance, and the
// mean CIE76 Delta E of the tone-mapped images (the paper's "Lab error"). Writes bench.csv, the
// images, and error-versus-time plots (gnuplot, when installed), and prints the ratios.
// `candela bench` itself picks the bench its flags name (cmdBench, at the end).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/commands/BenchHarness.h"
#include "app/commands/BenchUtil.h"
#include "app/commands/Commands.h"
#include "luminaires/Registry.h"
#include "luminaires/lightfield/LightField.h"
#include "scene/SceneIo.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

namespace fs = std::filesystem;

namespace {

struct LightFieldOptions {
    std::string lightField, out = "bench-lightfield";
    std::vector<int> spp = {4, 8, 16, 32, 64, 128, 256, 512};
    int referenceSpp = 8192;
    int width = 256, height = 192;  ///< Image size, pixels.
    /// The paper's Fig. 11 (`--fig11 63,63000`): restricted-cdf at fig11[0] spp against the
    /// shared global set of fig11[1] samples (and precomputed-global at as many); empty (the
    /// default: minutes of rendering at the paper's counts): not rendered.
    std::vector<int> fig11;
};

LightFieldOptions parseOptions(const Args& args) {
    LightFieldOptions o;
    BenchFlags()
        .text("--lightfield", o.lightField)
        .text("--out", o.out)
        .counts("--spp", o.spp)
        .integer("--reference-spp", o.referenceSpp, 16, 1 << 22)
        .size("--size", o.width, o.height)
        .value("--fig11",
               [&](const std::string& v) {
                   if (v == "none") {
                       o.fig11.clear();
                       return;
                   }
                   std::vector<int> counts = parseList(v);
                   if (counts.size() != 2)
                       throw InputError("--fig11: expected SPP,SAMPLES (e.g. 63,63000) or none");
                   o.fig11 = counts;
               })
        .parse(args, [](const std::string& a) { return "bench: unknown option " + a; });
    if (o.lightField.empty())
        throw UsageError(
            "usage: candela bench --lightfield FILE.lf.json [--out DIR] [--spp 4,8,...] "
            "[--reference-spp N] [--size WxH] [--fig11 SPP,SAMPLES|none]");
    return o;
}

/// The sweep: every light-field technique the renderer shades with shadow maps, in registry
/// order (restricted-cdf-raytraced is restricted-cdf with exact visibility, measured by
/// `bench --shadows`; `reference` is CPU only), against restricted-cdf converged.
Sweep lightFieldSweep(const LightFieldOptions& o) {
    Sweep sweep;
    sweep.reference = "restricted-cdf";
    sweep.referenceSpp = o.referenceSpp;
    sweep.spp = o.spp;
    sweep.timedPasses = "shade:";
    for (const TechniqueInfo& t : techniques())
        if (t.kind == "lightfield" && t.shadowMaps)
            (t.progressive ? sweep.progressive : sweep.deterministic).emplace_back(t.name);
    return sweep;
}

/// The bench scene, scaled to the luminaire's size R (the larger half-extent of S): the luminaire
/// 1.5 R above a floor and 8 R from a wall, aimed down the room and slightly down, so the floor
/// under and ahead of it is in its near field (receivers a few delta to a few R away, where the
/// restricted boxes are much smaller than the images) and the wall shows the beam.
Scene benchScene(const fs::path& lightField, const fs::path& outDir, ProtectedInputs& inputs) {
    auto lf = LightFieldData::load(lightField);
    double R = std::max(
        {std::abs(lf->imageMin.x), std::abs(lf->imageMin.y), lf->imageMax.x, lf->imageMax.y});
    auto num = [](double v) { return std::to_string(v); };
    std::string text =
        R"({"geometry": [
        {"plane": {"center": [0,0,)" +
        num(-6 * R) + R"(], "normal": [0,1,0], "size": [)" + num(24 * R) + "," + num(20 * R) +
        R"(]}, "albedo": [0.6,0.6,0.6]},
        {"plane": {"center": [0,)" +
        num(5 * R) + "," + num(-8 * R) + R"(], "normal": [0,0,1], "size": [)" + num(24 * R) + "," +
        num(10 * R) + R"(]}, "albedo": [0.7,0.7,0.7]}],
      "luminaires": [{"type": "lightfield", "name": "LF", "file": ")" +
        fs::absolute(lightField).generic_string() + R"(",
        "position": [0, )" +
        num(1.5 * R) +
        R"(, 0], "aim": [0, -0.25, -1], "c0": [1, 0, 0], "technique": "restricted-cdf"}],
      "camera": {"position": [)" +
        num(3 * R) + "," + num(4 * R) + "," + num(3 * R) + R"(], "target": [0, )" + num(0.5 * R) +
        "," + num(-4 * R) + R"(], "fov_deg": 65}})";
    Scene scene = parseScene(nlohmann::json::parse(text),
                             (fs::absolute(lightField).parent_path() / "bench.json").string());
    inputs.add(scene.luminaires[0]->sourceFiles());
    // Kept beside the results, so `candela render` can reproduce any image.
    writeFileAtomically((outDir / "bench_scene.json").string(),
                        nlohmann::json::parse(text).dump(2) + "\n");
    return scene;
}

/// The paper's comparison (Fig. 11 and 12): at each count, the baselines' error against the
/// restricted CDFs', and what they need in samples and time to match it.
void addRatios(BenchSummary& summary, const std::vector<BenchRow>& rows,
               const std::vector<int>& sppList) {
    for (int spp : sppList) {
        BenchRow restricted = rowAt(rows, "restricted-cdf", spp);
        double rc = restricted.rmse, tRc = restricted.shadeMs;
        double ur = rowAt(rows, "uniform-restricted", spp).rmse,
               gl = rowAt(rows, "precomputed-global", spp).rmse;
        double need = atError(rows, "uniform-restricted", rc, false);
        double tGl = atError(rows, "precomputed-global", rc, true);
        double tUr = atError(rows, "uniform-restricted", rc, true);
        summary.add(
            "%5d spp: error uniform/restricted %.2fx, global/restricted %.2fx; for restricted's "
            "error uniform needs %s spp (%s) and %s the time, global %s the time\n",
            spp, ur / rc, gl / rc,
            std::isnan(need) ? "more than the sweep's" : std::to_string(int(need)).c_str(),
            formatRatio(need / spp).c_str(), formatRatio(tUr / tRc).c_str(),
            formatRatio(tGl / tRc).c_str());
    }
    for (const BenchRow& r : rows)
        if (r.technique == "granier2003")
            summary.add(
                "granier2003 (deterministic, approximate): rel. RMSE %.4f, Delta E %.3f in %.1f "
                "ms\n",
                r.rmse, r.deltaE, r.shadeMs);
}

/// The paper's Fig. 11 (Lu et al. 2015): restricted-cdf at a few samples per pixel against one
/// shared set of many samples from the global CDFs (`precomputed-shared`, the paper's baseline),
/// and against as many samples drawn per pixel (`precomputed-global`): error and time, and their
/// ratios to restricted-cdf's. Rows go to fig11.csv, images to FIG11/.
void addFig11(BenchSummary& summary, Renderer& renderer, const Scene& scene,
              const RenderSettings& settings, const Reference& ref, const LightFieldOptions& o,
              const fs::path& out) {
    if (o.fig11.empty()) return;
    auto run = [&](const std::string& technique, int spp) {
        Sweep sweep;
        sweep.reference = "restricted-cdf";
        sweep.progressive = {technique};
        sweep.spp = {spp};
        sweep.timedPasses = "shade:";
        return runSweep(renderer, scene, settings, sweep, ref, out / "fig11").front();
    };
    fs::create_directories(out / "fig11");
    std::vector<BenchRow> rows = {run("restricted-cdf", o.fig11[0]),
                                  run("precomputed-shared", o.fig11[1]),
                                  run("precomputed-global", o.fig11[1])};
    writeBenchCsv((out / "fig11.csv").string(), rows);
    const BenchRow& r = rows[0];
    summary.add("Fig. 11: restricted-cdf %d spp: rel. RMSE %.4f, Delta E %.3f, %.1f ms\n", r.spp,
                r.rmse, r.deltaE, r.shadeMs);
    for (size_t i = 1; i < rows.size(); ++i)
        summary.add(
            "Fig. 11: %-18s %d samples: rel. RMSE %.4f (%.2fx restricted's), Delta E %.3f "
            "(%.2fx), %.1f ms (%.1fx)\n",
            rows[i].technique.c_str(), rows[i].spp, rows[i].rmse, rows[i].rmse / r.rmse,
            rows[i].deltaE, rows[i].deltaE / r.deltaE, rows[i].shadeMs,
            rows[i].shadeMs / r.shadeMs);
}

/// Error against GPU time, log-log: relative RMSE and Delta E side by side.
void plotErrorAgainstTime(const fs::path& out, const Sweep& sweep) {
    std::string list;
    for (const auto* names : {&sweep.progressive, &sweep.deterministic})
        for (const std::string& t : *names) list += (list.empty() ? "" : " ") + t;
    writePlot(out, 900, 420,
              "set logscale xy\nset grid\nset key bottom left\nset multiplot layout 1,2\n"
              "set xlabel 'GPU time of the shading pass (ms)'\nset ylabel 'rel. RMSE (luminance, "
              "ref. noise removed)'\n" +
                  sweepPlot(list, 3, 4) + "set ylabel 'mean Delta E (CIE76, tone-mapped)'\n" +
                  sweepPlot(list, 3, 5) + "unset multiplot\n",
              "error_vs_time.png");
}

/// `candela bench --lightfield`.
int benchLightField(const Args& args) {
    LightFieldOptions o = parseOptions(args);
    BenchFolder folder(o.out);  // whole or not at all: committed at the end
    const fs::path& out = folder.path();
    auto loadStart = std::chrono::steady_clock::now();
    ProtectedInputs inputs;  // the light field and its images, once loaded
    Scene scene = benchScene(o.lightField, out, inputs);
    double loadMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - loadStart)
            .count();
    const auto& lf = *static_cast<const LightFieldLuminaire&>(*scene.luminaires[0]).data;
    BenchGpu gpu;
    RenderSettings settings;
    settings.width = o.width;
    settings.height = o.height;

    Sweep sweep = lightFieldSweep(o);
    Reference ref = renderReference(gpu.renderer, scene, settings, sweep, out);
    std::vector<BenchRow> rows = runSweep(gpu.renderer, scene, settings, sweep, ref, out);
    writeBenchCsv((out / "bench.csv").string(), rows);

    BenchSummary summary;
    summary.light(
        "the light field's direct light with shadows (shadow maps; the reference a shadow ray per "
        "sample); no interreflected light: the images compare techniques");
    summary.add("light field: %s (%dx%d images of %dx%d), precomputation %.1f ms, load %.0f ms\n",
                o.lightField.c_str(), lf.count.x, lf.count.y, lf.width, lf.height, lf.precomputeMs,
                loadMs);
    summary.add(
        "reference: %s, %d spp, %dx%d, own noise (rel. RMSE) %.5f, removed from every error below "
        "in "
        "quadrature\ncontext: %s\n",
        sweep.reference.c_str(), o.referenceSpp, o.width, o.height, ref.noise,
        gpu.context->description().c_str());
    addRatios(summary, rows, o.spp);
    addFig11(summary, gpu.renderer, scene, settings, ref, o, out);
    summary.write(out);
    plotErrorAgainstTime(out, sweep);
    folder.commit();
    std::printf("wrote %s/bench.csv and images\n", o.out.c_str());
    return 0;
}

bool hasFlag(const Args& args, const char* flag) {
    return std::find(args.begin(), args.end(), flag) != args.end();
}

}  // namespace

int cmdBench(const Args& args) {
    if (hasFlag(args, "--prost")) return benchProst(args);
    if (hasFlag(args, "--environment")) return benchEnvironment(args);
    if (hasFlag(args, "--shadows")) return benchShadows(args);
    if (hasFlag(args, "--indirect")) return benchIndirect(args);
    if (hasFlag(args, "--drag")) return benchDrag(args);
    if (hasFlag(args, "--design")) return benchDesign(args);
    return benchLightField(args);
}

}  // namespace candela
