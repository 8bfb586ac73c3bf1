// The photometric area light model (its physics at a pose, its opening) and its adapter (scene
// entry, GPU record and tables, shadow maps, body, a GLDF variant's companions).
#include "luminaires/photometric/PhotometricLuminaire.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>

#include "formats/Gldf.h"
#include "formats/L3d.h"
#include "luminaires/photometric/IntensitySampler.h"
#include "shaders/shared/Constants.h"
#include "shaders/shared/GpuTypes.h"
#include "util/Error.h"
#include "util/JsonRead.h"
#include "util/Polygon.h"
#include "util/TextEncoding.h"

namespace candela {

namespace fs = std::filesystem;

namespace {

using gpu::kPi;

/// Openings smaller than this (m2, relative to the squared extent) are a segment or a point.
constexpr double kDegenerateArea = 1e-9;
/// Largest "scale" (a multiplier of the file's flux): a million lamps in one is beyond any
/// design, and 1e308 made the light infinite or, through rounding, 0.
constexpr double kMaxScale = 1e6;
/// Largest "colour" component (a tint of the file's light, normally at most 1).
constexpr double kMaxColour = 1e3;
using photometry_detail::formatNumber;

glm::dvec3 toLocalDir(const PhotometricLuminaire& l, const Pose& pose, const glm::dvec3& w) {
    glm::dvec3 x, y, z;
    l.photometricFrame(pose, x, y, z);
    return {glm::dot(w, x), glm::dot(w, y), glm::dot(w, z)};
}

}  // namespace

std::shared_ptr<const PhotometricData> PhotometricLuminaire::load(const std::string& path) {
    // One copy per file and modification time, shared by every instance that places it.
    static std::mutex mutex;
    static std::map<std::string,
                    std::pair<fs::file_time_type, std::weak_ptr<const PhotometricData>>>
        cache;
    std::error_code ec;
    if (!fs::exists(path, ec)) throw InputError(path + ": no such file");
    fs::path canonical = fs::weakly_canonical(path, ec);
    std::string key = ec ? path : canonical.string();
    fs::file_time_type stamp = fs::last_write_time(path, ec);
    std::lock_guard<std::mutex> lock(mutex);
    auto it = cache.find(key);
    if (it != cache.end() && it->second.first == stamp)
        if (auto data = it->second.second.lock()) return data;
    std::shared_ptr<const PhotometricData> data;
    try {
        data = std::make_shared<const PhotometricData>(loadPhotometry(path));
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throw InputError(e.what());
    }
    cache[key] = {stamp, data};
    return data;
}

void PhotometricLuminaire::loadGldf(const std::string& path, const std::string& variant,
                                    int emitter) {
    // Like load(): one copy per container, variant and modification time.
    struct Entry {
        fs::file_time_type stamp;
        std::weak_ptr<const GldfProduct> product;
        std::weak_ptr<const PhotometricData> data;
        std::shared_ptr<const L3dLuminaire> geometry;
        std::optional<Placement> placement;
        int emitterCount = 1;
    };
    static std::mutex mutex;
    static std::map<std::pair<std::string, std::string>, Entry> cache;
    // A variant's product and geometry, shared by its placements: the container's product.xml
    // and L3D are parsed once for all the emitters it places.
    struct VariantEntry {
        fs::file_time_type stamp;
        std::weak_ptr<const GldfProduct> product;
        std::weak_ptr<const L3dLuminaire> geometry;
    };
    static std::map<std::pair<std::string, std::string>, VariantEntry> variants;
    std::error_code ec;
    fs::path canonical = fs::weakly_canonical(path, ec);
    std::pair<std::string, std::string> key{ec ? path : canonical.string(),
                                            variant + "\n" + std::to_string(emitter)};
    fs::file_time_type stamp = fs::last_write_time(path, ec);
    std::lock_guard<std::mutex> lock(mutex);
    auto it = cache.find(key);
    if (it != cache.end() && it->second.stamp == stamp) {
        auto product = it->second.product.lock();
        auto photometry = it->second.data.lock();
        if (product && photometry) {
            gldf = product;
            data = photometry;
            gldfVariant = variant.empty() ? product->variants.front().id : variant;
            geometry = it->second.geometry;
            placement = it->second.placement;
            gldfEmitter = emitter;
            gldfEmitterCount = it->second.emitterCount;
            return;
        }
    }
    std::string bytes = readGldfBytes(path);
    std::pair<std::string, std::string> variantKey{key.first, variant};
    std::shared_ptr<const GldfProduct> product;
    std::shared_ptr<const L3dLuminaire> knownGeometry;
    if (auto v = variants.find(variantKey); v != variants.end() && v->second.stamp == stamp) {
        product = v->second.product.lock();
        knownGeometry = v->second.geometry.lock();
    }
    if (!product || !knownGeometry) {
        product = std::make_shared<const GldfProduct>(candela::parseGldf(bytes, path));
        knownGeometry = nullptr;
    }
    const GldfVariant* chosen =
        variant.empty() ? &product->variants.front() : product->variant(variant);
    if (!chosen) {
        std::string ids;
        for (const GldfVariant& v : product->variants) ids += (ids.empty() ? "" : ", ") + v.id;
        throw InputError(
            toValidUtf8(path + ": no variant \"" + variant + "\" (it has " + ids + ")"));
    }
    if (emitter < 0) throw InputError(toValidUtf8(path + ": emitter " + std::to_string(emitter)));
    GldfPhotometry read = gldfVariantPhotometry(
        bytes, *product, *chosen, defaultPhotometryOptions(), size_t(emitter), knownGeometry);
    if (read.geometry) {
        // Under the name asked for ("" for the first variant) and the variant's own id, which
        // the other placements are loaded with.
        variants[variantKey] = {stamp, product, read.geometry};
        variants[{key.first, chosen->id}] = {stamp, product, read.geometry};
    }
    auto photometry = std::make_shared<const PhotometricData>(std::move(read.data));
    gldf = product;
    data = photometry;
    gldfVariant = chosen->id;
    geometry = read.geometry;
    gldfEmitter = emitter;
    gldfEmitterCount = int(chosen->emitters.size());
    placement.reset();
    if (const L3dEmitter* leo = read.opening) {
        Placement p;
        p.object = leo->name;
        p.centre = leo->centre;
        p.c0 = leo->x;
        p.aim = leo->normal;
        p.opening.shape = leo->shape == L3dEmitter::Shape::Circle
                              ? LuminousOpening::Shape::Ellipse
                              : LuminousOpening::Shape::Rectangle;
        p.opening.length = leo->sizeX;
        p.opening.width = leo->sizeY;
        placement = p;
    }
    // The emitter's <Rotation> turns its photometric solid; without a placement, from the
    // luminaire frame's own (C0 along x, aiming down -z, the opening at the insertion point).
    if (read.emitter && !read.emitter->lights.empty() && read.emitter->lights.front().rotated()) {
        if (!placement) {
            Placement p;
            p.opening = photometry->opening;
            placement = p;
        }
        gldfRotateEmitter(read.emitter->lights.front(), placement->c0, placement->aim);
    }
    cache[key] = {stamp, product, photometry, geometry, placement, gldfEmitterCount};
}

LuminousOpening PhotometricLuminaire::opening() const {
    LuminousOpening opening = data ? data->opening : LuminousOpening{};
    if (placement) opening = placement->opening;
    if (openingOverride.x > 0.0 || openingOverride.y > 0.0) {
        opening.shape = LuminousOpening::Shape::Rectangle;
        opening.length = openingOverride.x;
        opening.width = openingOverride.y;
        opening.height = 0.0;
    }
    return opening;
}

void PhotometricLuminaire::updateOpening() {
    mPolygon = opening().polygon();
    if (signedArea(mPolygon) < 0.0) std::reverse(mPolygon.begin(), mPolygon.end());
    mSize = 0.0;
    for (const auto& a : mPolygon)
        for (const auto& b : mPolygon) mSize = std::max(mSize, glm::length(a - b));
    mArea = std::abs(signedArea(mPolygon));
    if (mSize == 0.0) {
        mPolygon.clear();  // a point
        mArea = 0.0;
    } else if (mArea <= kDegenerateArea * mSize * mSize) {
        // A segment: keep its two farthest corners.
        glm::dvec2 a = mPolygon[0], b = mPolygon[0];
        for (const auto& u : mPolygon)
            for (const auto& v : mPolygon)
                if (glm::length(u - v) >= glm::length(a - b)) a = u, b = v;
        mPolygon = {a, b};
        mArea = 0.0;
    }
}

bool PhotometricLuminaire::contains(const glm::dvec2& q, double slack) const {
    for (size_t i = 0; i < mPolygon.size(); ++i) {
        glm::dvec2 a = mPolygon[i], e = mPolygon[(i + 1) % mPolygon.size()] - a;
        if (e.x * (q.y - a.y) - e.y * (q.x - a.x) < -slack * glm::length(e)) return false;
    }
    return true;
}

void PhotometricLuminaire::photometricFrame(const Pose& pose, glm::dvec3& x, glm::dvec3& y,
                                            glm::dvec3& z) const {
    emitterPose(pose).frame(x, y, z);
    y = -y;  // c0 x aim
}

Pose PhotometricLuminaire::emitterPose(const Pose& pose) const {
    if (!placement) return pose;
    // The luminaire's L3D frame placed at the pose: x along C0, y along C90 (c0 x aim, the
    // negative of Pose::frame's y), z up, against the aim (a proper rotation: x cross y = z).
    glm::dvec3 x, y, z;
    pose.frame(x, y, z);
    auto place = [&](const glm::dvec3& v) { return v.x * x - v.y * y - v.z * z; };
    Pose e;
    e.position = pose.position + place(placement->centre);
    e.aim = place(placement->aim);
    e.c0 = place(placement->c0);
    return e;
}

double PhotometricLuminaire::intensity(const Pose& pose, const glm::dvec3& w) const {
    double l = glm::length(w);
    if (!(l > 0.0) || !data) return 0.0;
    return scale * data->intensity(toLocalDir(*this, pose, w / l));
}

glm::dvec3 PhotometricLuminaire::radiance(const Pose& pose, const glm::dvec3& xWorld,
                                          const glm::dvec3& w) const {
    if (mArea <= 0.0) return glm::dvec3(0.0);
    glm::dvec3 x = toLocalDir(*this, pose, xWorld - emitterPose(pose).position);
    double size = std::max(mSize, 1e-9);
    if (std::abs(x.z) > 1e-6 * size || !contains(glm::dvec2(x), 1e-9 * size))
        return glm::dvec3(0.0);
    double l = glm::length(w);
    if (!(l > 0.0)) return glm::dvec3(0.0);
    double cosL = std::abs(glm::dot(toLocalDir(*this, pose, w), glm::dvec3(0, 0, 1))) / l;
    if (!(cosL > 1e-12)) return glm::dvec3(0.0);
    return colour * (intensity(pose, w) / (mArea * cosL));
}

glm::dvec3 PhotometricLuminaire::power() const {
    return data ? colour * (scale * data->fluxFromTable()) : glm::dvec3(0.0);
}

LightSample PhotometricLuminaire::sample(const Pose& pose, const glm::dvec3& p,
                                         const glm::dvec2& u) const {
    LightSample s;
    glm::dvec3 ex, ey, ez;
    photometricFrame(pose, ex, ey, ez);
    glm::dvec2 local(0.0);
    if (mPolygon.size() >= 3) {
        // Uniform in area: a triangle of the fan by area, then a uniform point in it.
        auto fanArea = [&](size_t i) {
            glm::dvec2 a = mPolygon[i] - mPolygon[0], b = mPolygon[i + 1] - mPolygon[0];
            return 0.5 * std::abs(a.x * b.y - b.x * a.y);
        };
        double total = 0.0;
        for (size_t i = 1; i + 1 < mPolygon.size(); ++i) total += fanArea(i);
        double pick = std::clamp(u.x, 0.0, 1.0) * total, v = u.x;
        size_t tri = 1;
        for (; tri + 1 < mPolygon.size(); ++tri) {
            double a = fanArea(tri);
            if (pick < a || tri + 2 == mPolygon.size()) {
                v = a > 0.0 ? std::clamp(pick / a, 0.0, 1.0) : 0.0;
                break;
            }
            pick -= a;
        }
        // Uniform in the triangle (P0, P1, P2): P0 (1 - sqrt v) + sqrt v ((1 - w) P1 + w P2).
        double su = std::sqrt(v), w = std::clamp(u.y, 0.0, 1.0);
        local = mPolygon[0] * (1.0 - su) + mPolygon[tri] * (su * (1.0 - w)) +
                mPolygon[tri + 1] * (su * w);
    } else if (mPolygon.size() == 2) {
        local = mPolygon[0] + std::clamp(u.x, 0.0, 1.0) * (mPolygon[1] - mPolygon[0]);
    }
    s.position = emitterPose(pose).position + local.x * ex + local.y * ey;
    glm::dvec3 d = s.position - p;
    s.distance = glm::length(d);
    if (!(s.distance > 0.0) || mArea <= 0.0) return s;
    s.wi = d / s.distance;
    double cosL = std::abs(glm::dot(s.wi, ez));
    if (!(cosL > 1e-12)) return s;
    s.pdf = s.distance * s.distance / (mArea * cosL);
    s.radiance = colour * (intensity(pose, -s.wi) / (mArea * cosL));
    return s;
}

double PhotometricLuminaire::pdf(const Pose& pose, const glm::dvec3& p,
                                 const glm::dvec3& wi) const {
    if (mArea <= 0.0) return 0.0;
    glm::dvec3 ex, ey, ez;
    photometricFrame(pose, ex, ey, ez);
    double denom = glm::dot(wi, ez);
    if (std::abs(denom) < 1e-12) return 0.0;
    glm::dvec3 centre = emitterPose(pose).position;
    double t = glm::dot(centre - p, ez) / denom;
    if (!(t > 0.0)) return 0.0;
    glm::dvec3 x = p + t * wi - centre;
    if (!contains({glm::dot(x, ex), glm::dot(x, ey)})) return 0.0;
    return t * t / (mArea * std::abs(denom));
}

std::vector<glm::dvec3> PhotometricLuminaire::outline(const Pose& pose) const {
    glm::dvec3 ex, ey, ez;
    photometricFrame(pose, ex, ey, ez);
    glm::dvec3 centre = emitterPose(pose).position;
    std::vector<glm::dvec3> out;
    if (mPolygon.size() >= 3) {
        for (const auto& q : mPolygon) out.push_back(centre + q.x * ex + q.y * ey);
        return out;
    }
    // A point or a segment still needs something to draw and to click: a thin quad around it.
    glm::dvec2 a = mPolygon.empty() ? glm::dvec2(0.0) : mPolygon[0];
    glm::dvec2 b = mPolygon.empty() ? glm::dvec2(0.0) : mPolygon[1];
    const double r = 0.01;
    glm::dvec2 lo = glm::min(a, b) - r, hi = glm::max(a, b) + r;
    for (glm::dvec2 q : {lo, glm::dvec2(hi.x, lo.y), hi, glm::dvec2(lo.x, hi.y)})
        out.push_back(centre + q.x * ex + q.y * ey);
    return out;
}

const GldfLightEmitter* PhotometricLuminaire::gldfLightEmitter() const {
    if (!gldf) return nullptr;
    const GldfVariant* v = gldf->variant(gldfVariant);
    if (!v || size_t(gldfEmitter) >= v->emitters.size()) return nullptr;
    const GldfEmitter* e = gldf->emitter(v->emitters[size_t(gldfEmitter)]);
    return e && !e->lights.empty() ? &e->lights.front() : nullptr;
}

/// The kind's adapter (luminaires/Adapter.h): a friend, for the model's private polygon and
/// tables.
struct PhotometricAdapter {
    static const PhotometricLuminaire& of(const LuminaireModel& model) {
        return static_cast<const PhotometricLuminaire&>(model);
    }
    static std::unique_ptr<Luminaire> parse(const nlohmann::json& entry, const json::Where& where);
    static std::unique_ptr<Luminaire> parseGldf(const nlohmann::json& entry,
                                                const json::Where& where);
    static std::unique_ptr<Luminaire> create();
    static LuminaireBody body(const Luminaire& luminaire) {
        const PhotometricLuminaire& l = of(luminaire.model());
        const Pose& pose = luminaire.pose;
        LuminaireBody out;
        out.reflectance = l.bodyReflectance;
        if (!l.showBody) return out;
        if (l.geometry) {
            if (l.gldfEmitter != 0) return out;  // the first placement gives the variant's body
            // The L3D frame at the pose, as emitterPose() places it.
            glm::dvec3 x, y, z;
            pose.frame(x, y, z);
            auto place = [&](const glm::dvec3& v) {
                return pose.position + v.x * x - v.y * y - v.z * z;
            };
            out.triangles.reserve(3 * l.geometry->triangleCount());
            for (const L3dPart& part : l.geometry->parts)
                for (uint32_t i : part.indices) out.triangles.push_back(place(part.positions[i]));
            return out;
        }
        // The luminous opening's box: its polygon swept over the opening's height, centred on the
        // emitting plane (LM-63 and EULUMDAT measure a luminaire about the centre of its luminous
        // volume); a flat opening is the polygon alone. A point or a segment has none.
        if (l.mPolygon.size() < 3 || !(l.mArea > 0.0)) return out;
        out.drawn = false;
        double half = 0.5 * std::max(0.0, l.opening().height);
        glm::dvec3 x, y, z;
        l.photometricFrame(pose, x, y, z);
        glm::dvec3 centre = l.emitterPose(pose).position;
        auto at = [&](const glm::dvec2& q, double h) { return centre + q.x * x + q.y * y + h * z; };
        size_t n = l.mPolygon.size();
        for (double h : half > 0.0 ? std::vector<double>{-half, half} : std::vector<double>{0.0})
            for (size_t i = 1; i + 1 < n; ++i)
                for (const glm::dvec2& q : {l.mPolygon[0], l.mPolygon[i], l.mPolygon[i + 1]})
                    out.triangles.push_back(at(q, h));
        if (half > 0.0)
            for (size_t i = 0; i < n; ++i) {
                const glm::dvec2 &a = l.mPolygon[i], &b = l.mPolygon[(i + 1) % n];
                for (auto [q, h] : {std::pair{a, -half}, std::pair{b, -half}, std::pair{b, half},
                                    std::pair{a, -half}, std::pair{b, half}, std::pair{a, half}})
                    out.triangles.push_back(at(q, h));
            }
        // Every face wound so its normal points out of the box (the frame's handedness and the
        // polygon's turn decide the winding above; this does not depend on them).
        for (size_t t = 0; t + 2 < out.triangles.size(); t += 3) {
            glm::dvec3 &a = out.triangles[t], &b = out.triangles[t + 1], &c = out.triangles[t + 2];
            if (glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0 - centre) < 0.0)
                std::swap(b, c);
        }
        return out;
    }

    static ShadowLights shadowLights(const Luminaire& luminaire, int count) {
        const PhotometricLuminaire& l = of(luminaire.model());
        const Pose& pose = luminaire.pose;
        glm::dvec3 ex, ey, ez;
        l.photometricFrame(pose, ex, ey, ez);
        std::vector<glm::dvec2> points = {glm::dvec2(0.0)};
        if (count != 1 && l.mPolygon.size() == 2) {
            points.push_back(l.mPolygon[0]);
            points.push_back(l.mPolygon[1]);
        } else if (count != 1 && l.mPolygon.size() >= 3) {
            glm::dvec2 lo(1e300), hi(-1e300);
            for (const glm::dvec2& q : l.mPolygon) lo = glm::min(lo, q), hi = glm::max(hi, q);
            for (glm::dvec2 corner : {lo, glm::dvec2(hi.x, lo.y), hi, glm::dvec2(lo.x, hi.y)}) {
                glm::dvec2 best = l.mPolygon[0];
                for (const glm::dvec2& q : l.mPolygon)
                    if (glm::length(q - corner) < glm::length(best - corner)) best = q;
                points.push_back(best);
            }
        }
        ShadowLights out;
        int n = int(points.size());
        out.sharesPerItem = n;
        out.shares.assign(size_t(2 * n), {});
        for (int k = 0; k < n; ++k) {
            out.lights.push_back(l.emitterPose(pose).position + points[size_t(k)].x * ex +
                                 points[size_t(k)].y * ey);
            out.lit.push_back(1);
            out.shares[size_t(k)] = {k, 1.f / float(n)};
        }
        out.shares[size_t(n)] = {0, 1.f};  // item 1: the centre
        return out;
    }

    static glm::dvec3 displayRadiance(const Luminaire& luminaire) {
        const PhotometricLuminaire& l = of(luminaire.model());
        const Pose& pose = luminaire.pose;
        glm::dvec3 ex, ey, ez;
        l.photometricFrame(pose, ex, ey, ez);
        double area = l.mArea;
        if (area <= 0.0) {
            auto o = l.outline(pose);
            area = glm::length(o[1] - o[0]) * glm::length(o[3] - o[0]);
        }
        return l.colour * (l.intensity(pose, ez) / std::max(area, 1e-12));
    }

    static void writeJson(const LuminaireModel& model, nlohmann::json& out) {
        const PhotometricLuminaire& l = of(model);
        if (l.gldf) {
            out["type"] = "gldf";
            out["variant"] = l.gldfVariant;
            if (l.gldfEmitterCount > 1) out["emitter"] = l.gldfEmitter;
            if (l.gldfMaintenance) {
                const GldfMaintenanceChoice& c = *l.gldfMaintenance;
                nlohmann::json m = {{"hours", c.hours}};
                if (c.lmf >= 0.0)
                    m["lmf"] = c.lmf;
                else
                    m["years"] = c.years, m["room"] = c.room;
                if (c.rsmf != 1.0) m["rsmf"] = c.rsmf;
                out["maintenance"] = m;
            }
        }
        if (!l.showBody) out["body"] = false;
        if (l.bodyReflectance > 0.0) out["body_reflectance"] = l.bodyReflectance;
        out["file"] = l.file;
        out["scale"] = l.scale;  // always present, so the inspector offers it
        if (l.colour != glm::dvec3(1.0)) out["colour"] = {l.colour.x, l.colour.y, l.colour.z};
        if (l.openingOverride.x > 0.0 || l.openingOverride.y > 0.0)
            out["opening"] = {l.openingOverride.x, l.openingOverride.y};
    }

    static std::vector<std::byte> gpuData(const Luminaire& luminaire) {
        const PhotometricLuminaire& l = of(luminaire.model());
        const Pose& pose = luminaire.pose;
        const PhotometricData& d = *l.data;
        gpu::PhotometricGpu h{};
        glm::dvec3 x, y, z;
        l.photometricFrame(pose, x, y, z);
        h.position = glm::vec4(glm::vec3(l.emitterPose(pose).position), float(l.mArea));
        h.axisX = glm::vec4(glm::vec3(x), float(l.mSize));
        h.axisY = glm::vec4(glm::vec3(y), float(0.1 * l.mSize));
        h.axisZ = glm::vec4(glm::vec3(z), 0.f);
        h.colour = glm::vec4(glm::vec3(l.colour), float(l.scale));
        int nv = int(d.vertical.size()), nh = int(d.horizontal.size());
        int corners = int(l.mPolygon.size());
        h.dims = glm::ivec4(nv, nh, corners, d.goniometer == Goniometer::B ? 1 : 0);
        int base = int(sizeof(h) / sizeof(float));
        // The candela table is a texture (gpuTables); offsets.z is unused.
        h.offsets = glm::ivec4(base, base + nv, 0, base + nv + nh);
        const auto& p24 = poissonSet(24);
        const auto& p40 = poissonSet(40);
        h.samples = glm::ivec4(h.offsets.w + 2 * corners, h.offsets.w + 2 * corners + 48, 0, 0);
        // The reference's intensity-proportional directions: the cells' CDF (gpuTables).
        if (auto sampler = IntensitySampler::of(l.data); sampler && sampler->valid())
            h.samples.z = 1;
        std::vector<float> values(size_t(h.samples.y + 80), 0.f);
        for (int i = 0; i < nv; ++i)
            values[size_t(h.offsets.x + i)] = float(d.vertical[size_t(i)] * kPi / 180.0);
        for (int i = 0; i < nh; ++i)
            values[size_t(h.offsets.y + i)] = float(d.horizontal[size_t(i)] * kPi / 180.0);
        for (int i = 0; i < corners; ++i) {
            values[size_t(h.offsets.w + 2 * i)] = float(l.mPolygon[size_t(i)].x);
            values[size_t(h.offsets.w + 2 * i + 1)] = float(l.mPolygon[size_t(i)].y);
        }
        for (int i = 0; i < 24; ++i) {
            values[size_t(h.samples.x + 2 * i)] = float(p24[size_t(i)].x);
            values[size_t(h.samples.x + 2 * i + 1)] = float(p24[size_t(i)].y);
        }
        for (int i = 0; i < 40; ++i) {
            values[size_t(h.samples.y + 2 * i)] = float(p40[size_t(i)].x);
            values[size_t(h.samples.y + 2 * i + 1)] = float(p40[size_t(i)].y);
        }
        std::vector<std::byte> out(values.size() * sizeof(float));
        std::memcpy(out.data(), values.data(), out.size());
        std::memcpy(out.data(), &h, sizeof(h));
        return out;
    }

    static std::shared_ptr<const GpuTables> gpuTables(const LuminaireModel& model) {
        const PhotometricLuminaire& l = of(model);
        if (l.mGpuTablesFor != l.data.get()) {
            // The candela table, unscaled (the shader applies `scale`): vertical angle along x,
            // horizontal along y, as PhotometricData::candela holds it.
            const PhotometricData& d = *l.data;
            int nv = int(d.vertical.size()), nh = int(d.horizontal.size());
            GpuTable t{gpu::kUnitPhotometricIntensity, 1, nv, nh, 1, false, {}};
            t.texels.resize(size_t(nv) * size_t(nh));
            for (size_t i = 0; i < t.texels.size(); ++i) t.texels[i] = float(d.candela[i]);
            GpuTables tables{std::move(t)};
            // The cells' CDF for the reference's intensity-proportional directions
            // (IntensitySampler.h): (nv - 1)(nh - 1) + 1 entries, nv - 1 to a row.
            if (auto sampler = IntensitySampler::of(l.data); sampler && sampler->valid()) {
                std::vector<double> cdf = sampler->normalisedCdf();
                int width = std::max(nv - 1, 1),
                    height = int((cdf.size() + size_t(width) - 1) / size_t(width));
                GpuTable cells{gpu::kUnitPhotometricCellCdf, 1, width, height, 1, false, {}};
                cells.texels.assign(size_t(width) * size_t(height), 1.f);
                for (size_t i = 0; i < cdf.size(); ++i) cells.texels[i] = float(cdf[i]);
                tables.push_back(std::move(cells));
            }
            l.mGpuTables = std::make_shared<const GpuTables>(std::move(tables));
            l.mGpuTablesFor = l.data.get();
        }
        return l.mGpuTables;
    }

    static std::string describe(const LuminaireModel& model) {
        const PhotometricLuminaire& l = of(model);
        const PhotometricData& d = *l.data;
        const char* shape =
            l.mPolygon.empty() ? "point" : (l.mPolygon.size() == 2 ? "segment" : "polygon");
        char buf[768];
        std::snprintf(buf, sizeof buf,
                      "%s: %s, type %s, %zu x %zu angles, opening %.4g x %.4g m (%s, %.4g m2), "
                      "flux %.5g lm from the table%s",
                      source(l).c_str(), d.format.c_str(),
                      d.goniometer == Goniometer::B ? "B" : "C", d.vertical.size(),
                      d.horizontal.size(), l.opening().length, l.opening().width, shape, l.mArea,
                      l.scale * d.fluxFromTable(), l.scale != 1.0 ? " (scaled)" : "");
        std::string out = buf;
        if (l.gldfMaintenance)
            out += ", maintenance factor " + l.gldfFactors.text(l.gldfMaintenance->hours) +
                   " (from the GLDF data)";
        if (l.gldf && l.placement) {
            // Unit vectors to 4 decimals, without rounding noise (6e-17) or signed zeros.
            auto tidy = [](glm::dvec3 v) {
                for (int i = 0; i < 3; ++i) v[i] = std::round(v[i] * 1e4) / 1e4 + 0.0;
                return v;
            };
            glm::dvec3 c0 = tidy(l.placement->c0), aim = tidy(l.placement->aim);
            std::snprintf(
                buf, sizeof buf,
                ", C0 along (%.4g, %.4g, %.4g) and aim (%.4g, %.4g, %.4g) in the luminaire "
                "frame",
                c0.x, c0.y, c0.z, aim.x, aim.y, aim.z);
            out += buf;
        }
        if (l.placement && !l.placement->object.empty() &&
            !(l.openingOverride.x > 0.0 || l.openingOverride.y > 0.0)) {
            glm::dvec3 c = l.placement->centre;
            std::snprintf(buf, sizeof buf,
                          ", opening from its L3D object \"%s\" at (%.4g, %.4g, %.4g) m from the "
                          "insertion point",
                          l.placement->object.c_str(), c.x, c.y, c.z);
            out += buf;
        }
        if (d.lampFlux > 0.0) {
            std::snprintf(buf, sizeof buf, ", lamps %.5g lm x LOR %.3g = %.5g lm", d.lampFlux,
                          d.lightOutputRatio, d.lampFlux * d.lightOutputRatio);
            out += buf;
        }
        return out;
    }

    static std::vector<std::unique_ptr<Luminaire>> companions(const Luminaire& luminaire) {
        const PhotometricLuminaire& l = of(luminaire.model());
        std::vector<std::unique_ptr<Luminaire>> out;
        if (!l.gldf || !l.mAllEmitters || l.gldfEmitter != 0) return out;
        for (int k = 1; k < l.gldfEmitterCount; ++k) {
            auto other = std::make_shared<PhotometricLuminaire>(l);
            other->loadGldf(l.gldf->path, l.gldfVariant, k);
            other->mAllEmitters = false;
            other->updateOpening();
            auto placement = std::make_unique<Luminaire>(luminaire);
            placement->setModel(std::move(other));
            out.push_back(std::move(placement));
        }
        return out;
    }

    static std::string source(const PhotometricLuminaire& l) {
        if (!l.gldf) return "photometric " + l.file;
        std::string out = "GLDF " + l.file + " variant \"" + l.gldfVariant + "\"";
        if (l.gldfEmitterCount > 1)
            out += " emitter " + std::to_string(l.gldfEmitter) + " of " +
                   std::to_string(l.gldfEmitterCount);
        if (!l.gldf->manufacturer.empty() || !l.gldf->productName.empty())
            out += " (" + l.gldf->manufacturer + (l.gldf->manufacturer.empty() ? "" : " ") +
                   l.gldf->productName + ")";
        return out;
    }

    static std::vector<std::string> sourceFiles(const LuminaireModel& model) {
        const PhotometricLuminaire& l = of(model);
        if (l.gldf) return {l.gldf->path};
        std::vector<std::string> files;
        if (l.data && !l.data->path.empty()) files.push_back(l.data->path);
        if (l.data && !l.data->tiltPath.empty()) files.push_back(l.data->tiltPath);
        return files;
    }
};

namespace {

/// The fields a photometric and a GLDF entry share: scale, colour, opening; `file` resolved
/// against the scene's folder.
std::shared_ptr<PhotometricLuminaire> parseCommon(const nlohmann::json& entry,
                                                  const json::Where& where,
                                                  const std::string& fileWanted,
                                                  std::string& resolvedFile) {
    if (!entry.contains("file")) json::fail(where / "file", fileWanted);
    auto light = std::make_shared<PhotometricLuminaire>();
    light->file = json::string(entry["file"], where / "file");
    fs::path resolved(light->file);
    if (resolved.is_relative()) resolved = fs::path(where.file).parent_path() / resolved;
    resolvedFile = resolved.string();
    light->scale = json::optional(
        entry, "scale", where, 1.0, [](const nlohmann::json& v, const json::Where& w) {
            double s = json::positive(v, w);
            if (!(s <= kMaxScale))
                json::fail(w, "a positive multiplier of at most " + formatNumber(kMaxScale) +
                                  ", got " + v.dump());
            return s;
        });
    light->colour = json::optional(
        entry, "colour", where, glm::dvec3(1.0), [](const nlohmann::json& v, const json::Where& w) {
            glm::dvec3 c = json::vec3(v, w);
            if (c.x < 0.0 || c.y < 0.0 || c.z < 0.0)
                json::fail(w, "a colour with no negative component");
            if (!(glm::max(c.x, glm::max(c.y, c.z)) <= kMaxColour))
                json::fail(w, "a colour whose components are at most " + formatNumber(kMaxColour) +
                                  ", got " + v.dump());
            return c;
        });
    light->openingOverride = json::optional(
        entry, "opening", where, glm::dvec2(0.0),
        [](const nlohmann::json& v, const json::Where& w) {
            glm::dvec2 s = json::vec2(v, w);
            if (!(s.x >= 0.0 && s.y >= 0.0 && s.x + s.y > 0.0))
                json::fail(w, "[length, width] in metres, not negative, not both 0");
            if (!(s.x <= kMaxOpening && s.y <= kMaxOpening))
                json::fail(w, "[length, width] of at most " + formatNumber(kMaxOpening) +
                                  " m each, got " + v.dump());
            return s;
        });
    light->showBody = json::optional(entry, "body", where, true, json::boolean);
    light->bodyReflectance = json::optional(
        entry, "body_reflectance", where, 0.0, [](const nlohmann::json& v, const json::Where& w) {
            double r = json::number(v, w);
            if (!(r >= 0.0 && r < 1.0)) json::fail(w, "a reflectance from 0 up to (not) 1");
            return r;
        });
    return light;
}

}  // namespace

std::unique_ptr<Luminaire> PhotometricAdapter::parse(const nlohmann::json& entry,
                                                     const json::Where& where) {
    json::checkKeys(entry,
                    {"type", "name", "position", "aim", "c0", "technique", "maintenance_factor",
                     "file", "scale", "colour", "opening", "body", "body_reflectance"},
                    where);
    std::string resolved;
    auto light = parseCommon(entry, where,
                             "the path of an .ies, .ldt or TM-33 .xml photometric file", resolved);
    light->data = PhotometricLuminaire::load(resolved);
    light->updateOpening();
    return placed(std::move(light));
}

std::unique_ptr<Luminaire> PhotometricAdapter::parseGldf(const nlohmann::json& entry,
                                                         const json::Where& where) {
    json::checkKeys(entry,
                    {"type", "name", "position", "aim", "c0", "technique", "maintenance_factor",
                     "file", "variant", "emitter", "maintenance", "scale", "colour", "opening",
                     "body", "body_reflectance"},
                    where);
    std::string resolved;
    auto light = parseCommon(entry, where, "the path of a .gldf container", resolved);
    std::string variant = json::optional(entry, "variant", where, std::string(), json::string);
    int emitter = json::optional(
        entry, "emitter", where, 0, [](const nlohmann::json& v, const json::Where& w) {
            if (!v.is_number_integer() || v.get<int64_t>() < 0 || v.get<int64_t>() > 1000000)
                json::fail(w, "an emitter index from 0");
            return int(v.get<int64_t>());
        });
    light->loadGldf(resolved, variant, emitter);
    light->updateOpening();
    std::optional<double> maintenanceFactor;
    if (entry.contains("maintenance")) {
        // EN 12464-1's MF from the product's data: {"hours": h, "lmf": x | "years": y, "room":
        // r, "rsmf": x}.
        const nlohmann::json& m = entry["maintenance"];
        json::Where at = where / "maintenance";
        if (!m.is_object())
            json::fail(at,
                       "{\"hours\": h, \"lmf\": x or \"years\": y and \"room\": r, "
                       "\"rsmf\": x}");
        json::checkKeys(m, {"hours", "lmf", "years", "room", "rsmf"}, at);
        GldfMaintenanceChoice c;
        if (!m.contains("hours")) json::fail(at / "hours", "the burning time in hours");
        c.hours = json::number(m["hours"], at / "hours");
        auto unit = [](const nlohmann::json& v, const json::Where& w) {
            double x = json::number(v, w);
            if (!(x > 0.0 && x <= 1.0)) json::fail(w, "a factor in (0, 1]");
            return x;
        };
        c.lmf = json::optional(m, "lmf", at, -1.0, unit);
        c.rsmf = json::optional(m, "rsmf", at, 1.0, unit);
        if (c.lmf < 0.0) {
            if (!m.contains("years") || !m.contains("room"))
                json::fail(at,
                           "\"lmf\", or \"years\" and \"room\" to take the product's "
                           "luminaire maintenance factor");
            c.years = json::number(m["years"], at / "years");
            c.room = json::string(m["room"], at / "room");
        }
        const GldfLightEmitter* placed = light->gldfLightEmitter();
        if (!placed) json::fail(at, "a GLDF variant whose emitter has a light emitter");
        light->gldfMaintenance = c;
        light->gldfFactors = candela::gldfMaintenanceFactors(*light->gldf, *placed, c);
        double mf = light->gldfFactors.factor();
        // A saved scene states both; any other maintenance_factor contradicts the data.
        if (entry.contains("maintenance_factor") &&
            json::number(entry["maintenance_factor"], where / "maintenance_factor") != mf)
            json::fail(where / "maintenance_factor",
                       "no maintenance_factor beside \"maintenance\", which makes it " +
                           std::to_string(mf));
        maintenanceFactor = mf;
    }
    // Without "emitter", an entry is every emitter its variant places (companions()).
    light->mAllEmitters = !entry.contains("emitter");
    auto out = placed(std::move(light));
    out->maintenanceFactor = maintenanceFactor;
    return out;
}

std::unique_ptr<Luminaire> PhotometricAdapter::create() {
    // The editor's "Add": a bundled real file (resources/luminaires/photometric/LICENSE.md).
    auto light = std::make_shared<PhotometricLuminaire>();
    fs::path bundled =
        fs::path(CANDELA_SOURCE_DIR) / "resources/luminaires/photometric/linear-pendant.ies";
    light->file = bundled.generic_string();
    light->data = PhotometricLuminaire::load(light->file);
    light->updateOpening();
    return placed(std::move(light));
}

const LuminaireAdapter& photometricAdapter() {
    using A = PhotometricAdapter;
    static const LuminaireAdapter adapter{&A::parse,       &A::create,         &A::writeJson,
                                          &A::gpuData,     &A::gpuTables,      &A::describe,
                                          &A::sourceFiles, &A::shadowLights,   &A::body,
                                          &A::companions,  &A::displayRadiance};
    return adapter;
}

bool sameGldfVariant(const Luminaire& a, const Luminaire& b) {
    const PhotometricLuminaire *p = photometricModel(a), *q = photometricModel(b);
    return p && q && p->gldf && q->gldf && p->gldfEmitterCount > 1 && p->file == q->file &&
           p->gldfVariant == q->gldfVariant;
}

std::unique_ptr<Luminaire> parseGldfLuminaire(const nlohmann::json& entry,
                                              const json::Where& where) {
    return PhotometricAdapter::parseGldf(entry, where);
}

const PhotometricLuminaire* photometricModel(const Luminaire& luminaire) {
    return luminaire.kind() == LuminaireKind::Photometric
               ? &PhotometricAdapter::of(luminaire.model())
               : nullptr;
}

}  // namespace candela
