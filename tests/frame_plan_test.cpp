// The pass list is derived from the scene: only the passes and variants the scene needs.
#include <gtest/gtest.h>

#include <algorithm>

#include "renderer/FramePlan.h"
#include "scene/SceneIo.h"
#include "util/Error.h"

namespace candela {
namespace {

Scene sceneFrom(const std::string& geometry, const std::string& luminaires) {
    std::string text =
        R"({"geometry": [)" + geometry + R"(], "luminaires": [)" + luminaires +
        R"(], "camera": {"position": [0, 1.5, 4], "target": [0, 0.5, 0], "fov_deg": 50}})";
    return parseScene(nlohmann::json::parse(text), "test.json");
}

const std::string kFloor =
    R"({"plane": {"center": [0,0,0], "normal": [0,1,0], "size": [6,6]}, "albedo": [0.5,0.5,0.5]})";
const std::string kTable =
    R"({"box": {"center": [0,0.7,0], "size": [1,0.05,1]}, "albedo": [0.5,0.4,0.3]})";
const std::string kGlossyBox =
    R"({"box": {"center": [2,0.5,0], "size": [0.5,1,0.5]}, "albedo": [0.2,0.2,0.2], "specular": [0.5,0.5,0.5], "roughness": 0.2})";
const std::string kPanel =
    R"({"type": "lambertian-rect", "name": "Panel", "position": [0,2.5,0], "technique": "analytic"})";

glm::mat4 view(const Scene& s) {
    return cameraViewProj(s.camera, 1.0);
}

bool has(const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) != v.end();
}

TEST(FramePlan, FloorAndLightOnlyRunsNoShadowsAndConvergesAtOnce) {
    Scene scene = sceneFrom(kFloor, kPanel);
    FramePlan plan = planFrame(scene, view(scene));
    EXPECT_EQ(plan.passNames(),
              (std::vector<std::string>{"gbuffer", "shade:Panel:analytic", "resolve", "tonemap"}));
    ASSERT_EQ(plan.shading.size(), 1u);
    // The analytic technique's own shader, and no variant (no SHADOWS, no GLOSSY).
    EXPECT_EQ(plan.shading[0].program.fragment, "lambertian_rect_analytic.frag");
    EXPECT_EQ(plan.shading[0].program.defines, std::vector<std::string>{});
    EXPECT_FALSE(plan.needsBvh);
    EXPECT_FALSE(plan.progressive());
}

TEST(FramePlan, TableUnderTheLightTurnsShadowsOn) {
    Scene scene = sceneFrom(kFloor + "," + kTable, kPanel);
    FramePlan plan = planFrame(scene, view(scene));
    ASSERT_EQ(plan.shading.size(), 1u);
    EXPECT_TRUE(has(plan.shading[0].program.defines, "SHADOWS"));
    EXPECT_TRUE(plan.needsBvh);
    EXPECT_TRUE(plan.progressive());
}

TEST(FramePlan, GlossyVariantOnlyWithAGlossyMaterial) {
    Scene plain = sceneFrom(kFloor, kPanel);
    EXPECT_FALSE(has(planFrame(plain, view(plain)).shading[0].program.defines, "GLOSSY"));
    Scene glossy = sceneFrom(kFloor + "," + kGlossyBox, kPanel);
    EXPECT_TRUE(has(planFrame(glossy, view(glossy)).shading[0].program.defines, "GLOSSY"));
}

TEST(FramePlan, NoLuminaireNoShadingPass) {
    Scene scene = sceneFrom(kFloor + "," + kTable, "");
    FramePlan plan = planFrame(scene, view(scene));
    EXPECT_TRUE(plan.shading.empty());
    EXPECT_FALSE(plan.needsBvh);
    EXPECT_EQ(plan.passNames(), (std::vector<std::string>{"gbuffer", "resolve", "tonemap"}));
}

TEST(FramePlan, OneShadingPassPerLuminaireWithItsTechnique) {
    std::string second =
        R"({"type": "lambertian-rect", "name": "Spot", "position": [1,2.5,0], "technique": "reference"})";
    Scene scene = sceneFrom(kFloor, kPanel + "," + second);
    FramePlan plan = planFrame(scene, view(scene));
    EXPECT_EQ(plan.passNames(),
              (std::vector<std::string>{"gbuffer", "shade:Panel:analytic", "shade:Spot:reference",
                                        "resolve", "tonemap"}));
    EXPECT_TRUE(plan.progressive());  // the reference technique refines over frames
    FramePlan overridden = planFrame(scene, view(scene), "reference");
    EXPECT_EQ(overridden.shading[0].name, "shade:Panel:reference");
}

TEST(FramePlan, OverrideListGivesEachKindTheFirstItHas) {
    std::string photometric =
        R"({"type": "photometric", "name": "Pendant", "file": ")" CANDELA_SOURCE_DIR
        R"(/resources/luminaires/photometric/linear-pendant.ies", "position": [1,2.5,0],
                                   "technique": "hybrid"})";
    Scene scene = sceneFrom(kFloor, kPanel + "," + photometric);
    // "point" is photometric only, "reference" both kinds': the rectangle takes reference.
    FramePlan plan = planFrame(scene, view(scene), "point,reference");
    EXPECT_EQ(plan.shading[0].name, "shade:Panel:reference");
    EXPECT_EQ(plan.shading[1].name, "shade:Pendant:point");
    // A list naming nothing of a kind leaves that luminaire its own technique.
    FramePlan own = planFrame(scene, view(scene), "point,granier2003");
    EXPECT_EQ(own.shading[0].name, "shade:Panel:analytic");
    EXPECT_EQ(own.shading[1].name, "shade:Pendant:point");
    EXPECT_EQ(overrideFor("point,reference", LuminaireKind::LambertianRect), "reference");
    EXPECT_EQ(overrideFor("point,havran2005", LuminaireKind::Environment), "havran2005");
    EXPECT_EQ(overrideFor("point", LuminaireKind::LightField), "");
    // Scoped items: both kinds have "reference", only the photometric one is asked to use it.
    FramePlan scoped =
        planFrame(scene, view(scene), "photometric=reference,lambertian-rect=analytic");
    EXPECT_EQ(scoped.shading[0].name, "shade:Panel:analytic");
    EXPECT_EQ(scoped.shading[1].name, "shade:Pendant:reference");
    EXPECT_EQ(overrideFor("photometric=reference", LuminaireKind::LambertianRect), "");
    EXPECT_EQ(
        overrideFor("lightfield=reference,environment=balanced-mis", LuminaireKind::Environment),
        "balanced-mis");
}

TEST(FramePlan, TechniqueListsAreChecked) {
    EXPECT_NO_THROW(checkTechniqueList(""));
    EXPECT_NO_THROW(checkTechniqueList("point,reference,havran2005"));
    EXPECT_NO_THROW(
        checkTechniqueList("lightfield=restricted-cdf-raytraced,environment=balanced-mis"));
    for (const char* bad : {"magic", "point,magic", "photometric=restricted-cdf", "lamp=point",
                            "environment=point"}) {
        try {
            checkTechniqueList(bad);
            ADD_FAILURE() << bad << ": expected an InputError";
        } catch (const InputError& e) {
            std::string what = e.what();
            EXPECT_NE(what.find(bad), std::string::npos) << what;
        }
    }
}

TEST(FramePlan, UnknownTechniqueIsAClearError) {
    Scene scene = sceneFrom(kFloor, kPanel);
    scene.luminaires[0]->technique = "magic";
    try {
        planFrame(scene, view(scene));
        FAIL() << "expected an InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("magic"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("analytic"), std::string::npos);
    }
}

}  // namespace
}  // namespace candela
