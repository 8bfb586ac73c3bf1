// The light field's GLSL (shaders/lightfield.glsl, lightfield_shade.frag) under OSMesa: parity
// of the box integral and sampler with C++, a chi-square test of the GLSL sampler, and the
// production shading pass (through the GPU probe) against the CPU quadrature reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "luminaires/lightfield/LightField.h"
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

/// A placed light field of the given data.
Luminaire placedLightField(std::shared_ptr<const LightFieldData> data) {
    auto model = std::make_shared<LightFieldLuminaire>();
    model->data = std::move(data);
    return Luminaire(model);
}

Luminaire tiny() {
    return placedLightField(LightFieldData::load(kTiny));
}

std::vector<ParityOut> runParity(const Luminaire& light, const std::vector<ParityIn>& in) {
    return test::runComputeTest<ParityOut>("../tests/shaders/lightfield_parity.comp",
                                           gpuData(light), in, gpuTables(light).get());
}

TEST(LightFieldGl, BoxIntegralAndSamplerMatchCpp) {
    Luminaire light = tiny();
    const LightFieldData& lf = *lightFieldModel(light)->data;
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

/// An image of 256^2 pixels whose quadrant at the table's origin is 1e6 times brighter than the
/// rest (slightly structured): small boxes far from the origin hold 1e-10 of the table's largest
/// entries, so their A_m cancels catastrophically in float.
Luminaire farFromTheOrigin() {
    auto lf = std::make_shared<LightFieldData>();
    lf->count = {1, 1};
    lf->spacing = {0.1, 0.1};
    lf->origin = {0.0, 0.0};
    lf->delta = 0.05;
    lf->imageMin = {-0.128, -0.128};
    lf->imageMax = {0.128, 0.128};
    lf->width = lf->height = 256;
    lf->images.resize(1);
    std::vector<float>& c = lf->images[0].luminance;
    c.resize(256 * 256);
    for (int j = 0; j < 256; ++j)
        for (int i = 0; i < 256; ++i)
            c[size_t(j * 256 + i)] =
                i < 128 && j < 128 ? 1e6f : 1.f + 0.5f * float((i * 7 + j * 3) % 5);
    lf->validate("far-from-the-origin");
    lf->precompute();
    return placedLightField(lf);
}

/// Plain float summed-area table arithmetic (what the shaders would do without float-float
/// pairs), for the test below to show that its boxes need more than float.
double floatBoxIntegral(const LightFieldData& lf, glm::vec2 a, glm::vec2 b) {
    auto at = [&](glm::vec2 s) {
        glm::vec2 f = (s - glm::vec2(lf.imageMin)) / glm::vec2(lf.pixelSize());
        int i = std::min(int(f.x), lf.width - 1), j = std::min(int(f.y), lf.height - 1);
        float fx = f.x - float(i), fy = f.y - float(j);
        auto S = [&](int x, int y) {
            return float(lf.tables[0].sat[size_t(y * (lf.width + 1) + x)]);
        };
        float s00 = S(i, j), s10 = S(i + 1, j), s01 = S(i, j + 1), s11 = S(i + 1, j + 1);
        return s00 + fx * (s10 - s00) + fy * (s01 - s00) + fx * fy * (s11 - s10 - s01 + s00);
    };
    return double(at(b) - at({a.x, b.y}) - at({b.x, a.y}) + at(a));
}

TEST(LightFieldGl, SmallBoxesFarFromTheTableOriginKeepTheirDigits) {
    Luminaire light = farFromTheOrigin();
    const LightFieldData& lf = *lightFieldModel(light)->data;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> U(0.f, 1.f);
    std::vector<ParityIn> in;
    for (int k = 0; k < 256; ++k) {
        // In the dim far quadrant, 5 to 12 pixels a side (the summed-area table's path, beyond
        // the 4 pixels integrated directly); every fourth 0.3 pixels wide and 20 tall.
        glm::vec2 a = glm::vec2(0.06f + 0.05f * U(rng), 0.06f + 0.05f * U(rng));
        glm::vec2 size = k % 4 == 0 ? glm::vec2(0.0003f, 0.02f)
                                    : glm::vec2(0.005f + 0.007f * U(rng), 0.005f + 0.007f * U(rng));
        in.push_back({glm::vec4(a, a + size), glm::vec4(U(rng), U(rng), 0, 0), glm::ivec4(0)});
    }
    std::vector<ParityOut> out = runParity(light, in);
    double worstFloat = 0.0;
    for (size_t k = 0; k < in.size(); ++k) {
        glm::dvec2 a(in[k].box.x, in[k].box.y), b(in[k].box.z, in[k].box.w);
        double area = lf.boxIntegral(0, a, b);
        ASSERT_GT(area, 0.0);
        // Float's relative precision on the box's own energy (a few roundings of 6e-8), plus
        // what float-float pairs keep of the table: each difference of entries loses about 2^-48
        // of the largest (64-bit tables lost 2^-53). The thin boxes here hold 1e-9 of the
        // table's largest entry, so that term reaches about 5e-6 of them (measured 1.4e-6).
        double largest = lf.tables[0].sat.back();
        EXPECT_NEAR(out[k].area.x, area, 1e-6 * area + 2.0 * std::ldexp(largest, -48)) << k;
        worstFloat = std::max(
            worstFloat,
            std::abs(floatBoxIntegral(lf, in[k].box, {in[k].box.z, in[k].box.w}) - area) / area);
        // The sample's place in the box's marginal CDF, as in BoxIntegralAndSamplerMatchCpp.
        glm::dvec2 s;
        ASSERT_TRUE(lf.sampleBox(0, a, b, glm::dvec2(in[k].xi), s));
        ASSERT_GT(out[k].sampled.z, 0.5f) << k;
        auto marginal = [&](double x) { return lf.boxIntegral(0, a, {x, b.y}) / area; };
        // 1e-5, plus the float sample's own resolution and that of the pixel edge it is placed
        // against: an ulp of x each, 2.5e-5 of a thin box.
        double ulp = std::nextafter(out[k].sampled.x, 1.f) - out[k].sampled.x;
        EXPECT_NEAR(marginal(out[k].sampled.x), marginal(s.x), 1e-5 + 2.0 * ulp / (b.x - a.x)) << k;
    }
    // The case needs more than float: plain float tables miss these boxes by more than 10 %.
    EXPECT_GT(worstFloat, 0.1);
    std::printf("[ info ] far small boxes: plain float tables err by up to %.3g of the box\n",
                worstFloat);
}

TEST(LightFieldGl, GlslSamplerPassesChiSquare) {
    Luminaire light = tiny();
    const LightFieldData& lf = *lightFieldModel(light)->data;
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
    for (const TechniqueInfo& info : techniquesOf(LuminaireKind::LightField)) {
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
            const TechniqueInfo* t = findTechnique(LuminaireKind::LightField, technique);
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
