// The light field's GLSL (shaders/lightfield.glsl, lightfield_shade.frag) under OSMesa: parity
// of the box integral and sampler with C++, a chi-square test of the GLSL sampler, and the
// production shading pass (through the GPU probe) against the CPU quadrature reference.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "luminaires/LightField.h"
#include "renderer/Renderer.h"
#include "renderer/ShaderLibrary.h"
#include "renderer/context/GlContext.h"
#include "renderer/gl/GlObjects.h"
#include "scene/SceneIo.h"
#include "tests/TestUtil.h"

namespace candela {
namespace {

struct ParityIn {
    glm::vec4 box, xi;
    glm::ivec4 m;
};
struct ParityOut {
    glm::vec4 sampled, area;
};

const char* kTiny = CANDELA_TEST_DATA "/lightfield/tiny.lf.json";

LightFieldLuminaire tiny() {
    LightFieldLuminaire l;
    l.data = LightFieldData::load(kTiny);
    return l;
}

std::vector<ParityOut> runParity(const LightFieldLuminaire& light,
                                 const std::vector<ParityIn>& in) {
    return test::runComputeTest<ParityOut>("../tests/shaders/lightfield_parity.comp",
                                           light.gpuData(), in);
}

TEST(LightFieldGl, BoxIntegralAndSamplerMatchCpp) {
    LightFieldLuminaire light = tiny();
    const LightFieldData& lf = *light.data;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> U(0.f, 1.f);
    std::vector<ParityIn> in;
    for (int k = 0; k < 512; ++k) {
        glm::vec2 a = glm::vec2(lf.imageMin) + glm::vec2(U(rng), U(rng)) * 0.07f;
        glm::vec2 b = glm::min(a + glm::vec2(0.002f + 0.05f * U(rng), 0.002f + 0.05f * U(rng)),
                               glm::vec2(lf.imageMax));
        in.push_back({glm::vec4(a, b), glm::vec4(U(rng), U(rng), 0, 0),
                      glm::ivec4(k % lf.imageCount(), 0, 0, 0)});
    }
    std::vector<ParityOut> out = runParity(light, in);
    for (size_t k = 0; k < in.size(); ++k) {
        int m = in[k].m.x;
        glm::dvec2 a(in[k].box.x, in[k].box.y), b(in[k].box.z, in[k].box.w);
        double area = lf.boxIntegral(m, a, b);
        // The GLSL reads the same double table; the box corners are floats in both: 1e-6.
        EXPECT_NEAR(out[k].area.x, area, 1e-6 * area + 1e-9) << k;
        glm::dvec2 s;
        bool ok = lf.sampleBox(m, a, b, glm::dvec2(in[k].xi), s);
        ASSERT_EQ(out[k].sampled.z > 0.5f, ok)
            << k << " m " << m << " box " << a.x << "," << a.y << " .. " << b.x << "," << b.y
            << " xi " << in[k].xi.x << "," << in[k].xi.y << " area " << area;
        if (!ok) continue;
        // Compare in CDF space: the same search on the same doubles, but knot positions and the
        // result are floats, and in a pixel much dimmer than its neighbours a tiny CDF difference
        // is a large move in position (a 1000x dimmer pixel turns 1e-7 into 1e-4 of a pixel).
        // The marginal CDF of x over the box and the conditional CDF of y in the sample's pixel
        // column must agree to 1e-5.
        glm::dvec2 g(out[k].sampled.x, out[k].sampled.y);
        auto marginal = [&](double x) { return lf.boxIntegral(m, a, {x, b.y}) / area; };
        EXPECT_NEAR(marginal(g.x), marginal(s.x), 1e-5) << k;
        glm::dvec2 px = lf.pixelSize();
        double colL = lf.imageMin.x + std::floor((s.x - lf.imageMin.x) / px.x) * px.x;
        double xl = std::max(a.x, colL), xr = std::min(b.x, colL + px.x);
        if (xr - xl > 1e-9) {
            double column = lf.boxIntegral(m, {xl, a.y}, {xr, b.y});
            auto conditional = [&](double y) {
                return lf.boxIntegral(m, {xl, a.y}, {xr, y}) / column;
            };
            if (column > 0.0) {
                EXPECT_NEAR(conditional(g.y), conditional(s.y), 1e-5) << k;
            }
        }
        // And in position to 1e-4 of a pixel where the pixel is not much dimmer than the box.
        if (lf.lum(m, s) > 0.1 * area / ((b.x - a.x) * (b.y - a.y))) {
            EXPECT_NEAR(glm::length(g - s), 0.0, 1e-4 * px.x) << k;
        }
        EXPECT_GT(out[k].sampled.w, 0.f) << "GLSL sample in a zero-energy pixel, " << k;
    }
}

TEST(LightFieldGl, GlslSamplerPassesChiSquare) {
    LightFieldLuminaire light = tiny();
    const LightFieldData& lf = *light.data;
    const int kBins = 6, kSamples = 60000;
    const glm::vec2 boxes[][2] = {{{-0.031f, -0.025f}, {0.029f, 0.013f}},
                                  {{-0.04f, -0.04f}, {0.04f, 0.04f}}};
    double alpha = 1.0 - std::pow(1.0 - 1e-3, 1.0 / 2.0);  // Sidak over both boxes
    for (int t = 0; t < 2; ++t) {
        int m = 4 + t;
        glm::vec2 a = boxes[t][0], b = boxes[t][1];
        std::mt19937 rng(9);
        std::uniform_real_distribution<float> U(0.f, 1.f);
        std::vector<ParityIn> in(kSamples);
        for (auto& v : in)
            v = {glm::vec4(a, b), glm::vec4(U(rng), U(rng), 0, 0), glm::ivec4(m, 0, 0, 0)};
        std::vector<ParityOut> out = runParity(light, in);
        // Expected counts by direct pixel overlaps (not through the summed-area table).
        std::vector<double> expected(kBins * kBins, 0.0), observed(kBins * kBins, 0.0);
        glm::dvec2 px = lf.pixelSize();
        double total = 0.0;
        for (int bj = 0; bj < kBins; ++bj)
            for (int bi = 0; bi < kBins; ++bi) {
                glm::dvec2 lo =
                    glm::dvec2(a) + glm::dvec2(b - a) * glm::dvec2(bi, bj) / double(kBins);
                glm::dvec2 hi =
                    glm::dvec2(a) + glm::dvec2(b - a) * glm::dvec2(bi + 1, bj + 1) / double(kBins);
                double e = 0.0;
                for (int j = 0; j < lf.height; ++j)
                    for (int i = 0; i < lf.width; ++i) {
                        glm::dvec2 p0 = lf.imageMin + glm::dvec2(i, j) * px, p1 = p0 + px;
                        double ox = std::max(0.0, std::min(hi.x, p1.x) - std::max(lo.x, p0.x));
                        double oy = std::max(0.0, std::min(hi.y, p1.y) - std::max(lo.y, p0.y));
                        e += ox * oy * lf.images[size_t(m)].luminance[size_t(j * lf.width + i)];
                    }
                expected[size_t(bj * kBins + bi)] = e;
                total += e;
            }
        for (const ParityOut& o : out) {
            ASSERT_GT(o.sampled.z, 0.5f);
            glm::vec2 f = (glm::vec2(o.sampled) - a) / (b - a) * float(kBins);
            glm::ivec2 bin = glm::clamp(glm::ivec2(glm::floor(f)), 0, kBins - 1);
            observed[size_t(bin.y * kBins + bin.x)] += 1.0;
        }
        for (double& e : expected) e *= kSamples / total;
        test::ChiSquareResult r = test::chiSquare(observed, expected);
        EXPECT_GT(r.pValue, alpha)
            << "box " << t << " chi2 " << r.statistic << " dof " << r.degreesOfFreedom;
    }
}

TEST(LightFieldGl, ShadingPassMatchesTheCpuReference) {
    test::glContext();
    Scene scene = loadScene(CANDELA_TEST_DATA "/lightfield/scene.json");
    const Luminaire& light = *scene.luminaires[0];
    // Receivers from 1 mm to 2.5 m beyond S, facing the light, tilted and grazing.
    std::vector<glm::vec3> points = {{0.0f, 0.96f, 0.0f},    {0.01f, 0.95f, 0.005f},
                                     {0.2f, 0.5f, -0.1f},    {-0.5f, 0.0f, 0.4f},
                                     {0.003f, 0.9f, 0.001f}, {1.5f, -1.5f, 0.5f}};
    std::vector<glm::vec3> normals = {{0, 1, 0},
                                      {0, 1, 0},
                                      glm::normalize(glm::vec3(0.3f, 1, 0)),
                                      {0, 1, 0},
                                      glm::normalize(glm::vec3(1, 0.05f, 0)),
                                      {0, 1, 0}};
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    RenderSettings settings;
    settings.width = 16;
    settings.height = 16;
    renderer.setSettings(settings);
    // Every sampler of the kind (progressive, with a GPU pass).
    for (const TechniqueInfo& info : techniquesOf("lightfield")) {
        if (!info.progressive || info.shader.empty()) continue;
        const std::string technique(info.name);
        RenderSettings s = settings;
        s.techniqueOverride = technique;
        renderer.setSettings(s);
        std::vector<glm::vec3> gpu = renderer.probe(scene, points, normals, 16384);
        for (size_t i = 0; i < points.size(); ++i) {
            EstimateOptions o;
            Estimate ref =
                lightFieldReference(light, glm::dvec3(points[i]), glm::dvec3(normals[i]), o);
            o.spp = 16384;
            const TechniqueInfo* t = findTechnique("lightfield", technique);
            Estimate cpu = t->irradiance(light, glm::dvec3(points[i]), glm::dvec3(normals[i]), o);
            ASSERT_TRUE(std::isfinite(gpu[i].y));
            // The GPU estimator is the CPU one in float with its own random numbers: within 1 %
            // of the reference or five of the CPU estimator's standard errors at the same count.
            double tol = std::max(0.01 * ref.irradiance.y, 5.0 * cpu.stdError.y);
            EXPECT_NEAR(gpu[i].y, ref.irradiance.y, tol) << technique << " point " << i;
        }
    }
}

TEST(LightFieldGl, Granier2003MatchesCpp) {
    test::glContext();
    Scene scene = loadScene(CANDELA_TEST_DATA "/lightfield/scene.json");
    const Luminaire& light = *scene.luminaires[0];
    std::vector<glm::vec3> points = {
        {0.0f, 0.96f, 0.0f}, {0.2f, 0.5f, -0.1f}, {-0.5f, 0.0f, 0.4f}, {1.5f, -1.5f, 0.5f}};
    std::vector<glm::vec3> normals = {
        {0, 1, 0}, glm::normalize(glm::vec3(0.3f, 1, 0)), {0, 1, 0}, {0, 1, 0}};
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    RenderSettings s;
    s.width = s.height = 8;
    s.techniqueOverride = "granier2003";
    renderer.setSettings(s);
    std::vector<glm::vec3> gpu = renderer.probe(scene, points, normals, 1);
    for (size_t i = 0; i < points.size(); ++i) {
        Estimate e =
            lightFieldGranier2003(light, glm::dvec3(points[i]), glm::dvec3(normals[i]), {});
        // Deterministic; the same sums in float (the box mean divides two float differences): 1e-3.
        EXPECT_NEAR(gpu[i].y, e.irradiance.y, 1e-3 * e.irradiance.y) << i;
    }
}

}  // namespace
}  // namespace candela
