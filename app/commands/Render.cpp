#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/commands/Commands.h"
#include "calculation/CalculationGrid.h"
#include "calculation/Interreflection.h"
#include "calculation/InterreflectionWorker.h"
#include "renderer/Comparison.h"
#include "renderer/ImageFile.h"
#include "renderer/Renderer.h"
#include "renderer/context/GlContext.h"
#include "report/ComparisonExport.h"
#include "report/Report.h"
#include "scene/SceneIo.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

namespace {

/// The brightest pixel's luminance (lux in illuminance mode).
float peakLuminance(const std::vector<float>& rgb) {
    float peak = 0.f;
    for (size_t i = 0; i + 2 < rgb.size(); i += 3)
        peak = std::max(peak, 0.2126f * rgb[i] + 0.7152f * rgb[i + 1] + 0.0722f * rgb[i + 2]);
    return peak;
}

}  // namespace

namespace {

/// "--pane LIST[:SPP]": a pane's technique list and its sample budget (default spp).
PaneSpec parsePane(const std::string& text, int spp) {
    PaneSpec pane{text, spp};
    size_t colon = text.rfind(':');
    if (colon != std::string::npos) {
        pane.technique = text.substr(0, colon);
        pane.samples = parseInt("--pane", text.substr(colon + 1), 1, 1 << 20);
    }
    checkTechniqueList(pane.technique);
    return pane;
}

/// `candela render --pane ... --sheet DIR`: the editor's comparison, headless, to its sheet.
int renderComparison(const std::string& scenePath, const RenderSettings& settings,
                     const std::vector<PaneSpec>& panes, int referenceSpp, const std::string& dir,
                     bool errorMaps) {
    Scene scene = loadScene(scenePath);
    ProtectedInputs inputs(scene.inputFiles());  // the sheet's files are new names, checked anyway
    auto context = createOffscreenContext();
    ShaderLibrary shaders;
    Comparison comparison(shaders);
    comparison.configure(panes, settings, referenceSpp);
    comparison.update(scene, kChangeAll);
    auto start = std::chrono::steady_clock::now();
    while (!comparison.done()) {
        comparison.step(0.0);
        std::string line = "\rcompare: reference " + std::to_string(comparison.referenceSpp()) +
                           "/" + std::to_string(referenceSpp) + " spp";
        for (size_t i = 0; i < comparison.paneCount(); ++i)
            line += ", " + std::string(1, char('A' + i)) + " " +
                    std::to_string(comparison.result(i).spp) + " spp";
        std::fprintf(stderr, "%s", line.c_str());
    }
    std::fprintf(stderr, "\n");
    std::vector<std::string> names;
    for (size_t i = 0; i < panes.size(); ++i) names.emplace_back(1, char('A' + i));
    SheetFiles files = exportComparisonSheet(dir, comparison, scene, names, errorMaps);
    double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("pane,techniques,spp,gpu_ms,mean_delta_e,rel_rmse\n");
    for (size_t i = 0; i < comparison.paneCount(); ++i) {
        const PaneResult& r = comparison.result(i);
        std::printf("%s,%s,%d,%.3f,%.4f,%.5f\n", names[i].c_str(),
                    techniqueSummary(comparison.paneRenderer(i).plan()).c_str(), r.spp, r.gpuMs,
                    r.latest.deltaE, r.latest.relRmse);
    }
    std::printf("reference: %d spp, own noise (rel. RMSE) %.5f\n", comparison.referenceSpp(),
                comparison.referenceNoise());
    std::printf("wrote %s\nwrote %s\nwrote %s\n(%.1f s)\n", files.png.c_str(), files.exr.c_str(),
                files.json.c_str(), seconds);
    return 0;
}

/// What `candela render` was asked for.
struct RenderOptions {
    std::string scenePath, out, sheetDir;
    RenderSettings settings;
    int spp = 64, referenceSpp = 512;
    std::vector<std::string> paneTexts;
    bool printStats = false, falseColour = false, haveLegend = false, errorMaps = false,
         indirect = true, haveExposure = false;
    bool askedIndirect = false, askedNoIndirect = false;  ///< --indirect, --no-indirect given.
    int patches = 4000;  ///< Asked of the interreflection's mesher.
};

/// The options of both forms: the image's size and sampling, the shadow maps, the tone mapping.
void declareShared(CommandLine& cli, RenderOptions& o) {
    RenderSettings& settings = o.settings;
    cli.argument("scene.json", o.scenePath, "the scene file");
    cli.group("options of both forms");
    cli.option(
        "--size", "WxH", "the image's size, pixels (512x512)",
        [&settings](const std::string& v) { parseSize(v, settings.width, settings.height); });
    cli.integer("--spp", o.spp, 1, 1 << 24, "N",
                "light samples per pixel per luminaire of progressive techniques (64; exact ones "
                "finish in one frame); in a sheet, the samples of each pane without :SPP");
    cli.integer("--env-face-size", settings.environmentFaceSize, 4, 2048, "N",
                "the environment's cube faces of N x N texels (default: half the map's width, "
                "within 8..256)");
    cli.integer("--shadow-maps", settings.shadowMaps.count, 0, 4096, "N",
                "shadow maps per luminaire, about, for techniques that read them (49; 0: one per "
                "cell)");
    cli.integer("--shadow-map-size", settings.shadowMaps.resolution, 8, 4096, "R",
                "texels along the edge of a shadow map's cube face (192)");
    cli.option(
        "--tonemap", "exponential|reinhard", "the tone mapping of PNG images (exponential)",
        [&settings](const std::string& op) {
            if (op == "exponential")
                settings.toneMap = ToneMapOperator::Exponential;
            else if (op == "reinhard")
                settings.toneMap = ToneMapOperator::Reinhard;
            else
                throw InputError("--tonemap: expected exponential or reinhard, got \"" + op + "\"");
        });
    cli.option("--exposure", "K",
               "the tone mapping's exposure k (default: the scene camera's exposure when it has "
               "one, else 1; a sheet: 1)",
               [&o](const std::string& v) {
                   o.settings.exposure = parseNumberList("--exposure", v).at(0);
                   o.haveExposure = true;
               });
    cli.strictPhotometry();
}

/// --indirect and --no-indirect; `--indirect on|off`, their old spelling, with a line saying so.
void declareIndirect(CommandLine& cli, RenderOptions& o) {
    cli.optionalValue(
        "--indirect", {"on", "off"},
        "interreflected light, computed first on the CPU where some surface reflects onto another "
        "(the default); on and off are old spellings of --indirect and --no-indirect",
        [&o](const std::string& v) {
            if (!v.empty() && v != "on" && v != "off")
                throw InputError(
                    "--indirect: a switch (--indirect, or --no-indirect to leave the light out); "
                    "expected no value, or on or off, got \"" +
                    v + "\"");
            if (!v.empty())
                std::fprintf(stderr,
                             "candela render: --indirect %s is now spelled %s (the old spelling "
                             "will stop working in the next release)\n",
                             v.c_str(), v == "on" ? "--indirect" : "--no-indirect");
            (v == "off" ? o.askedNoIndirect : o.askedIndirect) = true;
        });
    cli.flag("--no-indirect", o.askedNoIndirect, "leave interreflected light out");
    cli.integer("--patches", o.patches, 16, 50000, "N",
                "about this many patches for the interreflection (4000)");
}

/// The options of the single view (--out).
void declareView(CommandLine& cli, RenderOptions& o) {
    RenderSettings& settings = o.settings;
    cli.group("the single view (--out)");
    cli.output("--out", o.out, "F.png|F.exr",
               "the image: PNG tone-mapped (sRGB), EXR linear (radiance in cd/m2 or W/(m2 sr), "
               "which it prints; with --false-colour, illuminance)");
    cli.text("--technique", settings.techniqueOverride, "T",
             "a technique, or a comma-separated list, for every luminaire, each taking the first "
             "its kind has (default: each luminaire's own)");
    cli.text("--env-technique", settings.environmentTechnique, "T",
             "the environment's technique (default: --technique's when it names one, else "
             "balanced)");
    declareIndirect(cli, o);
    cli.option("--light", "total|direct|interreflected", "the light the image shows (total)",
               [&settings](const std::string& v) {
                   if (v == "total")
                       settings.parts = LightParts::Total;
                   else if (v == "direct")
                       settings.parts = LightParts::Direct;
                   else if (v == "interreflected")
                       settings.parts = LightParts::Interreflected;
                   else
                       throw InputError(
                           "--light: expected total, direct or interreflected, got \"" + v + "\"");
               });
    cli.flag("--stats", o.printStats,
             "print the GL context, the interreflection, each pass's total GPU time and the "
             "shader variants compiled");
    cli.flag(
        "--false-colour", o.falseColour,
        "the illuminance in false colour with isolux lines, in the scene's unit (lx, or W/m2); "
        "a PNG carries its legend on its right");
    FalseColourLegend& legend = settings.legend;
    cli.option(
        "--legend", "MIN,MAX",
        "with --false-colour: the scale's range, in the scene's unit (default: fitted to the "
        "image)",
        [&o, &legend](const std::string& v) {
            std::vector<float> range = parseNumberList("--legend", v);
            if (range.size() != 2 || !(range[1] > range[0]))
                throw InputError("--legend: expected MIN,MAX in lux with MAX > MIN");
            legend.min = range[0];
            legend.max = range[1];
            o.haveLegend = true;
        });
    cli.flag("--log", legend.logScale,
             "with --false-colour: a log scale, decades equally spaced (default: linear)");
    cli.option("--isolux", "L,..|none",
               "with --false-colour: the isolux levels, in the scene's unit (default: at the "
               "legend's ticks); none: no isolux lines",
               [&legend](const std::string& v) {
                   if (v == "none")
                       legend.contours = false;
                   else
                       legend.levels = parseNumberList("--isolux", v);
               });
}

/// The options of the comparison sheet (--sheet DIR --pane ...).
void declareSheet(CommandLine& cli, RenderOptions& o) {
    cli.group("the comparison sheet (--sheet DIR --pane ...)");
    cli.output("--sheet", o.sheetDir, "DIR",
               "the folder the sheet is written into (sheet-NNN.png, .exr and .json)");
    cli.option("--pane", "TECHNIQUES[:SPP]",
               "a pane, 1 to 4 times: a technique list such as "
               "photometric=scattered,lightfield=precomputed-global (empty: each luminaire's own) "
               "and its samples per pixel (default: --spp)",
               [&o](const std::string& v) { o.paneTexts.push_back(v); });
    cli.integer("--reference-spp", o.referenceSpp, 1, 1 << 20, "N",
                "samples per pixel of the progressive reference (512)");
    cli.flag("--error-maps", o.errorMaps,
             "each pane's tile shows its error against the reference instead of its image");
}

/// Whether the options given are the comparison sheet's (else the single view's); options of
/// the other form, and contradictory ones, are bad usage.
bool chooseForm(const CommandLine& cli, RenderOptions& o) {
    static const char* const kView[] = {
        "--out",   "--technique", "--env-technique", "--indirect", "--no-indirect", "--patches",
        "--light", "--stats",     "--false-colour",  "--legend",   "--log",         "--isolux"};
    static const char* const kSheet[] = {"--sheet", "--pane", "--reference-spp", "--error-maps"};
    if (o.askedIndirect && o.askedNoIndirect)
        throw CommandUsageError(
            "interreflected light both asked for (--indirect) and left out (--no-indirect): give "
            "one of them",
            cli.shortHelp());
    o.indirect = !o.askedNoIndirect;
    bool sheet = cli.given("--sheet") || cli.given("--pane");
    if (sheet) {
        for (const char* name : kView)
            if (cli.given(name))
                throw CommandUsageError(std::string(name) +
                                            ": an option of the single view (--out F.png|F.exr), "
                                            "not of a comparison sheet (--sheet DIR --pane ...)",
                                        cli.shortHelp());
        if (!cli.given("--sheet"))
            throw CommandUsageError(
                "missing --sheet DIR (the folder the comparison sheet is "
                "written into)",
                cli.shortHelp());
        if (o.paneTexts.empty())
            throw CommandUsageError(
                "missing --pane TECHNIQUES[:SPP] (a pane of the comparison, 1 to 4 times)",
                cli.shortHelp());
        if (o.paneTexts.size() > 4)
            throw CommandUsageError(
                "--pane: expected 1 to 4 times, got " + std::to_string(o.paneTexts.size()),
                cli.shortHelp());
        return true;
    }
    for (const char* name : kSheet)
        if (cli.given(name))
            throw CommandUsageError(std::string(name) +
                                        ": an option of a comparison sheet (--sheet DIR --pane "
                                        "...), not of the single view (--out F.png|F.exr)",
                                    cli.shortHelp());
    if (!cli.given("--out"))
        throw CommandUsageError(
            "missing --out F.png|F.exr (the image to write; --sheet DIR --pane ... writes a "
            "comparison sheet instead)",
            cli.shortHelp());
    return false;
}

/// The comparison sheet: panes, a reference, errors (the editor's Export sheet).
int renderSheet(RenderOptions& o) {
    std::vector<PaneSpec> panes;
    for (const std::string& p : o.paneTexts) panes.push_back(parsePane(p, o.spp));
    o.settings.samplesPerFrame = 16;
    return renderComparison(o.scenePath, o.settings, panes, o.referenceSpp, o.sheetDir,
                            o.errorMaps);
}

/// Checks an image render's options; returns the output's extension.
std::string checkImageOptions(RenderOptions& o) {
    RenderSettings& settings = o.settings;
    if (o.falseColour) {
        settings.quantity = Quantity::Illuminance;
        settings.toneMap = ToneMapOperator::FalseColour;
        if (settings.legend.logScale && o.haveLegend && !(settings.legend.min > 0.f))
            throw InputError("--legend: a log scale (--log) needs MIN > 0 lux");
    }
    std::string ext = std::filesystem::path(o.out).extension().string();
    if (ext != ".png" && ext != ".exr")
        throw InputError(o.out + ": unsupported output extension \"" + ext +
                         "\" (use .png or .exr)");
    return ext;
}

using Clock = std::chrono::steady_clock;

/// Interreflected light, computed first on the CPU: only where some surface reflects onto
/// another (docs/computation.md, "Interreflected light"). Returns the line that says what it did.
std::string addInterreflection(Renderer& renderer, const Scene& scene, const RenderOptions& o,
                               Clock::time_point start) {
    if (!o.indirect) return "interreflection: off (--no-indirect)";
    InterreflectionOptions io;
    io.mesh.targetPatches = o.patches;
    const std::string& technique = o.settings.techniqueOverride;
    io.technique = technique.find(',') == std::string::npos ? technique : "";
    io.directSpp = InterreflectionWorker::kFineSpp;
    Interreflection ir(scene, io);
    if (std::string w = ir.orientationWarning(scene); !w.empty())
        std::fprintf(stderr, "render: warning: %s\n", w.c_str());
    std::string line = "interreflection: none (no surface reflects onto another)";
    if (ir.mesh().reflects() && ir.compute() && ir.hasInterreflection()) {
        std::vector<glm::vec3> v;
        for (const glm::dvec3& e : ir.indirectAtVertices()) v.push_back(glm::vec3(e));
        renderer.setIndirect(std::make_shared<RadiosityMesh>(ir.mesh()), std::move(v));
        char text[160];
        std::snprintf(text, sizeof text, "interreflection: %zu patches, %d iterations, %.2f s",
                      ir.mesh().patches.size(), ir.lastIterations(),
                      std::chrono::duration<double>(Clock::now() - start).count());
        line = text;
    }
    std::fprintf(stderr, "render: %s\n", line.c_str());
    return line;
}

/// Renders until converged, showing progress; each pass's GPU time summed over the frames.
std::vector<PassTiming> refine(Renderer& renderer, int spp, int& frames) {
    std::vector<PassTiming> totals;
    frames = 0;
    do {
        renderer.renderFrame();
        ++frames;
        for (const auto& p : renderer.stats().passes) {
            auto it = std::find_if(totals.begin(), totals.end(),
                                   [&](const PassTiming& t) { return t.name == p.name; });
            if (it == totals.end())
                totals.push_back(p);
            else
                it->gpuMs += p.gpuMs;
        }
        if (renderer.plan().progressive() && frames % 8 == 0)
            std::fprintf(stderr, "\rrender: %d / %d samples per pixel",
                         renderer.stats().samplesPerPixel, spp);
    } while (!renderer.converged());
    if (renderer.plan().progressive()) std::fprintf(stderr, "\n");
    return totals;
}

/// --false-colour: fits the legend to the image unless --legend gave it, and prints it.
void reportFalseColour(Renderer& renderer, const Scene& scene, RenderOptions& o) {
    RenderSettings& settings = o.settings;
    if (!o.haveLegend) {
        fitLegend(settings.legend, peakLuminance(renderer.readLinear()));
        renderer.setSettings(settings);
        renderer.renderFrame();  // converged: tone mapping only, with the new legend
    }
    FalseColourLegend legend = sanitizedLegend(settings.legend);
    const char* unit = scene.units().irradiance();
    std::printf("false colour: %g .. %g %s (%s)", legend.min, legend.max, unit,
                legend.logScale ? "log" : "linear");
    std::vector<float> levels = contourLevels(legend);
    for (size_t k = 0; k < levels.size(); ++k)
        std::printf("%s%g", k ? ", " : ", isolux at ", levels[k]);
    std::printf("%s%s", levels.empty() ? ", no isolux lines" : " ", levels.empty() ? "" : unit);
    if (scene.units().converted) std::printf(" (%s)", scene.units().note().c_str());
    std::printf("\n");
}

/// --stats: the context, the interreflection, each pass's total GPU time and the variants.
void printStats(const GlContext& context, const ShaderLibrary& shaders,
                const std::string& indirectLine, const std::vector<PassTiming>& totals) {
    std::printf("context: %s\n", context.description().c_str());
    std::printf("%s\n", indirectLine.c_str());
    std::printf("pass,gpu_ms_total\n");
    for (const auto& p : totals) std::printf("%s,%.3f\n", p.name.c_str(), p.gpuMs);
    std::printf("variants:");
    for (const auto& v : shaders.compiledVariants()) std::printf(" %s", v.c_str());
    std::printf("\n");
}

/// Writes the PNG (tone-mapped) or EXR (linear, in the unit it prints).
void writeRender(const Renderer& renderer, const Scene& scene, const RenderOptions& o,
                 const std::string& ext, int frames, double seconds) {
    const RenderSettings& settings = o.settings;
    if (ext == ".png" && o.falseColour) {
        // The legend beside the picture: the scale, its ticks in the scene's unit, the isolux
        // levels (report/Report.h).
        int width = settings.width;
        std::vector<unsigned char> withLegend =
            withFalseColourLegend(renderer.readDisplay(), width, settings.height, settings.legend,
                                  scene.units().irradiance());
        writeImage8(o.out, width, settings.height, withLegend);
    } else if (ext == ".png") {
        writeImage8(o.out, settings.width, settings.height, renderer.readDisplay());
    } else
        writeImageFloat(o.out, settings.width, settings.height, renderer.readLinear());
    std::printf(
        "wrote %s (%dx%d%s, %d frames, %.3f s)\n", o.out.c_str(), settings.width, settings.height,
        ext == ".png" && o.falseColour ? " and the legend on its right" : "", frames, seconds);
    if (ext != ".png") {
        UnitSystem units = scene.units();
        bool illuminance = settings.quantity == Quantity::Illuminance;
        std::printf("linear values in %s%s%s\n",
                    illuminance ? units.irradiance() : units.radiance(),
                    units.converted ? ", " : "", units.note().c_str());
    }
}

}  // namespace

void checkSceneViewSize(int width, int height) {
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    auto context = createOffscreenContext();
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    renderer.setSettings(settings);
    renderer.allocateImages();
}

std::vector<unsigned char> renderSceneView(const Scene& scene, const GridSpec& how, int width,
                                           int height, int spp, std::string& note) {
    RenderOptions o;
    o.settings.width = width;
    o.settings.height = height;
    if (scene.camera.exposure > 0.0) o.settings.exposure = float(scene.camera.exposure);
    o.spp = spp;
    o.settings.samplesPerFrame = std::min(spp, 16);
    o.settings.maxSamples = spp;
    o.indirect = how.indirect;
    o.patches = how.patches;
    auto context = createOffscreenContext();
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    renderer.setSettings(o.settings);
    renderer.update(scene, kChangeAll);
    renderer.allocateImages();  // a size too large fails before the interreflection
    auto start = Clock::now();
    addInterreflection(renderer, scene, o, start);
    int frames = 0;
    refine(renderer, spp, frames);
    std::fprintf(stderr, "view: %dx%d pixels, %d samples per pixel in %.1f s\n", width, height, spp,
                 std::chrono::duration<double>(Clock::now() - start).count());
    note = std::to_string(width) + "x" + std::to_string(height) + " pixels, " +
           std::to_string(spp) + " samples per pixel, direct light with shadows" +
           (how.indirect ? " and the interreflected light of the same surface patches as the "
                           "numbers"
                         : ", without interreflected light");
    return renderer.readDisplay();
}

int cmdRender(const Args& args) {
    RenderOptions o;
    CommandLine cli("render");
    declareShared(cli, o);
    declareView(cli, o);
    declareSheet(cli, o);
    if (!cli.parse(args)) return 0;
    if (chooseForm(cli, o)) return renderSheet(o);
    std::string ext = checkImageOptions(o);
    Scene scene = loadScene(o.scenePath);
    ProtectedInputs inputs(scene.inputFiles());
    checkNotAnInput(o.out, "--out");
    if (!o.haveExposure && scene.camera.exposure > 0.0)
        o.settings.exposure = float(scene.camera.exposure);
    auto context = createOffscreenContext();
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    renderer.setExactTimes(true);  // --passes-csv and the sidecar report each pass's own time
    o.settings.samplesPerFrame = std::min(o.spp, 16);
    o.settings.maxSamples = o.spp;
    renderer.setSettings(o.settings);
    renderer.update(scene, kChangeAll);
    renderer.allocateImages();  // a size too large fails before the interreflection

    auto start = Clock::now();
    std::string indirectLine = addInterreflection(renderer, scene, o, start);
    int frames = 0;
    std::vector<PassTiming> totals = refine(renderer, o.spp, frames);
    if (o.falseColour) reportFalseColour(renderer, scene, o);
    double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    writeRender(renderer, scene, o, ext, frames, seconds);
    if (o.printStats) printStats(*context, shaders, indirectLine, totals);
    return 0;
}

}  // namespace candela
