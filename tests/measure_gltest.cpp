// Illuminance mode and the false-colour operator under OSMesa: the G-buffer's albedo override
// turns every shading pass's radiance into the irradiance E (checked against the CPU closed form
// on a glossy, coloured floor), switching the quantity restarts accumulation, and the false-colour
// picture shows the C++ colour scale (shaders/shared/FalseColour.h) with 1 px isolux lines.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "luminaires/lambertian/LambertianRect.h"
#include "renderer/Renderer.h"
#include "scene/SceneIo.h"
#include "shaders/shared/FalseColour.h"
#include "tests/TestUtil.h"

namespace candela {
namespace {

// A glossy floor with a coloured albedo: in illuminance mode neither may show in the image.
const std::string kScene = R"({
  "geometry": [{"plane": {"center": [0,0,0], "normal": [0,1,0], "size": [6,6]},
                "albedo": [0.5,0.6,0.7], "specular": [0.4,0.4,0.4], "roughness": 0.3}],
  "luminaires": [{"type": "lambertian-rect", "name": "Panel", "size": [1, 0.5],
                  "radiance": [10, 20, 30], "position": [0.2,2.5,-0.3], "aim": [0.1,-1,0],
                  "technique": "analytic"}],
  "camera": {"position": [0, 1.5, 4], "target": [0, 0.5, 0], "fov_deg": 50}})";

constexpr int kWidth = 96, kHeight = 72;

RenderSettings settings(Quantity quantity) {
    RenderSettings s;
    s.width = kWidth;
    s.height = kHeight;
    s.samplesPerFrame = 4;
    s.maxSamples = 8;
    s.quantity = quantity;
    return s;
}

/// Where the ray through the centre of pixel (x, y) (row 0 at the top) meets the floor y = 0.
/// Only points at most `half` m from the centre in x and z (the floor is 6 m square).
std::optional<glm::dvec3> floorPoint(const Renderer& renderer, int x, int y, double half = 2.9) {
    glm::dmat4 inv = glm::inverse(glm::dmat4(renderer.viewProj()));
    double ndcX = (x + 0.5) / kWidth * 2.0 - 1.0, ndcY = 1.0 - (y + 0.5) / kHeight * 2.0;
    glm::dvec4 a = inv * glm::dvec4(ndcX, ndcY, -1.0, 1.0),
               b = inv * glm::dvec4(ndcX, ndcY, 1.0, 1.0);
    glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::dvec3(b) / b.w - o;
    if (d.y >= 0.0) return std::nullopt;
    glm::dvec3 p = o - d * (o.y / d.y);
    if (std::abs(p.x) > half || std::abs(p.z) > half) return std::nullopt;
    return p;
}

TEST(Measure, IlluminanceModeWritesTheIrradianceOfTheClosedForm) {
    test::glContext();
    Scene scene = parseScene(nlohmann::json::parse(kScene), "test.json");
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    renderer.setSettings(settings(Quantity::Illuminance));
    renderer.update(scene, kChangeAll);
    renderer.renderFrame();
    // No glossy lobe in illuminance mode: the analytic technique is exact in one frame.
    EXPECT_TRUE(renderer.converged());
    for (const auto& v : shaders.compiledVariants())
        EXPECT_EQ(v.find("GLOSSY"), std::string::npos) << v;

    std::vector<float> rgb = renderer.readLinear();
    const auto& light = *scene.luminaires[0];
    int checked = 0;
    double worst = 0.0;
    for (int y = 0; y < kHeight; y += 6)
        for (int x = 0; x < kWidth; x += 6) {
            auto p = floorPoint(renderer, x, y);
            if (!p) continue;
            Estimate e = lambertianRectAnalytic(light, *p, {0.0, 1.0, 0.0}, EstimateOptions{});
            const float* px = &rgb[(size_t(y) * kWidth + size_t(x)) * 3];
            for (int c = 0; c < 3; ++c) {
                // Float G-buffer positions (~1e-7 m) and float shading against the double closed
                // form: 1e-3 relative is ample (as in renderer_gltest). The albedo (0.5, 0.6, 0.7)
                // or the glossy lobe leaking through would be off by 30 % or more.
                EXPECT_NEAR(px[c], e.irradiance[c], 1e-3 * e.irradiance[c] + 1e-6) << x << "," << y;
                worst = std::max(worst, std::abs(px[c] - e.irradiance[c]) / e.irradiance[c]);
            }
            ++checked;
        }
    EXPECT_GT(checked, 40);
    std::printf("illuminance mode: %d pixels, worst relative error %.2e (tolerance 1e-3)\n",
                checked, worst);
}

TEST(Measure, SwitchingTheQuantityRestartsAccumulation) {
    test::glContext();
    Scene scene = parseScene(nlohmann::json::parse(kScene), "test.json");
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    RenderSettings s = settings(Quantity::Radiance);
    renderer.setSettings(s);
    renderer.update(scene, kChangeAll);
    do renderer.renderFrame();
    while (!renderer.converged());
    std::vector<float> radiance = renderer.readLinear();
    s.quantity = Quantity::Illuminance;
    renderer.setSettings(s);
    renderer.renderFrame();
    ASSERT_FALSE(renderer.stats().passes.empty());
    EXPECT_EQ(renderer.stats().passes.front().name, "gbuffer");
    std::vector<float> irradiance = renderer.readLinear();
    // At a floor pixel the ratio E / L_radiance-mode is pi / albedo plus the glossy lobe: far
    // from 1.
    auto p = floorPoint(renderer, kWidth / 2, kHeight - 5);
    ASSERT_TRUE(p);
    size_t i = (size_t(kHeight - 5) * kWidth + size_t(kWidth / 2)) * 3;
    EXPECT_GT(irradiance[i] / radiance[i], 2.0f);
}

/// sRGB-encoded 8-bit value of the scale at legend position t.
glm::vec3 scaleAt(float t) {
    return gpu::falseColour(t) * 255.f;
}

TEST(Measure, FalseColourShowsTheScaleWithThinIsoluxLines) {
    test::glContext();
    Scene scene = parseScene(nlohmann::json::parse(kScene), "test.json");
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    RenderSettings s = settings(Quantity::Illuminance);
    s.toneMap = ToneMapOperator::FalseColour;
    renderer.setSettings(s);
    renderer.update(scene, kChangeAll);
    renderer.renderFrame();
    std::vector<float> rgb = renderer.readLinear();
    auto value = [&](int x, int y) {
        const float* c = &rgb[(size_t(y) * kWidth + size_t(x)) * 3];
        return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
    };
    float peak = 0.f;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) peak = std::max(peak, value(x, y));
    ASSERT_GT(peak, 0.f);
    // The legend spans 1.25 peak, four isolux levels at 0.2 .. 0.8 peak.
    s.legend.min = 0.f;
    s.legend.max = 1.25f * peak;
    s.legend.levels = {0.2f * peak, 0.4f * peak, 0.6f * peak, 0.8f * peak};
    renderer.setSettings(s);
    renderer.renderFrame();  // converged: only the display changes
    std::vector<unsigned char> shown = renderer.readDisplay();
    int plain = 0, onLine = 0, background = 0;
    float worstPlain = 0.f;
    for (int y = 1; y + 1 < kHeight; ++y)
        for (int x = 1; x + 1 < kWidth; ++x) {
            const unsigned char* px = &shown[(size_t(y) * kWidth + size_t(x)) * 3];
            glm::vec3 got(px[0], px[1], px[2]);
            if (!floorPoint(renderer, x, y)) {
                // No surface: neutral dark grey (0.12 of full scale).
                if (!floorPoint(renderer, x, y, 3.1)) {
                    EXPECT_NEAR(got.x, 0.12f * 255.f, 1.f) << x << "," << y;
                    ++background;
                }
                continue;
            }
            float e = value(x, y);
            // Distance in pixels to the nearest level, by the local gradient (central differences).
            float gx = 0.5f * std::abs(value(x + 1, y) - value(x - 1, y));
            float gy = 0.5f * std::abs(value(x, y + 1) - value(x, y - 1));
            float g = std::max(std::hypot(gx, gy), 1e-6f), distance = 1e9f;
            for (float level : s.legend.levels)
                distance = std::min(distance, std::abs(e - level) / g);
            glm::vec3 expected = scaleAt(e / s.legend.max);
            float diff = glm::length(got - expected);
            if (distance > 2.f) {
                // Away from the lines the picture is the C++ scale: 8-bit rounding is 0.5 per
                // channel, so 1.5 (rounding of three channels plus float noise) is the bound.
                EXPECT_LT(diff, 1.5f) << x << "," << y;
                worstPlain = std::max(worstPlain, diff);
                ++plain;
            } else if (diff > 40.f) {
                // A pixel the lines darken must lie within 1.5 px of a level (lines are 1 px wide
                // with a 1 px box filter; the gradient here is estimated, hence 1.5).
                EXPECT_LT(distance, 1.5f) << x << "," << y;
                ++onLine;
            }
        }
    EXPECT_GT(plain, 1000);
    EXPECT_GT(onLine, 40);  // the four isolux rings are drawn
    EXPECT_GT(background, 10);
    std::printf(
        "false colour: %d plain pixels (worst 8-bit distance %.2f, tolerance 1.5), %d line "
        "pixels, %d background\n",
        plain, worstPlain, onLine, background);
}

}  // namespace
}  // namespace candela
