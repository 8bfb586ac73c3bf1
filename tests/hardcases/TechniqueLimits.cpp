#include "tests/hardcases/TechniqueLimits.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "luminaires/photometric/PhotometricLuminaire.h"

namespace candela::hard {

namespace {

Promise exact(double rel, std::string why) {
    return {Promise::Exact, rel, 0.0, 0.0, 0.0, std::move(why)};
}
Promise unbiased(double rel, std::string why) {
    return {Promise::Unbiased, rel, 0.0, 0.0, 0.0, std::move(why)};
}
Promise bounded(double lo, double hi, std::string why) {
    return {Promise::Bounded, 0.0, lo, hi, 0.0, std::move(why)};
}

/// Every technique of every kind on the cases where the answer is settled by geometry alone.
bool common(const TechniqueInfo& t, const Case& c, Promise& out) {
    // Exactly no light: behind the emitter, edge-on, a table of zeros. No technique may leak.
    if (c.expected == 0.0 && c.cls != Class::OnPlane) {
        out = exact(0.0, "no light reaches the receiver: exactly 0");
        return true;
    }
    if (c.expected == 0.0) {
        out = exact(0.0, "in the emitter's plane, beside it: exactly 0");
        return true;
    }
    // A receiver on the emitter itself: the limit from its front is pi L, from behind 0; any
    // value between is a correct reading of an ill-posed question (docs/hard-cases.md says so).
    if (c.cls == Class::OnPlane && c.kind != LuminaireKind::LightField) {
        out = bounded(0.0, c.expected * (1.0 + 1e-9),
                      "on the emitter: between the limits 0 and pi L");
        return true;
    }
    (void)t;
    return false;
}

/// The promise a technique states in its registry line (TechniqueInfo::limits), on this case.
Promise stated(const TechniqueInfo& t, const Case& c) {
    const StatedLimits& l = t.limits;
    const std::string why(l.statement);
    if (l.statement.empty())  // no statement: the strictest
        return t.progressive ? unbiased(2e-3, "(no stated limit: held to unbiased)")
                             : exact(1e-3, "(no stated limit: held to exact)");
    if (l.accuracy == StatedLimits::PointLaw) return {Promise::PointLaw, l.tolerance, 0, 0, 0, why};
    // A peak narrower than the technique's few sample directions: within [0, pi F L_max].
    if (!l.resolvesPeaks && c.cls == Class::Spike && c.upperBound > 0.0)
        return bounded(0.0, c.upperBound,
                       "a peak narrower than the sample directions: within [0, pi F L_max]");
    if (l.fromOpeningSizes > 0.0 && openingSizesAway(c) < l.fromOpeningSizes)
        return {Promise::Finite,
                0,
                0,
                0,
                0,
                "nearer than its stated distance: any factor off (" + why + ")"};
    // A smooth table near a large opening (not Lambertian): what the technique's few samples make
    // of it, as measured.
    if (c.cls == Class::Table && l.accuracy != StatedLimits::Unbiased) {
        if (l.tableTolerance < 0.0)
            return {Promise::Finite,
                    0,
                    0,
                    0,
                    0,
                    "a measured table near the opening: any factor off (" + why + ")"};
        return exact(l.tableTolerance, why);
    }
    switch (l.accuracy) {
        case StatedLimits::Unbiased:
            return unbiased(l.tolerance, why);
        case StatedLimits::Approximate:
            return exact(
                c.cls == Class::Far && l.farTolerance >= 0.0 ? l.farTolerance : l.tolerance, why);
        default:
            return exact(l.tolerance, why);
    }
}

}  // namespace

double openingSizesAway(const Case& c) {
    const PhotometricLuminaire* light = photometricModel(*c.light);
    if (!light || !(light->area() > 0.0)) return std::numeric_limits<double>::infinity();
    return glm::length(c.p - c.light->pose.position) / light->size();
}

Promise promise(const TechniqueInfo& t, const Case& c) {
    Promise p;
    if (common(t, c, p)) return p;
    return stated(t, c);
}

Promise gpuPromise(const TechniqueInfo& t, const Case& c) {
    Promise p = promise(t, c);
    // At grazing normals the cosine carries the rounding of float unit vectors, about 6e-8
    // absolute: E / cos times that (1 % of E at cos = 1e-6).
    if (c.cls == Class::Grazing && c.expected > 0.0) {
        glm::dvec3 to = glm::dvec3(0.0, kH, 0.0) - c.p;
        double cosine = std::abs(glm::dot(c.n, to)) / glm::length(to);
        if (cosine > 0.0) p.abs += c.expected / cosine * 6e-8;
    }
    // Float positions carry half an ulp of their largest coordinate, 6e-8 of it: the point law
    // is exact only to that fraction of the distance to the centre and of the height above the
    // opening's plane (its cosine), each twice over.
    if (p.kind == Promise::PointLaw) {
        double r = glm::length(c.p - glm::dvec3(0.0, kH, 0.0)), h = std::abs(kH - c.p.y);
        double rounding = 6e-8 * std::max({std::abs(c.p.x), std::abs(c.p.y), std::abs(c.p.z), kH});
        p.rel += 1e-3 + 2.0 * rounding / r + (h > 0.0 ? 2.0 * rounding / h : 0.0);
        return p;
    }
    if (c.belowFloat && c.expected > 0.0)
        // 2 %: a direction grazing the opening from 1e-6 m has an angle to its axis within 3e-6
        // rad of 90 degrees, which float (1e-7 rad of absolute rounding there) reads 2 % off, and
        // the radiance I / (A cos) with it.
        return bounded(0.0, c.expected * (1.0 + 2e-2),
                       "within float rounding of the emitter (1e-7 of the distance from the "
                       "origin): the GPU sees "
                       "the receiver on it, any value between 0 and the front limit (+2 %)");
    // Float: 1e-3 covers rounding through the shaders' trigonometry and sums (single precision
    // keeps ~6 digits; the longest chains, spherical polygons of up to 8 vertices, lose one or
    // two more).
    if (p.kind == Promise::Exact || p.kind == Promise::Unbiased) p.rel += 1e-3;
    if (p.kind == Promise::Bounded) p.hi *= 1.0 + 1e-3;
    return p;
}

namespace {
double luminance(const glm::dvec3& v) {
    return 0.2126 * v.x + 0.7152 * v.y + 0.0722 * v.z;
}
}  // namespace

std::string judge(const Case& c, const Promise& p, const Estimate& e) {
    char buf[768];
    double got = luminance(e.irradiance), se = luminance(e.stdError), want = c.expected;
    for (int k = 0; k < 3; ++k)
        if (!std::isfinite(e.irradiance[k]) || e.irradiance[k] < 0.0 ||
            !std::isfinite(e.stdError[k]) || e.stdError[k] < 0.0) {
            std::snprintf(buf, sizeof buf, "not a finite, non-negative value: %g +- %g",
                          e.irradiance[k], e.stdError[k]);
            return buf;
        }
    bool ok = true;
    switch (p.kind) {
        case Promise::Exact:
            // A relative tolerance, and a floor of 1e-12 of the value for double rounding;
            // expected 0 requires exactly 0.
            ok = want == 0.0 ? got == 0.0
                             : std::abs(got - want) <= (p.rel + 1e-12) * std::abs(want) + p.abs;
            break;
        case Promise::Unbiased:
            // The z-score: four standard errors (a 6e-5 two-sided chance for a normal error at
            // one fixed seed) plus the tolerance of the expected value's own quadrature.
            ok = std::abs(got - want) <= 4.0 * se + p.rel * std::abs(want) + p.abs;
            break;
        case Promise::Bounded:
            // The bound holds for the expectation: a stochastic estimate may stray 4 standard
            // errors beyond it.
            ok = got >= p.lo - 4.0 * se - p.abs && got <= p.hi + 4.0 * se + p.abs;
            break;
        case Promise::PointLaw: {
            double law = pointLaw(c);
            ok = std::abs(got - law) <= p.rel * law + p.abs + 1e-300;
            want = law;
            break;
        }
        case Promise::Finite:
            break;
    }
    if (ok) return "";
    std::snprintf(buf, sizeof buf,
                  "expected %.9g (%s), got %.9g +- %.3g; bounds [%g, %g]; its limit: %s", want,
                  c.how.c_str(), got, se, p.lo, p.hi, p.why.c_str());
    return buf;
}

}  // namespace candela::hard
