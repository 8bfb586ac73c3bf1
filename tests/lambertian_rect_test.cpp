// Tests of the Lambertian rectangle against references that share no code with it: closed-form
// configuration factors from catalogues, adaptive Gauss-Legendre quadrature of the defining
// integrals, and a chi-square test of the sampler.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "luminaires/lambertian/LambertianRect.h"
#include "shaders/shared/Constants.h"
#include "tests/LambertianRectFixture.h"
#include "tests/TestUtil.h"

namespace candela {
namespace {

using gpu::kPi;

// ---------------------------------------------------------------------------------------------
// Quadrature: Gauss-Legendre nodes from Newton's method on the Legendre recurrence, and an
// adaptive rule that halves intervals until the 16-node results of one and two halves agree.

struct GaussRule {
    std::vector<double> x, w;  ///< Nodes and weights on [-1, 1].
};

GaussRule gaussLegendre(int n) {
    GaussRule rule;
    for (int i = 1; i <= n; ++i) {
        double x = std::cos(kPi * (i - 0.25) / (n + 0.5));
        double dp = 1.0;
        for (int iter = 0; iter < 100; ++iter) {
            double p0 = 1.0, p1 = x;
            for (int k = 2; k <= n; ++k) {
                double pk = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = pk;
            }
            dp = n * (x * p1 - p0) / (x * x - 1.0);
            double step = p1 / dp;
            x -= step;
            if (std::abs(step) < 1e-16) break;
        }
        rule.x.push_back(x);
        rule.w.push_back(2.0 / ((1.0 - x * x) * dp * dp));
    }
    return rule;
}

const GaussRule& rule16() {
    static const GaussRule rule = gaussLegendre(16);
    return rule;
}

using Fn1 = std::function<double(double)>;

double gauss16(const Fn1& f, double a, double b) {
    const GaussRule& g = rule16();
    double mid = 0.5 * (a + b), half = 0.5 * (b - a), sum = 0.0;
    for (size_t i = 0; i < g.x.size(); ++i) sum += g.w[i] * f(mid + half * g.x[i]);
    return sum * half;
}

double adaptive(const Fn1& f, double a, double b, double whole, double tol, int depth) {
    double mid = 0.5 * (a + b);
    double left = gauss16(f, a, mid), right = gauss16(f, mid, b);
    double diff = std::abs(left + right - whole);
    // Stop at the tolerance, or where the difference is rounding (a few ulps of the parts).
    if (depth <= 0 || diff <= tol || diff <= 1e-15 * (std::abs(left) + std::abs(right)))
        return left + right;
    return adaptive(f, a, mid, left, 0.5 * tol, depth - 1) +
           adaptive(f, mid, b, right, 0.5 * tol, depth - 1);
}

/// Integral of f over [a, b] split at the given breakpoints, to about relTol of the result.
double integrate(const Fn1& f, double a, double b, std::vector<double> breaks, double relTol) {
    if (!(b > a)) return 0.0;
    breaks.push_back(a);
    breaks.push_back(b);
    std::sort(breaks.begin(), breaks.end());
    std::vector<double> pts;
    for (double x : breaks)
        if (x >= a && x <= b && (pts.empty() || x > pts.back())) pts.push_back(x);
    double estimate = 0.0;
    for (size_t i = 0; i + 1 < pts.size(); ++i)
        estimate += std::abs(gauss16(f, pts[i], pts[i + 1]));
    double sum = 0.0;
    for (size_t i = 0; i + 1 < pts.size(); ++i) {
        double piece = gauss16(f, pts[i], pts[i + 1]);
        sum += adaptive(f, pts[i], pts[i + 1], piece, relTol * estimate + 1e-300, 30);
    }
    return sum;
}

// ---------------------------------------------------------------------------------------------
// Test geometry: the tilted light and its frame, from LambertianRectFixture.h.

using test::dirToWorld;
using test::Frame;
using test::frameOf;
using test::makeLight;
using test::toWorld;

/// The rectangle model of a light from makeLight().
const LambertianRect& rect(const Luminaire& light) {
    return *lambertianRectModel(light);
}

/// The solid angle the light subtends at p (LambertianRect::solidAngle at its pose).
double solidAngle(const Luminaire& light, const glm::dvec3& p) {
    return rect(light).solidAngle(light.pose, p);
}

/// The light with another size (a copy of its model), at the same pose.
Luminaire withSize(const Luminaire& light, const glm::dvec2& size) {
    auto model = std::make_shared<LambertianRect>(rect(light));
    model->size = size;
    Luminaire out = light;
    out.setModel(model);
    return out;
}

/// Integral over the sub-rectangle [s0, s1] x [t0, t1] of the light (s, t measured from its
/// centre along local x, y) of max(0, cos_r) cos_e / r^2 for a receiver at local position q with
/// local unit normal m (useCosR false: of cos_e / r^2, the solid angle). Iterated adaptive
/// Gauss-Legendre, split where the receiver's horizon cuts the rectangle and at q's foot point;
/// the requested relative accuracy is ~1e-11.
double rectIntegral(const glm::dvec3& q, const glm::dvec3& m, bool useCosR, double s0, double s1,
                    double t0, double t1) {
    if (!(q.z > 0.0)) return 0.0;
    // n . (X - q) = a + b s + c t over the rectangle.
    double a = -glm::dot(m, q), b = m.x, c = m.y;
    auto inner = [&](double s) {
        // Along t the cosine's numerator is c (t - tStar): written so, it carries no rounding
        // noise from the cancelling a + b s + c t near the horizon, which would stall the
        // adaptive rule.
        double tStar = c != 0.0 ? -(a + b * s) / c : 0.0;
        double rest = a + b * s;
        auto f = [&](double t) {
            glm::dvec3 v(s - q.x, t - q.y, -q.z);
            double r2 = glm::dot(v, v), r = std::sqrt(r2);
            double cosE = q.z / r;
            double up = c != 0.0 ? c * (t - tStar) : rest;
            double cosR = useCosR ? std::max(0.0, up / r) : 1.0;
            return cosR * cosE / r2;
        };
        std::vector<double> br = {q.y};
        if (useCosR && c != 0.0) br.push_back(tStar);
        return integrate(f, t0, t1, br, 1e-12);
    };
    std::vector<double> br = {q.x};
    if (useCosR && b != 0.0) {
        br.push_back(-(a + c * t0) / b);
        br.push_back(-(a + c * t1) / b);
    }
    return integrate(inner, s0, s1, br, 1e-11);
}

/// Quadrature irradiance (W/m2 per channel) for local receiver position q and normal m.
glm::dvec3 quadratureIrradiance(const Luminaire& light, const glm::dvec3& q, const glm::dvec3& m) {
    double hw = 0.5 * rect(light).size.x, hh = 0.5 * rect(light).size.y;
    return rect(light).emitted * rectIntegral(q, m, true, -hw, hw, -hh, hh);
}

// ---------------------------------------------------------------------------------------------
// Configuration factors from catalogues (Howell, "A Catalog of Radiation Heat Transfer
// Configuration Factors"), superposed over the four corner rectangles.

/// Differential element parallel to a rectangle [0, a] x [0, b] at distance h, on the normal
/// through a corner (Howell's catalogue, element-to-parallel-rectangle factor).
double parallelCornerFactor(double a, double b, double h) {
    double x = a / h, y = b / h;
    double sx = std::sqrt(1.0 + x * x), sy = std::sqrt(1.0 + y * y);
    return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2.0 * kPi);
}

/// Receiver at local (px, py, h) facing the light (normal -aim): factor of the whole rectangle.
double parallelFactor(const Luminaire& light, double px, double py, double h) {
    auto g = [&](double x, double y) {
        double sx = x < 0.0 ? -1.0 : 1.0, sy = y < 0.0 ? -1.0 : 1.0;
        return sx * sy * parallelCornerFactor(std::abs(x), std::abs(y), h);
    };
    double x0 = -0.5 * rect(light).size.x - px, x1 = 0.5 * rect(light).size.x - px;
    double y0 = -0.5 * rect(light).size.y - py, y1 = 0.5 * rect(light).size.y - py;
    return g(x1, y1) - g(x1, y0) - g(x0, y1) + g(x0, y0);
}

/// Differential element whose normal lies in a plane parallel to the rectangle, pointing along
/// the rectangle's edge of length a; the element sits at distance c from the rectangle's plane on
/// the normal through a corner, the rectangle spans [0, a] x [0, b]. Derived by integrating
/// cos_r cos_e / (pi r^2) = c x / (pi (x^2 + y^2 + c^2)^2) over x then y:
///   F = 1/(2 pi) [atan(b/c) - c / sqrt(a^2 + c^2) atan(b / sqrt(a^2 + c^2))],
/// which is Howell's factor for an element on a plane perpendicular to a rectangle.
double perpendicularCornerFactor(double a, double b, double c) {
    double s = std::sqrt(a * a + c * c);
    return (std::atan(b / c) - c / s * std::atan(b / s)) / (2.0 * kPi);
}

/// Receiver at local (px, py, h) with normal +x (parallel to the light's plane). The part of the
/// rectangle with x < px is behind the receiver's tangent plane and drops out.
double perpendicularFactor(const Luminaire& light, double px, double py, double h) {
    double x0 = std::max(-0.5 * rect(light).size.x - px, 0.0), x1 = 0.5 * rect(light).size.x - px;
    if (x1 <= x0) return 0.0;
    double y0 = -0.5 * rect(light).size.y - py, y1 = 0.5 * rect(light).size.y - py;
    auto g = [&](double x, double y) {
        double sy = y < 0.0 ? -1.0 : 1.0;
        return sy * perpendicularCornerFactor(x, std::abs(y), h);
    };
    return g(x1, y1) - g(x1, y0) - g(x0, y1) + g(x0, y0);
}

// ---------------------------------------------------------------------------------------------
// Irradiance at 16 receivers.

enum class Ref { None, Parallel, Perpendicular };

struct Receiver {
    const char* what;
    glm::dvec3 q;  ///< Local position: along the light's x, y, and in front along aim (m).
    glm::dvec3 m;  ///< Local normal (normalised before use).
    Ref closedForm;
    bool quadrature;
};

std::vector<Receiver> receivers() {
    glm::dvec3 down(0.0, 0.0, -1.0);  // facing the light
    // Grazing normal: perpendicular to the direction to the centre, tilted 1e-3 rad towards it.
    glm::dvec3 q9(0.2, 0.1, 1.0), d9 = glm::normalize(-q9);
    glm::dvec3 p9 = glm::normalize(glm::cross(d9, glm::dvec3(0.0, 1.0, 0.0)));
    return {
        {"below the centre", {0.0, 0.0, 1.0}, down, Ref::Parallel, true},
        {"off centre", {0.4, -0.2, 0.5}, down, Ref::Parallel, true},
        {"outside the footprint", {1.5, 0.9, 0.8}, down, Ref::Parallel, true},
        {"1e-3 m below the surface", {0.1, 0.05, 1e-3}, down, Ref::Parallel, true},
        {"far away, 50 m", {0.3, 0.2, 50.0}, down, Ref::Parallel, true},
        {"far and oblique", {30.0, -20.0, 50.0}, {-30.0, 20.0, -50.0}, Ref::None, true},
        {"perpendicular, beside", {-0.9, 0.1, 0.4}, {1.0, 0.0, 0.0}, Ref::Perpendicular, true},
        {"half below the horizon", {0.1, -0.1, 0.3}, {1.0, 0.0, 0.0}, Ref::Perpendicular, true},
        {"grazing, horizon through the light", q9, p9 + 1e-3 * d9, Ref::None, true},
        {"grazing, 1e-3 rad", {-0.7, 0.0, 0.5}, {1.0, 0.0, -1e-3}, Ref::None, true},
        {"1e-3 m in front, beside", {-0.9, 0.1, 1e-3}, down, Ref::Parallel, true},
        {"1e-6 m in front, beside", {-0.9, 0.1, 1e-6}, down, Ref::Parallel, true},
        {"1e-6 m in front, beside, oblique", {0.2, 0.5, 1e-6}, {0.3, -1.0, -0.5}, Ref::None, true},
        {"behind the light", {0.1, 0.1, -0.5}, {0.0, 0.0, 1.0}, Ref::None, false},
        {"facing away", {0.1, 0.1, 0.7}, {0.0, 0.0, 1.0}, Ref::None, true},
        {"tilted 60 degrees", {0.5, 0.0, 0.3}, {1.0, 0.3, -0.5}, Ref::None, true},
    };
}

TEST(LambertianRect, ClosedFormMatchesCatalogueAndQuadrature) {
    Luminaire light = makeLight();
    for (const Receiver& rc : receivers()) {
        SCOPED_TRACE(rc.what);
        glm::dvec3 m = glm::normalize(rc.m);
        glm::dvec3 p = toWorld(light, rc.q), n = dirToWorld(light, m);
        Estimate e = lambertianRectAnalytic(light, p, n, EstimateOptions{});
        EXPECT_EQ(e.stdError, glm::dvec3(0.0));
        std::vector<glm::dvec3> refs;
        if (rc.closedForm == Ref::Parallel)
            refs.push_back(rect(light).emitted * kPi *
                           parallelFactor(light, rc.q.x, rc.q.y, rc.q.z));
        if (rc.closedForm == Ref::Perpendicular)
            refs.push_back(rect(light).emitted * kPi *
                           perpendicularFactor(light, rc.q.x, rc.q.y, rc.q.z));
        if (rc.quadrature) refs.push_back(quadratureIrradiance(light, rc.q, m));
        if (rc.q.z <= 0.0) refs.push_back(glm::dvec3(0.0));
        for (const glm::dvec3& ref : refs)
            for (int c = 0; c < 3; ++c)
                // Both sides are exact up to rounding (the references to ~1e-12 relative): 1e-5
                // relative leaves room for the conditioning of the near-plane cases; 1e-12 W/m2
                // absolute where the irradiance vanishes.
                EXPECT_NEAR(e.irradiance[c], ref[c], 1e-5 * ref[c] + 1e-12) << "channel " << c;
        if (rc.q.z <= 0.0 || rc.m.z > 0.0) {
            EXPECT_EQ(e.irradiance, glm::dvec3(0.0));
        }
    }
}

TEST(LambertianRect, ReferenceEstimatorConverges) {
    Luminaire light = makeLight();
    EstimateOptions options;
    options.spp = 1 << 16;
    options.seed = 12345;
    for (const Receiver& rc : receivers()) {
        SCOPED_TRACE(rc.what);
        glm::dvec3 m = glm::normalize(rc.m);
        glm::dvec3 p = toWorld(light, rc.q), n = dirToWorld(light, m);
        Estimate exact = lambertianRectAnalytic(light, p, n, EstimateOptions{});
        Estimate mc = lambertianRectReference(light, p, n, options);
        for (int c = 0; c < 3; ++c) {
            double diff = std::abs(mc.irradiance[c] - exact.irradiance[c]);
            EXPECT_TRUE(std::isfinite(mc.stdError[c]));
            if (exact.irradiance[c] == 0.0) {
                // No sample can contribute where the light is behind or below the horizon.
                EXPECT_EQ(mc.irradiance[c], 0.0);
                continue;
            }
            // 4 standard errors: a deviation this large has probability 6e-5 per check.
            EXPECT_LE(diff, 4.0 * mc.stdError[c]) << "channel " << c;
            // Accuracy asked of 2^16 solid-angle samples at these receivers: 0.5%.
            EXPECT_LE(diff, 5e-3 * exact.irradiance[c]) << "channel " << c;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Power and solid angle.

TEST(LambertianRect, PowerMatchesIntegralOfEmittedRadiance) {
    Luminaire light = makeLight();
    Frame f = frameOf(light.pose);
    const GaussRule& g = rule16();
    // Radiance is integrated over the surface (4 x 4 nodes: it must be constant there) and over
    // the whole sphere of directions, split at the horizon where it drops to 0 on the back.
    GaussRule area = gaussLegendre(4);
    glm::dvec3 flux(0.0);
    for (size_t i = 0; i < area.x.size(); ++i)
        for (size_t j = 0; j < area.x.size(); ++j) {
            double s = 0.5 * rect(light).size.x * area.x[i],
                   t = 0.5 * rect(light).size.y * area.x[j];
            double dA = 0.25 * rect(light).size.x * rect(light).size.y * area.w[i] * area.w[j];
            glm::dvec3 x = light.pose.position + s * f.x + t * f.y;
            for (int side = 0; side < 2; ++side)
                for (size_t a = 0; a < g.x.size(); ++a)
                    for (size_t b = 0; b < g.x.size(); ++b) {
                        double theta = kPi / 4.0 * (g.x[a] + 1.0) + side * kPi / 2.0;
                        double phi = kPi * (g.x[b] + 1.0);
                        double dOmega = kPi / 4.0 * g.w[a] * kPi * g.w[b] * std::sin(theta);
                        glm::dvec3 w = std::sin(theta) * std::cos(phi) * f.x +
                                       std::sin(theta) * std::sin(phi) * f.y +
                                       std::cos(theta) * f.z;
                        flux += light.radiance(x, w) * std::abs(std::cos(theta)) * dOmega * dA;
                    }
        }
    glm::dvec3 power = light.power();
    for (int c = 0; c < 3; ++c)
        // Gauss-Legendre is exact to rounding for the smooth cos(theta) sin(theta) on each half.
        EXPECT_NEAR(flux[c], power[c], 1e-12 * power[c]);
    EXPECT_NEAR(power.x, kPi * 1.2 * 0.6 * 10.0, 1e-12);
}

TEST(LambertianRect, SolidAngleMatchesQuadrature) {
    Luminaire light = makeLight();
    const glm::dvec3 points[] = {{0.0, 0.0, 1.0},     {0.4, -0.2, 0.1},  {3.0, 2.0, 0.5},
                                 {0.2, 0.1, 1e-3},    {-0.9, 0.1, 1e-6}, {0.0, 0.0, 100.0},
                                 {40.0, -70.0, 100.0}};
    double hw = 0.5 * rect(light).size.x, hh = 0.5 * rect(light).size.y;
    for (const glm::dvec3& q : points) {
        double exact = rectIntegral(q, glm::dvec3(0.0), false, -hw, hw, -hh, hh);
        double omega = solidAngle(light, toWorld(light, q));
        // Quadrature to ~1e-12; 1e-9 also absorbs the rounding of the world position near the
        // plane (|p| ~ 2 m makes ~4e-16 m of error in a 1e-6 m distance).
        EXPECT_NEAR(omega, exact, 1e-9 * exact) << q.x << ", " << q.y << ", " << q.z;
    }
    EXPECT_EQ(solidAngle(light, toWorld(light, {0.1, 0.1, -0.3})), 0.0);  // behind
    EXPECT_EQ(solidAngle(light, toWorld(light, {0.1, 0.1, 0.0})), 0.0);   // in the plane
}

// ---------------------------------------------------------------------------------------------
// The sampler.

/// Upper regularised incomplete gamma function Q(a, x), through the shared chi-square survival
/// function (Q(k/2, x/2) is the chi-square survival of x with k degrees of freedom).
double gammaQ(double a, double x) {
    return test::chiSquareSurvival(2.0 * x, 2.0 * a);
}

TEST(LambertianRect, IncompleteGammaMatchesKnownValues) {
    // Q(1, x) = exp(-x); Q(k/2, x/2) is the chi-square survival function: 3.841 is the 5% point
    // of 1 degree of freedom, 18.307 that of 10, 124.342 that of 100.
    EXPECT_NEAR(gammaQ(1.0, 2.5), std::exp(-2.5), 1e-14);
    EXPECT_NEAR(gammaQ(0.5, 3.841459 / 2.0), 0.05, 1e-6);
    EXPECT_NEAR(gammaQ(5.0, 18.307038 / 2.0), 0.05, 1e-6);
    EXPECT_NEAR(gammaQ(50.0, 124.342113 / 2.0), 0.05, 1e-6);
}

struct ChiSquare {
    double statistic = 0.0;
    int dof = 0;
    double pValue = 0.0;
};

/// Pearson's test; cells expecting fewer than 5 counts are pooled into one cell.
ChiSquare pearson(const std::vector<double>& observed, const std::vector<double>& expected) {
    ChiSquare r;
    double pooledObs = 0.0, pooledExp = 0.0;
    int cells = 0;
    for (size_t i = 0; i < expected.size(); ++i) {
        if (expected[i] < 5.0) {
            pooledObs += observed[i];
            pooledExp += expected[i];
            continue;
        }
        r.statistic += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
        ++cells;
    }
    if (pooledExp > 0.0) {
        r.statistic += (pooledObs - pooledExp) * (pooledObs - pooledExp) / pooledExp;
        ++cells;
    } else if (pooledObs > 0.0) {
        r.statistic = std::numeric_limits<double>::infinity();  // counts where none can fall
    }
    r.dof = cells - 1;
    r.pValue = std::isfinite(r.statistic) ? gammaQ(0.5 * r.dof, 0.5 * r.statistic) : 0.0;
    return r;
}

const glm::dvec3 kChiSquareReceivers[] = {
    {0.0, 0.0, 1.0},    // below the centre
    {2.5, 1.0, 0.7},    // oblique
    {-0.8, 0.1, 1e-3},  // close to the plane, beside the light
    {0.1, 0.05, 0.02},  // close to the plane, over the light
    {0.3, -0.2, 50.0},  // far away
};

TEST(LambertianRect, SamplerPassesChiSquare) {
    Luminaire light = makeLight();
    Frame f = frameOf(light.pose);
    const int kBins = 16, kSamples = 1 << 18;
    const int kTests = int(std::size(kChiSquareReceivers));
    // Sidak correction: with kTests independent tests at level alpha each, the chance that any
    // fails by accident is 1 - (1 - alpha)^kTests = 1e-3.
    const double alpha = 1.0 - std::pow(1.0 - 1e-3, 1.0 / kTests);
    double hw = 0.5 * rect(light).size.x, hh = 0.5 * rect(light).size.y;
    for (const glm::dvec3& q : kChiSquareReceivers) {
        SCOPED_TRACE(testing::Message() << q.x << ", " << q.y << ", " << q.z);
        glm::dvec3 p = toWorld(light, q);
        std::vector<double> expected(size_t(kBins * kBins)), observed(expected.size(), 0.0);
        double omega = 0.0;
        for (int j = 0; j < kBins; ++j)
            for (int i = 0; i < kBins; ++i) {
                double s0 = -hw + 2.0 * hw * i / kBins, s1 = -hw + 2.0 * hw * (i + 1) / kBins;
                double t0 = -hh + 2.0 * hh * j / kBins, t1 = -hh + 2.0 * hh * (j + 1) / kBins;
                double cell = rectIntegral(q, glm::dvec3(0.0), false, s0, s1, t0, t1);
                expected[size_t(j * kBins + i)] = cell;
                omega += cell;
            }
        for (double& e : expected) e *= kSamples / omega;
        std::mt19937_64 rng(99);
        std::uniform_real_distribution<double> uniform(0.0, 1.0);
        int offLight = 0;
        for (int k = 0; k < kSamples; ++k) {
            LightSample s = light.sample(p, {uniform(rng), uniform(rng)});
            ASSERT_GT(s.pdf, 0.0);
            glm::dvec3 local = s.position - light.pose.position;
            double ls = glm::dot(local, f.x), lt = glm::dot(local, f.y);
            int i = std::min(int(std::floor((ls + hw) / (2.0 * hw) * kBins)), kBins - 1);
            int j = std::min(int(std::floor((lt + hh) / (2.0 * hh) * kBins)), kBins - 1);
            if (i < 0 || j < 0)
                ++offLight;
            else
                observed[size_t(j * kBins + i)] += 1.0;
        }
        EXPECT_EQ(offLight, 0);
        ChiSquare r = pearson(observed, expected);
        EXPECT_GT(r.pValue, alpha) << "chi2 " << r.statistic << " with " << r.dof << " dof";
    }
}

TEST(LambertianRect, SamplesAreOnTheLightAndAgreeWithPdf) {
    Luminaire light = makeLight();
    Frame f = frameOf(light.pose);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (const glm::dvec3& q : kChiSquareReceivers) {
        glm::dvec3 p = toWorld(light, q);
        double omega = solidAngle(light, p);
        for (int k = 0; k < 2000; ++k) {
            LightSample s = light.sample(p, {uniform(rng), uniform(rng)});
            ASSERT_GT(s.pdf, 0.0);
            EXPECT_EQ(s.pdf, 1.0 / omega);
            EXPECT_EQ(s.pdf, light.pdf(p, s.wi));
            EXPECT_EQ(s.radiance, rect(light).emitted);
            // Unit direction, consistent distance, and a point on the rectangle: tolerances are
            // a few hundred roundings of the coordinates (|p| < 60 m).
            EXPECT_NEAR(glm::length(s.wi), 1.0, 1e-14);
            EXPECT_LT(glm::length(p + s.distance * s.wi - s.position), 1e-12 * (1.0 + s.distance));
            glm::dvec3 local = s.position - light.pose.position;
            EXPECT_NEAR(glm::dot(local, f.z), 0.0, 1e-13);
            EXPECT_LE(std::abs(glm::dot(local, f.x)), 0.5 * rect(light).size.x + 1e-13);
            EXPECT_LE(std::abs(glm::dot(local, f.y)), 0.5 * rect(light).size.y + 1e-13);
            EXPECT_GT(glm::length(light.radiance(s.position, -s.wi)), 0.0);
        }
    }
}

/// Solid angle of the local rectangle [s0, s1] x [t0, t1] seen from q (q.z > 0 above its plane):
/// the signed sum over its corners of atan(x y / (h sqrt(x^2 + y^2 + h^2))), the closed form of
/// the solid angle of a rectangle with one corner under the receiver (Howell's catalogue, the
/// parallel element-to-rectangle geometry). Checked against quadrature in
/// SolidAngleClosedFormMatchesQuadrature below.
double rectSolidAngle(const glm::dvec3& q, double s0, double s1, double t0, double t1) {
    auto corner = [&](double s, double t) {
        double x = s - q.x, y = t - q.y;
        return std::atan2(x * y, q.z * std::sqrt(x * x + y * y + q.z * q.z));
    };
    return corner(s1, t1) - corner(s0, t1) - corner(s1, t0) + corner(s0, t0);
}

TEST(LambertianRect, SolidAngleClosedFormMatchesQuadrature) {
    Luminaire light = makeLight();
    double hw = 0.5 * rect(light).size.x, hh = 0.5 * rect(light).size.y;
    const glm::dvec3 points[] = {{0.1, 0.05, 0.3}, {-0.9, 0.1, 0.05}, {2.0, -1.0, 1.5}};
    for (const glm::dvec3& q : points) {
        double quad = rectIntegral(q, glm::dvec3(0.0), false, -hw, 0.2, -hh, hh);
        // Both are exact to rounding; the adaptive rule stops at 1e-11 relative.
        EXPECT_NEAR(rectSolidAngle(q, -hw, 0.2, -hh, hh), quad, 1e-9 * quad) << q.z;
    }
}

TEST(LambertianRect, SamplerInvertsItsCdfPrecisely) {
    // The sample for (u1, u2) must split the solid angle exactly: the part of the rectangle left
    // of the sample's x holds u1 of the solid angle, and along the sample's column the part below
    // it holds u2 of that column's. Checked where the map is ill-conditioned: 1e-6 m from the
    // plane, on all four sides and over the light, and 100 m away. Both splits are closed forms.
    Luminaire light = makeLight();
    Frame f = frameOf(light.pose);
    double hw = 0.5 * rect(light).size.x, hh = 0.5 * rect(light).size.y;
    const glm::dvec3 points[] = {{-0.9, 0.1, 1e-6},   {0.9, -0.1, 1e-6}, {0.2, 0.5, 1e-6},
                                 {-0.2, -0.5, 1e-6},  {0.1, 0.05, 1e-6}, {0.0, 0.0, 100.0},
                                 {60.0, -80.0, 10.0}, {0.7, 0.4, 1e-3}};
    const double us[] = {0.001, 0.1, 0.37, 0.5, 0.8, 0.999};
    for (const glm::dvec3& q : points) {
        glm::dvec3 p = toWorld(light, q);
        double omega = rectSolidAngle(q, -hw, hw, -hh, hh);
        for (double u1 : us)
            for (double u2 : us) {
                LightSample s = light.sample(p, {u1, u2});
                ASSERT_GT(s.pdf, 0.0);
                glm::dvec3 local = s.position - light.pose.position;
                double xs = glm::dot(local, f.x), ys = glm::dot(local, f.y);
                double left = rectSolidAngle(q, -hw, xs, -hh, hh);
                // Column density at x = xs is proportional to (d^2 + y^2)^(-3/2), y = t - q.y,
                // whose integral is y / (d^2 sqrt(d^2 + y^2)): the split is a ratio of
                // eta(y) = y / sqrt(d^2 + y^2).
                double d2 = (xs - q.x) * (xs - q.x) + q.z * q.z;
                auto eta = [&](double t) {
                    return (t - q.y) / std::sqrt(d2 + (t - q.y) * (t - q.y));
                };
                double below = eta(ys) - eta(-hh), all = eta(hh) - eta(-hh);
                // The world position's rounding (~4e-16 m) is up to 4e-10 of a 1e-6 m height:
                // 1e-8 of the solid angle bounds the resulting shift of the split.
                EXPECT_NEAR(left / omega, u1, 1e-8) << q.z << " u = " << u1 << ", " << u2;
                EXPECT_NEAR(below / all, u2, 1e-8) << q.z << " u = " << u1 << ", " << u2;
            }
    }
}

TEST(LambertianRect, PdfIsZeroOffTheLightAndBehindIt) {
    Luminaire light = makeLight();
    glm::dvec3 p = toWorld(light, {0.1, 0.1, 1.0});
    glm::dvec3 toCentre = glm::normalize(light.pose.position - p);
    EXPECT_EQ(light.pdf(p, toCentre), 1.0 / solidAngle(light, p));
    EXPECT_EQ(light.pdf(p, 3.0 * toCentre), 1.0 / solidAngle(light, p));  // need not be unit
    EXPECT_EQ(light.pdf(p, -toCentre), 0.0);
    EXPECT_EQ(light.pdf(p, glm::normalize(toWorld(light, {2.0, 0.0, 0.0}) - p)), 0.0);
    EXPECT_EQ(light.pdf(p, glm::dvec3(0.0)), 0.0);
    glm::dvec3 behind = toWorld(light, {0.1, 0.1, -1.0});
    EXPECT_EQ(light.pdf(behind, glm::normalize(light.pose.position - behind)), 0.0);
}

// ---------------------------------------------------------------------------------------------
// Shadowing.

/// Blocks every segment that ends on the light's x < 0 half.
class HalfBlocked final : public Visibility {
  public:
    explicit HalfBlocked(const Luminaire& light) : mLight(light) {}
    bool visible(const glm::dvec3&, const glm::dvec3& to) const override {
        return glm::dot(to - mLight.pose.position, frameOf(mLight.pose).x) >= 0.0;
    }
    bool visibleToward(const glm::dvec3&, const glm::dvec3&) const override { return true; }

  private:
    const Luminaire& mLight;
};

class AllVisible final : public Visibility {
  public:
    bool visible(const glm::dvec3&, const glm::dvec3&) const override { return true; }
    bool visibleToward(const glm::dvec3&, const glm::dvec3&) const override { return true; }
};

TEST(LambertianRect, VisibilityScalesBothEstimators) {
    Luminaire light = makeLight();
    HalfBlocked half(light);
    AllVisible all;
    glm::dvec3 q(0.3, 0.1, 0.8), m = glm::normalize(glm::dvec3(0.2, 0.1, -1.0));
    glm::dvec3 p = toWorld(light, q), n = dirToWorld(light, m);
    double hh = 0.5 * rect(light).size.y;
    glm::dvec3 exact =
        rect(light).emitted * rectIntegral(q, m, true, 0.0, 0.5 * rect(light).size.x, -hh, hh);
    EstimateOptions options;
    options.spp = 1 << 16;
    options.visibility = &all;
    Estimate unoccluded = lambertianRectAnalytic(light, p, n, EstimateOptions{});
    Estimate open = lambertianRectAnalytic(light, p, n, options);
    EXPECT_EQ(open.irradiance, unoccluded.irradiance);  // ratio exactly 1
    EXPECT_EQ(open.stdError, glm::dvec3(0.0));
    options.visibility = &half;
    for (Estimate e : {lambertianRectAnalytic(light, p, n, options),
                       lambertianRectReference(light, p, n, options)}) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_GT(e.stdError[c], 0.0);
            // 4 standard errors (the ratio estimator's bias is O(1/N), far below that).
            EXPECT_NEAR(e.irradiance[c], exact[c], 4.0 * e.stdError[c]) << "channel " << c;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Hard cases: nothing may be NaN or infinite.

void expectFinite(const Luminaire& light, const glm::dvec3& p, const glm::dvec3& n) {
    EstimateOptions options;
    options.spp = 64;
    AllVisible all;
    for (const Visibility* v : {(const Visibility*)nullptr, (const Visibility*)&all}) {
        options.visibility = v;
        for (Estimate e : {lambertianRectAnalytic(light, p, n, options),
                           lambertianRectReference(light, p, n, options)})
            for (int c = 0; c < 3; ++c) {
                EXPECT_TRUE(std::isfinite(e.irradiance[c]) && e.irradiance[c] >= 0.0);
                EXPECT_TRUE(std::isfinite(e.stdError[c]) && e.stdError[c] >= 0.0);
            }
    }
    double omega = solidAngle(light, p);
    EXPECT_TRUE(std::isfinite(omega) && omega >= 0.0 && omega <= 2.0 * kPi);
    for (glm::dvec2 u : {glm::dvec2(0.0), glm::dvec2(1.0), glm::dvec2(0.5, 0.999999),
                         glm::dvec2(std::nan(""), 2.0)}) {
        LightSample s = light.sample(p, u);
        EXPECT_TRUE(std::isfinite(s.pdf) && s.pdf >= 0.0);
        for (int c = 0; c < 3; ++c)
            EXPECT_TRUE(std::isfinite(s.wi[c]) && std::isfinite(s.position[c]));
        EXPECT_TRUE(std::isfinite(s.distance));
        double pdf = light.pdf(p, s.wi);
        EXPECT_TRUE(std::isfinite(pdf) && pdf >= 0.0);
    }
}

TEST(LambertianRect, HardCasesStayFinite) {
    Luminaire light = makeLight();
    glm::dvec3 n = dirToWorld(light, {0.1, 0.2, -1.0});
    // Exactly in the plane, over the light and beside it: nothing is emitted there.
    for (glm::dvec3 q : {glm::dvec3(0.1, 0.1, 0.0), glm::dvec3(-2.0, 0.1, 0.0)}) {
        glm::dvec3 p = toWorld(light, q);
        expectFinite(light, p, n);
        EXPECT_EQ(solidAngle(light, p), 0.0);
        EXPECT_EQ(light.sample(p, {0.3, 0.6}).pdf, 0.0);
        EXPECT_EQ(lambertianRectAnalytic(light, p, n, {}).irradiance, glm::dvec3(0.0));
    }
    // 1e-6 m in front of the centre: the light fills almost the whole hemisphere, E -> pi L.
    glm::dvec3 close = toWorld(light, {0.0, 0.0, 1e-6});
    expectFinite(light, close, n);
    glm::dvec3 facing = dirToWorld(light, {0.0, 0.0, -1.0});
    Estimate e = lambertianRectAnalytic(light, close, facing, {});
    // The missing part of the hemisphere is ~1e-6 / 0.3 of it (the nearest edge is 0.3 m away).
    EXPECT_NEAR(e.irradiance.x, kPi * rect(light).emitted.x, 1e-4 * kPi * rect(light).emitted.x);
    EXPECT_NEAR(solidAngle(light, close), 2.0 * kPi, 1e-4);
    // Far and very far away, and a light of 1e-9 m: tiny but finite, and the far-field limit
    // E = L A cos_e cos_r / r^2 where that is representable.
    for (double dist : {1e3, 1e6, 1e12, 1e200}) {
        glm::dvec3 p = toWorld(light, {0.0, 0.0, dist});
        expectFinite(light, p, facing);
        if (dist <= 1e12) {
            double far =
                rect(light).emitted.x * rect(light).size.x * rect(light).size.y / (dist * dist);
            // Relative difference from the far-field limit is ~(size / dist)^2.
            EXPECT_NEAR(lambertianRectAnalytic(light, p, facing, {}).irradiance.x, far, 1e-6 * far);
            EXPECT_NEAR(solidAngle(light, p), far / rect(light).emitted.x,
                        1e-6 * far / rect(light).emitted.x);
        }
    }
    Luminaire tiny = withSize(light, {1e-9, 1e-9});
    for (double dist : {1e-12, 1e-9, 1.0, 100.0}) {
        glm::dvec3 p = toWorld(tiny, {0.3e-9, 0.1e-9, dist});
        expectFinite(tiny, p, facing);
        expectFinite(tiny, toWorld(tiny, {5e-9, 0.0, dist}), facing);
    }
    glm::dvec3 p1 = toWorld(tiny, {0.0, 0.0, 1.0});
    double farTiny = rect(tiny).emitted.x * 1e-18;
    EXPECT_NEAR(lambertianRectAnalytic(tiny, p1, facing, {}).irradiance.x, farTiny, 1e-6 * farTiny);
    // Bad receivers: zero or NaN normal, NaN or infinite position.
    expectFinite(light, toWorld(light, {0.0, 0.0, 1.0}), glm::dvec3(0.0));
    expectFinite(light, toWorld(light, {0.0, 0.0, 1.0}), glm::dvec3(std::nan("")));
    expectFinite(light, glm::dvec3(std::nan("")), facing);
    expectFinite(light, glm::dvec3(1e300, -1e300, std::numeric_limits<double>::infinity()), facing);
    // Degenerate lights from the editor: zero or negative size.
    Luminaire flat = withSize(light, {0.0, 1.0});
    expectFinite(flat, toWorld(light, {0.0, 0.0, 1.0}), facing);
    EXPECT_EQ(flat.power(), glm::dvec3(0.0));
    flat = withSize(light, {-1.0, 1.0});
    expectFinite(flat, toWorld(light, {0.0, 0.0, 1.0}), facing);
}

}  // namespace
}  // namespace candela
