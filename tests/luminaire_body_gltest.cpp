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
    // "reference" traces a ray per sample through the BVH; "hybrid" reads the shadow maps. The
    // same samples with and without the body: equal to float rounding (1e-5).
    for (const char* technique : {"reference", "hybrid"}) {
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
                              std::string(technique) == "hybrid" ? "SHADOW_MAPS" : "SHADOWS") !=
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

}  // namespace
}  // namespace candela
