#include "luminaires/lightfield/FarField.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <vector>

#include "luminaires/environment/Environment.h"  // luminanceOf

namespace candela {

std::shared_ptr<const PhotometricData> farFieldPhotometry(const LightFieldData& lf, double stepDeg,
                                                          int points) {
    auto out = std::make_shared<PhotometricData>();
    out->path = lf.path.empty() ? std::string("(light field in memory)") : lf.path.string();
    out->format = "far field of a light field";
    out->name = "far field of " + out->path;
    out->goniometer = Goniometer::C;
    out->symmetry = PhotometricSymmetry::None;
    int nv = int(std::lround(180.0 / stepDeg)) + 1;
    int nh = int(std::lround(360.0 / (2.0 * stepDeg))) + 1;
    for (int v = 0; v < nv; ++v) out->vertical.push_back(180.0 * v / (nv - 1));
    for (int h = 0; h < nh; ++h) out->horizontal.push_back(360.0 * h / (nh - 1));
    out->candela.assign(size_t(nv) * size_t(nh), 0.0);

    // C_m is constant over a pixel: sum pixel centres (every k-th pixel on large images, each
    // standing for its k x k block), never pixel edges, where a point would see one side only.
    glm::dvec2 extent = lf.imageMax - lf.imageMin;
    glm::dvec2 pixel = lf.pixelSize();
    int kx = std::max(1, (lf.width + points - 1) / std::max(1, points));
    int ky = std::max(1, (lf.height + points - 1) / std::max(1, points));
    std::vector<glm::dvec2> centres;
    for (int j = ky / 2; j < lf.height; j += ky)
        for (int i = kx / 2; i < lf.width; i += kx)
            centres.push_back(lf.imageMin + (glm::dvec2(i, j) + 0.5) * pixel);
    double dA = extent.x * extent.y / double(std::max<size_t>(1, centres.size()));
    for (int h = 0; h + 1 < nh; ++h) {  // the last column repeats the first (C = 360 = 0)
        double c = glm::radians(out->horizontal[size_t(h)]);
        for (int v = 0; v < nv; ++v) {
            double g = glm::radians(out->vertical[size_t(v)]);
            // The photometric frame's y is c0 x aim, the light field's aim x c0: flip y.
            glm::dvec3 w(std::sin(g) * std::cos(c), -std::sin(g) * std::sin(c), std::cos(g));
            if (!(w.z > 1e-6)) continue;  // S emits towards +z only
            glm::dvec2 shift = lf.delta * glm::dvec2(w.x, w.y) / w.z;
            double sum = 0.0;
            for (const glm::dvec2& s : centres)
                sum += luminanceOf(
                    lf.radiance(s - shift, s));  // one channel; the colour goes to the tint
            out->candela[size_t(h) * size_t(nv) + size_t(v)] = std::max(0.0, sum * dA * w.z);
        }
    }
    for (int v = 0; v < nv; ++v)
        out->candela[size_t(nh - 1) * size_t(nv) + size_t(v)] = out->candela[size_t(v)];
    out->opening.shape = LuminousOpening::Shape::Rectangle;
    out->opening.length = extent.x;
    out->opening.width = extent.y;
    return out;
}

std::unique_ptr<Luminaire> farFieldTwin(const Luminaire& placedLight) {
    const LightFieldLuminaire* model = lightFieldModel(placedLight);
    if (!model) return nullptr;
    const LightFieldLuminaire& light = *model;
    // One table per light-field data, kept while the data lives (instances share data).
    static std::mutex mutex;
    static std::map<const LightFieldData*, std::pair<std::weak_ptr<const LightFieldData>,
                                                     std::shared_ptr<const PhotometricData>>>
        cache;
    std::shared_ptr<const PhotometricData> table;
    {
        std::lock_guard<std::mutex> lock(mutex);
        for (auto it = cache.begin(); it != cache.end();)
            it = it->second.first.expired() ? cache.erase(it) : std::next(it);
        auto& entry = cache[light.data.get()];
        if (!entry.second) entry = {light.data, farFieldPhotometry(*light.data)};
        table = entry.second;
    }
    const LightFieldData& lf = *light.data;
    auto twinModel = std::make_shared<PhotometricLuminaire>();
    twinModel->data = table;
    twinModel->file = table->path;
    glm::dvec3 power = lf.cachedPower();
    double l = luminanceOf(power);
    twinModel->colour = l > 0.0 ? power / l : glm::dvec3(1.0);
    twinModel->updateOpening();
    auto twin = placed(std::move(twinModel));
    twin->technique = "scattered";
    placeFarFieldTwin(*twin, placedLight);
    return twin;
}

std::vector<unsigned char> footprintImage(const PhotometricData& data, int size, double height) {
    size = std::max(size, 1);
    std::vector<double> e(size_t(size) * size_t(size), 0.0);
    double half = 2.5 * height, peak = 0.0;
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i) {
            // Local photometric frame: +z the aim (down to the floor), +x C0, +y C90.
            double x = -half + (i + 0.5) * 2.0 * half / size,
                   y = half - (j + 0.5) * 2.0 * half / size;
            glm::dvec3 d(x, y, height);
            double r2 = glm::dot(d, d);
            double value =
                data.intensity(d / std::sqrt(r2)) * height / (r2 * std::sqrt(r2));  // I cos / r^2
            e[size_t(j) * size_t(size) + size_t(i)] = value;
            peak = std::max(peak, value);
        }
    std::vector<unsigned char> rgb(size_t(size) * size_t(size) * 3, 0);
    if (!(peak > 0.0)) return rgb;
    for (size_t k = 0; k < e.size(); ++k) {
        double t = e[k] > 0.0 ? std::clamp(1.0 + std::log10(e[k] / peak) / 3.0, 0.0, 1.0) : 0.0;
        // Black through amber to white.
        glm::dvec3 c(std::min(1.0, 1.6 * t), std::clamp(1.6 * t - 0.35, 0.0, 1.0),
                     std::clamp(2.2 * t - 1.2, 0.0, 1.0));
        for (int ch = 0; ch < 3; ++ch)
            rgb[3 * k + size_t(ch)] = (unsigned char)std::lround(255.0 * c[ch]);
    }
    return rgb;
}

void placeFarFieldTwin(Luminaire& twin, const Luminaire& light) {
    const LightFieldLuminaire* model = lightFieldModel(light);
    if (!model) return;
    const LightFieldData& lf = *model->data;
    glm::dvec3 x, y, z;
    light.pose.frame(x, y, z);
    glm::dvec2 centre = 0.5 * (lf.imageMin + lf.imageMax);
    twin.name = light.name;
    twin.pose = light.pose;
    twin.pose.position = light.pose.position + centre.x * x + centre.y * y + lf.delta * z;
}

}  // namespace candela
