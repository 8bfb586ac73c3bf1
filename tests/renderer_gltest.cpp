// The renderer end to end under OSMesa: which passes run (frame statistics), pixel radiance
// against the CPU closed form, the GPU probe against the CPU probe, and no NaN in hard cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "luminaires/lambertian/LambertianRect.h"
#include "renderer/Renderer.h"
#include "renderer/context/GlContext.h"
#include "scene/SceneIo.h"
#include "tests/TestUtil.h"

namespace candela {
namespace {

Scene sceneFrom(const std::string& geometry, const std::string& luminaires,
                const std::string& camera =
                    R"({"position": [0, 1.5, 4], "target": [0, 0.5, 0], "fov_deg": 50})") {
    std::string text = R"({"geometry": [)" + geometry + R"(], "luminaires": [)" + luminaires +
                       R"(], "camera": )" + camera + "}";
    return parseScene(nlohmann::json::parse(text), "test.json");
}

const std::string kFloor =
    R"({"plane": {"center": [0,0,0], "normal": [0,1,0], "size": [6,6]}, "albedo": [0.5,0.6,0.7]})";
const std::string kTable =
    R"({"box": {"center": [0,0.7,0], "size": [1,0.05,1]}, "albedo": [0.5,0.4,0.3]})";
const std::string kPanel =
    R"({"type": "lambertian-rect", "name": "Panel", "size": [1, 0.5], "radiance": [10, 10, 10], "position": [0.2,2.5,-0.3], "aim": [0.1,-1,0], "technique": "analytic"})";

std::vector<std::string> names(const FrameStats& stats) {
    std::vector<std::string> out;
    for (const auto& p : stats.passes) out.push_back(p.name);
    return out;
}

RenderSettings small() {
    RenderSettings s;
    s.width = 64;
    s.height = 48;
    s.samplesPerFrame = 4;
    s.maxSamples = 8;
    return s;
}

TEST(Renderer, RunsExactlyThePlannedPassesThenNothingOnceConverged) {
    test::glContext();
    Scene scene = sceneFrom(kFloor, kPanel);
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    renderer.setSettings(small());
    renderer.update(scene, kChangeAll);
    renderer.renderFrame();
    EXPECT_EQ(names(renderer.stats()), renderer.plan().passNames());
    EXPECT_TRUE(renderer.converged());  // closed form, no occluder: exact in one frame
    for (const auto& p : renderer.stats().passes) EXPECT_GE(p.gpuMs, 0.0) << p.name;
    renderer.renderFrame();
    EXPECT_TRUE(renderer.stats().passes.empty());
    for (const auto& v : shaders.compiledVariants())
        EXPECT_EQ(v.find("SHADOWS"), std::string::npos) << v;

    scene.camera.position.x += 0.5;  // a camera move re-renders the G-buffer and restarts
    renderer.update(scene, kChangeCamera);
    renderer.renderFrame();
    EXPECT_EQ(names(renderer.stats()).front(), "gbuffer");
}

TEST(Renderer, OccludedSceneTracesShadowsProgressively) {
    test::glContext();
    Scene scene = sceneFrom(kFloor + "," + kTable, kPanel);
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    renderer.setSettings(small());
    renderer.update(scene, kChangeAll);
    renderer.renderFrame();
    EXPECT_FALSE(renderer.converged());
    renderer.renderFrame();
    // Second frame: no G-buffer, one shading pass, resolve and tone mapping.
    EXPECT_EQ(names(renderer.stats()),
              (std::vector<std::string>{"shade:Panel:analytic", "resolve", "tonemap"}));
    EXPECT_TRUE(renderer.converged());  // maxSamples = 8 at 4 per frame
    auto variants = shaders.compiledVariants();
    EXPECT_TRUE(std::find(variants.begin(), variants.end(),
                          "lambertian_rect_analytic.frag[SHADOWS]") != variants.end());
}

TEST(Renderer, BandedRefinementGivesTheSameImageAndShowsOnlyWholePasses) {
    // The editor shades a pass in bands that fit its frame budget (RenderSettings::bandBudgetMs).
    // Each pixel's random numbers depend on the pixel and the pass only, so the banded image must
    // equal the whole-pass image exactly, and between passes the shown image must not change.
    test::glContext();
    Scene scene = sceneFrom(kFloor + "," + kTable, kPanel);
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    RenderSettings whole = small();
    whole.maxSamples = 12;  // three passes of 4
    renderer.setSettings(whole);
    renderer.update(scene, kChangeAll);
    do renderer.renderFrame();
    while (!renderer.converged());
    std::vector<float> expected = renderer.readLinear();

    RenderSettings banded = whole;
    banded.bandRows = 1;  // one row per call
    renderer.setSettings(banded);
    renderer.update(scene, kChangeAll);
    int calls = 0;
    std::vector<float> shownAfterPass1;
    do {
        renderer.renderFrame();
        ++calls;
        if (renderer.stats().accumulatedFrames == 1 && shownAfterPass1.empty())
            shownAfterPass1 = renderer.readLinear();
        if (renderer.stats().accumulatedFrames == 1 && !renderer.stats().passes.empty()) {
            // Mid-way through pass 2: still pass 1's image.
            ASSERT_EQ(renderer.readLinear(), shownAfterPass1) << "call " << calls;
        }
    } while (!renderer.converged() && calls < 10000);
    ASSERT_TRUE(renderer.converged());
    // One row per call, three passes.
    EXPECT_GE(calls, 3 * whole.height);
    std::vector<float> got = renderer.readLinear();
    ASSERT_EQ(got.size(), expected.size());
    size_t differ = 0;
    for (size_t i = 0; i < got.size(); ++i) differ += got[i] != expected[i];
    EXPECT_EQ(differ, 0u);
}

/// Two panels for the per-luminaire tests: A low and closed-form (deterministic), B Monte Carlo.
const std::string kLowPanelA =
    R"({"type": "lambertian-rect", "name": "A", "size": [0.6, 0.4], "radiance": [10, 10, 10], "position": [-0.6,1.2,0.5], "aim": [0,-1,0], "technique": "analytic"})";
const std::string kMonteCarloPanelB =
    R"({"type": "lambertian-rect", "name": "B", "size": [1, 0.5], "radiance": [5, 8, 10], "position": [0.8,2.5,-0.3], "technique": "reference"})";

TEST(Renderer, MovingOneLuminaireRefinesOnlyIt) {
    // Two panels over a floor, both in view: A closed form (deterministic), B Monte Carlo. After
    // both converge, A moves (in place, as the editor's drag does): only A is shaded again, and
    // the image equals a fresh render of the moved scene (B's accumulation is kept: the same
    // passes with the same random numbers a fresh render draws). The pixels A covered before now
    // show the floor, lit by both, as the fresh render has them.
    test::glContext();
    const std::string a = kLowPanelA, b = kMonteCarloPanelB;
    const std::string camera =
        R"({"position": [0, 2.5, 3.5], "target": [0, 0.3, 0], "fov_deg": 60})";
    Scene scene = sceneFrom(kFloor, a + "," + b, camera);
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    RenderSettings s = small();
    s.maxSamples = 16;
    renderer.setSettings(s);
    renderer.update(scene, kChangeAll);
    do renderer.renderFrame();
    while (!renderer.converged());
    std::vector<unsigned char> maskBefore = renderer.readEmitterMask();
    scene.luminaires[0]->pose.position = glm::dvec3(0.7, 1.2, 0.9);
    renderer.update(scene, kChangeLuminaires);
    renderer.renderFrame();
    EXPECT_EQ(names(renderer.stats()),
              (std::vector<std::string>{"gbuffer", "shade:A:analytic", "resolve", "tonemap"}));
    EXPECT_TRUE(renderer.converged());
    std::vector<float> moved = renderer.readLinear();
    std::vector<unsigned char> maskAfter = renderer.readEmitterMask();

    Renderer fresh(shaders);
    fresh.setSettings(s);
    fresh.update(scene, kChangeAll);
    do fresh.renderFrame();
    while (!fresh.converged());
    std::vector<float> expected = fresh.readLinear();
    ASSERT_EQ(moved.size(), expected.size());
    double worst = 0.0, peak = 0.0;
    int uncovered = 0;
    for (size_t i = 0; i < moved.size(); ++i) {
        worst = std::max(worst, double(std::abs(moved[i] - expected[i])));
        peak = std::max(peak, double(expected[i]));
    }
    for (size_t p = 0; p < maskBefore.size(); ++p) uncovered += maskBefore[p] && !maskAfter[p];
    int before = 0;
    for (unsigned char m : maskBefore) before += m;
    EXPECT_GT(uncovered, 5) << "A covered " << before
                            << " pixels";  // A's old place is in view, now the floor
    // The same estimates summed in another order: 1e-5 of the brightest pixel.
    EXPECT_LT(worst, 1e-5 * peak) << "largest difference " << worst << " of " << peak;
}

TEST(Renderer, AMovedLuminaireCatchesUpInLargerPasses) {
    // A Monte Carlo panel moves after both panels converged at 24 spp (4 per pass): it alone is
    // shaded, 12 spp in its first pass (RenderSettings::catchUpPasses = 3 passes' worth), then
    // the 12 left. Passes of different sizes are weighted by their samples: the image matches a
    // fresh 24-spp render within the two renders' own noise (measured by two fresh seeds).
    test::glContext();
    const std::string a = kLowPanelA, b = kMonteCarloPanelB;
    Scene scene = sceneFrom(kFloor, a + "," + b);
    ShaderLibrary shaders;
    RenderSettings s = small();
    s.maxSamples = 24;
    auto converge = [&](Renderer& r) {
        do r.renderFrame();
        while (!r.converged());
        return r.readLinear();
    };
    Renderer renderer(shaders);
    renderer.setSettings(s);
    renderer.update(scene, kChangeAll);
    converge(renderer);
    scene.luminaires[1]->pose.position = glm::dvec3(0.2, 2.3, 0.4);
    renderer.update(scene, kChangeLuminaires);
    renderer.renderFrame();
    EXPECT_EQ(names(renderer.stats()),
              (std::vector<std::string>{"gbuffer", "shade:B:reference", "resolve", "tonemap"}));
    EXPECT_EQ(renderer.stats().samplesPerPixel, 12);
    renderer.renderFrame();
    EXPECT_EQ(renderer.stats().samplesPerPixel, 24);
    EXPECT_TRUE(renderer.converged());
    std::vector<float> moved = renderer.readLinear();

    std::vector<std::vector<float>> fresh;
    for (uint32_t seed : {0u, 7u}) {
        Renderer r(shaders);
        RenderSettings f = s;
        f.seed = seed;
        r.setSettings(f);
        r.update(scene, kChangeAll);
        fresh.push_back(converge(r));
    }
    auto rel = [](const std::vector<float>& x, const std::vector<float>& y) {
        double num = 0.0, den = 0.0;
        for (size_t i = 0; i < x.size(); ++i) {
            num += double(x[i] - y[i]) * double(x[i] - y[i]);
            den += double(y[i]) * double(y[i]);
        }
        return std::sqrt(num / den);
    };
    double noise = rel(fresh[0], fresh[1]);  // two independent 24-spp images
    ASSERT_GT(noise, 0.0);
    // Same noise level when the weights are right; a pass counted as one sample (weights 1/2
    // instead of 12/24 each) would still agree, but 1/passes for 24 spp in 2 passes would not.
    EXPECT_LT(rel(moved, fresh[1]), 1.5 * noise) << "noise " << noise;
}

TEST(Renderer, DeterministicStepsOfAProgressiveFrameAreShadedOnce) {
    // A photometric `hybrid` light (deterministic) beside a `reference` panel (Monte Carlo): the
    // hybrid step runs in the first pass only and the resolve adds it once. The image must equal
    // the panel's own image (the pendant dimmed to 1e-20, same step indices, so the same random
    // numbers) plus the pendant's alone (a non-progressive frame: the ordinary path).
    test::glContext();
    const std::string pendant =
        R"({"type": "photometric", "name": "Pendant", "file": ")" CANDELA_SOURCE_DIR
        R"(/resources/luminaires/photometric/linear-pendant.ies", "position": [-0.5,2.2,0],
                                "technique": "hybrid", "scale": SCALE})";
    auto withScale = [&](const char* scale) {
        std::string p = pendant;
        p.replace(p.find("SCALE"), 5, scale);
        return p;
    };
    const std::string panel =
        R"({"type": "lambertian-rect", "name": "Panel", "size": [1, 0.5], "radiance": [10, 10, 10], "position": [0.8,2.5,-0.3], "technique": "reference"})";
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    RenderSettings s = small();
    s.maxSamples = 12;
    renderer.setSettings(s);
    auto render = [&](const Scene& scene, std::vector<std::string>* passes2) {
        renderer.update(scene, kChangeAll);
        renderer.renderFrame();
        renderer.renderFrame();
        if (passes2) *passes2 = names(renderer.stats());
        while (!renderer.converged()) renderer.renderFrame();
        return renderer.readLinear();
    };
    Scene both = sceneFrom(kFloor, withScale("1.0") + "," + panel);
    Scene panelOnly = sceneFrom(kFloor, withScale("1e-20") + "," + panel);  // scale must be > 0
    Scene pendantOnly = sceneFrom(kFloor, withScale("1.0"));
    std::vector<std::string> second;
    std::vector<float> a = render(both, &second);
    EXPECT_EQ(second, (std::vector<std::string>{"shade:Panel:reference", "resolve", "tonemap"}));
    std::vector<float> b = render(panelOnly, nullptr);
    std::vector<float> c = render(pendantOnly, nullptr);
    ASSERT_EQ(a.size(), b.size());
    double worst = 0.0, peak = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
        worst = std::max(worst, double(std::abs(a[i] - (b[i] + c[i]))));
        peak = std::max(peak, double(a[i]));
    }
    ASSERT_GT(peak, 0.0);
    // Float sums in another order: 1e-5 of the brightest pixel.
    EXPECT_LT(worst, 1e-5 * peak) << "largest difference " << worst << " of " << peak;
}

TEST(Renderer, PixelRadianceMatchesTheClosedForm) {
    test::glContext();
    Scene scene = sceneFrom(kFloor, kPanel);
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    RenderSettings s = small();
    renderer.setSettings(s);
    renderer.update(scene, kChangeAll);
    renderer.renderFrame();
    std::vector<float> rgb = renderer.readLinear();
    glm::dmat4 inv = glm::inverse(glm::dmat4(renderer.viewProj()));
    const Luminaire& light = *scene.luminaires[0];
    ASSERT_NE(lambertianRectModel(light), nullptr);
    int checked = 0;
    for (int y = 0; y < s.height; y += 5)
        for (int x = 0; x < s.width; x += 5) {
            // Ray through the pixel centre (row 0 at the top) meets the floor y = 0.
            double ndcX = (x + 0.5) / s.width * 2.0 - 1.0, ndcY = 1.0 - (y + 0.5) / s.height * 2.0;
            glm::dvec4 a = inv * glm::dvec4(ndcX, ndcY, -1.0, 1.0),
                       b = inv * glm::dvec4(ndcX, ndcY, 1.0, 1.0);
            glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::dvec3(b) / b.w - o;
            if (d.y >= 0.0) continue;
            glm::dvec3 p = o - d * (o.y / d.y);
            if (std::abs(p.x) > 2.9 || std::abs(p.z) > 2.9) continue;
            Estimate e = lambertianRectAnalytic(light, p, {0.0, 1.0, 0.0}, EstimateOptions{});
            glm::dvec3 expected = glm::dvec3(0.5, 0.6, 0.7) / 3.141592653589793 * e.irradiance;
            const float* px = &rgb[(size_t(y) * size_t(s.width) + size_t(x)) * 3];
            for (int c = 0; c < 3; ++c)
                // Float G-buffer positions (~1e-7 m) and float shading: 1e-3 relative is ample.
                EXPECT_NEAR(px[c], expected[c], 1e-3 * expected[c] + 1e-6) << x << "," << y;
            ++checked;
        }
    EXPECT_GT(checked, 20);
}

TEST(Renderer, GpuProbeMatchesCpuProbe) {
    test::glContext();
    Scene scene = sceneFrom(kFloor, kPanel);
    const Luminaire& light = *scene.luminaires[0];
    ASSERT_NE(lambertianRectModel(light), nullptr);
    std::vector<glm::vec3> points, normals;
    for (int i = 0; i < 16; ++i) {
        points.push_back(
            {-1.5f + 0.2f * float(i), 0.1f * float(i % 3), 0.3f - 0.1f * float(i % 5)});
        normals.push_back(glm::normalize(glm::vec3(0.1f * float(i % 4), 1.f, -0.05f * float(i))));
    }
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    renderer.setSettings(small());
    std::vector<glm::vec3> analytic = renderer.probe(scene, points, normals, 1);
    RenderSettings ref = small();
    ref.techniqueOverride = "reference";
    renderer.setSettings(ref);
    std::vector<glm::vec3> reference = renderer.probe(scene, points, normals, 8192);
    for (size_t i = 0; i < points.size(); ++i) {
        Estimate e =
            lambertianRectAnalytic(light, glm::dvec3(points[i]), glm::dvec3(normals[i]), {});
        // Float closed form against double: see lambertian_rect_gltest.
        EXPECT_NEAR(analytic[i].x, e.irradiance.x, 1e-4 * e.irradiance.x + 1e-4) << i;
        // 8192 solid-angle samples: the estimator's relative standard deviation is below
        // 0.3 / sqrt(8192) = 0.33 % for these receivers (cosine varies by < 30 % over the
        // light); 2 % is over 5 sigma.
        EXPECT_NEAR(reference[i].x, e.irradiance.x, 0.02 * e.irradiance.x + 1e-4) << i;
    }
}

TEST(Renderer, ReceiversInTheLightsPlaneStayFinite) {
    test::glContext();
    // A ceiling through the emitter's plane, a wall perpendicular to it touching its edge.
    std::string ceiling =
        R"({"plane": {"center": [0,2.5,0], "normal": [0,-1,0], "size": [6,6]}, "albedo": [0.8,0.8,0.8]})";
    std::string wall =
        R"({"plane": {"center": [0.7,1.5,0], "normal": [-1,0,0], "size": [6,3]}, "albedo": [0.8,0.8,0.8]})";
    std::string light =
        R"({"type": "lambertian-rect", "name": "L", "size": [1, 0.5], "radiance": [1e6, 1e6, 1e6], "position": [0.2,2.5,0], "technique": "reference"})";
    Scene scene =
        sceneFrom(kFloor + "," + ceiling + "," + wall, light,
                  R"({"position": [-2, 1.5, 2.5], "target": [0.5, 2.2, 0], "fov_deg": 70})");
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    renderer.setSettings(small());
    renderer.update(scene, kChangeAll);
    while (!renderer.converged()) renderer.renderFrame();
    std::vector<float> rgb = renderer.readLinear();
    for (float v : rgb) ASSERT_TRUE(std::isfinite(v));
}

TEST(Renderer, AMixedSceneShowsRadiometricLightAt683LumensPerWatt) {
    // The same panel (W/(m2 sr)) alone, and beside a photometric lamp that emits nothing (colour
    // 0): the second scene is mixed, reports lux, and shows the panel's light and emission 683
    // times brighter, in the image and through the GPU probe (float: 1e-5 relative).
    test::glContext();
    Scene alone = sceneFrom(kFloor, kPanel);
    std::string dark =
        R"({"type": "photometric", "name": "Dark", "file": ")" + test::dataDir() +
        R"(/photometric/lambert.ies", "colour": [0, 0, 0], "position": [1, 2, 0], "technique": "point",
            "body": false})";  // no body: it would shadow the panel's light
    Scene mixed = sceneFrom(kFloor, kPanel + "," + dark);
    ASSERT_FALSE(alone.units().converted);
    ASSERT_TRUE(mixed.units().converted);
    ShaderLibrary shaders;
    auto linear = [&](const Scene& scene) {
        Renderer renderer(shaders);
        renderer.setSettings(small());
        renderer.update(scene, kChangeAll);
        do renderer.renderFrame();
        while (!renderer.converged());
        return renderer.readLinear();
    };
    std::vector<float> a = linear(alone), b = linear(mixed);
    ASSERT_EQ(a.size(), b.size());
    float brightest = *std::max_element(a.begin(), a.end());
    ASSERT_GT(brightest, 0.f);
    for (size_t i = 0; i < a.size(); ++i)
        ASSERT_NEAR(b[i], 683.f * a[i], 1e-5f * 683.f * brightest) << "value " << i;
    Renderer renderer(shaders);
    renderer.setSettings(small());
    std::vector<glm::vec3> p = {{0.2f, 0.f, -0.3f}}, n = {{0.f, 1.f, 0.f}};
    float ea = renderer.probe(alone, p, n, 1)[0].y, eb = renderer.probe(mixed, p, n, 1)[0].y;
    EXPECT_GT(ea, 0.f);
    EXPECT_NEAR(eb, 683.f * ea, 1e-5f * 683.f * ea);
}

}  // namespace
}  // namespace candela
