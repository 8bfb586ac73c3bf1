// CPU estimators of a light-field luminaire's irradiance (double precision): the quadrature
// reference, the restricted-CDF sampler of Lu et al. 2015 and its two baselines. They serve
// `candela probe`, the tests and the benches; the GPU passes implement the same estimators.
#include <algorithm>
#include <cmath>
#include <vector>

#include "luminaires/Random.h"
#include "luminaires/lightfield/LightField.h"

namespace candela {

namespace {

struct Setup {
    const LightFieldLuminaire* light = nullptr;
    Pose pose;
    const LightFieldData* lf = nullptr;
    glm::dvec3 q{0.0};      ///< Receiver in the luminaire's frame, metres.
    glm::dvec3 n{0.0};      ///< Unit receiver normal in the luminaire's frame.
    double dz = 0.0;        ///< Delta(p): distance from S, metres.
    glm::dvec3 x, y, z;     ///< The luminaire's frame.
    glm::dvec3 world{0.0};  ///< The receiver in world space.
};

/// False when p cannot receive light (behind S or between U and S): the estimate is exactly 0.
bool setup(const Luminaire& l, const glm::dvec3& p, const glm::dvec3& n, Setup& s) {
    s.light = lightFieldModel(l);
    s.pose = l.pose;
    s.lf = s.light->data.get();
    s.q = s.pose.toLocal(p);
    s.world = p;
    s.pose.frame(s.x, s.y, s.z);
    double len = glm::length(n);
    if (!(len > 0.0)) return false;
    glm::dvec3 un = n / len;
    s.n = {glm::dot(un, s.x), glm::dot(un, s.y), glm::dot(un, s.z)};
    s.dz = s.q.z - s.lf->delta;
    // Within ~1e-9 of the distance to U of S (either side: the world position of a receiver on S
    // carries that much rounding), the restricted boxes are below the rounding of the
    // coordinates: treat p as on S (Eq. 9), which the irradiance tends to continuously.
    if (std::abs(s.dz) < 1e-9 * s.q.z) s.dz = 0.0;
    return s.dz >= 0.0 && std::isfinite(s.dz);
}

glm::dvec3 worldOf(const Setup& s, glm::dvec2 sl) {
    return s.pose.position + sl.x * s.x + sl.y * s.y + s.lf->delta * s.z;
}

/// Halton radical inverse in base b.
double radicalInverse(uint32_t i, uint32_t b) {
    double inv = 1.0 / double(b), f = inv, r = 0.0;
    while (i > 0) {
        r += f * double(i % b);
        i /= b;
        f *= inv;
    }
    return r;
}

/// The k-th point of the 2D Halton sequence (bases 2, 3) shared by all receivers (Sec. 6.3),
/// rotated by a per-estimate random offset (Cranley-Patterson) so that each estimate is unbiased.
glm::dvec2 halton(uint32_t k, glm::dvec2 shift) {
    glm::dvec2 h(radicalInverse(k + 1, 2), radicalInverse(k + 1, 3));
    return glm::fract(h + shift);
}

/// Running mean and variance of the per-sample terms (Welford).
struct Accumulator {
    glm::dvec3 mean{0.0}, m2{0.0};
    int count = 0;
    void add(const glm::dvec3& v) {
        ++count;
        glm::dvec3 d = v - mean;
        mean += d / double(count);
        m2 += d * (v - mean);
    }
    Estimate estimate(double scale) const {
        Estimate e;
        e.irradiance = mean * scale;
        if (count > 1)
            e.stdError = glm::sqrt(glm::max(m2, 0.0) / double(count - 1) / double(count)) * scale;
        return e;
    }
};

/// Eq. (9): p on S. I_m = delta C_m(p) int_U Psi_m cos_r / |u - p|^3 du, with u uniform over
/// each support and the sample budget split over images in proportion to C_m(p) hx hy.
Estimate onPlaneS(const Setup& s, const EstimateOptions& o) {
    const LightFieldData& lf = *s.lf;
    glm::dvec2 p(s.q.x, s.q.y);
    std::vector<double> cdf(size_t(lf.imageCount()) + 1, 0.0);
    for (int m = 0; m < lf.imageCount(); ++m) cdf[size_t(m) + 1] = cdf[size_t(m)] + lf.lum(m, p);
    double total = cdf.back();
    Estimate e;
    if (!(total > 0.0) || o.spp <= 0) return e;
    Random rng(o.seed);
    double offset = rng.uniform();
    glm::dvec2 shift(rng.uniform(), rng.uniform());
    double area = 9.0 * lf.spacing.x * lf.spacing.y;  // support of each Phi_m
    Accumulator acc;
    for (int k = 0; k < o.spp; ++k) {
        double target = (double(k) + offset) / double(o.spp) * total;
        int m = int(std::upper_bound(cdf.begin() + 1, cdf.end(), target) - cdf.begin()) - 1;
        m = std::clamp(m, 0, lf.imageCount() - 1);
        glm::dvec2 uMin, uMax;
        lf.support(m, uMin, uMax);
        glm::dvec2 u = uMin + halton(uint32_t(k), shift) * (uMax - uMin);
        glm::dvec3 d(u.x - s.q.x, u.y - s.q.y, -s.q.z);
        double r = glm::length(d);
        double cosR = std::max(0.0, glm::dot(s.n, d / r));
        glm::dvec3 term(0.0);
        if (cosR > 0.0) {
            glm::dvec3 uWorld = s.pose.position + u.x * s.x + u.y * s.y;
            bool visible = !o.visibility || o.visibility->visible(s.world, uWorld);
            // f / pdf with pdf = (C_m / total) / area: total * area * Psi * c * delta cos / r^3.
            if (visible) term = lf.psi(m, u, p) * lf.colour(m, p) * (lf.delta * cosR / (r * r * r));
        }
        acc.add(term);
    }
    return acc.estimate(total * area);
}

enum class Strategy { Restricted, Uniform, Global };

/// Where each image m may be sampled for one receiver (its restricted box, or the whole image for
/// the global CDF), the energy A_m there, and the CDF over images.
struct ImageBoxes {
    std::vector<glm::dvec2> lo, hi;
    std::vector<double> weight, cdf;
    double total() const { return cdf.back(); }  ///< A(p) (Eq. 12), or all the energy (global)
};

ImageBoxes imageBoxes(const LightFieldData& lf, const glm::dvec3& q, Strategy strategy) {
    size_t count = size_t(lf.imageCount());
    ImageBoxes b{std::vector<glm::dvec2>(count), std::vector<glm::dvec2>(count),
                 std::vector<double>(count, 0.0), std::vector<double>(count + 1, 0.0)};
    for (size_t m = 0; m < count; ++m) {
        if (strategy == Strategy::Global) {
            b.lo[m] = lf.imageMin;
            b.hi[m] = lf.imageMax;
            b.weight[m] = lf.tables[m].total;
        } else if (lf.restrictedBox(int(m), q, b.lo[m], b.hi[m])) {
            // Eq. (10): A_m(p), the energy of C_m in the restricted box.
            b.weight[m] = lf.boxIntegral(int(m), b.lo[m], b.hi[m]);
        }
        b.cdf[m + 1] = b.cdf[m] + b.weight[m];
    }
    return b;
}

/// One sample's contribution f / pdf from image m at the unit square point xi (0 where the
/// sample carries no light).
glm::dvec3 sampleTerm(const Setup& s, const glm::dvec3& p, const EstimateOptions& o,
                      const ImageBoxes& b, int m, glm::dvec2 xi, Strategy strategy) {
    const LightFieldData& lf = *s.lf;
    size_t i = size_t(m);
    glm::dvec2 sPos;
    double inversePdf = 0.0;  // 1 / pdf of (m, s) over S, in C's unit times m2
    if (strategy == Strategy::Uniform) {
        sPos = b.lo[i] + xi * (b.hi[i] - b.lo[i]);
        glm::dvec2 size = b.hi[i] - b.lo[i];
        if (lf.lum(m, sPos) > 0.0) inversePdf = b.total() / b.weight[i] * size.x * size.y;
    } else {
        if (!lf.sampleBox(m, b.lo[i], b.hi[i], xi, sPos)) return glm::dvec3(0.0);
        double c = lf.lum(m, sPos);
        if (c > 0.0) inversePdf = b.total() / c;  // pdf = C_m(s) / A (Eq. 10 times A_m / A)
    }
    if (!(inversePdf > 0.0)) return glm::dvec3(0.0);
    glm::dvec3 d(sPos.x - s.q.x, sPos.y - s.q.y, -s.dz);
    double r = glm::length(d);
    double cosR = std::max(0.0, glm::dot(s.n, d / r));
    // u: where the line from q through s meets U.
    glm::dvec2 pq(s.q.x, s.q.y);
    glm::dvec2 u = pq + (sPos - pq) * (s.q.z / s.dz);
    double psi = lf.psi(m, u, sPos);
    if (!(cosR > 0.0 && psi > 0.0)) return glm::dvec3(0.0);
    if (o.visibility && !o.visibility->visible(p, worldOf(s, sPos))) return glm::dvec3(0.0);
    // Eq. (14): C_m Psi_m c_m cos_r Delta / r^3 divided by the pdf.
    double c = lf.lum(m, sPos);
    return c * psi * lf.colour(m, sPos) * (cosR * s.dz / (r * r * r)) * inversePdf;
}

Estimate sampled(const Luminaire& l, const glm::dvec3& p, const glm::dvec3& n,
                 const EstimateOptions& o, Strategy strategy) {
    Setup s;
    Estimate e;
    if (!setup(l, p, n, s) || o.spp <= 0) return e;
    if (s.dz == 0.0) return onPlaneS(s, o);
    const LightFieldData& lf = *s.lf;
    int count = lf.imageCount();
    ImageBoxes boxes = imageBoxes(lf, s.q, strategy);
    double total = boxes.total();
    if (!(total > 0.0)) return e;  // every A_m(p) = 0: no sample, exactly 0

    Random rng(o.seed);
    double offset = rng.uniform();
    glm::dvec2 shift(rng.uniform(), rng.uniform());
    Accumulator acc;
    int hits = 0;  // samples that carried light
    for (int k = 0; k < o.spp; ++k) {
        // Eq. (12) balancing made exactly unbiased: K slots spread over the images in proportion
        // to A_m with one random offset (systematic sampling), so image m gets the nearest
        // integers below or above K A_m / A, and every slot has the marginal density A_m / A.
        double target = (double(k) + offset) / double(o.spp) * total;
        int m = int(std::upper_bound(boxes.cdf.begin() + 1, boxes.cdf.end(), target) -
                    boxes.cdf.begin()) -
                1;
        m = std::clamp(m, 0, count - 1);
        while (m > 0 && !(boxes.weight[size_t(m)] > 0.0)) --m;
        glm::dvec3 term = sampleTerm(s, p, o, boxes, m, halton(uint32_t(k), shift), strategy);
        hits += term != glm::dvec3(0.0);
        acc.add(term);
    }
    e = acc.estimate(1.0);
    // The global CDF ignores where the receiver can see each image, so close to S almost none of
    // its samples land (1 m beyond S of a 5 cm luminaire: a few in 4096), and its sample variance
    // knows nothing of the light it missed (it reported 0 +- 0, or a tenth of the truth +- a
    // twentieth). Where fewer than 16 samples carried light, the error bar also takes the
    // distance to a restricted-CDF pilot estimate (unbiased, 256 samples), so it covers the miss.
    if (strategy == Strategy::Global && hits < 16) {
        EstimateOptions pilotOptions = o;
        pilotOptions.spp = 256;
        pilotOptions.seed = o.seed * 0x9E3779B97F4A7C15ull + 1;
        Estimate pilot = sampled(l, p, n, pilotOptions, Strategy::Restricted);
        glm::dvec3 miss = glm::abs(pilot.irradiance - e.irradiance);
        e.stdError =
            glm::sqrt(e.stdError * e.stdError + miss * miss + pilot.stdError * pilot.stdError);
    }
    return e;
}

// --- Reference: Gauss-Legendre over U ------------------------------------------------------

constexpr double kGx[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
constexpr double kGw[3] = {0.5555555555555556, 0.8888888888888888, 0.5555555555555556};

/// Breakpoints of [a, b]: the ends, the given knots and pixel edges mapped to U, sorted.
std::vector<double> breaks(double a, double b, std::vector<double> extra) {
    std::vector<double> out{a, b};
    for (double v : extra)
        if (v > a && v < b) out.push_back(v);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

struct RefContext {
    const Setup* s;
    int m;
    const EstimateOptions* o;
    glm::dvec2 p;  ///< q.xy
    double f;      ///< delta / q.z: s(u) = u (1 - f) + p f
};

/// The integrand at u; `shadowed` tells whether a shadow ray removed it (for refCell's
/// refinement along shadow edges).
glm::dvec3 refIntegrand(const RefContext& c, glm::dvec2 u, bool& shadowed) {
    shadowed = false;
    const Setup& s = *c.s;
    const LightFieldData& lf = *s.lf;
    glm::dvec2 sPos = u * (1.0 - c.f) + c.p * c.f;
    double lum = lf.lum(c.m, sPos);
    if (!(lum > 0.0)) return glm::dvec3(0.0);
    glm::dvec3 d(u.x - s.q.x, u.y - s.q.y, -s.q.z);
    double r2 = glm::dot(d, d), r = std::sqrt(r2);
    double cosR = glm::dot(s.n, d) / r;
    if (!(cosR > 0.0)) return glm::dvec3(0.0);
    if (c.o->visibility && !c.o->visibility->visible(s.world, worldOf(s, sPos))) {
        shadowed = true;
        return glm::dvec3(0.0);
    }
    // E = q.z int_U L cos_r / |u - q|^3 du: the solid angle of du seen from q is q.z du / r^3.
    return lum * lf.psi(c.m, u, sPos) * lf.colour(c.m, sPos) * (cosR * s.q.z / (r2 * r));
}

/// Deepest refinement along shadow edges: cells 2^-12 of a basis support across, so an edge's
/// cells hold ~1e-3 of the support's energy in all (the edge's length over the cell width).
constexpr int kShadowDepth = 12;

glm::dvec3 refCell(const RefContext& c, glm::dvec2 lo, glm::dvec2 hi, int depth) {
    const Setup& s = *c.s;
    glm::dvec2 size = hi - lo;
    // Refine where the kernel (width q.z) is narrow against the cell, and where the receiver's
    // horizon n . (u - q) = 0 crosses the cell (the integrand has a kink there).
    glm::dvec2 nearest = glm::clamp(c.p, lo, hi);
    double dist = glm::length(nearest - c.p);
    bool narrow = std::max(size.x, size.y) > 0.5 * (dist + s.q.z);
    auto side = [&](double ux, double uy) {
        return glm::dot(s.n, glm::dvec3(ux - s.q.x, uy - s.q.y, -s.q.z));
    };
    double h00 = side(lo.x, lo.y), h10 = side(hi.x, lo.y), h01 = side(lo.x, hi.y),
           h11 = side(hi.x, hi.y);
    bool kink = std::min({h00, h10, h01, h11}) < 0.0 && std::max({h00, h10, h01, h11}) > 0.0;
    if (std::max({h00, h10, h01, h11}) <= 0.0) return glm::dvec3(0.0);  // wholly below the horizon
    if ((narrow && depth < 10) || (kink && depth < 7)) {
        glm::dvec2 mid = 0.5 * (lo + hi);
        return refCell(c, lo, mid, depth + 1) +
               refCell(c, {mid.x, lo.y}, {hi.x, mid.y}, depth + 1) +
               refCell(c, {lo.x, mid.y}, {mid.x, hi.y}, depth + 1) + refCell(c, mid, hi, depth + 1);
    }
    glm::dvec3 sum(0.0);
    int shadowedPoints = 0, litPoints = 0;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            glm::dvec2 u = lo + 0.5 * (glm::dvec2(kGx[i], kGx[j]) + 1.0) * size;
            bool shadowed = false;
            glm::dvec3 value = refIntegrand(c, u, shadowed);
            sum += kGw[i] * kGw[j] * value;
            shadowedPoints += shadowed;
            litPoints += value != glm::dvec3(0.0);
        }
    // The Gauss points lie inside the cell (the outer ones 11 % of its width from its edges): a
    // shadow edge there would go unseen. The corners and edge midpoints tell too.
    if (c.o->visibility && depth < kShadowDepth && (shadowedPoints == 0 || litPoints == 0))
        for (double fy : {0.0, 0.5, 1.0})
            for (double fx : {0.0, 0.5, 1.0}) {
                if (fx == 0.5 && fy == 0.5) continue;
                bool shadowed = false;
                glm::dvec3 value = refIntegrand(c, lo + glm::dvec2(fx, fy) * size, shadowed);
                shadowedPoints += shadowed;
                litPoints += value != glm::dvec3(0.0);
            }
    // A shadow edge crosses the cell (some points lit, some shadowed): the integrand jumps there,
    // so halve the cell until the edge's cells are 2^-kShadowDepth of the support.
    if (shadowedPoints > 0 && litPoints > 0 && depth < kShadowDepth) {
        glm::dvec2 mid = 0.5 * (lo + hi);
        return refCell(c, lo, mid, depth + 1) +
               refCell(c, {mid.x, lo.y}, {hi.x, mid.y}, depth + 1) +
               refCell(c, {lo.x, mid.y}, {mid.x, hi.y}, depth + 1) + refCell(c, mid, hi, depth + 1);
    }
    return sum * (0.25 * size.x * size.y);
}

}  // namespace

Estimate lightFieldReference(const Luminaire& l, const glm::dvec3& p, const glm::dvec3& n,
                             const EstimateOptions& o) {
    Setup s;
    Estimate e;
    if (!setup(l, p, n, s)) return e;
    const LightFieldData& lf = *s.lf;
    RefContext c{&s, 0, &o, {s.q.x, s.q.y}, s.dz == 0.0 ? 1.0 : lf.delta / s.q.z};
    double g = 1.0 - c.f;  // ds/du = Delta / q.z
    glm::dvec2 px = lf.pixelSize();
    for (int m = 0; m < lf.imageCount(); ++m) {
        glm::dvec2 uMin, uMax;
        lf.support(m, uMin, uMax);
        if (g > 0.0) {
            // Only u whose ray meets S inside the image.
            uMin = glm::max(uMin, (lf.imageMin - c.p * c.f) / g);
            uMax = glm::min(uMax, (lf.imageMax - c.p * c.f) / g);
        } else if (lf.lum(m, c.p) <= 0.0) {
            continue;  // p on S: C_m(p) is constant over U
        }
        if (!(uMax.x > uMin.x && uMax.y > uMin.y)) continue;
        glm::dvec2 node = lf.node(m);
        std::vector<double> kx, ky;
        for (double k : {-1.5, -0.5, 0.5, 1.5}) {
            kx.push_back(node.x + k * lf.spacing.x);
            ky.push_back(node.y + k * lf.spacing.y);
        }
        if (g > 0.0) {
            // Pixel edges i px + imageMin, mapped back to U.
            auto edges = [&](double a, double b, double o0, double step, double pc,
                             std::vector<double>& out) {
                double sa = a * g + pc * c.f, sb = b * g + pc * c.f;
                for (int i = int(std::ceil((sa - o0) / step)); o0 + i * step < sb; ++i)
                    out.push_back((o0 + i * step - pc * c.f) / g);
            };
            edges(uMin.x, uMax.x, lf.imageMin.x, px.x, c.p.x, kx);
            edges(uMin.y, uMax.y, lf.imageMin.y, px.y, c.p.y, ky);
        }
        std::vector<double> bx = breaks(uMin.x, uMax.x, kx), by = breaks(uMin.y, uMax.y, ky);
        c.m = m;
        for (size_t j = 0; j + 1 < by.size(); ++j)
            for (size_t i = 0; i + 1 < bx.size(); ++i)
                e.irradiance += refCell(c, {bx[i], by[j]}, {bx[i + 1], by[j + 1]}, 0);
    }
    return e;
}

Estimate lightFieldGranier2003(const Luminaire& l, const glm::dvec3& p, const glm::dvec3& n,
                               const EstimateOptions& o) {
    Setup s;
    Estimate e;
    if (!setup(l, p, n, s)) return e;
    // On S the footprints shrink to the receiver's pixel: the limit from beyond S.
    if (s.dz == 0.0) {
        s.dz = 1e-9 * s.q.z;
        s.q.z += s.dz;
    }
    const LightFieldData& lf = *s.lf;
    const GranierTable& farField = lf.granierTable();
    double phiIntegral = lf.spacing.x * lf.spacing.y;  // A = int Phi_m du (Eq. 14)
    for (int m = 0; m < lf.imageCount(); ++m) {
        glm::dvec2 a, b;
        if (!lf.restrictedBox(m, s.q, a, b)) continue;
        // E'_m averaged over the support's whole footprint on S (3h scaled by Delta / q.z per
        // axis; C_m is 0 where it leaves the image), from the box integral.
        double footprint = 9.0 * lf.spacing.x * lf.spacing.y * (s.dz / s.q.z) * (s.dz / s.q.z);
        double mean = lf.boxIntegral(m, a, b) / footprint;
        if (!(mean > 0.0)) continue;
        // f_m (Eq. 13): cos(theta) cos(theta') / d^2 at the support's centre, the node.
        glm::dvec2 node = lf.node(m);
        glm::dvec3 d(node.x - s.q.x, node.y - s.q.y, -s.q.z);
        double dist = glm::length(d);
        double cosR = glm::dot(s.n, d / dist), cosL = s.q.z / dist;
        if (!(cosR > 0.0)) continue;
        glm::dvec2 centre = 0.5 * (a + b);
        // The goesele model's factor at the node (1 for canned): Psi / Phi there.
        double model = lf.psi(m, node, centre) / std::max(lf.basis(m, node), 1e-300);
        // The spot light's shadow ray ends where its ray to the receiver leaves the luminaire,
        // on S (what lies between U and S is the measured luminaire itself, docs/visibility.md).
        if (o.visibility) {
            glm::dvec3 onS = glm::dvec3(s.q.x, s.q.y, s.q.z) + (lf.delta - s.q.z) / (-s.q.z) * d;
            if (!o.visibility->visible(p, worldOf(s, glm::dvec2(onS.x, onS.y)))) continue;
        }
        // The far-field correction (GranierTable): W_m / U_m for the support centred where this
        // direction's box is far away, blended in with the footprint's area, (1 - delta /
        // q.z)^2: nothing on S (Granier's own limit there), all of it far away.
        glm::dvec2 farCentre = node + (glm::dvec2(s.q.x, s.q.y) - node) * (lf.delta / s.q.z);
        glm::dvec2 half = 1.5 * lf.spacing;
        double uniform = lf.boxIntegral(m, farCentre - half, farCentre + half) / 9.0;
        double blend = (1.0 - lf.delta / s.q.z) * (1.0 - lf.delta / s.q.z);
        double conserve =
            uniform > 0.0 ? (1.0 - blend) + blend * farField.at(m, farCentre) / uniform : 1.0;
        e.irradiance += conserve * phiIntegral * mean * model * lf.colour(m, centre) *
                        (cosR * cosL / (dist * dist));
    }
    return e;
}

Estimate lightFieldRestrictedCdf(const Luminaire& l, const glm::dvec3& p, const glm::dvec3& n,
                                 const EstimateOptions& o) {
    return sampled(l, p, n, o, Strategy::Restricted);
}

Estimate lightFieldUniformRestricted(const Luminaire& l, const glm::dvec3& p, const glm::dvec3& n,
                                     const EstimateOptions& o) {
    return sampled(l, p, n, o, Strategy::Uniform);
}

Estimate lightFieldPrecomputedGlobal(const Luminaire& l, const glm::dvec3& p, const glm::dvec3& n,
                                     const EstimateOptions& o) {
    return sampled(l, p, n, o, Strategy::Global);
}

}  // namespace candela
