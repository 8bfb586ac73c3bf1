// `candela bench --shadows [SCENE] --out DIR`: what the per-cell shadow maps of Lu et al. 2015
// (Sec. 6.2) cost and how far they are from exact visibility, on a scene with light-field
// luminaires and occluders (by default the demo room with the car headlight). Every image uses
// restricted-cdf with the same seed, so all of them draw the same light samples; they differ only
// in visibility: the reference traces a shadow ray per sample (restricted-cdf-raytraced), the
// others read shadow maps. Sweeps the map count at one resolution and the resolution at one
// count. A second ray-traced image with another seed gives the sampling noise's own Delta E.
// Writes shadows.csv, summary.txt, the images and plot.png.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "app/commands/BenchUtil.h"
#include "app/commands/Commands.h"
#include "renderer/ImageFile.h"
#include "renderer/Renderer.h"
#include "renderer/context/GlContext.h"
#include "scene/SceneIo.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

namespace fs = std::filesystem;

namespace {

struct ShadowShot {
    std::vector<float> linear;
    std::vector<unsigned char> display;
    double shadowMs = 0.0;  ///< GPU time of the shadow-map passes
    double shadeMs = 0.0;   ///< GPU time of the shading passes
    int maps = 0;           ///< Maps per luminaire actually rendered (the first luminaire's)
};

ShadowShot shoot(Renderer& renderer, const Scene& scene, RenderSettings settings, const std::string& technique,
                 int spp, uint32_t seed) {
    settings.techniqueOverride = technique;
    settings.samplesPerFrame = std::min(spp, 16);
    settings.maxSamples = spp;
    settings.seed = seed;
    renderer.setSettings(settings);
    renderer.update(scene, kChangeAll);
    ShadowShot shot;
    do {
        renderer.renderFrame();
        for (const auto& p : renderer.stats().passes) {
            if (p.name.rfind("shadow:", 0) == 0) shot.shadowMs += p.gpuMs;
            else if (p.name.rfind("shade:", 0) == 0) shot.shadeMs += p.gpuMs;
        }
    } while (!renderer.converged());
    shot.linear = renderer.readLinear();
    shot.display = renderer.readDisplay();
    for (const auto& lum : scene.luminaires)
        if (lum->kind() == "lightfield") {
            shot.maps = int(lum->shadowLights(settings.shadowMaps.count).lights.size());
            break;
        }
    return shot;
}

}  // namespace

int benchShadows(const Args& args) {
    std::string scenePath = std::string(CANDELA_SOURCE_DIR) + "/resources/scenes/headlight-room.json";
    std::string outDir = "bench-shadows";
    std::vector<int> counts = {1, 4, 9, 16, 25, 49, 0};
    std::vector<int> sizes = {32, 64, 128, 192, 256, 512};
    int spp = 256, width = 480, height = 270, fixedCount = 49, fixedSize = 192;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--shadows") {
            if (i + 1 < args.size() && args[i + 1].rfind("--", 0) != 0) scenePath = args[++i];
        } else if (a == "--out") outDir = flagValue(args, i);
        else if (a == "--spp") spp = parseInt(a, flagValue(args, i), 1, 1 << 20);
        else if (a == "--size") parseSize(flagValue(args, i), width, height);
        else if (a == "--maps") {
            counts.clear();
            for (int c : parseNumberList(a, flagValue(args, i))) counts.push_back(c);
        } else if (a == "--map-sizes") sizes = parseList(flagValue(args, i));
        else if (a == "--count-at") fixedSize = parseInt(a, flagValue(args, i), 8, 4096);
        else if (a == "--size-at") fixedCount = parseInt(a, flagValue(args, i), 0, 4096);
        else throw InputError("usage: candela bench --shadows [SCENE.json] [--out DIR] [--spp N] [--size WxH] "
                              "[--maps 1,4,...,0] [--map-sizes 32,64,...] [--count-at R] [--size-at N]");
    }
    Scene scene = loadScene(scenePath);
    ProtectedInputs inputs(scene.inputFiles());
    bool any = false;
    for (const auto& lum : scene.luminaires) any = any || lum->kind() == "lightfield";
    if (!any) throw InputError(scenePath + ": the shadow bench needs a light-field luminaire in the scene");
    fs::create_directories(outDir);
    const fs::path out(outDir);
    auto context = createOffscreenContext();
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    const uint32_t seed = 7;

    std::printf("shadow bench: %s, %dx%d, %d spp\n", scenePath.c_str(), width, height, spp);
    ShadowShot ref = shoot(renderer, scene, settings, "restricted-cdf-raytraced", spp, seed);
    writeImage8((out / "raytraced.png").string(), width, height, ref.display);
    ShadowShot other = shoot(renderer, scene, settings, "restricted-cdf-raytraced", spp, seed + 1);
    double noiseDeltaE = meanDeltaE(other.display, ref.display);
    double noiseRmse = relRmse(other.linear, ref.linear);
    std::printf("ray-traced: shading %.0f ms; another seed: Delta E %.3f, rel. RMSE %.4f\n", ref.shadeMs,
                noiseDeltaE, noiseRmse);

    std::ostringstream csv;  // shadows.csv, rewritten whole after every row (a long sweep shows its progress)
    csv << "sweep,maps_requested,maps,resolution,shadow_ms,shade_ms,mean_delta_e,rel_rmse\n";
    char row[256];
    auto measure = [&](const char* sweep, int count, int size) {
        RenderSettings s = settings;
        s.shadowMaps.count = count;
        s.shadowMaps.resolution = size;
        ShadowShot shot = shoot(renderer, scene, s, "restricted-cdf", spp, seed);
        double dE = meanDeltaE(shot.display, ref.display), rmse = relRmse(shot.linear, ref.linear);
        std::snprintf(row, sizeof row, "%s,%d,%d,%d,%.3f,%.1f,%.4f,%.5f\n", sweep, count, shot.maps, size,
                      shot.shadowMs, shot.shadeMs, dE, rmse);
        csv << row;
        writeFileAtomically((out / "shadows.csv").string(), csv.str());
        std::printf("%-10s %4d maps of %4d^2: shadow pass %8.1f ms, shading %8.0f ms, Delta E %.3f, rel. RMSE %.4f\n",
                    sweep, shot.maps, size, shot.shadowMs, shot.shadeMs, dE, rmse);
        std::fflush(stdout);
        std::snprintf(row, sizeof row, "maps-%d-%d.png", shot.maps, size);
        writeImage8((out / row).string(), width, height, shot.display);
    };
    for (int c : counts) measure("count", c, fixedSize);
    for (int r : sizes) measure("resolution", fixedCount, r);

    std::ostringstream summary;
    summary << "scene: " << scenePath << ", " << width << "x" << height << ", " << spp
            << " spp, seed " << seed << " for every image\ncontext: " << context->description()
            << "\nreference: restricted-cdf-raytraced (a shadow ray per sample), shading " << ref.shadeMs
            << " ms\nsampling noise (the reference against seed " << seed + 1 << "): mean Delta E "
            << noiseDeltaE << ", rel. RMSE " << noiseRmse << "\n";
    writeFileAtomically((out / "summary.txt").string(), summary.str());
    std::ostringstream gp;
    gp << "set terminal pngcairo size 1000,420 noenhanced\nset datafile separator ','\nset grid\n"
           "set multiplot layout 1,2\nset logscale x\nset ylabel 'mean Delta E against ray-traced'\n"
           "set xlabel 'shadow maps per luminaire ("
        << fixedSize << "^2 faces)'\nplot 'shadows.csv' using (strcol(1) eq 'count' ? $3 : 1/0):7 with linespoints "
        << "pointsize 1.5 title 'shadow maps', " << noiseDeltaE << " title 'noise: ray-traced, another seed' dt 2\n"
        << "set xlabel 'cube-face resolution (" << fixedCount << " maps)'\nset logscale x 2\n"
        << "plot 'shadows.csv' using (strcol(1) eq 'resolution' ? $4 : 1/0):7 with linespoints pointsize 1.5 "
        << "title 'shadow maps', " << noiseDeltaE << " title 'noise: ray-traced, another seed' dt 2\n"
        << "unset multiplot\n";
    writeFileAtomically((out / "plot.gp").string(), gp.str());
    runGnuplot(outDir, "plot.png");
    std::printf("wrote %s/shadows.csv, summary.txt\n", outDir.c_str());
    return 0;
}

}  // namespace candela
