// `candela bench --lightfield FILE.lf.json --out DIR`: what accuracy costs in time for the
// light-field techniques (Lu et al. 2015, Fig. 11 and 12). Each technique renders a fixed scene
// and view at increasing sample counts; every render is timed on the GPU (the shading pass's
// timer queries) and compared with a reference image: relative RMSE of linear luminance, and the
// mean CIE76 Delta E of the tone-mapped images (the paper's "Lab error"). Writes bench.csv, the
// images, and error-versus-time plots (gnuplot, when installed), and prints the ratios.
// cmdBench, at the end, reads the command line of every bench and runs the one it names.
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

/// A default path as the help shows it: relative to the source folder, where the examples run.
std::string shown(const std::string& path) {
    const std::string root = std::string(CANDELA_SOURCE_DIR) + "/";
    return path.rfind(root, 0) == 0 ? path.substr(root.size()) : path;
}

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
        if (t.kind == LuminaireKind::LightField && t.shadowMaps)
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
    inputs.add(sourceFiles(*scene.luminaires[0]));
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
int benchLightField(const LightFieldOptions& o) {
    BenchFolder folder(o.out);  // whole or not at all: committed at the end
    const fs::path& out = folder.path();
    auto loadStart = std::chrono::steady_clock::now();
    ProtectedInputs inputs;  // the light field and its images, once loaded
    Scene scene = benchScene(o.lightField, out, inputs);
    double loadMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - loadStart)
            .count();
    const auto& lf = *lightFieldModel(*scene.luminaires[0])->data;
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

/// The range of an integer option for one bench: converts it (parseInt's error) and states it,
/// with the default, in the help.
struct Range {
    int min, max;
    int parse(const std::string& flag, const std::string& text) const {
        return parseInt(flag, text, min, max);
    }
    std::string text(int value) const { return formatText("%d..%d (%d)", min, max, value); }
};

// The ranges of the options several benches take.
constexpr Range kReferenceSpp{16, 1 << 22};  // --lightfield, --environment, --prost
constexpr Range kDragReferenceSpp{16, 1 << 20}, kDesignReferenceSpp{64, 1 << 20};
constexpr Range kEnvironmentFrames{3, 10000}, kDragFrames{4, 100000};
constexpr Range kShadowSpp{1, kMaxSampleCount}, kProstSize{8, 2048};

/// A bench of `candela bench`: its flag and the options it takes besides --out.
struct Bench {
    const char* flag;
    std::vector<std::string> options;
    bool takes(const std::string& option) const {
        return std::find(options.begin(), options.end(), option) != options.end();
    }
};

const std::vector<Bench>& benches() {
    static const std::vector<Bench> list = {
        {"--lightfield", {"--spp", "--reference-spp", "--size", "--fig11"}},
        {"--environment", {"--spp", "--reference-spp", "--size", "--frames", "--repeats"}},
        {"--prost", {"--size", "--reference-spp"}},
        {"--shadows", {"--spp", "--size", "--maps", "--map-sizes", "--count-at", "--size-at"}},
        {"--indirect", {"--patches", "--move"}},
        {"--drag",
         {"--size", "--frames", "--reference-spp", "--preview-scale", "--preview-techniques",
          "--preview-spp", "--samples-per-frame", "--timeout"}},
        {"--design", {"--reference-spp", "--scenes"}},
    };
    return list;
}

/// The one bench the command line names, every option given being one it takes; throws
/// CommandUsageError otherwise.
const Bench& chosenBench(const CommandLine& cli) {
    std::vector<const Bench*> named;
    for (const Bench& b : benches())
        if (cli.given(b.flag)) named.push_back(&b);
    if (named.empty())
        throw CommandUsageError(
            "missing the bench to run: --lightfield F.lf.json, --environment sky|MAP.hdr|MAP.exr, "
            "--prost, --shadows, --indirect, --drag or --design",
            cli.shortHelp());
    if (named.size() > 1)
        throw CommandUsageError(
            std::string(named[0]->flag) + " and " + named[1]->flag + " are two benches: give one",
            cli.shortHelp());
    const Bench& bench = *named[0];
    for (const Bench& other : benches())
        for (const std::string& option : other.options) {
            if (!cli.given(option) || bench.takes(option)) continue;
            std::vector<std::string> owners;
            for (const Bench& b : benches())
                if (b.takes(option)) owners.emplace_back(b.flag);
            std::string list = owners[0];
            for (size_t i = 1; i < owners.size(); ++i)
                list += (i + 1 < owners.size() ? ", " : " and ") + owners[i];
            throw CommandUsageError(option + " is an option of " + list + ", not of " + bench.flag,
                                    cli.shortHelp());
        }
    return bench;
}

/// "4,8,16".
std::string listText(const std::vector<int>& values) {
    std::string text;
    for (int v : values) {
        if (!text.empty()) text += ',';
        text += std::to_string(v);
    }
    return text;
}

/// `v`, refusing an empty file or folder name.
std::string named(const std::string& flag, const std::string& v, const char* what) {
    if (v.empty()) throw InputError(flag + ": expected a " + what + " name, got an empty one");
    return v;
}

}  // namespace

int cmdBench(const Args& args) {
    LightFieldOptions lightField;
    EnvironmentOptions environment;
    ProstOptions prost;
    ShadowOptions shadows;
    IndirectOptions indirect;
    DragOptions drag;
    DesignOptions design;
    std::vector<std::string> files;
    // The options several benches take, as given: converted for the bench chosen, after parse.
    std::string out, size, spp, referenceSpp, frames;
    auto keep = [](std::string& to) { return [&to](const std::string& v) { to = v; }; };

    CommandLine cli("bench");
    cli.group("the bench (one of them)");
    cli.option(
        "--lightfield", "F.lf.json",
        "the light-field techniques' error against GPU time, on a scene scaled to the "
        "light field (Lu et al. 2015, Fig. 11 and 12)",
        [&](const std::string& v) { lightField.lightField = named("--lightfield", v, "file"); });
    cli.option(
        "--environment", "sky|MAP.hdr|MAP.exr",
        "the environment techniques (Lu et al. 2013) under the map (sky: the bench's "
        "procedural sky): error against samples and GPU time, the cost of a changing map, "
        "stability while the sun moves",
        [&](const std::string& v) { environment.source = named("--environment", v, "file"); });
    cli.flag("--prost",
             "Prost's evaluation (2019, Sec. 6.2) of the photometric techniques on the FILEs: "
             "NMSE, error bounds, light bumps, GPU time",
             [] {});
    cli.flag("--shadows",
             "per-cell shadow maps against ray-traced shadows, on the scene FILE (default " +
                 shown(shadows.scenePath) + ")",
             [] {});
    cli.flag("--indirect",
             "what interreflected light costs in time, from scratch and after a luminaire moves, "
             "and how it scales with the patches, on the scene FILE (default " +
                 shown(indirect.scenePath) + ")",
             [] {});
    cli.flag("--drag",
             "how live the editor stays while each luminaire of the scene FILE is dragged, and how "
             "soon the image is right again after release (default " +
                 shown(drag.scenePath) + ")",
             [] {});
    cli.flag("--design",
             "a designer's calculations (grid, surfaces, reports) on the shipped office and "
             "classroom: time, and accuracy against a reference",
             [] {});
    cli.arguments(
        "FILE", files,
        "--prost: the photometry files, one or more (FILE.ies, FILE.ldt; a folder stands "
        "for every .ies and .ldt file under it); --shadows, --indirect, --drag: the scene",
        false);

    cli.group("options of several benches");
    cli.option("--out", "DIR",
               "the folder to write, whole or not at all (created with its parents); default " +
                   lightField.out + ", " + environment.out + ", " + prost.out + ", " + shadows.out +
                   ", " + indirect.out + ", " + drag.out + " or " + design.out + " after the bench",
               [&out](const std::string& v) { out = named("--out", v, "folder"); });
    cli.option("--spp", "N,N,..|N",
               "samples per pixel. --lightfield, --environment: the counts swept, each 1.." +
                   std::to_string(kMaxSampleCount) + " (" +
                   (lightField.spp == environment.spp
                        ? listText(lightField.spp)
                        : listText(lightField.spp) + ", " + listText(environment.spp)) +
                   "); --shadows: of every image, " + kShadowSpp.text(shadows.spp),
               keep(spp));
    cli.option("--reference-spp", "N",
               "the reference's samples per pixel: --lightfield " +
                   kReferenceSpp.text(lightField.referenceSpp) + ", --environment " +
                   kReferenceSpp.text(environment.referenceSpp) + ", --prost " +
                   kReferenceSpp.text(prost.referenceSpp) + ", --drag " +
                   kDragReferenceSpp.text(drag.referenceSpp) +
                   "; --design: the rays gathering each point's interreflected light in the "
                   "reference, " +
                   kDesignReferenceSpp.text(design.referenceSpp),
               keep(referenceSpp));
    auto sizeText = [](int width, int height) { return formatText("%dx%d", width, height); };
    cli.option("--size", "WxH|N",
               "the image's size in pixels, each side 1..16384 (--lightfield " +
                   sizeText(lightField.width, lightField.height) + ", --environment " +
                   sizeText(environment.width, environment.height) + ", --shadows " +
                   sizeText(shadows.width, shadows.height) + ", --drag " +
                   sizeText(drag.width, drag.height) +
                   ": the full image); --prost: N, the receivers along each side of the ground "
                   "imaged, " +
                   kProstSize.text(prost.size),
               keep(size));
    cli.option("--frames", "N",
               "--environment: frames of the moving sun for the temporal stability, " +
                   kEnvironmentFrames.text(environment.temporalFrames) +
                   "; --drag: frames of each drag, " + kDragFrames.text(drag.frames),
               keep(frames));

    // An integer option of one bench, its range and default in the help.
    auto integer = [&cli](const std::string& name, int& value, Range range, const char* form,
                          const std::string& help) {
        cli.integer(name, value, range.min, range.max, form, help + ", " + range.text(value));
    };
    cli.group("options of --lightfield");
    cli.option(
        "--fig11", "SPP,SAMPLES|none",
        "the paper's Fig. 11 too: restricted-cdf at SPP samples per pixel against SAMPLES "
        "shared samples of the global CDFs (precomputed-shared) and as many per pixel "
        "(precomputed-global), e.g. 63,63000 (minutes of rendering); none: not rendered (" +
            (lightField.fig11.empty() ? "the default" : "default " + listText(lightField.fig11)) +
            ")",
        [&](const std::string& v) {
            if (v == "none") {
                lightField.fig11.clear();
                return;
            }
            std::vector<int> counts = parseList(v, "--fig11");
            if (counts.size() != 2)
                throw InputError("--fig11: expected SPP,SAMPLES (e.g. 63,63000) or none");
            lightField.fig11 = counts;
        });
    cli.group("options of --environment");
    integer("--repeats", environment.repeats, {1, 64}, "K",
            "images of independent seeds averaged at each point of the sweep");
    cli.group("options of --shadows");
    cli.option("--maps", "N,N,..",
               "the shadow maps per luminaire swept, 0 meaning one per cell of the light field (" +
                   listText(shadows.counts) + ")",
               [&shadows](const std::string& v) {
                   shadows.counts.clear();
                   for (float c : parseNumberList("--maps", v)) shadows.counts.push_back(int(c));
               });
    cli.option("--map-sizes", "N,N,..",
               "the cube-face resolutions swept, texels, each 1.." +
                   std::to_string(kMaxSampleCount) + " (" + listText(shadows.sizes) + ")",
               [&shadows](const std::string& v) { shadows.sizes = parseList(v, "--map-sizes"); });
    integer("--count-at", shadows.fixedSize, {8, 4096}, "TEXELS",
            "the cube-face resolution while the map count is swept, texels");
    integer("--size-at", shadows.fixedCount, {0, 4096}, "N",
            "the shadow maps per luminaire while the resolution is swept, 0 meaning one per cell");
    cli.group("options of --indirect");
    integer("--patches", indirect.patches, {16, 50000}, "N",
            "about this many patches for the interreflection (asked of the mesher)");
    cli.text("--move", indirect.moved, "NAME",
             "the luminaire moved 1 m along x (" + indirect.moved + ")");
    cli.group("options of --drag");
    cli.option(
        "--preview-scale", "S",
        "the preview's pixels per full-resolution pixel, per axis, in (0, 1] (" +
            formatText("%g", drag.policy.scale) + ")",
        [&drag](const std::string& v) {
            float scale = parseNumberList("--preview-scale", v).at(0);
            if (!(scale > 0.f && scale <= 1.f))
                throw InputError("--preview-scale: expected a number in (0, 1], got \"" + v + "\"");
            drag.policy.scale = scale;
        });
    cli.text("--preview-techniques", drag.policy.techniques, "T,T,..",
             "the techniques the preview tries first, before each luminaire kind's preview "
             "technique (" +
                 (drag.policy.techniques.empty() ? "none" : drag.policy.techniques) + ")");
    integer("--preview-spp", drag.policy.samplesPerFrame, {1, 1024}, "N",
            "the preview's light samples per pixel and luminaire each frame");
    integer("--samples-per-frame", drag.samplesPerFrame, {1, 1024}, "N",
            "the full settings' samples per pixel each pass, as the editor refines");
    cli.option(
        "--timeout", "SECONDS",
        "the longest refinement after a release, seconds of rendering, 1..100000 (" +
            formatText("%g", drag.timeout) + ")",
        [&drag](const std::string& v) { drag.timeout = parseInt("--timeout", v, 1, 100000); });
    cli.group("options of --design");
    cli.text("--scenes", design.scenes, "DIR",
             "the folder of office.json, classroom.json and office-gldf.json (" +
                 shown(design.scenes) + ")");
    if (!cli.parse(args)) return 0;

    const Bench& bench = chosenBench(cli);
    const std::string flag = bench.flag;
    auto given = [&cli](const char* option) { return cli.given(option); };
    // FILE...: --prost's files, or the scene of a bench that takes one.
    std::string* scene = flag == "--shadows"    ? &shadows.scenePath
                         : flag == "--indirect" ? &indirect.scenePath
                         : flag == "--drag"     ? &drag.scenePath
                                                : nullptr;
    if (flag == "--prost") {
        if (files.empty())
            throw CommandUsageError(
                "missing FILE... (the photometry files, or folders of them, to evaluate)",
                cli.shortHelp());
        prost.files = files;
    } else if (!files.empty()) {
        if (!scene || files.size() > 1)
            throw CommandUsageError("unexpected argument " + files[scene ? 1 : 0], cli.shortHelp());
        *scene = files[0];
    }

    if (flag == "--lightfield") {
        if (given("--out")) lightField.out = out;
        if (given("--spp")) lightField.spp = parseList(spp);
        if (given("--reference-spp"))
            lightField.referenceSpp = kReferenceSpp.parse("--reference-spp", referenceSpp);
        if (given("--size")) parseSize(size, lightField.width, lightField.height);
        return benchLightField(lightField);
    }
    if (flag == "--environment") {
        if (given("--out")) environment.out = out;
        if (given("--spp")) environment.spp = parseList(spp);
        if (given("--reference-spp"))
            environment.referenceSpp = kReferenceSpp.parse("--reference-spp", referenceSpp);
        if (given("--size")) parseSize(size, environment.width, environment.height);
        if (given("--frames"))
            environment.temporalFrames = kEnvironmentFrames.parse("--frames", frames);
        return benchEnvironment(environment);
    }
    if (flag == "--prost") {
        if (given("--out")) prost.out = out;
        if (given("--size")) prost.size = kProstSize.parse("--size", size);
        if (given("--reference-spp"))
            prost.referenceSpp = kReferenceSpp.parse("--reference-spp", referenceSpp);
        return benchProst(prost);
    }
    if (flag == "--shadows") {
        if (given("--out")) shadows.out = out;
        if (given("--spp")) shadows.spp = kShadowSpp.parse("--spp", spp);
        if (given("--size")) parseSize(size, shadows.width, shadows.height);
        return benchShadows(shadows);
    }
    if (flag == "--indirect") {
        if (given("--out")) indirect.out = out;
        return benchIndirect(indirect);
    }
    if (flag == "--drag") {
        if (given("--out")) drag.out = out;
        if (given("--size")) parseSize(size, drag.width, drag.height);
        if (given("--frames")) drag.frames = kDragFrames.parse("--frames", frames);
        if (given("--reference-spp"))
            drag.referenceSpp = kDragReferenceSpp.parse("--reference-spp", referenceSpp);
        return benchDrag(drag);
    }
    if (given("--out")) design.out = out;
    if (given("--reference-spp"))
        design.referenceSpp = kDesignReferenceSpp.parse("--reference-spp", referenceSpp);
    return benchDesign(design);
}

}  // namespace candela
