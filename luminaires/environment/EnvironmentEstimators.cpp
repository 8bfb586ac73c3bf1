// CPU irradiance estimators of environment maps (used by `candela probe` and the tests).
#include <algorithm>
#include <cmath>

#include "luminaires/Random.h"
#include "luminaires/environment/EnvironmentSampling.h"
#include "shaders/shared/Constants.h"

namespace candela {

namespace {

using gpu::kPi;

bool unitNormal(const glm::dvec3& n, glm::dvec3& out) {
    double len = glm::length(n);
    if (!(len > 0.0) || !std::isfinite(len)) return false;
    out = n / len;
    return true;
}

bool visibleAlong(const EstimateOptions& o, const glm::dvec3& p, const glm::dvec3& w) {
    return !o.visibility || o.visibility->visibleToward(p, w);
}

/// Gauss-Legendre nodes and weights on [0, 1] (8 points, tabulated to 16 digits).
constexpr int kGauss = 8;
constexpr double kGaussX[kGauss] = {0.0198550717512319, 0.1016667612931866, 0.2372337950418355,
                                    0.4082826787521751, 0.5917173212478249, 0.7627662049581645,
                                    0.8983332387068134, 0.9801449282487681};
constexpr double kGaussW[kGauss] = {0.0506142681451881, 0.1111905172266872, 0.1568533229389436,
                                    0.1813418916891810, 0.1813418916891810, 0.1568533229389436,
                                    0.1111905172266872, 0.0506142681451881};

/// Integral over psi in [p0, p1] (p1 - p0 <= 2 pi) of max(0, A cos(psi) + B), A >= 0.
double clippedCosine(double A, double B, double p0, double p1) {
    auto full = [&](double lo, double hi) {
        return A * (std::sin(hi) - std::sin(lo)) + B * (hi - lo);
    };
    if (A <= 1e-300) return std::max(0.0, B) * (p1 - p0);
    double c = -B / A;
    if (c <= -1.0) return full(p0, p1);
    if (c >= 1.0) return 0.0;
    double pc = std::acos(c);
    // Positive where cos(psi) > c: (-pc, pc) + 2 pi k. Shift p0 into [-pi, pi).
    double shift = 2.0 * kPi * std::floor((p0 + kPi) / (2.0 * kPi));
    double a = p0 - shift, b = p1 - shift, sum = 0.0;
    for (double centre : {0.0, 2.0 * kPi}) {
        double lo = std::max(a, centre - pc), hi = std::min(b, centre + pc);
        if (hi > lo) sum += full(lo, hi);
    }
    return sum;
}

/// The sum of Eq. (4)-(6): strategies of fractional sample counts, each sample weighted by
/// beta_i (Eq. 5: 1 for i <= N, frac(N) for the last one), with the variance of the sum from each
/// strategy's sample variance.
struct FractionalSum {
    glm::dvec3 sum{0.0}, variance{0.0};

    /// Adds ceil(count) samples of draw() (a function returning one sample's value).
    template <class Draw>
    void add(double count, Draw&& draw) {
        int total = int(std::ceil(count));
        glm::dvec3 mean(0.0), m2(0.0);
        double betaSq = 0.0;
        for (int i = 1; i <= total; ++i) {
            double beta = double(i) <= count ? 1.0 : count - std::floor(count);
            glm::dvec3 y = draw();
            sum += beta * y;
            betaSq += beta * beta;
            glm::dvec3 d = y - mean;
            mean += d / double(i);
            m2 += d * (y - mean);
        }
        if (total > 1) variance += betaSq * m2 / double(total - 1);
    }
    /// The estimate of the sum divided by N_s.
    Estimate estimate(double ns) const {
        Estimate e;
        e.irradiance = sum / ns;
        e.stdError = glm::sqrt(glm::max(variance, glm::dvec3(0.0))) / ns;
        return e;
    }
};

}  // namespace

// Exact irradiance of the piecewise-constant map: E = sum_t L_t int_t max(0, n.w) dw. With
// n.w = a sin(theta) cos(phi - phi_n) + n_y cos(theta), a = |n_xz|:
// - a texel wholly above the horizon integrates in closed form:
//   a (sin(psi1) - sin(psi0)) int sin^2 + n_y (phi1 - phi0) int sin cos over [theta0, theta1];
// - a texel the horizon may cross integrates max(0, .) over phi in closed form (clipped
//   cosine) and over theta with 8-point Gauss-Legendre (the integrand is C^1 there, and only a
//   band of texels one texel wide around the horizon uses the quadrature);
// - a texel wholly below contributes 0.
// "Wholly above / below": |n.w(x) - n.w(centre)| <= |x - centre| <= the texel's diameter.
/// Visible part of texel (x, y) of a w x h map from p for the unit normal n: the fraction of
/// k x k rays at the centres of its sub-cells that escape, each weighted by its cosine and the
/// sub-cell's solid angle (so the texel's exact integral is kept where nothing occludes).
double texelVisibility(const EnvironmentMap& map, const glm::dvec3& p, const glm::dvec3& n, int x,
                       int y, int k, const Visibility& visibility) {
    double sum = 0.0, visible = 0.0;
    for (int j = 0; j < k; ++j)
        for (int i = 0; i < k; ++i) {
            double u = (x + (i + 0.5) / k) / map.width(), v = (y + (j + 0.5) / k) / map.height();
            glm::dvec3 w = map.direction(u, v);
            double weight = std::max(0.0, glm::dot(n, w)) * std::sin(kPi * v);
            if (!(weight > 0.0)) continue;
            sum += weight;
            if (visibility.visibleToward(p, w)) visible += weight;
        }
    return sum > 0.0 ? visible / sum : 1.0;
}

Estimate environmentReference(const EnvironmentLighting& lighting, const glm::dvec3& p,
                              const glm::dvec3& normal, const EstimateOptions& options) {
    // Exact without visibility. With it, each texel's exact integral is scaled by its visible
    // part from k x k rays, k chosen so at least 2^16 rays cover the sphere (2 x 2 for maps of
    // 128 x 64 texels and more): the error is confined to texels an occluder's outline crosses.
    Estimate e;
    glm::dvec3 n;
    if (!unitNormal(normal, n)) return e;
    const EnvironmentMap& map = lighting.map();
    const int w = map.width(), h = map.height();
    const double a = std::sqrt(n.x * n.x + n.z * n.z), phiN = std::atan2(n.z, n.x);
    const double dPhi = 2.0 * kPi / w, dTheta = kPi / h;
    std::vector<double> sinEdge(size_t(w) + 1);
    for (int x = 0; x <= w; ++x) sinEdge[size_t(x)] = std::sin(x * dPhi + map.rotation() - phiN);
    const int k = std::max(2, int(std::ceil(std::sqrt(65536.0 / (double(w) * double(h))))));
    glm::dvec3 sum(0.0);
    for (int y = 0; y < h; ++y) {
        double t0 = y * dTheta, t1 = (y + 1) * dTheta, tc = 0.5 * (t0 + t1);
        double s2 = 0.5 * (t1 - t0) - 0.25 * (std::sin(2.0 * t1) - std::sin(2.0 * t0));
        double sc = 0.5 * (std::sin(t1) * std::sin(t1) - std::sin(t0) * std::sin(t0));
        double sinMax =
            (t0 <= 0.5 * kPi && t1 >= 0.5 * kPi) ? 1.0 : std::max(std::sin(t0), std::sin(t1));
        double diameter = std::sqrt(dTheta * dTheta + sinMax * dPhi * sinMax * dPhi);
        double sinC = std::sin(tc), cosC = std::cos(tc);
        for (int x = 0; x < w; ++x) {
            glm::dvec3 L = map.texel(x, y);
            if (!(L.x + L.y + L.z > 0.0)) continue;
            double p0 = x * dPhi + map.rotation() - phiN, p1 = p0 + dPhi;
            double centre = a * sinC * std::cos(0.5 * (p0 + p1)) + n.y * cosC;
            double integral;
            if (centre >= diameter) {
                integral = a * (sinEdge[size_t(x) + 1] - sinEdge[size_t(x)]) * s2 + n.y * dPhi * sc;
            } else if (centre <= -diameter) {
                continue;
            } else {
                integral = 0.0;
                for (int g = 0; g < kGauss; ++g) {
                    double t = t0 + kGaussX[g] * (t1 - t0);
                    double st = std::sin(t);
                    integral += kGaussW[g] * st * clippedCosine(a * st, n.y * std::cos(t), p0, p1);
                }
                integral *= (t1 - t0);
            }
            if (integral > 0.0 && options.visibility)
                integral *= texelVisibility(map, p, n, x, y, k, *options.visibility);
            sum += L * std::max(0.0, integral);
        }
    }
    e.irradiance = sum;
    return e;
}

Estimate environmentFaceEstimate(const EnvironmentLighting& lighting, const glm::dvec3& p,
                                 const glm::dvec3& normal, const EstimateOptions& options,
                                 const std::array<double, 6>& mu, SampleCounts* counts) {
    Estimate e;
    glm::dvec3 n;
    if (options.spp <= 0 || !unitNormal(normal, n)) return e;
    const CubeMapDistribution& cube = lighting.cube();
    const EnvironmentMap& map = lighting.map();
    Random rng(options.seed);
    const double ns = options.spp;
    SampleCounts c;
    FractionalSum total;
    for (int f = 0; f < 6; ++f) {
        double nf = mu[size_t(f)] * ns;  // N_f(n) = mu_f(n) N_s, fractional (Eq. 4)
        if (!(nf > 0.0)) continue;
        total.add(nf, [&] {
            double u1 = rng.uniform(), u2 = rng.uniform();
            DirectionSample s = cube.sampleFace(f, {u1, u2});
            ++c.drawn;
            if (!(s.pdf > 0.0)) return glm::dvec3(0.0);
            double cosine = glm::dot(n, s.w);
            if (!(cosine > 0.0)) return glm::dvec3(0.0);
            ++c.effective;
            if (!visibleAlong(options, p, s.w)) return glm::dvec3(0.0);
            return map.radiance(s.w) * cosine / (mu[size_t(f)] * s.pdf);
        });
    }
    if (counts) *counts = c;
    return total.estimate(ns);
}

Estimate environmentBalanced(const EnvironmentLighting& lighting, const glm::dvec3& p,
                             const glm::dvec3& n, const EstimateOptions& options) {
    glm::dvec3 unit;
    if (!unitNormal(n, unit)) return {};
    return environmentFaceEstimate(lighting, p, unit, options, lighting.cube().balance(unit),
                                   nullptr);
}

Estimate environmentBalancedInteger(const EnvironmentLighting& lighting, const glm::dvec3& p,
                                    const glm::dvec3& n, const EstimateOptions& options) {
    glm::dvec3 unit;
    if (!unitNormal(n, unit) || options.spp <= 0) return {};
    // N_f rounded to whole samples; the weights follow the counts actually drawn. A face whose
    // count rounds to 0 is skipped: biased, and the count jumps as mu_f(n) crosses k + 1/2.
    std::array<double, 6> mu = lighting.cube().balance(unit);
    for (double& m : mu) m = std::round(m * options.spp) / options.spp;
    return environmentFaceEstimate(lighting, p, unit, options, mu, nullptr);
}

Estimate environmentUniformFaces(const EnvironmentLighting& lighting, const glm::dvec3& p,
                                 const glm::dvec3& n, const EstimateOptions& options) {
    std::array<double, 6> mu;
    mu.fill(1.0 / 6.0);
    return environmentFaceEstimate(lighting, p, n, options, mu, nullptr);
}

Estimate environmentGlobalCdf(const EnvironmentLighting& lighting, const glm::dvec3& p,
                              const glm::dvec3& normal, const EstimateOptions& options) {
    Estimate e;
    glm::dvec3 n;
    if (options.spp <= 0 || !unitNormal(normal, n)) return e;
    Random rng(options.seed);
    glm::dvec3 mean(0.0), m2(0.0);
    for (int k = 0; k < options.spp; ++k) {
        double u1 = rng.uniform(), u2 = rng.uniform();
        DirectionSample s = lighting.global().sample({u1, u2});
        glm::dvec3 y(0.0);
        double cosine = s.pdf > 0.0 ? glm::dot(n, s.w) : 0.0;
        if (cosine > 0.0 && visibleAlong(options, p, s.w))
            y = lighting.map().radiance(s.w) * cosine / s.pdf;
        glm::dvec3 d = y - mean;
        mean += d / double(k + 1);
        m2 += d * (y - mean);
    }
    e.irradiance = mean;
    double count = options.spp;
    e.stdError = count > 1 ? glm::sqrt(glm::max(m2, glm::dvec3(0.0)) / (count - 1) / count)
                           : glm::dvec3(0.0);
    return e;
}

Estimate environmentHavran(const EnvironmentLighting& lighting, const glm::dvec3& p,
                           const glm::dvec3& normal, const EstimateOptions& options) {
    Estimate e;
    glm::dvec3 n;
    if (!unitNormal(normal, n)) return e;
    for (const HavranLights::Light& light : lighting.havran().lights()) {
        double cosine = glm::dot(n, light.direction);
        if (cosine > 0.0 && visibleAlong(options, p, light.direction))
            e.irradiance += light.power * cosine;
    }
    return e;
}

// Eq. (6) of Lu et al. 2013 for a Lambertian receiver (s = L cos, rho = 1): N_f = mu_f N_s / 2
// light samples per face and N_b = N_s / 2 cosine samples (pdf_B = cos / pi), each weighted by
// the balance heuristic 1 / ((1/2) mu_f pdf_L + (1/2) pdf_B), fractional counts through beta.
Estimate environmentBalancedMis(const EnvironmentLighting& lighting, const glm::dvec3& p,
                                const glm::dvec3& normal, const EstimateOptions& options) {
    Estimate e;
    glm::dvec3 n;
    if (options.spp <= 0 || !unitNormal(normal, n)) return e;
    const CubeMapDistribution& cube = lighting.cube();
    const EnvironmentMap& map = lighting.map();
    std::array<double, 6> mu = cube.balance(n);
    Random rng(options.seed);
    const double ns = options.spp;
    FractionalSum total;
    auto weighted = [&](const glm::dvec3& w) {
        double cosine = glm::dot(n, w);
        if (!(cosine > 0.0) || !visibleAlong(options, p, w)) return glm::dvec3(0.0);
        double denom = 0.5 * cube.pdf(mu, w) + 0.5 * cosine / kPi;
        return denom > 0.0 ? map.radiance(w) * cosine / denom : glm::dvec3(0.0);
    };
    for (int f = 0; f < 6; ++f) {
        double nf = 0.5 * mu[size_t(f)] * ns;
        if (!(nf > 0.0)) continue;
        total.add(nf, [&] {
            double u1 = rng.uniform(), u2 = rng.uniform();
            DirectionSample s = cube.sampleFace(f, {u1, u2});
            return s.pdf > 0.0 ? weighted(s.w) : glm::dvec3(0.0);
        });
    }
    glm::dvec3 t, b;
    {
        double sign = std::copysign(1.0, n.z);
        double aa = -1.0 / (sign + n.z), c = n.x * n.y * aa;
        t = {1.0 + sign * n.x * n.x * aa, sign * c, -sign * n.x};
        b = {c, sign + n.y * n.y * aa, -n.y};
    }
    total.add(0.5 * ns, [&] {
        // Cosine-weighted hemisphere (Malley's method): pdf_B = cos / pi.
        double u1 = rng.uniform(), u2 = rng.uniform();
        double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
        glm::dvec3 w =
            r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(std::max(0.0, 1.0 - u1)) * n;
        return weighted(glm::normalize(w));
    });
    e = total.estimate(ns);
    return e;
}

}  // namespace candela
