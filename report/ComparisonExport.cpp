#include "report/ComparisonExport.h"

#include <cmath>
#include <cstdio>

#include "report/Screenshot.h"
#include "scene/SceneIo.h"
#include "util/Error.h"

namespace candela {

namespace {

nlohmann::json seriesJson(const std::vector<ErrorPoint>& series) {
    nlohmann::json out = nlohmann::json::array();
    for (const ErrorPoint& p : series)
        out.push_back({{"gpu_ms", p.timeMs},
                       {"spp", p.spp},
                       {"rel_rmse", p.relRmse},
                       {"mean_delta_e", p.deltaE}});
    return out;
}

/// A number for JSON: null where it is not finite (JSON has no NaN).
nlohmann::json number(double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

}  // namespace

std::string formatMs(double ms, int msDecimals) {
    char text[32];
    if (ms < 1000.0)
        std::snprintf(text, sizeof text, "%.*f ms", msDecimals, ms);
    else
        std::snprintf(text, sizeof text, "%.2f s", ms / 1000.0);
    return text;
}

nlohmann::json comparisonJson(const Comparison& c, const std::vector<std::string>& paneNames) {
    nlohmann::json panes = nlohmann::json::array();
    for (size_t i = 0; i < c.paneCount(); ++i) {
        const PaneResult& r = c.result(i);
        const RenderSettings& s = c.paneRenderer(i).settings();
        panes.push_back({
            {"name", i < paneNames.size() ? paneNames[i] : std::to_string(i)},
            {"technique", c.spec(i).technique},
            {"techniques", techniqueSummary(c.paneRenderer(i).plan())},
            {"sample_budget", c.spec(i).samples},
            {"samples_per_pass", s.samplesPerFrame},
            {"seed", s.seed},
            {"spp", r.spp},
            {"done", r.done},
            {"gpu_ms", r.gpuMs},
            {"measured", r.measured},
            {"mean_delta_e", r.measured ? number(r.latest.deltaE) : nlohmann::json(nullptr)},
            {"rel_rmse", r.measured ? number(r.latest.relRmse) : nlohmann::json(nullptr)},
            {"rel_rmse_raw", r.measured ? number(r.rawRelRmse) : nlohmann::json(nullptr)},
            {"series", seriesJson(r.series)},
        });
    }
    const Renderer& ref = c.referenceRenderer();
    const RenderSettings& rs = ref.settings();
    return {
        {"panes", std::move(panes)},
        {"reference",
         {{"technique", rs.techniqueOverride},
          {"environment_technique", rs.environmentTechnique},
          {"techniques", techniqueSummary(ref.plan())},
          {"sample_budget", c.referenceSamples()},
          {"spp", c.referenceSpp()},
          {"seed", rs.seed},
          {"gpu_ms", c.referenceGpuMs()},
          {"noise_rel_rmse", number(c.referenceNoise())},
          {"done", c.referenceDone()}}},
        {"render_size", {rs.width, rs.height}},
        {"quantity", rs.quantity == Quantity::Illuminance ? "illuminance" : "radiance"},
        {"tonemap",
         {{"operator", rs.toneMap == ToneMapOperator::Reinhard ? "reinhard" : "exponential"},
          {"exposure", rs.exposure},
          {"average", c.toneAverage()}}},
        {"shadow_maps", {{"count", rs.shadowMaps.count}, {"resolution", rs.shadowMaps.resolution}}},
        {"error_map_scale", c.errorScale()},
        {"metrics",
         "rel_rmse: relative RMSE of luminance against the reference over the pixels that do not "
         "see a "
         "luminaire, with the reference's noise removed in "
         "quadrature; mean_delta_e: mean CIE76 Delta E of both images tone-mapped against the "
         "reference's "
         "mean luminance; gpu_ms: shading and shadow passes of the pane's accumulation"},
    };
}

SheetFiles exportComparisonSheet(const std::filesystem::path& dir, Comparison& c,
                                 const Scene& scene, const std::vector<std::string>& paneNames,
                                 bool errorMaps) {
    if (c.paneCount() == 0) throw InputError("comparison sheet: no panes");
    c.measureNow();
    if (c.referenceImage().empty())
        throw InputError("comparison sheet: the reference has no pass yet, try again in a moment");
    std::vector<SheetTile> tiles;
    for (size_t i = 0; i < c.paneCount(); ++i) {
        const Renderer& r = c.paneRenderer(i);
        const PaneResult& res = c.result(i);
        if (c.paneImage(i).empty())
            throw InputError("comparison sheet: pane " + std::to_string(i) +
                             " has no pass yet, try again in a moment");
        SheetTile tile;
        tile.width = r.settings().width;
        tile.height = r.settings().height;
        tile.linear = c.paneImage(i);
        tile.display =
            errorMaps && !c.errorImage(i).empty() ? c.errorImage(i) : c.toneMapped(tile.linear);
        std::string name = i < paneNames.size() ? paneNames[i] : std::to_string(i);
        tile.lines.push_back(name + "  " + techniqueSummary(r.plan()) +
                             (errorMaps ? "  (signed error)" : ""));
        std::string spp = r.plan().progressive() ? std::to_string(res.latest.spp) + " spp"
                                                 : std::string("exact, 1 pass");
        tile.lines.push_back(spp + " \xc2\xb7 " + formatMs(res.latest.timeMs) + " GPU");
        char text[128];
        if (res.measured)
            std::snprintf(text, sizeof text,
                          "\xce\x94"
                          "E %.2f \xc2\xb7 rel. RMSE %.2f %%",
                          res.latest.deltaE, 100.0 * res.latest.relRmse);
        else
            std::snprintf(text, sizeof text, "not measured yet");
        tile.lines.emplace_back(text);
        tiles.push_back(std::move(tile));
    }
    const Renderer& ref = c.referenceRenderer();
    SheetTile reference;
    reference.width = ref.settings().width;
    reference.height = ref.settings().height;
    reference.linear = c.referenceImage();
    reference.display = c.toneMapped(reference.linear);
    reference.lines.push_back("Reference \xc2\xb7 " + techniqueSummary(ref.plan()));
    reference.lines.push_back(std::to_string(c.referenceSpp()) + " spp \xc2\xb7 " +
                              formatMs(c.referenceGpuMs()) + " GPU");
    double noise = c.referenceNoise();
    char text[96];
    if (std::isfinite(noise))
        std::snprintf(text, sizeof text, "own noise: rel. RMSE %.2f %%", 100.0 * noise);
    else
        std::snprintf(text, sizeof text, "own noise: not measured yet");
    reference.lines.emplace_back(text);
    tiles.push_back(std::move(reference));

    std::string sceneName = scene.path.empty()
                                ? std::string("untitled scene")
                                : std::filesystem::path(scene.path).filename().string();
    SheetImage sheet = composeSheet(tiles, 2,
                                    "Candela comparison \xc2\xb7 " + sceneName + " \xc2\xb7 " +
                                        std::to_string(ref.settings().width) + "x" +
                                        std::to_string(ref.settings().height));
    nlohmann::json sidecar = comparisonJson(c, paneNames);
    sidecar["scene_file"] = scene.path;
    sidecar["scene"] = sceneToJson(scene);  // everything to render it again, as it was
    sidecar["timestamp"] = utcTimestamp();
    sidecar["error_maps_shown"] = errorMaps;
    nlohmann::json order = nlohmann::json::array();
    for (size_t i = 0; i < c.paneCount(); ++i)
        order.push_back(i < paneNames.size() ? paneNames[i] : std::to_string(i));
    order.push_back("reference");
    sidecar["tiles"] = std::move(order);
    return writeSheet(dir, sheet, sidecar);
}

}  // namespace candela
