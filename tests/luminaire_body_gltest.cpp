// Luminaire bodies on the GPU (issue 21, part 2): the body a GLDF variant's L3D gives is in the
// BVH the shadow rays trace and in the shadow maps, and casts no shadow on its own openings'
// light (shaders/bvh_traverse.glsl, renderer/passes/ShadowMapPass: the rule of
// scene/Scene.h insideBody). Illuminance images of a floor seen from below the pendant, rendered
// with the same seed with and without the body ("body": false), so that they differ only in
// visibility.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "renderer/Renderer.h"
#include "renderer/ShaderLibrary.h"
#include "scene/SceneIo.h"
#include "tests/TestUtil.h"

namespace candela {
namespace {

/// A floor with a box on it (so that the frame traces shadows at all: a floor alone shadows
/// nothing), the pendant at (0, 2.2, 0) (its body about 1.70 to 1.74 m up) and, with `panel`, a
/// small bright panel at 2.9 m right above it; the camera below the body, looking at the floor.
Scene pendantRoom(bool body, bool panel) {
    nlohmann::json doc = nlohmann::json::parse(R"({"geometry": [
        {"plane": {"center": [0, 0, 0], "normal": [0, 1, 0], "size": [6, 6]}, "albedo": [0.5, 0.5, 0.5]},
        {"box": {"center": [-1.2, 0.2, -1.0], "size": [0.3, 0.4, 0.3]}}],
        "camera": {"position": [0, 1.2, 1.2], "target": [0, 0, 0], "fov_deg": 60}})");
    nlohmann::json lamp = {{"type", "gldf"},
                           {"name", "Pendant"},
                           {"file", test::dataDir() + "/gldf/PendantTwoEmitters.gldf"},
                           {"position", {0, 2.2, 0}},
                           {"aim", {0, -1, 0}},
                           {"c0", {1, 0, 0}}};
    if (!body) lamp["body"] = false;
    doc["luminaires"] = {lamp};
    if (panel)
        doc["luminaires"].push_back(nlohmann::json::parse(
            R"({"type": "lambertian-rect", "name": "Panel", "size": [0.04, 0.04],
                "luminance": [1e6, 1e6, 1e6], "position": [0, 2.9, 0], "aim": [0, -1, 0]})"));
    return parseScene(doc, test::dataDir() + "/body.json");
}

std::vector<float> illuminance(Renderer& renderer, const Scene& scene, const std::string& technique,
                               int spp) {
    RenderSettings s;
    s.width = 96;
    s.height = 64;
    s.samplesPerFrame = std::min(spp, 16);
    s.maxSamples = spp;
    s.seed = 5;
    s.quantity = Quantity::Illuminance;
    s.techniqueOverride = technique;
    return test::renderConverged(renderer, scene, s);
}

class LuminaireBodyGl : public ::testing::Test {
  protected:
    GlContext& context = test::glContext();
    ShaderLibrary shaders;
    Renderer renderer{shaders};
};

TEST_F(LuminaireBodyGl, ItsOwnLightIsTheSameWithShadowRaysAndShadowMaps) {
    // "reference" traces a ray per sample through the BVH; "adaptive" reads the shadow maps. The
    // same samples with and without the body: equal to float rounding (1e-5).
    for (const char* technique : {"reference", "adaptive"}) {
        std::vector<float> with = illuminance(renderer, pendantRoom(true, false), technique, 64);
        std::vector<float> without =
            illuminance(renderer, pendantRoom(false, false), technique, 64);
        ASSERT_EQ(with.size(), without.size());
        size_t lit = 0, differ = 0;
        for (size_t i = 1; i < with.size(); i += 3) {
            if (!(without[i] > 0.f)) continue;
            ++lit;
            differ += std::abs(with[i] - without[i]) > 1e-5f * without[i];
        }
        std::printf("%s: %zu lit pixels, %zu differ\n", technique, lit, differ);
        // The frame did trace shadows (rays or maps), so the body was there to be left out.
        const auto& defines = renderer.plan().shading[0].program.defines;
        EXPECT_TRUE(std::find(defines.begin(), defines.end(),
                              std::string(technique) == "adaptive" ? "SHADOW_MAPS" : "SHADOWS") !=
                    defines.end())
            << technique;
        EXPECT_GT(lit, with.size() / 3 / 2) << technique;
        EXPECT_EQ(differ, 0u) << technique;
    }
}

TEST_F(LuminaireBodyGl, ItShadowsAnotherLuminairesLight) {
    // The panel's light through the body: under the pendant the floor loses it (the panel's
    // 1e6 cd/m2 x 16 cm2 / 2.9^2 m2 = 190 lx at the centre, all of it blocked there), and
    // nothing gains. The rays' penumbra is the umbra's few pixels of blur.
    std::vector<float> with = illuminance(renderer, pendantRoom(true, true), "reference", 64);
    std::vector<float> without = illuminance(renderer, pendantRoom(false, true), "reference", 64);
    ASSERT_EQ(with.size(), without.size());
    size_t shadowed = 0, gained = 0;
    double lost = 0.0, most = 0.0;
    for (size_t i = 1; i < with.size(); i += 3) {
        double d = double(without[i]) - double(with[i]);
        gained += d < -1e-4 * without[i];
        if (d > 1.0) ++shadowed;  // lx
        lost += std::max(d, 0.0);
        most = std::max(most, d);
    }
    std::printf("panel: %zu pixels shadowed, most lost %.1f lx, none gained: %zu\n", shadowed, most,
                gained);
    EXPECT_EQ(gained, 0u);
    EXPECT_GT(shadowed, 20u);
    // Right under the body the whole panel is hidden: up to its full 190 lx (point law, 1e-3).
    EXPECT_NEAR(most, 190.3, 5.0);
}

/// The up-and-down box luminaire (0.45 x 0.45 x 0.07 m) at 2.2 m over a floor with a box on it,
/// its luminous box as its body or not, and optionally the 4 x 4 cm panel of 1e6 cd/m2 at 2.9 m
/// right above it; the camera below, looking up at the luminaire and the floor beyond.
Scene boxLuminaireRoom(bool body, bool panel, bool lookUp) {
    nlohmann::json doc = nlohmann::json::parse(R"({"geometry": [
        {"plane": {"center": [0, 0, 0], "normal": [0, 1, 0], "size": [6, 6]}, "albedo": [0.5, 0.5, 0.5]},
        {"box": {"center": [-1.2, 0.2, -1.0], "size": [0.3, 0.4, 0.3]}}]})");
    doc["camera"] =
        lookUp ? nlohmann::json::parse(
                     R"({"position": [0, 1.0, 0.6], "target": [0, 2.2, 0], "fov_deg": 40})")
               : nlohmann::json::parse(
                     R"({"position": [0, 1.2, 1.2], "target": [0, 0, 0], "fov_deg": 60})");
    nlohmann::json lamp = {{"type", "photometric"},
                           {"name", "Box"},
                           {"file", test::dataDir() + "/photometric/up-down-box.ies"},
                           {"position", {0, 2.2, 0}},
                           {"aim", {0, -1, 0}},
                           {"c0", {1, 0, 0}}};
    if (!body) lamp["body"] = false;
    doc["luminaires"] = {lamp};
    if (panel)
        doc["luminaires"].push_back(nlohmann::json::parse(
            R"({"type": "lambertian-rect", "name": "Panel", "size": [0.04, 0.04],
                "luminance": [1e6, 1e6, 1e6], "position": [0, 2.9, 0], "aim": [0, -1, 0]})"));
    return parseScene(doc, test::dataDir() + "/box-luminaire.json");
}

TEST_F(LuminaireBodyGl, ALuminousBoxIsSeenThroughAndShadowsOtherLight) {
    // Seen from below, the luminaire looks the same with its box (hidden from the camera: the
    // opening's light shows, not a black box): radiance images equal to float rounding.
    RenderSettings s;
    s.width = 64;
    s.height = 48;
    s.samplesPerFrame = 4;
    s.maxSamples = 4;
    s.seed = 3;
    std::vector<float> with =
        test::renderConverged(renderer, boxLuminaireRoom(true, false, true), s);
    std::vector<float> without =
        test::renderConverged(renderer, boxLuminaireRoom(false, false, true), s);
    ASSERT_EQ(with.size(), without.size());
    double brightest = 0.0;
    size_t differ = 0;
    for (size_t i = 0; i < with.size(); ++i) {
        brightest = std::max(brightest, double(without[i]));
        differ += std::abs(with[i] - without[i]) > 1e-4f * std::max(1.f, without[i]);
    }
    EXPECT_EQ(differ, 0u);
    EXPECT_GT(brightest, 100.0);  // the opening is in view
    // The panel's light through the box on the floor below, with the box's own light read from
    // shadow maps (adaptive) and the panel's by shadow rays: lost right under it, none gained.
    std::vector<float> shadowed =
        illuminance(renderer, boxLuminaireRoom(true, true, false), "", 16);
    std::vector<float> open = illuminance(renderer, boxLuminaireRoom(false, true, false), "", 16);
    ASSERT_EQ(shadowed.size(), open.size());
    double most = 0.0;
    size_t gained = 0;
    for (size_t i = 1; i < open.size(); i += 3) {
        double d = double(open[i]) - double(shadowed[i]);
        gained += d < -1e-3 * open[i] - 1e-3;
        most = std::max(most, d);
    }
    EXPECT_EQ(gained, 0u);
    // Under the box the whole panel is hidden: its 190 lx (1e6 cd/m2 x 16 cm2 / 2.9^2 m2).
    EXPECT_NEAR(most, 190.3, 5.0);
}

}  // namespace
}  // namespace candela
