// Luminaire bodies (issue 21, part 2): a GLDF variant's L3D geometry becomes one mesh of the
// scene (Scene::updateBodies), placed at the luminaire's pose, drawn and casting shadows on every
// other light while its own openings' light passes (scene/Scene.h: insideBody). Checked against
// the L3D's own triangles and bounds, against the same scene with "body": false (the luminaire's
// own light must not change, sample for sample), against the closed form of a small source whose
// light the body blocks completely, and through both CPU visibility paths (Embree and the BVH).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "calculation/CalculationGrid.h"
#include "formats/L3d.h"
#include "luminaires/Registry.h"
#include "luminaires/lambertian/LambertianRect.h"
#include "luminaires/photometric/PhotometricLuminaire.h"
#include "scene/Bvh.h"
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
    ASSERT_NE(photometricModel(*scene.luminaires[0]), nullptr);
    const PhotometricLuminaire& lamp = *photometricModel(*scene.luminaires[0]);
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
    const TechniqueInfo* analytic = findTechnique(LuminaireKind::LambertianRect, "analytic");
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

// --- The luminous box: a photometric file's body without L3D geometry ----------------------------

/// A closed 4 x 4 x 3 m room (ceiling 0.7, walls 0.5, floor 0.2) with the up-and-down box
/// luminaire (0.45 x 0.45 x 0.07 m) hung at 2.2 m, its body as `body` says, and optionally the
/// 4 x 4 cm panel of 1000 cd/m2 at 2.9 m right above it.
Scene boxRoom(bool body, bool panel = false, double reflectance = 0.0) {
    nlohmann::json doc = nlohmann::json::parse(R"({"geometry": [
        {"plane": {"center": [0, 0, 0], "normal": [0, 1, 0], "size": [4, 4]}, "albedo": [0.2, 0.2, 0.2]},
        {"plane": {"center": [0, 3, 0], "normal": [0, -1, 0], "size": [4, 4]}, "albedo": [0.7, 0.7, 0.7]},
        {"plane": {"center": [2, 1.5, 0], "normal": [-1, 0, 0], "size": [4, 3]}, "albedo": [0.5, 0.5, 0.5]},
        {"plane": {"center": [-2, 1.5, 0], "normal": [1, 0, 0], "size": [4, 3]}, "albedo": [0.5, 0.5, 0.5]},
        {"plane": {"center": [0, 1.5, 2], "normal": [0, 0, -1], "size": [4, 3]}, "albedo": [0.5, 0.5, 0.5]},
        {"plane": {"center": [0, 1.5, -2], "normal": [0, 0, 1], "size": [4, 3]}, "albedo": [0.5, 0.5, 0.5]}]})");
    nlohmann::json lamp = {{"type", "photometric"},
                           {"name", "Box"},
                           {"file", test::dataDir() + "/photometric/up-down-box.ies"},
                           {"position", {0, 2.2, 0}},
                           {"aim", {0, -1, 0}},
                           {"c0", {1, 0, 0}}};
    if (!body) lamp["body"] = false;
    if (reflectance > 0.0) lamp["body_reflectance"] = reflectance;
    doc["luminaires"] = {lamp};
    if (panel)
        doc["luminaires"].push_back(nlohmann::json::parse(
            R"({"type": "lambertian-rect", "name": "Panel", "size": [0.04, 0.04],
                "luminance": [1000, 1000, 1000], "position": [0, 2.9, 0], "aim": [0, -1, 0],
                "technique": "analytic"})"));
    return parseScene(doc, test::dataDir() + "/box-room.json");
}

TEST(LuminaireBody, APhotometryWithoutGeometryHasItsLuminousBox) {
    Scene scene = boxRoom(true);
    ASSERT_EQ(scene.bodyCount(), 1u);
    const Mesh* b = body(scene);
    ASSERT_NE(b, nullptr);
    // The file's 0.45 x 0.45 x 0.07 m, centred on the opening at 2.2 m.
    glm::dvec3 wantLo(-0.225, 2.2 - 0.035, -0.225), wantHi(0.225, 2.2 + 0.035, 0.225);
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(b->boundsMin[i], wantLo[i], 1e-6) << i;
        EXPECT_NEAR(b->boundsMax[i], wantHi[i], 1e-6) << i;
    }
    EXPECT_EQ(b->triangleCount(), 12u);  // two squares and four sides
    // Every face's normal points out of the box.
    glm::vec3 mid = 0.5f * (b->boundsMin + b->boundsMax);
    for (size_t t = 0; t < b->indices.size(); t += 3) {
        glm::vec3 centroid = (b->positions[b->indices[t]] + b->positions[b->indices[t + 1]] +
                              b->positions[b->indices[t + 2]]) /
                             3.f;
        EXPECT_GT(glm::dot(b->normals[b->indices[t]], centroid - mid), 0.f) << t / 3;
    }
    EXPECT_TRUE(b->hidden);  // the camera sees the opening's light, not the box
    EXPECT_EQ(scene.materials[b->material].albedo, glm::vec3(0.f));  // black
    for (const glm::dvec3& p : scene.luminaires[0]->outline())
        EXPECT_TRUE(insideBody(p, glm::dvec3(b->boundsMin), glm::dvec3(b->boundsMax)));
    EXPECT_EQ(boxRoom(false).bodyCount(), 0u);
    // A reflectance from the entry, saved with it; "body": false saved too.
    Scene grey = boxRoom(true, false, 0.6);
    EXPECT_FLOAT_EQ(grey.materials[body(grey)->material].albedo.x, 0.6f);
    EXPECT_EQ(sceneToJson(grey)["luminaires"][0]["body_reflectance"], 0.6);
    EXPECT_EQ(sceneToJson(boxRoom(false))["luminaires"][0]["body"], false);
    EXPECT_NE(scene.bodiesNote().find("1 luminous box, opaque and black"), std::string::npos);
    // A flat opening is its polygon; a point source has no body.
    nlohmann::json doc = sceneToJson(scene);
    doc["luminaires"][0]["file"] = test::dataDir() + "/photometric/spot.ies";
    Scene flat = parseScene(doc, scene.path);
    const Mesh* f = body(flat);
    ASSERT_NE(f, nullptr);
    EXPECT_NEAR(f->boundsMin.y, 2.2, 1e-6);
    EXPECT_NEAR(f->boundsMax.y, 2.2, 1e-6);
    doc["luminaires"][0]["file"] =
        test::dataDir() + "/photometry/ies/photometric-viewer/ies95/point_opening.ies";
    EXPECT_EQ(parseScene(doc, scene.path).bodyCount(), 0u);
}

TEST(LuminaireBody, ALuminousBoxShadowsOtherLightButNotItsOwn) {
    // The panel 0.7 m above the 0.45 m box: from the floor right below, every line to it passes
    // through the box (Embree and the BVH); without the box, the point law within 1e-3.
    const TechniqueInfo* analytic = findTechnique(LuminaireKind::LambertianRect, "analytic");
    for (bool withBody : {true, false}) {
        Scene scene = boxRoom(withBody, true);
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
    // The box's own light, up and down, sample for sample the same with and without it.
    GridSpec how;
    how.technique = "reference";
    how.spp = 256;
    how.visibility = true;
    std::vector<Receiver> points = {
        {{0, 0, 0}, {0, 1, 0}}, {{0.5, 2.99, 0.1}, {0, -1, 0}}, {{1.99, 2.2, 0}, {-1, 0, 0}}};
    ReceiverResult with = computeReceivers(boxRoom(true), how, points);
    ReceiverResult without = computeReceivers(boxRoom(false), how, points);
    for (size_t k = 0; k < points.size(); ++k) {
        EXPECT_GT(without.direct[k], 0.0) << k;
        EXPECT_EQ(with.direct[k], without.direct[k]) << k;
    }
}

TEST(LuminaireBody, ALuminousBoxAbsorbsReflectedLight) {
    // Interreflected light on the floor and the ceiling above the box: the black box takes its
    // share of the light going round the room, and shades the ceiling above it from the floor's.
    GridSpec how;
    how.technique = "adaptive";
    how.spp = 4;
    how.visibility = true;
    how.indirect = true;
    how.indirectMethod = GridSpec::Indirect::Patches;  // deterministic: differences are real
    std::vector<Receiver> points = {{{0.5, 0.75, 0.5}, {0, 1, 0}}, {{0, 2.99, 0}, {0, -1, 0}}};
    ReceiverResult with = computeReceivers(boxRoom(true), how, points);
    ReceiverResult without = computeReceivers(boxRoom(false), how, points);
    ReceiverResult grey = computeReceivers(boxRoom(true, false, 0.6), how, points);
    // On the work plane: the box is 0.7 % of the room's surface but sits where the light is
    // brightest, black where the ceiling reflects 0.7: some 4 % less.
    EXPECT_LT(with.indirect[0], 0.99 * without.indirect[0]);
    EXPECT_GT(with.indirect[0], 0.8 * without.indirect[0]);
    // Right above it, the ceiling sees the black box where it saw the floor: the box's form
    // factor from there (0.45 m square 0.755 m away: about 0.09) of its light is gone.
    EXPECT_LT(with.indirect[1], 0.95 * without.indirect[1]);
    // A reflecting housing gives some of it back.
    EXPECT_GT(grey.indirect[0], with.indirect[0]);
}

}  // namespace
}  // namespace candela
