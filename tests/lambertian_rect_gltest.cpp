// C++/GLSL parity of the Lambertian rectangle (closed form, solid angle, sampler) and a
// chi-square test of the GLSL sampler, run in a compute shader under OSMesa.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>

#include "luminaires/lambertian/LambertianRect.h"
#include "renderer/ShaderLibrary.h"
#include "renderer/context/GlContext.h"
#include "renderer/gl/GlObjects.h"
#include "tests/TestUtil.h"

namespace candela {
namespace {

struct ParityIn {
    glm::vec4 p, n, u;
};
struct ParityOut {
    glm::vec4 irradiance, sampleDir, sampleInfo;
};

std::vector<ParityOut> runParity(const Luminaire& light, const std::vector<ParityIn>& in) {
    return test::runComputeTest<ParityOut>("../tests/shaders/lambertian_rect_parity.comp",
                                           gpuData(light), in);
}

Luminaire testLight() {
    auto model = std::make_shared<LambertianRect>();
    model->size = {1.2, 0.5};
    model->emitted = {10.0, 7.0, 3.0};
    Luminaire light(model);
    light.pose.position = {0.3, 2.0, -0.2};
    light.pose.aim = {0.2, -1.0, 0.1};
    light.pose.c0 = {1.0, 0.0, 0.3};
    return light;
}

TEST(LambertianRectGl, ClosedFormAndSolidAngleMatchCpp) {
    Luminaire light = testLight();
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    std::vector<ParityIn> in;
    for (int i = 0; i < 512; ++i) {
        glm::dvec3 p(2.0 * U(rng), 1.2 + U(rng), 2.0 * U(rng));
        glm::dvec3 n = glm::normalize(glm::dvec3(U(rng), U(rng) + 0.3, U(rng)) + 1e-6);
        in.push_back({glm::vec4(glm::vec3(p), 1.f), glm::vec4(glm::vec3(n), 0.f), glm::vec4(0.5f)});
    }
    std::vector<ParityOut> out = runParity(light, in);
    EstimateOptions options;
    for (size_t i = 0; i < in.size(); ++i) {
        glm::dvec3 p(in[i].p), n(in[i].n);
        Estimate e = lambertianRectAnalytic(light, p, n, options);
        double omega = lambertianRectModel(light)->solidAngle(light.pose, p);
        // Float32 GLSL against double C++: the polygon formula sums a few O(1) angle terms, each
        // good to ~1e-6 relative, so 1e-4 of the value plus 1e-5 of the emitted radiance (the
        // scale of the irradiance near its maximum, pi L) bounds the difference.
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(out[i].irradiance[c], e.irradiance[c],
                        1e-4 * e.irradiance[c] + 1e-5 * lambertianRectModel(light)->emitted[c])
                << "point " << i << " channel " << c;
        EXPECT_NEAR(out[i].irradiance.w, omega, 1e-4 * omega + 1e-6) << "point " << i;
    }
}

TEST(LambertianRectGl, SamplerMatchesCppForTheSameRandomNumbers) {
    Luminaire light = testLight();
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    std::vector<ParityIn> in;
    for (int i = 0; i < 256; ++i) {
        glm::dvec3 p(4.0 * U(rng) - 2.0, 0.5 + U(rng), 4.0 * U(rng) - 2.0);
        in.push_back({glm::vec4(glm::vec3(p), 1.f), glm::vec4(0.f, 1.f, 0.f, 0.f),
                      glm::vec4(float(U(rng)), float(U(rng)), 0.f, 0.f)});
    }
    std::vector<ParityOut> out = runParity(light, in);
    for (size_t i = 0; i < in.size(); ++i) {
        LightSample s = light.sample(glm::dvec3(in[i].p), glm::dvec2(in[i].u));
        ASSERT_EQ(out[i].sampleInfo.y > 0.5f, s.pdf > 0.0) << "point " << i;
        if (s.pdf <= 0.0) continue;
        // Same algorithm in float: directions agree to ~1e-4 (the mapping's condition number
        // near the rectangle's edges amplifies float rounding of the inputs), pdf to 1e-4.
        EXPECT_NEAR(glm::length(glm::dvec3(out[i].sampleDir) - s.wi), 0.0, 2e-4) << "point " << i;
        EXPECT_NEAR(out[i].sampleInfo.x, s.pdf, 1e-4 * s.pdf) << "point " << i;
    }
}

/// Solid angle of a planar triangle seen from the origin (Van Oosterom and Strackee 1983).
double triangleSolidAngle(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
    double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    double num = std::abs(glm::dot(a, glm::cross(b, c)));
    double den = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
    return 2.0 * std::atan2(num, den);
}

TEST(LambertianRectGl, GlslSamplerPassesChiSquare) {
    Luminaire light = testLight();
    glm::dvec3 x, y, z;
    light.pose.frame(x, y, z);
    const glm::dvec2 size = lambertianRectModel(light)->size;
    glm::dvec3 corner = light.pose.position - 0.5 * size.x * x - 0.5 * size.y * y;
    const glm::dvec3 receivers[] = {{0.3, 0.5, -0.2}, {2.5, 1.6, 1.0}, {0.3, 1.95, 1.5}};
    const int kBins = 12, kSamples = 200000;
    for (const glm::dvec3& p : receivers) {
        std::mt19937 rng(3);
        std::uniform_real_distribution<float> U(0.f, 1.f);
        std::vector<ParityIn> in(kSamples);
        for (auto& v : in)
            v = {glm::vec4(glm::vec3(p), 1.f), glm::vec4(0.f, 1.f, 0.f, 0.f),
                 glm::vec4(U(rng), U(rng), 0.f, 0.f)};
        std::vector<ParityOut> out = runParity(light, in);
        std::vector<double> observed(kBins * kBins + 1, 0.0), expected(kBins * kBins + 1, 0.0);
        double omega = 0.0;
        for (int j = 0; j < kBins; ++j)
            for (int i = 0; i < kBins; ++i) {
                auto at = [&](double s, double t) {
                    return corner + s * size.x * x + t * size.y * y - p;
                };
                double s0 = double(i) / kBins, s1 = double(i + 1) / kBins;
                double t0 = double(j) / kBins, t1 = double(j + 1) / kBins;
                double cell = triangleSolidAngle(at(s0, t0), at(s1, t0), at(s1, t1)) +
                              triangleSolidAngle(at(s0, t0), at(s1, t1), at(s0, t1));
                expected[size_t(j * kBins + i)] = cell;
                omega += cell;
            }
        int produced = 0;
        for (const ParityOut& o : out) {
            if (o.sampleInfo.y < 0.5f) continue;
            ++produced;
            glm::dvec3 wi = glm::normalize(glm::dvec3(o.sampleDir));
            double t = glm::dot(corner - p, z) / glm::dot(wi, z);
            glm::dvec3 h = p + t * wi - corner;
            double fx = glm::dot(h, x) / size.x, fy = glm::dot(h, y) / size.y;
            // A float direction re-intersected with the plane at a grazing receiver lands up to
            // ~1e-4 of the size off the edge (float rounding times 1/cos of the incidence):
            // within 1e-3 it counts in the edge's bin, beyond that as off the light.
            const double kEdge = 1e-3;
            if (fx < -kEdge || fy < -kEdge || fx > 1.0 + kEdge || fy > 1.0 + kEdge) {
                observed.back() += 1.0;
                continue;
            }
            int i = std::clamp(int(std::floor(fx * kBins)), 0, kBins - 1);
            int j = std::clamp(int(std::floor(fy * kBins)), 0, kBins - 1);
            observed[size_t(j * kBins + i)] += 1.0;
        }
        ASSERT_EQ(produced, kSamples);
        for (size_t k = 0; k + 1 < expected.size(); ++k) expected[k] *= kSamples / omega;
        test::ChiSquareResult r = test::chiSquare(observed, expected);
        // Three receivers are tested: Sidak-corrected significance level 1e-3 overall.
        double alpha = 1.0 - std::pow(1.0 - 1e-3, 1.0 / 3.0);
        EXPECT_GT(r.pValue, alpha) << "chi2 " << r.statistic << " dof " << r.degreesOfFreedom
                                   << " at receiver " << p.x << "," << p.y << "," << p.z;
    }
}

}  // namespace
}  // namespace candela
