// Techniques for photometric area lights (Prost 2019, seed 004), CPU double precision. Each has
// a GLSL twin in shaders/photometric.glsl; the registry (luminaires/Registry.cpp) lists them.
//
// All work in the luminaire's local frame (opening in z = 0, aim +z) with vectors relative to the
// receiver p. Two forms of the same integral appear:
//   area form   E = (1/A) Int_opening I(w) cos(theta_p) / r^2 dA     (Eq. 6.3 with L = I/(A cos))
//   solid-angle E = Int_Omega L(w) cos(theta_p) dw,  L = I / (A |cos theta_L|)  (Eq. 2.46)
// The area form is finite everywhere, including receivers in the opening's plane; the solid-angle
// form is what structured, MRP and scattered sampling approximate.
//
// Visibility (EstimateOptions::visibility), as the GPU's SHADOWS variant: `reference` traces a
// shadow ray per sample; `point` the one ray to the centre; the other deterministic techniques
// multiply their unshadowed value by the irradiance-weighted visible fraction of `spp` random
// points on the opening, R = sum(E_i V_i) / sum(E_i) (consistent; exactly 1 where every ray is
// free, exactly 0 where none is); a segment's 16 Gauss points each trace their own ray.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <mutex>
#include <vector>

#include "luminaires/Random.h"
#include "luminaires/SphericalPolygon.h"
#include "luminaires/photometric/IntensitySampler.h"
#include "luminaires/photometric/PhotometricLuminaire.h"
#include "shaders/shared/Constants.h"
#include "shaders/shared/Photometric.h"

namespace candela {

namespace {

using gpu::kPi;
using spherical::Polygon;

struct Setup {
    const PhotometricLuminaire* light;
    glm::dvec3 p;        ///< Receiver, local frame (opening centre at the origin).
    glm::dvec3 n;        ///< Receiver's unit normal, local frame.
    glm::dvec3 x, y, z;  ///< The photometric frame (world directions of local axes).
    glm::dvec3 pWorld;   ///< Receiver, world, metres.
    glm::dvec3 centre;   ///< The opening's centre (the emitter pose's position), world, metres.
    const Visibility* visibility = nullptr;  ///< null: no shadowing.

    /// Whether the opening's local point q is free of occluders from the receiver.
    bool visible(const glm::dvec3& q) const {
        return !visibility || visibility->visible(pWorld, centre + q.x * x + q.y * y + q.z * z);
    }
};

Setup makeSetup(const Luminaire& l, const glm::dvec3& pWorld, const glm::dvec3& nWorld,
                const Visibility* visibility = nullptr) {
    Setup s;
    s.light = photometricModel(l);
    s.pWorld = pWorld;
    s.visibility = visibility;
    s.light->photometricFrame(l.pose, s.x, s.y, s.z);
    s.centre = l.emitterPose().position;
    glm::dvec3 d = pWorld - s.centre;
    s.p = {glm::dot(d, s.x), glm::dot(d, s.y), glm::dot(d, s.z)};
    glm::dvec3 n = {glm::dot(nWorld, s.x), glm::dot(nWorld, s.y), glm::dot(nWorld, s.z)};
    double ln = glm::length(n);
    s.n = ln > 0.0 ? n / ln : glm::dvec3(0.0);
    return s;
}

/// Candela from local opening point q towards the receiver (local direction q -> p).
double intensityTowards(const Setup& s, const glm::dvec3& v) {
    // v = q - p (receiver to light); the light emits along -v.
    double l = glm::length(v);
    if (!(l > 0.0)) return 0.0;
    glm::dvec3 w = -v / l;
    return s.light->scale * s.light->data->intensity(w);
}

/// Point-source irradiance at the receiver from opening point q (local): I cos(theta_p) / r^2.
double pointIrradiance(const Setup& s, const glm::dvec3& q) {
    glm::dvec3 v = q - s.p;
    double r2 = glm::dot(v, v);
    if (!(r2 > 0.0)) return 0.0;
    double c = glm::dot(s.n, v) / std::sqrt(r2);
    if (!(c > 0.0)) return 0.0;
    double e = intensityTowards(s, v) * c / r2;
    return std::isfinite(e) ? e : 0.0;
}

/// L(w) cos(theta_p) along the unit direction d from the receiver towards the opening, L = I /
/// (A |cos theta_L|): the solid-angle integrand.
double solidAngleIntegrand(const Setup& s, const glm::dvec3& d) {
    double c = glm::dot(s.n, d);
    double cosL = std::abs(d.z);
    if (!(c > 0.0) || !(cosL > 1e-12) || !(s.light->area() > 0.0)) return 0.0;
    double value = s.light->scale * s.light->data->intensity(-d) * c / (s.light->area() * cosL);
    return std::isfinite(value) ? value : 0.0;
}

Estimate withColour(const Setup& s, double e, double stdError = 0.0) {
    Estimate out;
    out.irradiance = s.light->colour * e;
    out.stdError = s.light->colour * stdError;
    return out;
}

/// Zero-area openings. A point: the point-source law. A segment: the average of point sources
/// along it (the limit of the area form as the width goes to 0), integrated over the angle
/// theta seen from the receiver rather than along the segment: with x = d tan(theta) from the
/// foot of the perpendicular (d its length), dx / r^2 = dtheta / d, so the integrand stays
/// smooth however close the receiver is (along x it would peak within d of the foot and a fixed
/// rule would miss it: 1e-22 of the truth 1e-9 m away). 16-point Gauss-Legendre on 4 panels on
/// each side of the foot (the table's bilinear interpolation has a kink at every one of its
/// angles: panels keep the rule's error near 1e-7).
bool degenerate(const Setup& s, double& e) {
    const auto& poly = s.light->polygon();
    if (poly.size() >= 3) return false;
    if (poly.empty()) {
        e = s.visible(glm::dvec3(0.0)) ? pointIrradiance(s, glm::dvec3(0.0)) : 0.0;
        return true;
    }
    const auto& node = gpu::kGaussLegendre16Node;  // the positive half of the rule
    const auto& weight = gpu::kGaussLegendre16Weight;
    glm::dvec3 a(poly[0], 0.0), b(poly[1], 0.0);
    double length = glm::length(b - a);
    e = 0.0;
    if (!(length > 0.0)) return true;
    glm::dvec3 axis = (b - a) / length;
    double foot = glm::dot(s.p - a, axis);            // the foot's position along the segment
    double d = glm::length((a + foot * axis) - s.p);  // the receiver's distance from the line
    if (!(d > 1e-300)) return true;  // on the line itself: no direction to light it
    double theta0 = std::atan2(-foot, d), theta1 = std::atan2(length - foot, d);
    // Both sides of the foot (theta = 0) when it lies on the segment, so the peak is an end.
    double split = std::clamp(0.0, theta0, theta1);
    const int kPanels = 4;
    for (auto [from, to] : {std::pair{theta0, split}, std::pair{split, theta1}})
        for (int panel = 0; panel < kPanels && to > from; ++panel) {
            double lo = from + (to - from) * panel / kPanels,
                   hi = from + (to - from) * (panel + 1) / kPanels;
            for (int i = 0; i < 8; ++i)
                for (double sign : {-1.0, 1.0}) {
                    double theta = 0.5 * (lo + hi) + 0.5 * sign * node[i] * (hi - lo);
                    double x = foot + d * std::tan(theta);
                    glm::dvec3 q = a + x * axis;
                    double point = pointIrradiance(s, q);
                    // dx = d / cos^2(theta) dtheta; the average over the segment divides by its
                    // length.
                    double c = std::cos(theta);
                    if (point > 0.0 && s.visible(q))
                        e += 0.5 * weight[i] * (hi - lo) * point * d / (c * c) / length;
                }
        }
    return true;
}

/// The opening as a polygon of vectors from the receiver.
Polygon openingFromReceiver(const Setup& s) {
    Polygon q;
    for (const auto& c : s.light->polygon())
        if (q.count < spherical::kMaxPolygon) q.v[size_t(q.count++)] = glm::dvec3(c, 0.0) - s.p;
    return q;
}

/// Bounding rectangle of the opening (local x, y).
void bounds(const PhotometricLuminaire& l, glm::dvec2& lo, glm::dvec2& hi) {
    lo = glm::dvec2(INFINITY);
    hi = glm::dvec2(-INFINITY);
    for (const auto& c : l.polygon()) {
        lo = glm::min(lo, c);
        hi = glm::max(hi, c);
    }
}

/// Area-form estimate with fixed points u in [0,1)^2 on the bounding rectangle: the mean over
/// the points inside the opening of I cos / r^2 (a ratio estimator: openings that do not fill the
/// rectangle, such as ellipses, lose no accuracy to rejected points).
double areaFormFixed(const Setup& s, const std::vector<glm::dvec2>& points) {
    glm::dvec2 lo, hi;
    bounds(*s.light, lo, hi);
    double sum = 0.0;
    int inside = 0;
    for (const auto& u : points) {
        glm::dvec2 q = lo + u * (hi - lo);
        if (!s.light->contains(q)) continue;
        sum += pointIrradiance(s, glm::dvec3(q, 0.0));
        ++inside;
    }
    return inside > 0 ? sum / inside : 0.0;
}

/// Closest point of polygon q (vectors from the receiver) to the point `target` in its plane.
spherical::ClosestPoint closestTo(const Polygon& q, const glm::dvec3& target, double tolerance) {
    Polygon shifted = q;
    for (int i = 0; i < q.count; ++i) shifted.v[size_t(i)] -= target;
    spherical::ClosestPoint cp = spherical::closestPoint(shifted, tolerance);
    cp.point += target;
    return cp;
}

double scatteredValue(const Setup& s, int* flips = nullptr) {
    Polygon full = openingFromReceiver(s);
    Polygon visible = spherical::clip(full, s.n);
    if (visible.count < 3) return 0.0;
    double projected = spherical::projectedSolidAngle(visible, s.n);  // pi times the form factor
    if (!(projected > 0.0)) return 0.0;
    // Samples on the opening clipped at the horizon tilted up by epsilon where it meets the
    // opening's plane (Sec. 5.2.4), so no corner sample lies in the horizon; falls back to the
    // true horizon if the tilted one leaves nothing.
    double eps = 0.1 * s.light->size();
    // Relative to the receiver the opening's plane is z = -p.z; the plane through the receiver
    // and the line where n.v = eps meets it has normal |p.z| n + sign(p.z) eps z, and on the
    // opening's plane (that normal).v = |p.z| (n.v - eps): it keeps what is eps above the horizon.
    double sign = s.p.z >= 0.0 ? 1.0 : -1.0;
    glm::dvec3 tilted = std::abs(s.p.z) * s.n + sign * eps * glm::dvec3(0.0, 0.0, 1.0);
    Polygon samplesPoly = spherical::clip(full, tilted);
    if (samplesPoly.count < 3) samplesPoly = visible;
    spherical::ClosestPoint cp = spherical::closestPoint(samplesPoly, 1e-6 * s.light->size());
    // Vertex 0 the closest point, 1..k the corners (Prost Sec. 5.2.2).
    glm::dvec3 dirs[spherical::kMaxPolygon + 1];
    double f[spherical::kMaxPolygon + 1], c[spherical::kMaxPolygon + 1];
    int k = samplesPoly.count;
    for (int i = 0; i <= k; ++i) {
        glm::dvec3 v = i == 0 ? cp.point : samplesPoly.v[size_t(i - 1)];
        double lv = glm::length(v);
        dirs[i] = lv > 0.0 ? v / lv : glm::dvec3(0, 0, 1);
        f[i] = solidAngleIntegrand(s, dirs[i]);
        c[i] = std::max(0.0, glm::dot(s.n, dirs[i]));
    }
    spherical::Triangulation t = spherical::initialTriangulation(k, cp);
    spherical::makeDelaunay(t, dirs);
    if (flips) *flips = t.flips;
    // Eq. (5.6) for the cosine-weighted mean of L (numerator and denominator), times the
    // projected solid angle in closed form (Eq. 5.11).
    double qf = 0.0, qc = 0.0;
    for (int i = 0; i < t.count; ++i) {
        const auto& tri = t.tri[size_t(i)];
        double area = spherical::triangleSolidAngle(dirs[tri[0]], dirs[tri[1]], dirs[tri[2]]);
        qf += area * (f[tri[0]] + f[tri[1]] + f[tri[2]]) / 3.0;
        qc += area * (c[tri[0]] + c[tri[1]] + c[tri[2]]) / 3.0;
    }
    if (!(qc > 0.0)) return 0.0;
    double e = projected * qf / qc;
    return std::isfinite(e) ? e : 0.0;
}

/// Irradiance-weighted visible fraction of the opening from the receiver, R = sum(E_i V_i) /
/// sum(E_i) over `spp` random points uniform on the opening (area form), and its standard error
/// by the delta method: sqrt(sum E_i^2 (V_i - R)^2) / sum E_i, where with V in {0, 1}
/// sum E_i^2 (V_i - R)^2 = (1 - 2R) sum(E_i^2 V_i) + R^2 sum(E_i^2).
double visibleFraction(const Setup& s, const EstimateOptions& o, double& stdError) {
    stdError = 0.0;
    if (!s.visibility || o.spp <= 0) return 1.0;
    glm::dvec2 lo, hi;
    bounds(*s.light, lo, hi);
    Random rng(o.seed ^ 0x7f4a7c159e3779b9ull);
    double sumE = 0.0, sumEV = 0.0, sumE2 = 0.0, sumE2V = 0.0;
    for (int k = 0; k < o.spp; ++k) {
        glm::dvec2 q = lo + glm::dvec2(rng.uniform(), rng.uniform()) * (hi - lo);
        if (!s.light->contains(q)) continue;
        double e = pointIrradiance(s, glm::dvec3(q, 0.0));
        if (!(e > 0.0)) continue;
        sumE += e;
        sumE2 += e * e;
        if (s.visible(glm::dvec3(q, 0.0))) {
            sumEV += e;
            sumE2V += e * e;
        }
    }
    if (!(sumE > 0.0)) return 1.0;  // no point sends light here: nothing to shadow
    double r = sumEV / sumE;
    stdError = std::sqrt(std::max(0.0, (1.0 - 2.0 * r) * sumE2V + r * r * sumE2)) / sumE;
    return r;
}

/// A deterministic technique's unshadowed irradiance (lux) for a receiver of an opening with area.
using Unshadowed = double (*)(const Setup&);

/// The deterministic techniques: a zero-area opening by its own law (each point's ray traced),
/// else the technique's value times the visible fraction (exactly the value when nothing
/// occludes, exactly 0 when every ray is blocked).
Estimate deterministic(const Luminaire& l, const glm::dvec3& p, const glm::dvec3& n,
                       const EstimateOptions& o, Unshadowed value) {
    Setup s = makeSetup(l, p, n, o.visibility);
    double e;
    if (degenerate(s, e)) return withColour(s, e);
    if (o.unshadowed) {
        // The caller's unshadowed estimate (colour times value(s)): only the shadow is left.
        const glm::dvec3& u = o.unshadowed->irradiance;
        if (!(std::max({u.x, u.y, u.z}) > 0.0) || !s.visibility) return *o.unshadowed;
        double se;
        double r = visibleFraction(s, o, se);
        Estimate out;
        out.irradiance = u * r;
        out.stdError = u * se;
        return out;
    }
    e = value(s);
    if (!(e > 0.0) || !s.visibility) return withColour(s, e);
    double se;
    double r = visibleFraction(s, o, se);
    return withColour(s, e * r, e * se);
}

double structuredValue(const Setup& s) {
    // The corners and the barycentre of the horizon-clipped opening as samples (Lagarde and de
    // Rousiers 2014): the cosine-weighted mean of L over them, times the closed-form projected
    // solid angle (Eq. 5.11), as scattered sampling normalises its cubature. (Eq. 4.3's "as if
    // uniform in solid angle", Omega times the mean of L cos, is 0.4 times the truth at contact,
    // where the corners lie at the horizon: issue 18.)
    Polygon visible = spherical::clip(openingFromReceiver(s), s.n);
    if (visible.count < 3) return 0.0;
    double projected = spherical::projectedSolidAngle(visible, s.n);
    glm::dvec3 centre(0.0);
    double sumF = 0.0, sumC = 0.0;
    auto add = [&](const glm::dvec3& v) {
        glm::dvec3 d = glm::normalize(v);
        sumF += solidAngleIntegrand(s, d);
        sumC += std::max(0.0, glm::dot(s.n, d));
    };
    for (int i = 0; i < visible.count; ++i) {
        centre += visible.v[size_t(i)];
        add(visible.v[size_t(i)]);
    }
    add(centre / double(visible.count));
    return sumC > 0.0 ? projected * sumF / sumC : 0.0;
}

/// The opening's radiance L = I / (A |cos theta_L|) along the unit direction d from the receiver
/// (0 where d is in the opening's plane).
double radianceAlong(const Setup& s, const glm::dvec3& d) {
    double cosL = std::abs(d.z);
    if (!(cosL > 1e-12) || !(s.light->area() > 0.0)) return 0.0;
    double value = s.light->scale * s.light->data->intensity(-d) / (s.light->area() * cosL);
    return std::isfinite(value) ? value : 0.0;
}

double mrpValue(const Setup& s) {
    // Drobot's most representative point (2014): the half-vector of the closest point and the
    // normal point, back on the opening's plane and clamped to the opening; one sample, Eq. (4.3).
    Polygon visible = spherical::clip(openingFromReceiver(s), s.n);
    if (visible.count < 3) return 0.0;
    double tol = 1e-9 * s.light->size();
    glm::dvec3 pc = spherical::closestPoint(visible, tol).point;
    double h = -s.p.z;  // plane of the opening: z = h relative to the receiver
    glm::dvec3 pn = pc;
    if (std::abs(s.n.z) > 1e-12) {
        double t = h / s.n.z;
        if (t > 0.0) pn = closestTo(visible, t * s.n, tol).point;
    }
    glm::dvec3 half = glm::normalize(pc) + glm::normalize(pn);
    glm::dvec3 pm = pc;
    if (std::abs(half.z) > 1e-12 && h / half.z > 0.0)
        pm = closestTo(visible, (h / half.z) * half, tol).point;
    double lm = glm::length(pm);
    if (!(lm > 0.0)) return 0.0;
    // The radiance at that point times the closed-form projected solid angle (Drobot's use of the
    // point: it stands for the light's radiance; the geometry is exact). Eq. 4.3's solid angle
    // times L cos there was twice the truth at contact and 0 with the normal in the plane.
    return spherical::projectedSolidAngle(visible, s.n) * radianceAlong(s, pm / lm);
}

/// A point of the adaptive cubature: p on the plane of its initial triangle's corners (unit
/// vectors from the receiver; the children of a triangle are the halves of its flat edges, so
/// their central projections tile it exactly, on the CPU and the GPU alike), its direction d,
/// the integrand f = L cos_p there and the cosine c = cos_p (0 below the horizon).
struct CubatureVertex {
    glm::dvec3 p, d;
    double f, c;
};

CubatureVertex cubatureVertex(const Setup& s, const glm::dvec3& p) {
    double length = glm::length(p);
    glm::dvec3 d = length > 0.0 ? p / length : glm::dvec3(0.0, 0.0, 1.0);
    return {p, d, solidAngleIntegrand(s, d), std::max(0.0, glm::dot(s.n, d))};
}

/// The solid angle of the spherical triangle of unit vectors a, b, c (Van Oosterom and Strackee:
/// spherical::triangleSolidAngle for vectors known to be unit).
double unitTriangleSolidAngle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    double num = std::abs(glm::dot(a, glm::cross(b, c)));
    double den = 1.0 + glm::dot(a, b) + glm::dot(b, c) + glm::dot(c, a);
    double omega = 2.0 * std::atan2(num, den);
    return std::isfinite(omega) ? omega : 0.0;
}

/// A triangle of the adaptive cubature: its corners and its edges' midpoints (indices into the
/// cubature's points: a, b, c, ab, bc, ca), the vertex rule on its four children (fine) and the
/// fine rule's disagreement with the triangle's own vertex rule (its error estimate).
struct CubatureTriangle {
    std::array<int, 6> v;
    double fineF = 0.0, fineC = 0.0, error = 0.0;
};

/// The four children of a triangle as indices into its six points (a, ab, ca), (ab, b, bc),
/// (ca, bc, c) and the middle one (ab, bc, ca); the GPU twin has the same table.
constexpr int kChildren[4][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}};

/// The `adaptive` technique: scattered sampling (Prost Ch. 5: the corners of the opening clipped
/// at the receiver's horizon and its closest point, triangulated on the sphere) refined where it
/// matters. Each spherical triangle carries the vertex rule of its four children
/// (split at its flat edges' midpoints: their central projections tile it exactly) and, as its
/// error, their disagreement with its own vertex rule; the triangle with the largest error is
/// split until the errors sum to kAdaptiveTolerance of the estimate or `maxSplits` splits are
/// spent. As scattered sampling, the cosine-weighted mean of L times the closed-form projected
/// solid angle (exact for a Lambertian opening at any depth). Unlike it, the samples lie on the
/// opening clipped at the true horizon: the tilted horizon of Sec. 5.2.4 keeps corners off the
/// horizon for five samples, but 0.1 opening sizes of tilt drop a band that a receiver beside the
/// opening gets most of its light from.
double adaptiveValue(const Setup& s, int maxSplits) {
    Polygon visible = spherical::clip(openingFromReceiver(s), s.n);
    if (visible.count < 3) return 0.0;
    double projected = spherical::projectedSolidAngle(visible, s.n);
    if (!(projected > 0.0)) return 0.0;
    spherical::ClosestPoint cp = spherical::closestPoint(visible, 1e-6 * s.light->size());
    std::vector<CubatureVertex> points;
    points.reserve(size_t(visible.count + 1 + 3 * (2 * spherical::kMaxPolygon + 4 * maxSplits)));
    auto point = [&](const glm::dvec3& p) {
        points.push_back(cubatureVertex(s, p));
        return int(points.size() - 1);
    };
    // Point 0 the closest point, 1..k the corners (Prost Sec. 5.2.2), as unit vectors.
    glm::dvec3 dirs[spherical::kMaxPolygon + 1];
    int k = visible.count;
    for (int i = 0; i <= k; ++i) {
        glm::dvec3 w = i == 0 ? cp.point : visible.v[size_t(i - 1)];
        double length = glm::length(w);
        dirs[i] = length > 0.0 ? w / length : glm::dvec3(0.0, 0.0, 1.0);
        point(dirs[i]);
    }
    // The fan from the closest point (Prost Fig. 5.8), not made Delaunay: the splits refine
    // whatever sliver matters, and on the GPU the flips cost more than the cubature (a 16-gon:
    // four fifths of a frame's shading on llvmpipe).
    spherical::Triangulation t = spherical::initialTriangulation(k, cp);

    std::vector<CubatureTriangle> triangles;
    triangles.reserve(size_t(t.count + 3 * maxSplits));
    // The triangles' indices, a heap on their errors: the worst is split first.
    std::vector<std::pair<double, int>> heap;
    double sumF = 0.0, sumError = 0.0;
    auto add = [&](int a, int b, int c) {
        CubatureTriangle tri;
        tri.v = {a,
                 b,
                 c,
                 point(0.5 * (points[size_t(a)].p + points[size_t(b)].p)),
                 point(0.5 * (points[size_t(b)].p + points[size_t(c)].p)),
                 point(0.5 * (points[size_t(c)].p + points[size_t(a)].p))};
        // The children tile the triangle: their areas sum to its own.
        double area = 0.0, coarseF = 0.0;
        for (const auto& child : kChildren) {
            const CubatureVertex& x = points[size_t(tri.v[size_t(child[0])])];
            const CubatureVertex& y = points[size_t(tri.v[size_t(child[1])])];
            const CubatureVertex& z = points[size_t(tri.v[size_t(child[2])])];
            double childArea = unitTriangleSolidAngle(x.d, y.d, z.d);
            area += childArea;
            tri.fineF += childArea * (x.f + y.f + z.f) / 3.0;
            tri.fineC += childArea * (x.c + y.c + z.c) / 3.0;
        }
        coarseF = area * (points[size_t(a)].f + points[size_t(b)].f + points[size_t(c)].f) / 3.0;
        tri.error = std::abs(tri.fineF - coarseF);
        sumF += tri.fineF;
        sumError += tri.error;
        heap.emplace_back(tri.error, int(triangles.size()));
        std::push_heap(heap.begin(), heap.end());
        triangles.push_back(tri);
    };
    for (int i = 0; i < t.count; ++i) {
        const auto& tri = t.tri[size_t(i)];
        add(tri[0], tri[1], tri[2]);
    }
    std::vector<bool> split(triangles.size(), false);
    for (int n = 0; n < maxSplits && sumError > gpu::kAdaptiveTolerance * sumF; ++n) {
        std::pop_heap(heap.begin(), heap.end());
        int worst = heap.back().second;
        heap.pop_back();
        CubatureTriangle parent = triangles[size_t(worst)];
        sumF -= parent.fineF;
        sumError -= parent.error;
        split.resize(triangles.size() + 4, false);
        split[size_t(worst)] = true;
        for (const auto& child : kChildren)
            add(parent.v[size_t(child[0])], parent.v[size_t(child[1])], parent.v[size_t(child[2])]);
    }
    // The sums again over the leaves, not the running ones (which carry the rounding of every
    // subtraction).
    double qf = 0.0, qc = 0.0;
    for (size_t i = 0; i < triangles.size(); ++i) {
        if (i < split.size() && split[i]) continue;
        qf += triangles[i].fineF;
        qc += triangles[i].fineC;
    }
    if (!(qc > 0.0)) return 0.0;
    double e = projected * qf / qc;
    return std::isfinite(e) ? e : 0.0;
}

double adaptiveOnCpu(const Setup& s) {
    return adaptiveValue(s, gpu::kAdaptiveCpuSplits);
}

double scatteredOnly(const Setup& s) {
    return scatteredValue(s);
}
double poisson24Value(const Setup& s) {
    return areaFormFixed(s, poissonSet(24));
}
double poisson40Value(const Setup& s) {
    return areaFormFixed(s, poissonSet(40));
}

double hybridValue(const Setup& s) {
    // Scattered sampling near the opening, where a fixed point set shows light bumps, the
    // 24-point Poisson set from 1.5 opening sizes on, a smooth blend between (Prost Sec. 6.6;
    // the distances are where `candela bench --prost` shows the bumps fade).
    double distance = glm::length(spherical::closestPoint(openingFromReceiver(s), 0.0).point);
    double w = gpu::hybridWeight(distance, s.light->size());
    double near = w < 1.0 ? scatteredValue(s) : 0.0;
    double far = w > 0.0 ? areaFormFixed(s, poissonSet(24)) : 0.0;
    return (1.0 - w) * near + w * far;
}

}  // namespace

const std::vector<glm::dvec2>& poissonSet(int n) {
    static std::mutex mutex;
    static std::map<int, std::vector<glm::dvec2>> sets;  // node-based: references stay valid
    std::lock_guard<std::mutex> lock(mutex);
    if (auto it = sets.find(n); it != sets.end()) return it->second;
    // Dart throwing with a shrinking radius: start at the radius of a hexagonal packing of n
    // disks in the unit square and shrink 5 % after every 1000 rejected darts.
    std::vector<glm::dvec2> points;
    Random rng(0x5eed0000ull + uint64_t(n));
    double r = std::sqrt(2.0 / (std::sqrt(3.0) * n));
    int misses = 0;
    while (int(points.size()) < n) {
        glm::dvec2 q(rng.uniform(), rng.uniform());
        bool ok = true;
        for (const auto& o : points) ok = ok && glm::length(q - o) >= r;
        if (ok) {
            points.push_back(q);
            misses = 0;
        } else if (++misses > 1000) {
            r *= 0.95;
            misses = 0;
        }
    }
    return sets.emplace(n, std::move(points)).first->second;
}

Estimate photometricPoint(const Luminaire& l, const glm::dvec3& p, const glm::dvec3& n,
                          const EstimateOptions& o) {
    // A point light: its shadow is the centre's.
    Setup s = makeSetup(l, p, n, o.visibility);
    double e = pointIrradiance(s, glm::dvec3(0.0));
    return withColour(s, e > 0.0 && s.visible(glm::dvec3(0.0)) ? e : 0.0);
}

namespace {

/// The reference's three strategies combined by the balance heuristic (Veach 1997), one chosen
/// per sample: a point uniform on the opening's bounding rectangle (the area form, Eq. 6.3: good
/// far away, finite in the opening's plane); a direction cosine-distributed about the receiver's
/// normal (good near and at contact, where the opening fills the hemisphere and area samples
/// almost never land near the receiver's foot: they gave 1e-13 of the truth 1e-9 m away); and a
/// direction drawn in proportion to the table's intensity (IntensitySampler: a 1e9 cd spike 0.5
/// degrees wide covers a thousandth of the opening seen from 1 m, so the other two missed it at a
/// few hundred samples and reported a tenth of a percent of the truth with a small error bar).
/// The intensity strategy takes a quarter of the samples (wasted far away, where few of its
/// directions meet the opening: at most 4/3 of the variance); cosine directions take the
/// opening's form factor from the receiver, clamped to [0.05, 0.5], of the rest. With
/// visibility, a shadow ray per sample.
struct ReferenceMixture {
    const Setup& s;
    glm::dvec2 lo, hi;
    double rect;
    std::shared_ptr<const IntensitySampler> table;
    double cTable, cCosine, cArea;
    glm::dvec3 t, bt;  ///< A frame about the receiver's normal (Duff et al. 2017).

    explicit ReferenceMixture(const Setup& setup) : s(setup) {
        bounds(*s.light, lo, hi);
        rect = (hi.x - lo.x) * (hi.y - lo.y);
        Polygon visible = spherical::clip(openingFromReceiver(s), s.n);
        table = IntensitySampler::of(s.light->data);
        cTable = table && table->valid() ? 0.25 : 0.0;
        double formFactor =
            visible.count >= 3 ? spherical::projectedSolidAngle(visible, s.n) / kPi : 0.0;
        cCosine = (1.0 - cTable) * std::clamp(formFactor, 0.05, 0.5);
        cArea = 1.0 - cTable - cCosine;
        double sign = std::copysign(1.0, s.n.z), a = -1.0 / (sign + s.n.z), b = s.n.x * s.n.y * a;
        t = glm::dvec3(1.0 + sign * s.n.x * s.n.x * a, sign * b, -sign * s.n.x);
        bt = glm::dvec3(b, sign + s.n.y * s.n.y * a, -s.n.y);
    }

    /// f / (sum of c_i pdf_i) for the direction d toward opening point q at distance r, with
    /// f = L cos_p = I cos_p / (A cos_L), pdf_area = r^2 / (rect cos_L), pdf_cosine = cos_p / pi
    /// and pdf_table(-d): multiplied through by cos_L so that it stays finite in the opening's
    /// plane (where L is infinite and the area form is not).
    double term(const glm::dvec3& q, const glm::dvec3& d, double r) const {
        if (!s.light->contains(glm::dvec2(q))) return 0.0;
        double cosP = glm::dot(s.n, d), cosL = std::abs(d.z);
        if (!(cosP > 0.0) || !s.visible(q)) return 0.0;
        double intensity = s.light->scale * s.light->data->intensity(-d);
        double pdfTable = cTable > 0.0 ? table->pdf(-d) : 0.0;
        double v = intensity * cosP / s.light->area() /
                   (cArea * r * r / rect + cCosine * cosL * cosP / kPi + cTable * cosL * pdfTable);
        return std::isfinite(v) && v > 0.0 ? v : 0.0;
    }

    /// A direction d from the receiver, followed to the opening's plane.
    double along(const glm::dvec3& d) const {
        if (!(std::abs(d.z) > 0.0)) return 0.0;
        double tHit = -s.p.z / d.z;
        glm::dvec3 hit = s.p + tHit * d;
        if (!(tHit > 0.0) || hit.x < lo.x || hit.x > hi.x || hit.y < lo.y || hit.y > hi.y)
            return 0.0;
        return term(glm::dvec3(hit.x, hit.y, 0.0), d, tHit);
    }

    /// One sample: the strategy picked by `pick` in [0, 1), its point or direction by (u1, u2).
    double sample(double pick, double u1, double u2) const {
        if (pick < cArea) {
            // A point on the bounding rectangle (outside the opening it counts 0).
            glm::dvec3 q(lo + glm::dvec2(u1, u2) * (hi - lo), 0.0);
            glm::dvec3 v = q - s.p;
            double r = glm::length(v);
            return r > 0.0 ? term(q, v / r, r) : 0.0;
        }
        if (pick < cArea + cCosine) {
            double rad = std::sqrt(u1), phi = 2.0 * kPi * u2;
            return along(rad * std::cos(phi) * t + rad * std::sin(phi) * bt +
                         std::sqrt(std::max(0.0, 1.0 - u1)) * s.n);
        }
        // The table's direction w leaves the opening toward the receiver: look along -w.
        double cell = (pick - cArea - cCosine) / cTable;
        return along(-table->sample(std::min(cell, 1.0 - 1e-16), glm::dvec2(u1, u2)));
    }
};

}  // namespace

Estimate photometricReference(const Luminaire& l, const glm::dvec3& p, const glm::dvec3& n,
                              const EstimateOptions& options) {
    Setup s = makeSetup(l, p, n, options.visibility);
    double e;
    if (degenerate(s, e)) return withColour(s, e);
    if (options.spp <= 0 || !(s.light->area() > 0.0)) return withColour(s, 0.0);
    ReferenceMixture mixture(s);
    Random rng(options.seed);
    double mean = 0.0, m2 = 0.0;
    for (int k = 0; k < options.spp; ++k) {
        // The strategy is picked stratified over the samples (sample k's pick is uniform in
        // [k, k + 1) / spp): every strategy gets its share of the samples instead of a binomial
        // count of them, which far from the opening (where cosine and table samples almost all
        // miss) cut the variance by a factor of about three. The average of the strata is the
        // uniform pick, so the estimate stays unbiased; the sample variance below ignores the
        // strata and so overstates the error (a conservative error bar).
        double pick = (k + rng.uniform()) / options.spp, u1 = rng.uniform(), u2 = rng.uniform();
        double value = mixture.sample(pick, u1, u2);
        double delta = value - mean;
        mean += delta / double(k + 1);
        m2 += delta * (value - mean);
    }
    double variance = options.spp > 1 ? std::max(0.0, m2) / double(options.spp - 1) : 0.0;
    return withColour(s, mean, std::sqrt(variance / double(options.spp)));
}

Estimate photometricPoisson24(const Luminaire& l, const glm::dvec3& p, const glm::dvec3& n,
                              const EstimateOptions& o) {
    return deterministic(l, p, n, o, &poisson24Value);
}

Estimate photometricPoisson40(const Luminaire& l, const glm::dvec3& p, const glm::dvec3& n,
                              const EstimateOptions& o) {
    return deterministic(l, p, n, o, &poisson40Value);
}

Estimate photometricStructured(const Luminaire& l, const glm::dvec3& p, const glm::dvec3& n,
                               const EstimateOptions& o) {
    return deterministic(l, p, n, o, &structuredValue);
}

Estimate photometricMrp(const Luminaire& l, const glm::dvec3& p, const glm::dvec3& n,
                        const EstimateOptions& o) {
    return deterministic(l, p, n, o, &mrpValue);
}

Estimate photometricScattered(const Luminaire& l, const glm::dvec3& p, const glm::dvec3& n,
                              const EstimateOptions& o) {
    return deterministic(l, p, n, o, &scatteredOnly);
}

Estimate photometricHybrid(const Luminaire& l, const glm::dvec3& p, const glm::dvec3& n,
                           const EstimateOptions& o) {
    return deterministic(l, p, n, o, &hybridValue);
}

Estimate photometricAdaptive(const Luminaire& l, const glm::dvec3& p, const glm::dvec3& n,
                             const EstimateOptions& o) {
    return deterministic(l, p, n, o, &adaptiveOnCpu);
}

}  // namespace candela
