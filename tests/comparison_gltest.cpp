// The comparison panes (renderer/Comparison.h) under OSMesa: the reference's noise estimate
// against independent renders, errors of exact, unbiased and biased techniques, the measurement
// schedule, the error map's sign and orientation, and the CPU tone mapping that Delta E uses
// against the renderer's own.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/Comparison.h"
#include "renderer/ImageMetrics.h"
#include "renderer/context/GlContext.h"
#include "scene/SceneIo.h"
#include "tests/TestUtil.h"

namespace candela {
namespace {

/// A floor lit by a Lambertian panel with no occluder (so "analytic" is exact) and a table
/// under a photometric downlight (IES file from tests/data).
Scene panelScene() {
    std::string text = R"({"geometry": [
        {"plane": {"center": [0,0,0], "normal": [0,1,0], "size": [6,6]}, "albedo": [0.5,0.6,0.7]}],
      "luminaires": [{"type": "lambertian-rect", "name": "Panel", "size": [1, 0.5],
        "radiance": [10, 10, 10], "position": [0.2, 2.5, -0.3], "aim": [0.1, -1, 0], "technique": "analytic"}],
      "camera": {"position": [0, 1.5, 4], "target": [0, 0.5, 0], "fov_deg": 50}})";
    return parseScene(nlohmann::json::parse(text), "test.json");
}

RenderSettings shared(int width = 64, int height = 48) {
    RenderSettings s;
    s.width = width;
    s.height = height;
    s.samplesPerFrame = 4;
    return s;
}

void runToEnd(Comparison& c) {
    for (int i = 0; i < 10000 && !c.done(); ++i) c.step(0.0);
    ASSERT_TRUE(c.done());
}

/// An independent render of the scene with the reference's techniques at spp samples.
std::vector<float> referenceRender(ShaderLibrary& shaders, const Scene& scene, int spp,
                                   uint32_t seed) {
    Renderer r(shaders);
    RenderSettings s = shared();
    s.techniqueOverride = Comparison::kReferenceTechniques;
    s.maxSamples = spp;
    s.seed = seed;
    return test::renderConverged(r, scene, s);
}

TEST(Comparison, ReferenceNoiseMatchesTwoIndependentRenders) {
    test::glContext();
    Scene scene = panelScene();
    ShaderLibrary shaders;
    Comparison c(shaders);
    c.configure({{"analytic", 4}}, shared(), 64);
    c.update(scene, kChangeAll);
    runToEnd(c);
    ASSERT_EQ(c.referenceSpp(), 64);
    // Two more independent 64-spp references: |A - B|^2 = 2 sigma^2.
    double independent =
        relRmse(referenceRender(shaders, scene, 64, 11), referenceRender(shaders, scene, 64, 23)) /
        std::sqrt(2.0);
    ASSERT_GT(independent, 0.0);
    // Both are estimates of sigma from about 3000 lit pixels with correlated neighbours (a
    // sample pattern per pixel, not per image): 20 % covers their spread (measured: 0.97).
    EXPECT_NEAR(c.referenceNoise() / independent, 1.0, 0.2)
        << "estimate " << c.referenceNoise() << ", independent " << independent;
}

TEST(Comparison, ExactTechniqueErrsByTheReferenceNoiseAndBiasedOneByMore) {
    test::glContext();
    Scene scene = panelScene();
    ShaderLibrary shaders;
    Comparison c(shaders);
    // Pane 0: the closed form (exact, no occluder). Pane 1: the same Monte Carlo estimator as
    // the reference at 16 spp, unbiased.
    c.configure({{"analytic", 4}, {"reference", 16}}, shared(), 128);
    c.update(scene, kChangeAll);
    runToEnd(c);
    const PaneResult& exact = c.result(0);
    const PaneResult& mc = c.result(1);
    ASSERT_TRUE(exact.measured && mc.measured);
    double noise = c.referenceNoise();
    ASSERT_TRUE(std::isfinite(noise) && noise > 0.0);
    // Against a noisy reference an exact image errs by the reference's noise alone, so the raw
    // error is that noise (the estimate's 20 % spread, as above) and the corrected one is small.
    EXPECT_NEAR(exact.rawRelRmse / noise, 1.0, 0.2);
    EXPECT_LT(exact.latest.relRmse, 0.7 * exact.rawRelRmse);
    // The 16-spp image's own noise is that of 128 spp times sqrt(128 / 16); the reference's
    // removed, what is left is it (20 % again, plus the correction's own spread).
    EXPECT_NEAR(mc.latest.relRmse / (noise * std::sqrt(8.0)), 1.0, 0.25);
    EXPECT_EQ(exact.latest.spp, 0);  // deterministic
    EXPECT_EQ(mc.latest.spp, 16);
    // Delta E follows: the exact image is closer.
    EXPECT_LT(exact.latest.deltaE, mc.latest.deltaE);
}

TEST(Comparison, MixedDeterministicAndProgressiveLuminairesRefineToTheBudget) {
    // A closed-form panel beside a Monte Carlo one in every image: the deterministic one holds
    // its single pass while the other refines, and the pane still reaches its budget and ends.
    test::glContext();
    Scene scene = panelScene();
    std::string second =
        R"({"type": "lambertian-rect", "name": "B", "size": [0.5, 0.5], "radiance": [4, 4, 4],
                            "position": [-1, 2, 0.5], "technique": "reference"})";
    scene.luminaires.push_back(
        parseLuminaire(nlohmann::json::parse(second), {"test.json", "luminaires[1]"}));
    ShaderLibrary shaders;
    Comparison c(shaders);
    c.configure({{"", 32}}, shared(), 32);
    c.update(scene, kChangeAll);
    runToEnd(c);
    EXPECT_EQ(c.result(0).spp, 32);
    EXPECT_EQ(c.result(0).series.size(), 4u);  // passes 1, 2, 4, 8 of 4 spp
    EXPECT_EQ(c.referenceSpp(), 32);
}

TEST(Comparison, MeasuresAtDoublingSamplesWithGrowingTime) {
    test::glContext();
    Scene scene = panelScene();
    ShaderLibrary shaders;
    Comparison c(shaders);
    c.configure({{"reference", 32}}, shared(), 32);
    c.update(scene, kChangeAll);
    runToEnd(c);
    const std::vector<ErrorPoint>& series = c.result(0).series;
    ASSERT_EQ(series.size(), 4u);  // 4 spp per pass: passes 1, 2, 4, 8
    const int spp[] = {4, 8, 16, 32};
    for (size_t i = 0; i < series.size(); ++i) {
        EXPECT_EQ(series[i].spp, spp[i]);
        if (i > 0) {
            EXPECT_GT(series[i].timeMs, series[i - 1].timeMs);
            // Monte Carlo: the error falls with more samples (1/sqrt(2) per doubling; its spread
            // at 64x48 is far smaller than the 30 % of a step).
            EXPECT_LT(series[i].relRmse, series[i - 1].relRmse);
        }
    }
    // A changed pane restarts, the other settings do not.
    c.configure({{"reference", 32}}, shared(), 32);
    EXPECT_TRUE(c.result(0).done);
    c.configure({{"reference", 16}}, shared(), 32);
    EXPECT_FALSE(c.result(0).done);
    EXPECT_TRUE(c.result(0).series.empty());
}

TEST(Comparison, ErrorMapSignAndRowsFollowThePixels) {
    test::glContext();
    Scene scene = panelScene();
    ShaderLibrary shaders;
    Comparison c(shaders);
    c.configure({{"reference", 4}}, shared(), 64);
    c.setErrorScale(0.05f);
    c.update(scene, kChangeAll);
    runToEnd(c);
    std::vector<float> pane = c.paneRenderer(0).readLinear();
    std::vector<float> ref = c.referenceRenderer().readLinear();
    const std::vector<unsigned char>& map = c.errorImage(0);
    ASSERT_EQ(map.size(), ref.size());
    double scale = 0.05 * c.toneAverage();
    int checked = 0;
    for (size_t i = 0; i < ref.size(); i += 3) {
        double e = (luma(&pane[i]) - luma(&ref[i])) / scale;
        if (std::abs(e) < 0.2) continue;  // too close to 0 for the colour to tell
        ++checked;
        // Above the reference: orange (red over blue); below: blue.
        if (e > 0)
            EXPECT_GT(map[i], map[i + 2]) << "pixel " << i / 3;
        else
            EXPECT_GT(map[i + 2], map[i]) << "pixel " << i / 3;
    }
    EXPECT_GT(checked, 100);  // 4 spp against 64: most lit pixels differ by more than that
    // The texture holds the same image, bottom row first.
    const gl::Texture2D& tex = c.errorMap(0);
    ASSERT_EQ(tex.width(), 64);
    std::vector<unsigned char> rgba(size_t(64) * 48 * 4);
    glGetTextureImage(tex.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(rgba.size()), rgba.data());
    for (int k = 0; k < 3; ++k)
        EXPECT_EQ(rgba[size_t(47 * 64 + 5) * 4 + size_t(k)], map[5 * 3 + size_t(k)]);
}

TEST(Comparison, EmitterPixelsAreLeftOutOfTheRelativeRmse) {
    test::glContext();
    // The camera under the panel looking up: its emitting face fills the middle of the image.
    Scene scene = panelScene();
    scene.camera = {glm::dvec3(0.2, 1.0, -0.8), glm::dvec3(0.2, 2.5, -0.3), 60.0};
    ShaderLibrary shaders;
    Renderer r(shaders);
    r.setSettings(shared());
    r.update(scene, kChangeAll);
    r.renderFrame();
    std::vector<unsigned char> mask = r.readEmitterMask();
    ASSERT_EQ(mask.size(), size_t(64 * 48));
    EXPECT_EQ(mask[size_t(24 * 64 + 32)], 1);  // the centre sees the panel
    EXPECT_EQ(mask[0], 0);                     // a corner sees the dark beyond it
    // Closed form on three pixels: the skipped one would dominate both sums.
    std::vector<float> x = {1, 1, 1, 2, 2, 2, 1000, 1000, 1000},
                       ref = {1, 1, 1, 1, 1, 1, 1000, 1000, 1000};
    EXPECT_NEAR(relRmse(x, ref, {0, 0, 1}), std::sqrt(1.0 / 2.0), 1e-12);
    EXPECT_NEAR(relRmse(x, ref), std::sqrt(1.0 / (2.0 + 1e6)), 1e-12);
}

TEST(Comparison, MeasuredErrorsAreThoseOfTheImagesShown) {
    test::glContext();
    Scene scene = panelScene();
    ShaderLibrary shaders;
    Comparison c(shaders);
    // The exact pane finishes in its first pass; the reference keeps refining after that, and
    // its later images must be the ones the pane is measured against.
    c.configure({{"analytic", 4}, {"reference", 64}}, shared(), 64);
    c.update(scene, kChangeAll);
    for (int steps : {3, 7, 100}) {
        for (int i = 0; i < steps && !c.done(); ++i) c.step(0.0);
        c.measureNow();
        const std::vector<float>& ref = c.referenceImage();
        for (size_t p = 0; p < 2; ++p) {
            const PaneResult& r = c.result(p);
            ASSERT_TRUE(r.measured);
            // Recomputed from the images themselves (double CIELAB per pixel here, cached float
            // CIELAB there: 1e-4 of a Delta E covers the float rounding).
            EXPECT_NEAR(r.latest.deltaE,
                        meanDeltaE(c.toneMapped(c.paneImage(p)), c.toneMapped(ref)), 1e-4)
                << "pane " << p << " after " << steps << " steps";
            EXPECT_NEAR(r.rawRelRmse, relRmse(c.paneImage(p), ref), 1e-9)
                << "pane " << p;  // no emitter in view
            EXPECT_EQ(r.series.back().deltaE, r.latest.deltaE);
        }
    }
}

TEST(Comparison, CpuToneMapMatchesTheRenderers) {
    test::glContext();
    Scene scene = panelScene();
    ShaderLibrary shaders;
    Renderer r(shaders);
    for (ToneMapOperator op : {ToneMapOperator::Exponential, ToneMapOperator::Reinhard}) {
        RenderSettings s = shared();
        s.toneMap = op;
        s.exposure = 1.7f;
        s.fixedAverage = 0.37f;
        r.setSettings(s);
        r.update(scene, kChangeAll);
        r.renderFrame();
        std::vector<unsigned char> cpu =
            toneMapSrgb8(r.readLinear(), 0.37, 1.7, op == ToneMapOperator::Reinhard);
        std::vector<unsigned char> gpu = r.readDisplay();
        ASSERT_EQ(cpu.size(), gpu.size());
        int worst = 0;
        for (size_t i = 0; i < cpu.size(); ++i)
            worst = std::max(worst, std::abs(int(cpu[i]) - int(gpu[i])));
        // One 8-bit step: float pow/exp on the GPU against double on the CPU, then rounding.
        EXPECT_LE(worst, 1) << int(op);
    }
}

}  // namespace
}  // namespace candela
