// `candela bench --lightfield FILE.lf.json --out DIR`: what accuracy costs in time for the
// light-field techniques (Lu et al. 2015, Fig. 11 and 12). Each technique renders a fixed scene
// and view at increasing sample counts; every render is timed on the GPU (the shading pass's
// timer queries) and compared with a reference image: relative RMSE of linear luminance, and the
// mean CIE76 Delta E of the tone-mapped images (the paper's "Lab error"). Writes bench.csv, the
// images, and error-versus-time plots (gnuplot, when installed), and prints the ratios.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "app/commands/BenchUtil.h"
#include "app/commands/Commands.h"
#include "luminaires/LightField.h"
#include "renderer/ImageFile.h"
#include "renderer/Renderer.h"
#include "renderer/context/GlContext.h"
#include "scene/SceneIo.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

namespace fs = std::filesystem;

namespace {

struct Image {
    std::vector<float> linear;          ///< RGB, W/(m2 sr) (or cd/m2)
    std::vector<unsigned char> display; ///< tone-mapped sRGB8
    double shadeMs = 0.0;               ///< GPU time of the shading passes, ms
    double wallS = 0.0;
};

/// The bench scene, scaled to the luminaire's size R (the larger half-extent of S): the luminaire
/// 1.5 R above a floor and 8 R from a wall, aimed down the room and slightly down, so the floor
/// under and ahead of it is in its near field (receivers a few delta to a few R away, where the
/// restricted boxes are much smaller than the images) and the wall shows the beam.
Scene benchScene(const fs::path& lightField, const fs::path& outDir, ProtectedInputs& inputs) {
    auto lf = LightFieldData::load(lightField);
    double R = std::max({std::abs(lf->imageMin.x), std::abs(lf->imageMin.y), lf->imageMax.x, lf->imageMax.y});
    auto num = [](double v) { return std::to_string(v); };
    std::string text = R"({"geometry": [
        {"plane": {"center": [0,0,)" + num(-6 * R) + R"(], "normal": [0,1,0], "size": [)" + num(24 * R) + "," + num(20 * R) + R"(]}, "albedo": [0.6,0.6,0.6]},
        {"plane": {"center": [0,)" + num(5 * R) + "," + num(-8 * R) + R"(], "normal": [0,0,1], "size": [)" + num(24 * R) + "," + num(10 * R) + R"(]}, "albedo": [0.7,0.7,0.7]}],
      "luminaires": [{"type": "lightfield", "name": "LF", "file": ")" +
                       fs::absolute(lightField).generic_string() + R"(",
        "position": [0, )" + num(1.5 * R) + R"(, 0], "aim": [0, -0.25, -1], "c0": [1, 0, 0], "technique": "restricted-cdf"}],
      "camera": {"position": [)" + num(3 * R) + "," + num(4 * R) + "," + num(3 * R) + R"(], "target": [0, )" + num(0.5 * R) + "," + num(-4 * R) + R"(], "fov_deg": 65}})";
    Scene scene = parseScene(nlohmann::json::parse(text), (fs::absolute(lightField).parent_path() / "bench.json").string());
    inputs.add(scene.luminaires[0]->sourceFiles());
    // Kept beside the results, so `candela render` can reproduce any image.
    writeFileAtomically((outDir / "bench_scene.json").string(), nlohmann::json::parse(text).dump(2) + "\n");
    return scene;
}

Image render(Renderer& renderer, const Scene& scene, RenderSettings settings, const std::string& technique,
             int spp, uint32_t seed) {
    settings.techniqueOverride = technique;
    settings.samplesPerFrame = std::min(spp, 64);
    settings.maxSamples = spp;
    settings.seed = seed;
    renderer.setSettings(settings);
    renderer.update(scene, kChangeAll);
    Image img;
    auto start = std::chrono::steady_clock::now();
    do {
        renderer.renderFrame();
        for (const auto& p : renderer.stats().passes)
            if (p.name.rfind("shade:", 0) == 0) img.shadeMs += p.gpuMs;
    } while (!renderer.converged());
    img.wallS = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    img.linear = renderer.readLinear();
    img.display = renderer.readDisplay();
    return img;
}

}  // namespace

int cmdBench(const Args& args) {
    if (std::find(args.begin(), args.end(), "--prost") != args.end()) return benchProst(args);
    if (std::find(args.begin(), args.end(), "--environment") != args.end()) return benchEnvironment(args);
    if (std::find(args.begin(), args.end(), "--shadows") != args.end()) return benchShadows(args);
    if (std::find(args.begin(), args.end(), "--indirect") != args.end()) return benchIndirect(args);
    if (std::find(args.begin(), args.end(), "--drag") != args.end()) return benchDrag(args);
    std::string lfPath, outDir = "bench-lightfield";
    std::vector<int> sppList = {4, 8, 16, 32, 64, 128, 256, 512};
    int refSpp = 8192, width = 256, height = 192;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--lightfield") lfPath = flagValue(args, i);
        else if (a == "--out") outDir = flagValue(args, i);
        else if (a == "--spp") sppList = parseList(flagValue(args, i));
        else if (a == "--reference-spp") refSpp = parseInt(a, flagValue(args, i), 16, 1 << 22);
        else if (a == "--size") parseSize(flagValue(args, i), width, height);
        else throw InputError("bench: unknown option " + a);
    }
    if (lfPath.empty())
        throw InputError("usage: candela bench --lightfield FILE.lf.json [--out DIR] [--spp 4,8,...] "
                         "[--reference-spp N] [--size WxH]");
    fs::create_directories(outDir);

    auto loadStart = std::chrono::steady_clock::now();
    ProtectedInputs inputs;  // the light field and its images, once loaded
    Scene scene = benchScene(lfPath, outDir, inputs);
    double loadMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - loadStart).count();
    const auto& lf = *static_cast<const LightFieldLuminaire&>(*scene.luminaires[0]).data;
    auto context = createOffscreenContext();
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    RenderSettings settings;
    settings.width = width;
    settings.height = height;

    // The reference: restricted-cdf converged, as two independent halves whose difference
    // measures its own noise (the floor under which no error below can be resolved).
    std::fprintf(stderr, "bench: reference, 2 x %d spp at %dx%d\n", refSpp / 2, width, height);
    Image half1 = render(renderer, scene, settings, "restricted-cdf", refSpp / 2, 1000001);
    Image half2 = render(renderer, scene, settings, "restricted-cdf", refSpp / 2, 2000003);
    Image ref = half1;
    for (size_t i = 0; i < ref.linear.size(); ++i) ref.linear[i] = 0.5f * (half1.linear[i] + half2.linear[i]);
    double refNoise = 0.5 * relRmse(half1.linear, half2.linear);  // of the mean of both halves
    double avg = meanLuminance(ref.linear);
    settings.fixedAverage = float(avg);  // every image tone-mapped against the reference's mean
    // Re-tone-map the reference with that average: one more (cheap, converged) render.
    Image refShown = render(renderer, scene, settings, "restricted-cdf", refSpp / 2, 1000001);
    ref.display = refShown.display;
    writeImage8((fs::path(outDir) / "reference.png").string(), width, height, ref.display);
    writeImageFloat((fs::path(outDir) / "reference.exr").string(), width, height, ref.linear);

    std::vector<BenchRow> rows;
    const char* techniques[] = {"restricted-cdf", "uniform-restricted", "precomputed-global"};
    // Compile every variant before timing anything.
    for (const char* t : techniques) render(renderer, scene, settings, t, 1, 1);
    uint32_t seed = 7;
    for (const char* t : techniques)
        for (int spp : sppList) {
            Image img = render(renderer, scene, settings, t, spp, seed++);
            // The image and the reference are independent, so E|x - r|^2 = |x - t|^2 + |r - t|^2:
            // the reference's own noise is removed from the error against it.
            BenchRow r = benchRow(t, spp, img.shadeMs, img.linear, img.display, ref.linear, ref.display, refNoise);
            rows.push_back(r);
            std::fprintf(stderr, "bench: %-20s %6d spp  %9.1f ms  rel. RMSE %.4f (raw %.4f)  Delta E %.3f\n", t,
                         spp, r.shadeMs, r.rmse, r.rawRmse, r.deltaE);
            if (spp == sppList.front() || spp == 64 || spp == sppList.back())
                writeImage8((fs::path(outDir) / (std::string(t) + "_" + std::to_string(spp) + ".png")).string(),
                            width, height, img.display);
        }

    // Granier et al. 2003: deterministic, one frame; its error is its bias.
    {
        render(renderer, scene, settings, "granier2003", 1, 1);  // compile
        Image img = render(renderer, scene, settings, "granier2003", 1, seed++);
        BenchRow r = benchRow("granier2003", 1, img.shadeMs, img.linear, img.display, ref.linear, ref.display,
                              refNoise);
        rows.push_back(r);
        std::fprintf(stderr, "bench: %-20s  1 frame  %9.1f ms  rel. RMSE %.4f  Delta E %.3f\n", "granier2003",
                     r.shadeMs, r.rmse, r.deltaE);
        writeImage8((fs::path(outDir) / "granier2003.png").string(), width, height, img.display);
    }

    writeBenchCsv((fs::path(outDir) / "bench.csv").string(), rows);

    // Ratios, measured side by side in this run.
    std::ostringstream summary;
    char line[256];
    std::snprintf(line, sizeof line, "light field: %s (%dx%d images of %dx%d), precomputation %.1f ms, load %.0f ms\n",
                  lfPath.c_str(), lf.count.x, lf.count.y, lf.width, lf.height, lf.precomputeMs, loadMs);
    summary << line;
    std::snprintf(line, sizeof line,
                  "reference: restricted-cdf, %d spp, %dx%d, own noise (rel. RMSE) %.5f, removed from every "
                  "error below in quadrature\n",
                  refSpp, width, height, refNoise);
    summary << line << "context: " << context->description() << "\n";
    for (int spp : sppList) {
        double rc = 0, ur = 0, gl = 0;
        for (const BenchRow& r : rows)
            if (r.spp == spp) (r.technique == "restricted-cdf" ? rc : r.technique == "uniform-restricted" ? ur : gl) = r.rmse;
        double need = atError(rows, "uniform-restricted", rc, false);
        double tRc = 0;
        for (const BenchRow& r : rows)
            if (r.spp == spp && r.technique == "restricted-cdf") tRc = r.shadeMs;
        double tGl = atError(rows, "precomputed-global", rc, true);
        double tUr = atError(rows, "uniform-restricted", rc, true);
        std::snprintf(line, sizeof line,
                      "%5d spp: error uniform/restricted %.2fx, global/restricted %.2fx; for restricted's "
                      "error uniform needs %s spp (%s) and %s the time, global %s the time\n",
                      spp, ur / rc, gl / rc, std::isnan(need) ? "more than the sweep's" : std::to_string(int(need)).c_str(),
                      formatRatio(need / spp).c_str(), formatRatio(tUr / tRc).c_str(), formatRatio(tGl / tRc).c_str());
        summary << line;
    }
    for (const BenchRow& r : rows)
        if (r.technique == "granier2003") {
            std::snprintf(line, sizeof line,
                          "granier2003 (deterministic, approximate): rel. RMSE %.4f, Delta E %.3f in %.1f ms\n",
                          r.rmse, r.deltaE, r.shadeMs);
            summary << line;
        }
    writeFileAtomically((fs::path(outDir) / "summary.txt").string(), summary.str());
    std::fputs(summary.str().c_str(), stdout);

    // Plots: error against GPU time, log-log.
    const std::string kTechniques = "restricted-cdf uniform-restricted precomputed-global granier2003";
    std::ostringstream gp;
    gp << "set terminal pngcairo size 900,420 noenhanced\nset datafile separator ','\nset logscale xy\n"
          "set grid\nset key bottom left\nset multiplot layout 1,2\n"
          "set xlabel 'GPU time of the shading pass (ms)'\nset ylabel 'rel. RMSE (luminance, ref. noise removed)'\n"
       << sweepPlot(kTechniques, 3, 4) << "set ylabel 'mean Delta E (CIE76, tone-mapped)'\n"
       << sweepPlot(kTechniques, 3, 5) << "unset multiplot\n";
    writeFileAtomically((fs::path(outDir) / "plot.gp").string(), gp.str());
    runGnuplot(outDir, "error_vs_time.png");
    std::printf("wrote %s/bench.csv and images\n", outDir.c_str());
    return 0;
}

}  // namespace candela
