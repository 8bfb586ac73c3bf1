// One unit system (issue 17, part 2): each source says what it emits in, a scene reports in one
// system, and a mixed scene converts its radiometric sources at 683 lm/W, never silently.
#include <gtest/gtest.h>

#include <string>

#include "TestUtil.h"
#include "calculation/CalculationGrid.h"
#include "luminaires/Registry.h"
#include "luminaires/lambertian/LambertianRect.h"
#include "scene/SceneIo.h"

namespace candela {
namespace {

const std::string kPanelW = R"({"type": "lambertian-rect", "name": "W", "size": [0.2, 0.2],
    "radiance": [2, 2, 2], "position": [0, 2, 0]})";
const std::string kPanelCd = R"({"type": "lambertian-rect", "name": "Cd", "size": [0.2, 0.2],
    "luminance": [500, 500, 500], "position": [1, 2, 0]})";
std::string lamp() {
    return R"({"type": "photometric", "name": "Lamp", "file": ")" + test::dataDir() +
           R"(/photometric/lambert.ies", "position": [-1, 2, 0], "technique": "scattered"})";
}

Scene sceneOf(const std::string& luminaires, const std::string& environment = "null") {
    std::string text =
        R"({"geometry": [{"plane": {"center": [0,0,0], "normal": [0,1,0], "size": [4,4]}}],
                           "luminaires": [)" +
        luminaires + R"(], "environment": )" + environment + "}";
    return parseScene(nlohmann::json::parse(text), test::dataDir() + "/units.json");
}

TEST(Units, EachSourceSaysWhatItEmitsIn) {
    Scene s = sceneOf(kPanelW + "," + kPanelCd + "," + lamp());
    EXPECT_EQ(s.luminaires[0]->quantities(), Quantities::Radiometric);
    EXPECT_EQ(s.luminaires[1]->quantities(), Quantities::Photometric);
    EXPECT_EQ(s.luminaires[2]->quantities(), Quantities::Photometric);
    // A luminance is written back as a luminance, a radiance as a radiance.
    nlohmann::json out;
    writeJson(*s.luminaires[1], out);
    EXPECT_TRUE(out.contains("luminance"));
    EXPECT_FALSE(out.contains("radiance"));
    EXPECT_NE(describe(*s.luminaires[1]).find("cd/m2"), std::string::npos)
        << describe(*s.luminaires[1]);
    EXPECT_NE(describe(*s.luminaires[1]).find(" lm"), std::string::npos)
        << describe(*s.luminaires[1]);
    EXPECT_NE(describe(*s.luminaires[0]).find("W/(m2 sr)"), std::string::npos)
        << describe(*s.luminaires[0]);
}

TEST(Units, AScenesUnitsFollowItsSources) {
    UnitSystem photometric = sceneOf(kPanelCd + "," + lamp()).units();
    EXPECT_TRUE(photometric.photometric);
    EXPECT_FALSE(photometric.converted);
    EXPECT_STREQ(photometric.irradiance(), "lx");
    UnitSystem radiometric = sceneOf(kPanelW).units();
    EXPECT_FALSE(radiometric.photometric);
    EXPECT_STREQ(radiometric.irradiance(), "W/m2");
    EXPECT_STREQ(radiometric.radiance(), "W/(m2 sr)");
    Scene mixed = sceneOf(kPanelW + "," + lamp());
    EXPECT_TRUE(mixed.units().photometric);
    EXPECT_TRUE(mixed.units().converted);
    EXPECT_EQ(mixed.unitScale(*mixed.luminaires[0]), 683.0);
    EXPECT_EQ(mixed.unitScale(*mixed.luminaires[1]), 1.0);
    EXPECT_NE(mixed.units().irradianceLabel().find("683 lm/W"), std::string::npos);
    // The environment counts too: the sky is in cd/m2, a map in W/(m2 sr) unless it says cd/m2.
    std::string map = R"({"file": ")" + test::dataDir() + R"(/environment/constant_2.exr")";
    EXPECT_TRUE(sceneOf(kPanelW, map + "}").units().photometric == false);
    Scene skyAndPanel = sceneOf(kPanelW, R"({"sky": {"sun_elevation_deg": 30, "resolution": 64}})");
    EXPECT_TRUE(skyAndPanel.units().converted);
    EXPECT_EQ(skyAndPanel.environmentUnitScale(), 1.0);
    Scene cdMap = sceneOf(kPanelCd, map + R"(, "unit": "cd/m2"})");
    EXPECT_FALSE(cdMap.units().converted);
    EXPECT_TRUE(cdMap.units().photometric);
}

TEST(Units, BadUnitsAreClearErrors) {
    std::string both = R"({"type": "lambertian-rect", "radiance": [1,1,1], "luminance": [1,1,1]})";
    std::string e = test::inputError([&] { sceneOf(both); });
    EXPECT_NE(e.find("units.json"), std::string::npos) << e;
    EXPECT_NE(e.find("not both"), std::string::npos) << e;
    e = test::inputError([&] { sceneOf(R"({"type": "lambertian-rect", "luminance": [1,-1,1]})"); });
    EXPECT_NE(e.find("luminance[1]"), std::string::npos) << e;
    std::string map =
        R"({"file": ")" + test::dataDir() + R"(/environment/constant_2.exr", "unit": "lux"})";
    e = test::inputError([&] { sceneOf(kPanelW, map); });
    EXPECT_NE(e.find("environment.unit"), std::string::npos) << e;
    EXPECT_NE(e.find("cd/m2"), std::string::npos) << e;
}

TEST(Units, AMixedGridAddsRadiometricLightAt683LumensPerWatt) {
    // The grid of the mixed scene equals the photometric lamp's lux plus 683 times the panel's
    // W/m2, each from its own estimator (exact techniques: equality to rounding).
    Scene mixed = sceneOf(kPanelW + "," + lamp());
    GridSpec spec;
    spec.plane.axis = 1;
    spec.lo = {-1.5, -1.0};
    spec.hi = {1.5, 1.0};
    spec.spacing = 0.5;
    GridResult r = computeGrid(mixed, spec);
    EXPECT_TRUE(r.units.converted);
    const TechniqueInfo* analytic = findTechnique(LuminaireKind::LambertianRect, "analytic");
    const TechniqueInfo* scattered = findTechnique(LuminaireKind::Photometric, "scattered");
    EstimateOptions o;
    for (size_t j = 0; j < r.v.size(); ++j)
        for (size_t i = 0; i < r.u.size(); ++i) {
            glm::dvec3 p = spec.plane.point(r.u[i], r.v[j]), n(0, 1, 0);
            double watts = analytic->irradiance(*mixed.luminaires[0], p, n, o).irradiance.y;
            double lux = scattered->irradiance(*mixed.luminaires[1], p, n, o).irradiance.y;
            ASSERT_GT(watts, 0.0);
            ASSERT_GT(lux, 0.0);
            EXPECT_NEAR(r.E[j * r.u.size() + i], lux + 683.0 * watts, 1e-9 * (lux + 683.0 * watts));
        }
}

}  // namespace
}  // namespace candela
