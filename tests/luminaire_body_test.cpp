// Luminaire bodies (issue 21, part 2): a GLDF variant's L3D geometry becomes one mesh of the
// scene (Scene::updateBodies), placed at the luminaire's pose, drawn and casting shadows on every
// other light while its own openings' light passes (scene/Scene.h: insideBody). Checked against
// the L3D's own triangles and bounds, against the same scene with "body": false (the luminaire's
// own light must not change, sample for sample), against the closed form of a small source whose
// light the body blocks completely, and through both CPU visibility paths (Embree and the BVH).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "luminaires/L3d.h"
#include "luminaires/LambertianRect.h"
#include "luminaires/PhotometricLuminaire.h"
#include "luminaires/Registry.h"
#include "scene/Bvh.h"
#include "scene/CalculationGrid.h"
#include "scene/EmbreeVisibility.h"
#include "scene/Occlusion.h"
#include "scene/SceneIo.h"
#include "tests/TestUtil.h"

namespace candela {
namespace {

std::string pendant() {
    return test::dataDir() + "/gldf/PendantTwoEmitters.gldf";
}

/// A floor, the pendant hung from (0, 2.2, 0) (its body from about 1.70 to 1.74 m), and
/// optionally a small Lambertian panel at 2.9 m right above it, facing down.
Scene room(bool body, bool panel = false) {
    nlohmann::json doc = nlohmann::json::parse(R"({"geometry": [
        {"plane": {"center": [0, 0, 0], "normal": [0, 1, 0], "size": [6, 6]}, "albedo": [0.5, 0.5, 0.5]}]})");
    nlohmann::json lamp = {{"type", "gldf"},          {"name", "Pendant"}, {"file", pendant()},
                           {"position", {0, 2.2, 0}}, {"aim", {0, -1, 0}}, {"c0", {1, 0, 0}}};
    if (!body) lamp["body"] = false;
    doc["luminaires"] = {lamp};
    if (panel)
        doc["luminaires"].push_back(nlohmann::json::parse(
            R"({"type": "lambertian-rect", "name": "Panel", "size": [0.04, 0.04],
                "luminance": [1000, 1000, 1000], "position": [0, 2.9, 0], "aim": [0, -1, 0],
                "technique": "analytic"})"));
    return parseScene(doc, test::dataDir() + "/body.json");
}

const Mesh* body(const Scene& scene) {
    for (const Mesh& m : scene.meshes)
        if (m.luminaireBody) return &m;
    return nullptr;
}

TEST(LuminaireBody, IsTheL3dGeometryAtThePoseOncePerVariant) {
    Scene scene = room(true);
    ASSERT_EQ(scene.luminaires.size(), 2u);  // the variant's two emitters
    EXPECT_EQ(scene.bodyCount(), 1u);        // and one body for both
    const Mesh* b = body(scene);
    ASSERT_NE(b, nullptr);
    auto& lamp = dynamic_cast<const PhotometricLuminaire&>(*scene.luminaires[0]);
    ASSERT_TRUE(lamp.geometry);
    EXPECT_EQ(b->triangleCount(), lamp.geometry->triangleCount());
    // The L3D frame at this pose (aim -y, C0 +x): x stays x, y (C90) is world -z, z is world y.
    glm::dvec3 lo, hi;
    lamp.geometry->bounds(lo, hi);
    glm::dvec3 wantLo(lo.x, 2.2 + lo.z, -hi.y), wantHi(hi.x, 2.2 + hi.z, -lo.y);
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(b->boundsMin[i], wantLo[i], 1e-6) << i;  // float vertices
        EXPECT_NEAR(b->boundsMax[i], wantHi[i], 1e-6) << i;
    }
    // Both openings lie on it: their light is its own.
    for (const auto& l : scene.luminaires)
        for (const glm::dvec3& p : l->outline())
            EXPECT_TRUE(insideBody(p, glm::dvec3(b->boundsMin), glm::dvec3(b->boundsMax)));
    EXPECT_EQ(scene.materials[b->material].name, "luminaire housing");
    // Not saved as geometry; "body": false is, and turns it off.
    nlohmann::json saved = sceneToJson(scene);
    EXPECT_EQ(saved["geometry"].size(), 1u);
    EXPECT_EQ(room(false).bodyCount(), 0u);
    Scene off = room(false);
    EXPECT_EQ(sceneToJson(off)["luminaires"][0]["body"], false);
    // Moved, it follows.
    scene.luminaires[0]->pose.position.x += 1.0;
    scene.luminaires[1]->pose.position.x += 1.0;
    EXPECT_TRUE(scene.updateBodies());
    EXPECT_NEAR(body(scene)->boundsMin.x, wantLo.x + 1.0, 1e-6);
    EXPECT_EQ(scene.bodyCount(), 1u);
}

TEST(LuminaireBody, ItsOwnLightPassesSampleForSample) {
    // The reference with shadow rays, with and without the body: the same samples, and the body
    // must block none of them (it encloses both openings). Points below, beside and above it.
    GridSpec how;
    how.technique = "reference";
    how.spp = 512;
    how.visibility = true;
    std::vector<Receiver> points = {{{0, 0, 0}, {0, 1, 0}},
                                    {{0.3, 0.8, 0.1}, {0, 1, 0}},
                                    {{0.4, 1.72, 0}, {-1, 0, 0}},
                                    {{0, 2.99, 0}, {0, -1, 0}},
                                    {{1, 2.99, 0.2}, {0, -1, 0}}};
    ReceiverResult with = computeReceivers(room(true), how, points);
    ReceiverResult without = computeReceivers(room(false), how, points);
    for (size_t k = 0; k < points.size(); ++k) {
        EXPECT_GT(without.E[k], 0.0) << k;
        EXPECT_EQ(with.E[k], without.E[k]) << k;
    }
}

TEST(LuminaireBody, ItShadowsOtherLightCompletely) {
    // The 4 x 4 cm panel 0.7 m above the 0.17 m wide body: from the floor right below, every
    // line to the panel passes through the body. Without it, the panel's light there is the
    // point law L A / d^2 within 1e-3 (the panel is 2.9 m away and 4 cm wide).
    const TechniqueInfo* analytic = findTechnique("lambertian-rect", "analytic");
    ASSERT_NE(analytic, nullptr);
    for (bool withBody : {true, false}) {
        Scene scene = room(withBody, true);
        EmbreeVisibility embree(scene);
        Bvh bvh = Bvh::build(scene);
        BvhVisibility rays(bvh);
        for (const Visibility* v :
             {static_cast<const Visibility*>(&embree), static_cast<const Visibility*>(&rays)}) {
            EstimateOptions o;
            o.spp = 256;
            o.visibility = v;
            Estimate e = analytic->irradiance(*scene.luminaires.back(), {0, 0, 0}, {0, 1, 0}, o);
            double pointLaw = 1000.0 * 0.04 * 0.04 / (2.9 * 2.9);
            if (withBody)
                EXPECT_EQ(e.irradiance.y, 0.0);
            else
                EXPECT_NEAR(e.irradiance.y, pointLaw, 1e-3 * pointLaw);
        }
    }
}

TEST(LuminaireBody, OnlyLightLeavingItsBoundsIsShadowed) {
    // A vertical segment through the body: towards a light point on its top face it passes
    // (the light is the body's own); towards a point above the body, or between two surface
    // points (interreflection), the body blocks it.
    Scene scene = room(true);
    const Mesh* b = body(scene);
    ASSERT_NE(b, nullptr);
    double top = b->boundsMax.y, bottom = b->boundsMin.y;
    glm::dvec3 below(0, bottom - 0.5, 0), onTop(0, top, 0), above(0, top + 0.5, 0);
    EmbreeVisibility embree(scene);
    Bvh bvh = Bvh::build(scene);
    BvhVisibility rays(bvh);
    for (const Visibility* v :
         {static_cast<const Visibility*>(&embree), static_cast<const Visibility*>(&rays)}) {
        EXPECT_TRUE(v->visible(below, onTop));
        EXPECT_FALSE(v->visible(below, above));
        EXPECT_FALSE(v->visibleBetweenSurfaces(below, onTop));
        EXPECT_FALSE(v->visibleToward(below, {0, 1, 0}));  // daylight from above
    }
}

TEST(LuminaireBody, NeedsNoShadowsForItsOwnLight) {
    // A pendant over a floor: planes shadow nothing and its own body does not count, so the
    // frame needs no shadow pass (simulate only what the scene calls for); a box beside it does.
    glm::mat4 view = glm::mat4(1.f);  // identity: everything near the origin is in view
    Scene scene = room(true);
    for (bool needs : luminairesNeedingShadows(scene, view)) EXPECT_FALSE(needs);
    nlohmann::json doc = sceneToJson(scene);
    doc["geometry"].push_back(
        nlohmann::json::parse(R"({"box": {"center": [0.5, 0.4, 0], "size": [0.3, 0.8, 0.3]}})"));
    Scene boxed = parseScene(doc, scene.path);
    EXPECT_TRUE(luminairesNeedingShadows(boxed, view)[0]);
}

}  // namespace
}  // namespace candela
