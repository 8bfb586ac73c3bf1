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

#include "app/commands/BenchHarness.h"
#include "app/commands/BenchUtil.h"
#include "app/commands/Commands.h"
#include "renderer/ImageFile.h"
#include "renderer/Renderer.h"
#include "scene/SceneIo.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

namespace fs = std::filesystem;

namespace {

/// Every image: restricted-cdf (or its ray-traced twin) with the same seed, so all of them draw
/// the same light samples and differ only in visibility. The two names are the comparison this
/// bench makes (Lu et al. 2015, Sec. 6.2: the per-cell maps against exact visibility), not a
/// list taken from the registry.
constexpr uint32_t kSeed = 7;
constexpr const char* kMapped = "restricted-cdf";
constexpr const char* kRayTraced = "restricted-cdf-raytraced";

/// One image, timed, with the maps per luminaire actually rendered (the first light field's).
Shot shoot(Renderer& renderer, const Scene& scene, const RenderSettings& settings,
           const std::string& technique, int spp, uint32_t seed, int& maps) {
    RenderSettings s =
        withBudget(withTechnique(settings, TechniqueSlot::Luminaires, technique), spp, seed, 16);
    Shot shot = renderShot(renderer, scene, s);
    for (const auto& lum : scene.luminaires)
        if (lum->kind() == LuminaireKind::LightField) {
            maps = int(shadowLights(*lum, settings.shadowMaps.count).lights.size());
            break;
        }
    return shot;
}

/// shadows.csv, rewritten whole after every row (a long sweep shows its progress), and the images.
struct ShadowSweep {
    Renderer& renderer;
    const Scene& scene;
    const RenderSettings& settings;
    const ShadowOptions& options;
    const Shot& reference;
    fs::path out;
    CsvFile csv{"sweep,maps_requested,maps,resolution,shadow_ms,shade_ms,mean_delta_e,rel_rmse"};
};

/// One image with `count` maps of `size`^2 texels per luminaire against the ray-traced one.
void measure(ShadowSweep& sweep, const char* name, int count, int size) {
    RenderSettings s = sweep.settings;
    s.shadowMaps.count = count;
    s.shadowMaps.resolution = size;
    int maps = 0;
    Shot shot = shoot(sweep.renderer, sweep.scene, s, kMapped, sweep.options.spp, kSeed, maps);
    double dE = meanDeltaE(shot.display, sweep.reference.display);
    double rmse = relRmse(shot.linear, sweep.reference.linear);
    double shadowMs = shot.gpuMs("shadow:"), shadeMs = shot.gpuMs("shade:");
    sweep.csv.line(formatText("%s,%d,%d,%d,%.3f,%.1f,%.4f,%.5f", name, count, maps, size, shadowMs,
                              shadeMs, dE, rmse));
    sweep.csv.write(sweep.out / "shadows.csv");
    std::printf(
        "%-10s %4d maps of %4d^2: shadow pass %8.1f ms, shading %8.0f ms, Delta E %.3f, rel. RMSE "
        "%.4f\n",
        name, maps, size, shadowMs, shadeMs, dE, rmse);
    std::fflush(stdout);
    writeImage8((sweep.out / formatText("maps-%d-%d.png", maps, size)).string(), s.width, s.height,
                shot.display);
}

void plotSweeps(const fs::path& out, const ShadowOptions& o, double noiseDeltaE) {
    std::string noise =
        formatText("%g title 'noise: ray-traced, another seed' dt 2\n", noiseDeltaE);
    writePlot(out, 1000, 420,
              "set grid\nset multiplot layout 1,2\nset logscale x\nset ylabel 'mean Delta E "
              "against ray-traced'\n" +
                  formatText("set xlabel 'shadow maps per luminaire (%d^2 faces)'\n", o.fixedSize) +
                  "plot 'shadows.csv' using (strcol(1) eq 'count' ? $3 : 1/0):7 with linespoints "
                  "pointsize 1.5 "
                  "title 'shadow maps', " +
                  noise +
                  formatText("set xlabel 'cube-face resolution (%d maps)'\nset logscale x 2\n",
                             o.fixedCount) +
                  "plot 'shadows.csv' using (strcol(1) eq 'resolution' ? $4 : 1/0):7 with "
                  "linespoints pointsize 1.5 "
                  "title 'shadow maps', " +
                  noise + "unset multiplot\n",
              "plot.png");
}

}  // namespace

int benchShadows(const ShadowOptions& o) {
    Scene scene = loadScene(o.scenePath);
    ProtectedInputs inputs(scene.inputFiles());
    bool any = false;
    for (const auto& lum : scene.luminaires) any = any || lum->kind() == LuminaireKind::LightField;
    if (!any)
        throw InputError(o.scenePath +
                         ": the shadow bench needs a light-field luminaire in the scene");
    BenchFolder folder(o.out);  // whole or not at all: committed at the end
    const fs::path& out = folder.path();
    BenchGpu gpu;
    RenderSettings settings;
    settings.width = o.width;
    settings.height = o.height;

    std::printf("shadow bench: %s, %dx%d, %d spp\n", o.scenePath.c_str(), o.width, o.height, o.spp);
    int maps = 0;
    Shot ref = shoot(gpu.renderer, scene, settings, kRayTraced, o.spp, kSeed, maps);
    writeImage8((out / "raytraced.png").string(), o.width, o.height, ref.display);
    Shot other = shoot(gpu.renderer, scene, settings, kRayTraced, o.spp, kSeed + 1, maps);
    double noiseDeltaE = meanDeltaE(other.display, ref.display),
           noiseRmse = relRmse(other.linear, ref.linear);
    double refShadeMs = ref.gpuMs("shade:");
    std::printf("ray-traced: shading %.0f ms; another seed: Delta E %.3f, rel. RMSE %.4f\n",
                refShadeMs, noiseDeltaE, noiseRmse);

    ShadowSweep sweep{gpu.renderer, scene, settings, o, ref, out};
    for (int c : o.counts) measure(sweep, "count", c, o.fixedSize);
    for (int r : o.sizes) measure(sweep, "resolution", o.fixedCount, r);

    BenchSummary summary;
    summary.light(
        "the luminaire's direct light with shadows, which the sweep varies; no interreflected "
        "light");
    std::ostringstream text;
    text << "scene: " << o.scenePath << ", " << o.width << "x" << o.height << ", " << o.spp
         << " spp, seed " << kSeed << " for every image\ncontext: " << gpu.context->description()
         << "\nreference: restricted-cdf-raytraced (a shadow ray per sample), shading "
         << refShadeMs << " ms\nsampling noise (the reference against seed " << kSeed + 1
         << "): mean Delta E " << noiseDeltaE << ", rel. RMSE " << noiseRmse << "\n";
    summary.addText(text.str());
    summary.write(out, false);
    plotSweeps(out, o, noiseDeltaE);
    folder.commit();
    std::printf("wrote %s/shadows.csv, summary.txt\n", o.out.c_str());
    return 0;
}

}  // namespace candela
