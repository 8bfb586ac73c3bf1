// The light-field luminaire model (its physics at a pose) and its adapter (scene entry, GPU
// record and tables, shadow maps, description).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/gtc/packing.hpp>
#include <map>
#include <mutex>

#include "luminaires/Adapter.h"
#include "luminaires/lightfield/LightField.h"
#include "luminaires/lightfield/ShadowCells.h"
#include "shaders/shared/GpuTypes.h"
#include "util/Error.h"
#include "util/FloatFloat.h"
#include "util/JsonRead.h"

namespace candela {

namespace fs = std::filesystem;

namespace {

/// Loaded models by canonical path and modification time: placing the same file twice, or
/// duplicating a luminaire, shares one copy.
std::shared_ptr<const LightFieldData> loadShared(const fs::path& file) {
    static std::mutex mutex;
    static std::map<std::string, std::pair<fs::file_time_type, std::weak_ptr<const LightFieldData>>>
        cache;
    std::error_code ec;
    fs::path canonical = fs::weakly_canonical(file, ec);
    std::string key = (ec ? file : canonical).string();
    fs::file_time_type stamp = fs::last_write_time(file, ec);
    std::lock_guard<std::mutex> lock(mutex);
    auto it = cache.find(key);
    if (it != cache.end() && it->second.first == stamp)
        if (auto data = it->second.second.lock()) return data;
    std::shared_ptr<const LightFieldData> data = LightFieldData::load(file);
    cache[key] = {stamp, data};
    return data;
}

}  // namespace

glm::dvec3 LightFieldLuminaire::radiance(const Pose& pose, const glm::dvec3& xWorld,
                                         const glm::dvec3& w) const {
    glm::dvec3 s = pose.toLocal(xWorld);
    glm::dvec3 x, y, z;
    pose.frame(x, y, z);
    glm::dvec3 wl(glm::dot(w, x), glm::dot(w, y), glm::dot(w, z));
    if (!(wl.z > 0.0)) return glm::dvec3(0.0);
    // Back along the ray from S (z = delta) to U (z = 0).
    glm::dvec2 u = glm::dvec2(s.x, s.y) - glm::dvec2(wl.x, wl.y) * (data->delta / wl.z);
    return data->radiance(u, glm::dvec2(s.x, s.y));
}

namespace {

const LightFieldLuminaire& lightFieldOf(const LuminaireModel& model) {
    return static_cast<const LightFieldLuminaire&>(model);
}

glm::dvec3 lightFieldDisplayRadiance(const Luminaire& luminaire) {
    const LightFieldData& lf = *lightFieldOf(luminaire.model()).data;
    glm::dvec3 sum(0.0);
    const int n = 32;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            glm::dvec2 s =
                lf.imageMin + (glm::dvec2(i, j) + 0.5) / double(n) * (lf.imageMax - lf.imageMin);
            sum += lf.radiance(s, s);
        }
    return sum / double(n * n);
}

}  // namespace

glm::dvec3 LightFieldLuminaire::power() const {
    return data->cachedPower();
}

LightSample LightFieldLuminaire::sample(const Pose& pose, const glm::dvec3& p,
                                        const glm::dvec2& u) const {
    LightSample out;
    const LightFieldData& lf = *data;
    glm::dvec3 q = pose.toLocal(p);
    if (!(q.z > lf.delta)) return out;
    // Image m with probability A_m / A (Eq. 12's balancing as a discrete choice), u.x reused.
    std::vector<double> cdf(size_t(lf.imageCount()) + 1, 0.0);
    std::vector<glm::dvec2> lo(size_t(lf.imageCount())), hi(size_t(lf.imageCount()));
    for (int m = 0; m < lf.imageCount(); ++m) {
        double a = lf.restrictedBox(m, q, lo[size_t(m)], hi[size_t(m)])
                       ? lf.boxIntegral(m, lo[size_t(m)], hi[size_t(m)])
                       : 0.0;
        cdf[size_t(m) + 1] = cdf[size_t(m)] + a;
    }
    double total = cdf.back();
    if (!(total > 0.0)) return out;
    double target = u.x * total;
    int m = int(std::upper_bound(cdf.begin() + 1, cdf.end(), target) - cdf.begin()) - 1;
    m = std::clamp(m, 0, lf.imageCount() - 1);
    while (m > 0 && !(cdf[size_t(m) + 1] > cdf[size_t(m)])) --m;
    double am = cdf[size_t(m) + 1] - cdf[size_t(m)];
    if (!(am > 0.0)) return out;
    double ux = std::clamp((target - cdf[size_t(m)]) / am, 0.0, 1.0);
    glm::dvec2 s;
    if (!lf.sampleBox(m, lo[size_t(m)], hi[size_t(m)], {ux, u.y}, s)) return out;
    glm::dvec3 sl(s.x, s.y, lf.delta);
    glm::dvec3 d = sl - q;
    double r = glm::length(d);
    if (!(r > 0.0)) return out;
    glm::dvec3 x, y, z;
    pose.frame(x, y, z);
    out.position = pose.position + sl.x * x + sl.y * y + sl.z * z;
    out.wi = pose.toWorldDir(d / r);
    out.distance = r;
    out.radiance = radiance(pose, out.position, -out.wi);
    out.pdf = pdf(pose, p, out.wi);
    return out;
}

double LightFieldLuminaire::pdf(const Pose& pose, const glm::dvec3& p, const glm::dvec3& wi) const {
    const LightFieldData& lf = *data;
    glm::dvec3 q = pose.toLocal(p);
    if (!(q.z > lf.delta)) return 0.0;
    glm::dvec3 x, y, z;
    pose.frame(x, y, z);
    glm::dvec3 w(glm::dot(wi, x), glm::dot(wi, y), glm::dot(wi, z));
    if (!(w.z < 0.0)) return 0.0;
    double dz = q.z - lf.delta;
    double t = dz / -w.z;
    glm::dvec2 s = glm::dvec2(q.x, q.y) + t * glm::dvec2(w.x, w.y);
    double total = 0.0, density = 0.0;
    for (int m = 0; m < lf.imageCount(); ++m) {
        glm::dvec2 lo, hi;
        if (!lf.restrictedBox(m, q, lo, hi)) continue;
        total += lf.boxIntegral(m, lo, hi);
        if (s.x >= lo.x && s.x <= hi.x && s.y >= lo.y && s.y <= hi.y) density += lf.lum(m, s);
    }
    if (!(total > 0.0)) return 0.0;
    // Area density on S to solid angle at q: r^2 / cos(theta_s), cos(theta_s) = dz / r.
    double r = t;  // |w| = 1
    return density / total * r * r * r / dz;
}

std::vector<glm::dvec3> LightFieldLuminaire::outline(const Pose& pose) const {
    glm::dvec3 x, y, z;
    pose.frame(x, y, z);
    const LightFieldData& lf = *data;
    glm::dvec3 c = pose.position + lf.delta * z;
    return {c + lf.imageMin.x * x + lf.imageMin.y * y, c + lf.imageMax.x * x + lf.imageMin.y * y,
            c + lf.imageMax.x * x + lf.imageMax.y * y, c + lf.imageMin.x * x + lf.imageMax.y * y};
}

namespace {

void lightFieldJson(const LuminaireModel& model, nlohmann::json& out) {
    out["file"] = lightFieldOf(model).file;
}

std::vector<std::byte> lightFieldGpuData(const Luminaire& luminaire) {
    const LightFieldData& lf = *lightFieldOf(luminaire.model()).data;
    const Pose& pose = luminaire.pose;
    constexpr int kMaxSamplesPerImage = LightFieldLuminaire::kMaxSamplesPerImage;
    gpu::LightFieldGpu h{};
    glm::dvec3 x, y, z;
    pose.frame(x, y, z);
    h.position = glm::vec4(glm::vec3(pose.position), 1.f);
    h.axisX = glm::vec4(glm::vec3(x), 0.f);
    h.axisY = glm::vec4(glm::vec3(y), 0.f);
    h.axisZ = glm::vec4(glm::vec3(z), 0.f);
    h.geometry = glm::vec4(float(lf.delta), float(lf.spacing.x), float(lf.spacing.y),
                           lf.model == LightFieldData::Model::Goesele ? 1.f : 0.f);
    h.origin = glm::vec4(float(lf.origin.x), float(lf.origin.y), float(lf.imageMin.x),
                         float(lf.imageMin.y));
    glm::dvec2 px = lf.pixelSize();
    h.image = glm::vec4(float(lf.imageMax.x), float(lf.imageMax.y), float(px.x), float(px.y));
    glm::vec2 inverseX = toFloatFloat(1.0 / px.x), inverseY = toFloatFloat(1.0 / px.y);
    h.grid = glm::vec4(toFloatFloat(lf.imageMin.x).y, toFloatFloat(lf.imageMin.y).y, inverseX.x,
                       inverseY.x);
    h.gridLow = glm::vec4(inverseX.y, inverseY.y, 0.f, 0.f);
    h.dims = glm::ivec4(lf.count.x, lf.count.y, lf.width, lf.height);
    h.options = glm::ivec4(kMaxSamplesPerImage, 0, 0, 0);
    // granier2003's far-field correction (LightFieldData::granierTable, made once per light field):
    // the grid's first and last centres on S here; its ratios, like the images' tables, are
    // textures (LightFieldData::gpuTables).
    h.offsets = glm::ivec4(0, 0, 0, lf.rgb ? 1 : 0);
    const GranierTable& granier = lf.granierTable();
    size_t granierOffset = sizeof(h) / sizeof(float);
    h.options.y = int(granierOffset);
    h.options.z = granier.size;
    std::vector<std::byte> out((granierOffset + 4) * 4);
    std::memcpy(out.data(), &h, sizeof(h));
    auto* far = reinterpret_cast<float*>(out.data()) + granierOffset;
    far[0] = float(granier.min.x), far[1] = float(granier.min.y), far[2] = float(granier.max.x),
    far[3] = float(granier.max.y);
    return out;
}

std::shared_ptr<const GpuTables> lightFieldGpuTables(const LuminaireModel& model) {
    return lightFieldOf(model).data->gpuTables();
}

}  // namespace

std::shared_ptr<const GpuTables> LightFieldData::gpuTables() const {
    std::call_once(mGpuTablesOnce, [&] {
        auto out = std::make_shared<GpuTables>();
        int layers = imageCount();
        size_t satCount = size_t(width + 1) * size_t(height + 1);
        size_t pixels = size_t(width) * size_t(height);
        GpuTable sat{gpu::kUnitLightFieldSat, 2, width + 1, height + 1, layers, false, {}};
        sat.texels.resize(size_t(layers) * satCount * 2);
        GpuTable lum{gpu::kUnitLightFieldLum, 1, width, height, layers, false, {}};
        lum.texels.resize(size_t(layers) * pixels);
        GpuTable colour{gpu::kUnitLightFieldColour, 4, width, height, layers, true, {}};
        if (rgb) colour.texels.resize(size_t(layers) * pixels * 4);
        for (size_t m = 0; m < size_t(layers); ++m) {
            for (size_t k = 0; k < satCount; ++k) {
                glm::vec2 pair = toFloatFloat(tables[m].sat[k]);
                sat.texels[(m * satCount + k) * 2] = pair.x;
                sat.texels[(m * satCount + k) * 2 + 1] = pair.y;
            }
            std::memcpy(&lum.texels[m * pixels], images[m].luminance.data(),
                        pixels * sizeof(float));
            if (!rgb) continue;
            for (size_t k = 0; k < pixels; ++k) {
                // Rounded to half here, so the texture holds exactly these values.
                glm::vec3 c = images[m].colour[k];
                glm::vec2 rg = glm::unpackHalf2x16(glm::packHalf2x16(glm::vec2(c.x, c.y)));
                glm::vec2 b = glm::unpackHalf2x16(glm::packHalf2x16(glm::vec2(c.z, 0.f)));
                float* t = &colour.texels[(m * pixels + k) * 4];
                t[0] = rg.x, t[1] = rg.y, t[2] = b.x, t[3] = 1.f;
            }
        }
        out->push_back(std::move(sat));
        out->push_back(std::move(lum));
        if (rgb) out->push_back(std::move(colour));
        if (const GranierTable& granier = granierTable(); granier.size >= 2)
            out->push_back(GpuTable{gpu::kUnitLightFieldGranier, 1, granier.size, granier.size,
                                    layers, false, granier.weighted});
        mGpuTables = std::move(out);
    });
    return mGpuTables;
}

namespace {

ShadowLights lightFieldShadowLights(const Luminaire& luminaire, int count) {
    const LightFieldData& lf = *lightFieldOf(luminaire.model()).data;
    const Pose& pose = luminaire.pose;
    glm::ivec2 cells = lf.count + 2;
    ShadowMapLayout layout = shadowMapLayout(lf, shadowMapGrid(cells, count));
    glm::dvec3 x, y, z;
    pose.frame(x, y, z);
    ShadowLights out;
    for (const ShadowMapLayout::Map& m : layout.mapList) {
        out.lights.push_back(pose.position + m.light.x * x + m.light.y * y + m.light.z * z);
        out.lit.push_back(m.lit ? 1 : 0);
    }
    out.sharesPerItem = 9;  // an image's n^2 cells lie in at most 9 maps
    out.shares.resize(size_t(lf.imageCount()) * 9);
    for (size_t m = 0; m < layout.perImage.size(); ++m)
        for (size_t j = 0; j < layout.perImage[m].size(); ++j)
            out.shares[m * 9 + j] = {layout.perImage[m][j].map,
                                     float(layout.perImage[m][j].weight)};
    return out;
}

std::string lightFieldDescribe(const LuminaireModel& model) {
    const LightFieldData& lf = *lightFieldOf(model).data;
    const std::string& file = lightFieldOf(model).file;
    char buf[640];
    glm::dvec3 flux = lf.cachedPower();
    bool photometric = lf.unit == "cd/m2";
    double total = 0.2126 * flux.x + 0.7152 * flux.y + 0.0722 * flux.z;
    std::snprintf(
        buf, sizeof buf,
        "lightfield %s: %dx%d images of %dx%d %s, delta %.4g m, S %.4g x %.4g m, radiance "
        "in %s, flux %.4g %s, precomputed in %.1f ms",
        file.c_str(), lf.count.x, lf.count.y, lf.width, lf.height, lf.rgb ? "RGB" : "luminance",
        lf.delta, lf.imageMax.x - lf.imageMin.x, lf.imageMax.y - lf.imageMin.y,
        photometric ? "cd/m2" : "W/(m2 sr)", total, photometric ? "lm" : "W", lf.precomputeMs);
    return buf;
}

std::vector<std::string> lightFieldSourceFiles(const LuminaireModel& model) {
    const std::shared_ptr<const LightFieldData>& data = lightFieldOf(model).data;
    std::vector<std::string> files;
    if (!data || data->path.empty()) return files;  // built in memory
    files.push_back(data->path.string());
    for (const fs::path& image : data->imageFiles) files.push_back(image.string());
    return files;
}

std::unique_ptr<Luminaire> lightFieldParse(const nlohmann::json& entry, const json::Where& where) {
    json::checkKeys(
        entry, {"type", "name", "position", "aim", "c0", "technique", "maintenance_factor", "file"},
        where);
    if (!entry.contains("file"))
        json::fail(where / "file", "the path of a .lf.json light-field file");
    auto light = std::make_shared<LightFieldLuminaire>();
    light->file = json::string(entry["file"], where / "file");
    fs::path resolved(light->file);
    if (resolved.is_relative()) resolved = fs::path(where.file).parent_path() / resolved;
    light->data = loadShared(resolved);
    return placed(std::move(light));
}

std::unique_ptr<Luminaire> lightFieldCreate() {
    // The editor's "Add": the bundled measured LED; a small uniform model if it is missing.
    auto light = std::make_shared<LightFieldLuminaire>();
    fs::path bundled = fs::path(CANDELA_SOURCE_DIR) / "resources/luminaires/osram-lertduw.lf.json";
    try {
        light->data = loadShared(bundled);
        light->file = bundled.generic_string();
        return placed(std::move(light));
    } catch (const InputError&) {
    }
    auto lf = std::make_shared<LightFieldData>();
    lf->count = {3, 3};
    lf->spacing = {0.02, 0.02};
    lf->origin = {-0.02, -0.02};
    lf->delta = 0.05;
    lf->imageMin = {-0.05, -0.05};
    lf->imageMax = {0.05, 0.05};
    lf->width = lf->height = 16;
    lf->images.assign(9, LightFieldImage{std::vector<float>(256, 1000.f), {}});
    lf->precompute();
    light->data = lf;
    return placed(std::move(light));
}

}  // namespace

const LightFieldLuminaire* lightFieldModel(const Luminaire& luminaire) {
    return luminaire.kind() == LuminaireKind::LightField ? &lightFieldOf(luminaire.model())
                                                         : nullptr;
}

const LuminaireAdapter& lightFieldAdapter() {
    static const LuminaireAdapter adapter{&lightFieldParse,
                                          &lightFieldCreate,
                                          &lightFieldJson,
                                          &lightFieldGpuData,
                                          &lightFieldGpuTables,
                                          &lightFieldDescribe,
                                          &lightFieldSourceFiles,
                                          &lightFieldShadowLights,
                                          nullptr,
                                          nullptr,
                                          &lightFieldDisplayRadiance};
    return adapter;
}

}  // namespace candela
