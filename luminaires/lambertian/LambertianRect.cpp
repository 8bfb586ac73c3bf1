#include "luminaires/lambertian/LambertianRect.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "luminaires/Adapter.h"
#include "luminaires/Random.h"
#include "luminaires/SphericalPolygon.h"
#include "shaders/shared/Constants.h"
#include "shaders/shared/GpuTypes.h"

namespace candela {

namespace {

using gpu::kPi;
/// Largest distance from the receiver to the centre that is evaluated, metres; beyond it the
/// rectangle subtends nothing representable and every estimator returns 0.
constexpr double kMaxDistance = 1e100;
/// A receiver closer to the emitter plane than this fraction of (its distance to the centre +
/// width + height) is treated as lying in the plane: the rounding of that distance is ~1e-16 of
/// it, so 1e-12 keeps the sign meaningful while 1e-6 m in front of a 1 m light is still in front.
constexpr double kPlaneTolerance = 1e-12;
/// Relative slack of the "is this point on the rectangle" tests for points computed elsewhere
/// (e.g. a sample position recomputed from a direction): ~1e7 times double rounding.
constexpr double kOnSurfaceTolerance = 1e-9;
/// Largest width or height accepted from a scene file, metres.
constexpr double kMaxSize = 1e6;
/// Largest radiance accepted from a scene file, W/(m2 sr): keeps power() far from overflow.
constexpr double kMaxRadiance = 1e20;

/// Width and height, metres, with negative or non-finite values read as 0 (an empty emitter).
glm::dvec2 extentOf(const LambertianRect& light) {
    auto clean = [](double v) { return v > 0.0 && v <= kMaxDistance ? v : 0.0; };
    return {clean(light.size.x), clean(light.size.y)};
}

/// The rectangle in its own frame as seen from a receiver p. Lengths are divided by `scale` (the
/// largest of |x0|, |x1|, |y0|, |y1|, h), so that no square over- or underflows: every quantity
/// below except the solid-angle pdf is scale invariant.
struct LocalRect {
    glm::dvec3 ex{0.0}, ey{0.0}, ez{0.0};  ///< World unit axes: width, height, emitting normal.
    double x0 = 0.0, x1 = 0.0;             ///< Edge offsets from p along ex (scaled), x0 < x1.
    double y0 = 0.0, y1 = 0.0;             ///< Edge offsets from p along ey (scaled), y0 < y1.
    double h = 0.0;                        ///< Distance from p to the emitter plane (scaled), > 0.
    double scale = 0.0;                    ///< Metres per local unit.
};

/// Fills r and returns true when p is strictly in front of a non-empty emitter.
bool seenFromFront(const LambertianRect& light, const Pose& pose, const glm::dvec3& p,
                   LocalRect& r) {
    glm::dvec2 size = extentOf(light);
    if (!(size.x > 0.0 && size.y > 0.0)) return false;
    glm::dvec3 c = pose.position - p;
    double dist = glm::length(c);
    if (!(dist <= kMaxDistance)) return false;  // also rejects NaN
    pose.frame(r.ex, r.ey, r.ez);
    double h = -glm::dot(c, r.ez);
    if (!(h > kPlaneTolerance * (dist + size.x + size.y))) return false;
    double cx = glm::dot(c, r.ex), cy = glm::dot(c, r.ey);
    double x0 = cx - 0.5 * size.x, x1 = cx + 0.5 * size.x;
    double y0 = cy - 0.5 * size.y, y1 = cy + 0.5 * size.y;
    r.scale = std::max({std::abs(x0), std::abs(x1), std::abs(y0), std::abs(y1), h});
    r.x0 = x0 / r.scale;
    r.x1 = x1 / r.scale;
    r.y0 = y0 / r.scale;
    r.y1 = y1 / r.scale;
    r.h = h / r.scale;
    return r.x1 > r.x0 && r.y1 > r.y0;
}

/// Signed solid angle of the rectangle [0, x] x [0, y] in the plane at distance h below the
/// receiver: atan(xy / (h sqrt(x^2 + y^2 + h^2))). Sums of four of these give any rectangle.
double cornerAngle(double x, double y, double h) {
    return std::atan2(x * y, h * std::sqrt(x * x + y * y + h * h));
}

/// eta(a) - eta(b) for eta(y) = y / sqrt(d^2 + y^2), without the cancellation of the direct
/// difference when a and b have the same sign and d is small.
double etaDifference(double a, double b, double d) {
    double ra = std::sqrt(d * d + a * a), rb = std::sqrt(d * d + b * b);
    if (!(ra > 0.0 && rb > 0.0)) return 0.0;
    if (a * b <= 0.0) return (a * rb - b * ra) / (ra * rb);
    // a rb - b ra = (a^2 rb^2 - b^2 ra^2) / (a rb + b ra) = d^2 (a - b)(a + b) / (a rb + b ra).
    return d * d * (a - b) * (a + b) / ((a * rb + b * ra) * ra * rb);
}

/// 1 - eta(y) and 1 + eta(y), each computed without cancellation.
double oneMinusEta(double y, double d) {
    double r = std::sqrt(d * d + y * y);
    if (!(r > 0.0)) return 1.0;
    return y > 0.0 ? d * d / (r * (r + y)) : 1.0 - y / r;
}
double onePlusEta(double y, double d) {
    double r = std::sqrt(d * d + y * y);
    if (!(r > 0.0)) return 1.0;
    return y < 0.0 ? d * d / (r * (r - y)) : 1.0 + y / r;
}

/// Solid angle of the rectangle (sr) from two triangles with the formula of Van Oosterom and
/// Strackee (1983), tan(Omega/2) = |a . (b x c)| / (abc + (a.b)c + (b.c)a + (c.a)b), written on
/// unit vectors. The triple product of both triangles is exactly h * width * height.
double solidAngleOf(const LocalRect& r) {
    glm::dvec3 v00(r.x0, r.y0, -r.h), v10(r.x1, r.y0, -r.h);
    glm::dvec3 v11(r.x1, r.y1, -r.h), v01(r.x0, r.y1, -r.h);
    double l00 = glm::length(v00), l10 = glm::length(v10);
    double l11 = glm::length(v11), l01 = glm::length(v01);
    glm::dvec3 a = v00 / l00, b = v10 / l10, c = v11 / l11, d = v01 / l01;
    double w = r.x1 - r.x0, t = r.y1 - r.y0;
    double num1 = (r.h / l00) * (w / l10) * (t / l11);
    double num2 = (r.h / l00) * (w / l11) * (t / l01);
    double den1 = 1.0 + glm::dot(a, b) + glm::dot(b, c) + glm::dot(c, a);
    double den2 = 1.0 + glm::dot(a, c) + glm::dot(c, d) + glm::dot(d, a);
    double omega = 2.0 * (std::atan2(num1, den1) + std::atan2(num2, den2));
    return std::isfinite(omega) ? omega : 0.0;
}

/// Integral of max(0, m . w) over the rectangle's solid angle (sr), m the receiver's unit normal
/// in the local frame: the rectangle clipped to the receiver's upper hemisphere, then Lambert's
/// polygon formula (Baum, Rushmeier, Winget 1989, Eq. 2), both from luminaires/SphericalPolygon.
double projectedSolidAngle(const LocalRect& r, const glm::dvec3& m) {
    spherical::Polygon quad;
    quad.count = 4;
    quad.v[0] = {r.x0, r.y0, -r.h};
    quad.v[1] = {r.x1, r.y0, -r.h};
    quad.v[2] = {r.x1, r.y1, -r.h};
    quad.v[3] = {r.x0, r.y1, -r.h};
    return spherical::projectedSolidAngle(spherical::clip(quad, m), m);
}

/// Clamps a sampler input to [0, 1]; NaN becomes 0.
double unitInterval(double v) {
    return v > 0.0 ? (v < 1.0 ? v : 1.0) : 0.0;
}

/// Local coordinates (scaled) of the point uniform in solid angle for inputs u: the map of
/// Urena, Fajardo and King (2013), Sec. 4, written with the exact corner angles and with
/// cancellation-free forms of its differences (see the comments) so that it keeps its precision
/// for receivers near the emitter plane and far away.
glm::dvec2 sampleLocal(const LocalRect& r, const glm::dvec2& u) {
    double u1 = unitInterval(u.x), u2 = unitInterval(u.y);
    double h = r.h, x0 = r.x0, x1 = r.x1, y0 = r.y0, y1 = r.y1;
    // Marginal in x. A(x) = F(x, y1) - F(x, y0) with F = cornerAngle; the solid angle of
    // [x0, x] x [y0, y1] is A(x) - A(x0). We need A(xu) = A(x0) + u1 S =: -phi. In the paper's
    // terms phi = pi - au with au = u1 S + k, so cos(au) = -cos(phi) and sin(au) = sin(phi).
    double f00 = cornerAngle(x0, y0, h), f01 = cornerAngle(x0, y1, h);
    double f10 = cornerAngle(x1, y0, h), f11 = cornerAngle(x1, y1, h);
    double total = (f11 - f10) - (f01 - f00);
    double phi = (f00 - f01) - u1 * total;
    double sinPhi = std::sin(phi), cosPhi = std::cos(phi);
    // z component of the normal of the plane through p and the edge y = y0 (the paper's b0;
    // its b1 = y1 / sqrt(h^2 + y1^2) only enters through the sums below).
    double b0 = -y0 / std::sqrt(h * h + y0 * y0);
    // The paper's fu = (cos(au) b0 - b1) / sin(au) = -num / sin(phi) with num = b0 cos(phi) + b1.
    // num nearly cancels when |b0| ~ |b1| ~ 1 (p near the plane): expand cos(phi) around 1 or
    // -1 and take b0 + b1 = eta(y1) - eta(y0), b1 - b0 = eta(y1) + eta(y0) without cancellation.
    double num;
    if (cosPhi >= 0.0) {
        double s = std::sin(0.5 * phi);
        num = etaDifference(y1, y0, h) - 2.0 * b0 * s * s;
    } else {
        double c = std::cos(0.5 * phi);
        num = etaDifference(y1, -y0, h) + 2.0 * b0 * c * c;
    }
    // The paper's cu = sign(fu) / sqrt(fu^2 + b0^2) and xu = -cu z0 / sqrt(1 - cu^2) (z0 = -h)
    // simplify to xu = sign(fu) h / sqrt(fu^2 - (1 - b0^2)) with 1 - b0^2 = h^2 / (h^2 + y0^2);
    // multiplied through by |sin(phi)|: xu = -sign(num) h sin(phi) / sqrt(q).
    double q = num * num - h * h / (h * h + y0 * y0) * sinPhi * sinPhi;
    double top = (num >= 0.0 ? -h : h) * sinPhi;
    // q <= 0 only by rounding where xu runs off to infinity: clamp to the edge it runs to.
    double xu = q > 0.0 ? top / std::sqrt(q) : (top >= 0.0 ? x1 : x0);
    xu = std::clamp(xu, x0, x1);

    // Conditional in y along the line x = xu: the solid-angle density is d / (d^2 + y^2)^(3/2)
    // up to a constant, whose integral is eta(y) = y / sqrt(d^2 + y^2); invert it linearly
    // (the paper's h0, h1, hv), forming 1 - hv and 1 + hv without cancellation.
    double d = std::sqrt(xu * xu + h * h);
    double eta0 = y0 / std::sqrt(d * d + y0 * y0);
    double span = etaDifference(y1, y0, d);
    double hv = eta0 + u2 * span;
    double oneMinus = oneMinusEta(y1, d) + (1.0 - u2) * span;
    double onePlus = onePlusEta(y0, d) + u2 * span;
    double den = std::sqrt(oneMinus * onePlus);
    double yv = den > 0.0 ? hv * d / den : (hv >= 0.0 ? y1 : y0);
    yv = std::clamp(yv, y0, y1);
    return {xu, yv};
}

/// The receiver's unit normal in the light's frame; false for a zero or non-finite normal.
bool localNormal(const LocalRect& r, const glm::dvec3& n, glm::dvec3& m) {
    double len = glm::length(n);
    if (!(len > 0.0) || !std::isfinite(len)) return false;
    glm::dvec3 unit = n / len;
    m = {glm::dot(unit, r.ex), glm::dot(unit, r.ey), glm::dot(unit, r.ez)};
    return true;
}

/// A sample of `light` for the receiver described by r, which sees the solid angle omega (sr).
LightSample makeSample(const LambertianRect& light, const Pose& pose, const LocalRect& r,
                       double omega, const glm::dvec2& u) {
    LightSample s;
    if (!(omega >= DBL_MIN)) return s;
    glm::dvec2 xy = sampleLocal(r, u);
    glm::dvec3 local(xy.x, xy.y, -r.h);
    double len = glm::length(local);
    if (!(len > 0.0)) return s;
    s.wi = (local.x * r.ex + local.y * r.ey + local.z * r.ez) / len;
    s.distance = len * r.scale;
    // From the corner rather than from p: the point lies exactly in the emitter's plane.
    glm::dvec2 size = extentOf(light);
    glm::dvec3 corner = pose.position - 0.5 * size.x * r.ex - 0.5 * size.y * r.ey;
    s.position = corner + (xy.x - r.x0) * r.scale * r.ex + (xy.y - r.y0) * r.scale * r.ey;
    s.radiance = light.emitted;
    s.pdf = 1.0 / omega;
    return s;
}

/// Reads "size": two positive numbers (metres) of at most kMaxSize.
glm::dvec2 readSize(const nlohmann::json& v, const json::Where& where) {
    if (!v.is_array() || v.size() != 2)
        json::fail(where,
                   "an array of 2 positive numbers (width, height in metres), got " + v.dump());
    glm::dvec2 size;
    for (int i = 0; i < 2; ++i) {
        size[i] = json::positive(v[size_t(i)], where[size_t(i)]);
        if (size[i] > kMaxSize)
            json::fail(where[size_t(i)], "a size of at most 1e6 m, got " + v[size_t(i)].dump());
    }
    return size;
}

/// Reads "radiance" (W/(m2 sr)) or "luminance" (cd/m2): three non-negative numbers of at most
/// kMaxRadiance.
glm::dvec3 readEmitted(const nlohmann::json& v, const json::Where& where, const char* what) {
    glm::dvec3 radiance = json::vec3(v, where);
    for (int i = 0; i < 3; ++i)
        if (!(radiance[i] >= 0.0 && radiance[i] <= kMaxRadiance))
            json::fail(where[size_t(i)], std::string("a non-negative ") + what +
                                             " of at most 1e20, got " + v[size_t(i)].dump());
    return radiance;
}

}  // namespace

glm::dvec3 LambertianRect::radiance(const Pose& pose, const glm::dvec3& x,
                                    const glm::dvec3& w) const {
    glm::dvec2 s = extentOf(*this);
    if (!(s.x > 0.0 && s.y > 0.0)) return glm::dvec3(0.0);
    glm::dvec3 ex, ey, ez;
    pose.frame(ex, ey, ez);
    if (!(glm::dot(w, ez) > 0.0)) return glm::dvec3(0.0);
    glm::dvec3 q = x - pose.position;
    double tol = kOnSurfaceTolerance * (s.x + s.y + glm::length(q));
    bool on = std::abs(glm::dot(q, ez)) <= tol && std::abs(glm::dot(q, ex)) <= 0.5 * s.x + tol &&
              std::abs(glm::dot(q, ey)) <= 0.5 * s.y + tol;
    return on ? emitted : glm::dvec3(0.0);
}

glm::dvec3 LambertianRect::power() const {
    // A Lambertian emitter: M = pi L (the integral of L cos over the hemisphere), P = M A.
    glm::dvec2 s = extentOf(*this);
    return kPi * s.x * s.y * emitted;
}

double LambertianRect::solidAngle(const Pose& pose, const glm::dvec3& p) const {
    LocalRect r;
    return seenFromFront(*this, pose, p, r) ? solidAngleOf(r) : 0.0;
}

LightSample LambertianRect::sample(const Pose& pose, const glm::dvec3& p,
                                   const glm::dvec2& u) const {
    LocalRect r;
    if (!seenFromFront(*this, pose, p, r)) return {};
    return makeSample(*this, pose, r, solidAngleOf(r), u);
}

double LambertianRect::pdf(const Pose& pose, const glm::dvec3& p, const glm::dvec3& wi) const {
    LocalRect r;
    if (!seenFromFront(*this, pose, p, r)) return 0.0;
    double len = glm::length(wi);
    if (!(len > 0.0) || !std::isfinite(len)) return 0.0;
    glm::dvec3 w = wi / len;
    double wx = glm::dot(w, r.ex), wy = glm::dot(w, r.ey), down = -glm::dot(w, r.ez);
    if (!(down > 0.0)) return 0.0;
    // The ray meets the plane at (h wx, h wy) / down; compare without dividing, with a slack of
    // kOnSurfaceTolerance times (width + height + ray length).
    double slack = kOnSurfaceTolerance * ((r.x1 - r.x0 + r.y1 - r.y0) * down + r.h);
    double hx = r.h * wx, hy = r.h * wy;
    bool hit = hx >= r.x0 * down - slack && hx <= r.x1 * down + slack &&
               hy >= r.y0 * down - slack && hy <= r.y1 * down + slack;
    if (!hit) return 0.0;
    double omega = solidAngleOf(r);
    return omega >= DBL_MIN ? 1.0 / omega : 0.0;
}

std::vector<glm::dvec3> LambertianRect::outline(const Pose& pose) const {
    glm::dvec3 ex, ey, ez;
    pose.frame(ex, ey, ez);
    glm::dvec2 s = extentOf(*this);
    glm::dvec3 hx = 0.5 * s.x * ex, hy = 0.5 * s.y * ey;
    const glm::dvec3& c = pose.position;
    return {c - hx - hy, c + hx - hy, c + hx + hy, c - hx + hy};
}

namespace {

const LambertianRect& rectOf(const LuminaireModel& model) {
    return static_cast<const LambertianRect&>(model);
}

void rectJson(const LuminaireModel& model, nlohmann::json& out) {
    const LambertianRect& light = rectOf(model);
    out["size"] = {light.size.x, light.size.y};
    out[light.luminous ? "luminance" : "radiance"] = {light.emitted.x, light.emitted.y,
                                                      light.emitted.z};
}

std::vector<std::byte> rectGpuData(const Luminaire& luminaire) {
    const LambertianRect& light = rectOf(luminaire.model());
    const Pose& pose = luminaire.pose;
    const glm::dvec3& emitted = light.emitted;
    glm::dvec3 ex, ey, ez;
    pose.frame(ex, ey, ez);
    glm::dvec2 s = extentOf(light);
    glm::dvec3 corner = pose.position - 0.5 * s.x * ex - 0.5 * s.y * ey;
    gpu::LambertianRectGpu g{};
    g.corner = glm::vec4(glm::vec3(corner), float(s.x * s.y));
    g.edgeX = glm::vec4(glm::vec3(s.x * ex), float(s.x));
    g.edgeY = glm::vec4(glm::vec3(s.y * ey), float(s.y));
    g.radiance = glm::vec4(glm::vec3(emitted), 0.0f);
    g.normal = glm::vec4(glm::vec3(ez), 0.0f);
    std::vector<std::byte> bytes(sizeof(g));
    std::memcpy(bytes.data(), &g, sizeof(g));
    return bytes;
}

std::string rectDescribe(const LuminaireModel& model) {
    const LambertianRect& light = rectOf(model);
    const glm::dvec2& size = light.size;
    const glm::dvec3& emitted = light.emitted;
    bool luminous = light.luminous;
    glm::dvec3 p = light.power();
    char text[256];
    Quantities q = light.quantities();
    int n = std::snprintf(
        text, sizeof(text), "lambertian-rect %.2f x %.2f m, L = (%g, %g, %g) %s, %s ", size.x,
        size.y, emitted.x, emitted.y, emitted.z, radianceUnit(q), luminous ? "flux" : "power");
    std::string out(text, size_t(std::clamp(n, 0, int(sizeof(text)) - 1)));
    if (p.x == p.y && p.y == p.z)
        n = std::snprintf(text, sizeof(text), "%.1f %s", p.x, fluxUnit(q));
    else
        n = std::snprintf(text, sizeof(text), "(%.1f, %.1f, %.1f) %s", p.x, p.y, p.z, fluxUnit(q));
    return out + std::string(text, size_t(std::clamp(n, 0, int(sizeof(text)) - 1)));
}

std::unique_ptr<Luminaire> rectParse(const nlohmann::json& entry, const json::Where& where) {
    json::checkKeys(entry,
                    {"type", "name", "position", "aim", "c0", "technique", "maintenance_factor",
                     "size", "radiance", "luminance"},
                    where);
    auto light = std::make_shared<LambertianRect>();
    light->size = json::optional(entry, "size", where, light->size, readSize);
    if (entry.contains("radiance") && entry.contains("luminance"))
        json::fail(where / "luminance",
                   "either \"radiance\" (W/(m2 sr)) or \"luminance\" (cd/m2), not both");
    light->luminous = entry.contains("luminance");
    const char* key = light->luminous ? "luminance" : "radiance";
    if (entry.contains(key))
        light->emitted =
            readEmitted(entry[key], where / key,
                        light->luminous ? "luminance (cd/m2)" : "radiance (W/(m2 sr))");
    return placed(std::move(light));
}

std::unique_ptr<Luminaire> rectCreate() {
    return placed(std::make_shared<LambertianRect>());
}

}  // namespace

const LambertianRect* lambertianRectModel(const Luminaire& luminaire) {
    return luminaire.kind() == LuminaireKind::LambertianRect ? &rectOf(luminaire.model()) : nullptr;
}

const LuminaireAdapter& lambertianRectAdapter() {
    static const LuminaireAdapter adapter{&rectParse, &rectCreate,   &rectJson, &rectGpuData,
                                          nullptr,    &rectDescribe, nullptr,   nullptr,
                                          nullptr,    nullptr,       nullptr};
    return adapter;
}

Estimate lambertianRectAnalytic(const Luminaire& luminaire, const glm::dvec3& p,
                                const glm::dvec3& n, const EstimateOptions& options) {
    const auto& light = rectOf(luminaire.model());
    Estimate e;
    LocalRect r;
    glm::dvec3 m;
    if (!seenFromFront(light, luminaire.pose, p, r) || !localNormal(r, n, m)) return e;
    e.irradiance = light.emitted * projectedSolidAngle(r, m);
    if (!options.visibility || options.spp <= 0) return e;

    // Visible fraction of the cosine-weighted solid angle, estimated with solid-angle samples:
    // R = sum(c V) / sum(c). Its standard error by the delta method is sqrt(sum(c^2 (V - R)^2))
    // / sum(c); with V in {0, 1}, sum(c^2 (V - R)^2) = (1 - 2R) sum(c^2 V) + R^2 sum(c^2).
    double omega = solidAngleOf(r);
    glm::dvec3 unitN = n / glm::length(n);
    Random rng(options.seed);
    double sumCos = 0.0, sumCosV = 0.0, sumCos2 = 0.0, sumCos2V = 0.0;
    for (int k = 0; k < options.spp; ++k) {
        double u1 = rng.uniform(), u2 = rng.uniform();
        LightSample s = makeSample(light, luminaire.pose, r, omega, {u1, u2});
        if (s.pdf <= 0.0) continue;
        double c = std::max(0.0, glm::dot(unitN, s.wi));
        if (c <= 0.0) continue;
        sumCos += c;
        sumCos2 += c * c;
        if (options.visibility->visible(p, s.position)) {
            sumCosV += c;
            sumCos2V += c * c;
        }
    }
    if (!(sumCos > 0.0)) return e;
    double ratio = sumCosV / sumCos;
    double var = std::max(0.0, (1.0 - 2.0 * ratio) * sumCos2V + ratio * ratio * sumCos2);
    e.stdError = e.irradiance * (std::sqrt(var) / sumCos);
    e.irradiance *= ratio;
    return e;
}

Estimate lambertianRectReference(const Luminaire& luminaire, const glm::dvec3& p,
                                 const glm::dvec3& n, const EstimateOptions& options) {
    const auto& light = rectOf(luminaire.model());
    Estimate e;
    LocalRect r;
    glm::dvec3 m;
    if (options.spp <= 0 || !seenFromFront(light, luminaire.pose, p, r) || !localNormal(r, n, m))
        return e;
    double omega = solidAngleOf(r);
    glm::dvec3 unitN = n / glm::length(n);
    Random rng(options.seed);
    // Welford's running mean and sum of squared deviations of f = max(0, n.wi) V / pdf (sr);
    // the radiance is constant, so E = L mean(f).
    double mean = 0.0, m2 = 0.0;
    for (int k = 0; k < options.spp; ++k) {
        double u1 = rng.uniform(), u2 = rng.uniform();
        LightSample s = makeSample(light, luminaire.pose, r, omega, {u1, u2});
        double f = 0.0;
        if (s.pdf > 0.0) {
            double c = std::max(0.0, glm::dot(unitN, s.wi));
            bool v = c > 0.0 && (!options.visibility || options.visibility->visible(p, s.position));
            f = v ? c / s.pdf : 0.0;
        }
        double delta = f - mean;
        mean += delta / double(k + 1);
        m2 += delta * (f - mean);
    }
    int count = options.spp;
    double variance = count > 1 ? std::max(0.0, m2) / double(count - 1) : 0.0;
    e.irradiance = light.emitted * mean;
    e.stdError = light.emitted * std::sqrt(variance / double(count));
    return e;
}

}  // namespace candela
