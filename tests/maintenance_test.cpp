// Maintenance factors (issue 21, part 4): the project's and a luminaire's own, read and written
// with the scene, refused outside (0, 1] with the field named, and applied to every reported
// illuminance: the grid's values are the initial ones times each luminaire's factor, direct and
// interreflected, while the environment (daylight) takes none.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "app/commands/Commands.h"  // parsePlane
#include "calculation/CalculationGrid.h"
#include "scene/SceneIo.h"
#include "util/Error.h"

namespace candela {
namespace {

// A floor and a ceiling: the floor reflects the panels' light up, the ceiling back down.
const std::string kFloor =
    R"({"plane": {"center": [0,0,0], "normal": [0,1,0], "size": [6,6]}, "albedo": [0.5,0.5,0.5]},)"
    R"({"plane": {"center": [0,3.5,0], "normal": [0,-1,0], "size": [6,6]}, "albedo": [0.8,0.8,0.8]})";

std::string panel(const char* name, double x, const std::string& extra = "") {
    return R"({"type": "lambertian-rect", "name": ")" + std::string(name) +
           R"(", "size": [0.2, 0.2], "radiance": [1000, 1000, 1000], "position": [)" +
           std::to_string(x) + R"(,3,-0.2], "technique": "analytic")" + extra + "}";
}

Scene sceneWith(const std::string& luminaires, const std::string& project = "") {
    std::string text =
        R"({"geometry": [)" + kFloor + R"(], "luminaires": [)" + luminaires + "]" + project + "}";
    return parseScene(nlohmann::json::parse(text), "maintenance.json");
}

GridResult floorGrid(const Scene& scene, bool indirect = false) {
    GridSpec spec;
    spec.plane = parsePlane("y=0.75");
    spec.lo = {-1.0, -1.0};
    spec.hi = {1.0, 0.5};
    spec.spacing = 0.5;
    spec.indirect = indirect;
    spec.indirectMethod = GridSpec::Indirect::Patches;  // deterministic
    spec.patches = 300;
    return computeGrid(scene, spec);
}

TEST(Maintenance, FactorsAreReadWrittenAndInherited) {
    Scene scene =
        sceneWith(panel("A", 0.3) + "," + panel("B", -0.3, R"(, "maintenance_factor": 0.5)"),
                  R"(, "maintenance_factor": 0.8)");
    EXPECT_EQ(scene.maintenanceFactor, 0.8);
    EXPECT_EQ(scene.maintenanceFactorOf(*scene.luminaires[0]), 0.8);  // the project's
    EXPECT_EQ(scene.maintenanceFactorOf(*scene.luminaires[1]), 0.5);  // its own
    EXPECT_TRUE(scene.maintained());
    EXPECT_NE(scene.maintenanceNote().find("maintenance factor 0.8"), std::string::npos);
    EXPECT_NE(scene.maintenanceNote().find("\"B\" 0.5"), std::string::npos);

    // Written back as read: the project's factor, and only the luminaire that has its own.
    nlohmann::json doc = sceneToJson(scene);
    EXPECT_EQ(doc["maintenance_factor"], 0.8);
    EXPECT_FALSE(doc["luminaires"][0].contains("maintenance_factor"));
    EXPECT_EQ(doc["luminaires"][1]["maintenance_factor"], 0.5);
    Scene again = parseScene(doc, "again.json");
    EXPECT_EQ(again.maintenanceFactorOf(*again.luminaires[0]), 0.8);
    EXPECT_EQ(again.maintenanceFactorOf(*again.luminaires[1]), 0.5);

    // A scene without one is an initial installation, and its file stays as it was.
    Scene plain = sceneWith(panel("A", 0.3));
    EXPECT_FALSE(plain.maintained());
    EXPECT_EQ(plain.maintenanceNote(), "maintenance factor 1 (initial values)");
    EXPECT_FALSE(sceneToJson(plain).contains("maintenance_factor"));
    EXPECT_EQ(plain.clone().maintenanceFactor, 1.0);
    EXPECT_EQ(scene.clone().maintenanceFactor, 0.8);
}

TEST(Maintenance, FactorsOutsideZeroToOneAreRefusedNamingTheField) {
    for (const char* bad : {"0", "-0.5", "1.2", "\"0.8\"", "null", "[0.8]"}) {
        std::string value = bad;
        try {
            sceneWith(panel("A", 0.3), ", \"maintenance_factor\": " + value);
            ADD_FAILURE() << "project factor " << value << " accepted";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("maintenance_factor"), std::string::npos)
                << e.what();
        }
        try {
            sceneWith(panel("A", 0.3, ", \"maintenance_factor\": " + value));
            ADD_FAILURE() << "luminaire factor " << value << " accepted";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("luminaires[0].maintenance_factor"),
                      std::string::npos)
                << e.what();
        }
    }
}

TEST(Maintenance, GridValuesAreTheInitialOnesTimesEachLuminairesFactor) {
    // Each panel alone at its initial output, then both with factors: the analytic technique is
    // exact and deterministic, so the maintained grid is the weighted sum to rounding (1e-12).
    GridResult a = floorGrid(sceneWith(panel("A", 0.3)));
    GridResult b = floorGrid(sceneWith(panel("B", -0.3)));
    GridResult both = floorGrid(
        sceneWith(panel("A", 0.3) + "," + panel("B", -0.3, R"(, "maintenance_factor": 0.5)"),
                  R"(, "maintenance_factor": 0.8)"));
    ASSERT_EQ(both.E.size(), a.E.size());
    for (size_t k = 0; k < a.E.size(); ++k) {
        double want = 0.8 * a.E[k] + 0.5 * b.E[k];
        EXPECT_NEAR(both.E[k], want, 1e-12 * want) << k;
    }
}

TEST(Maintenance, InterreflectedLightIsMaintainedToo) {
    // Radiosity is linear in the sources: a factor on the only luminaire scales the reflected
    // light by the same factor (the patch solution is deterministic; 1e-9 for its iteration's
    // stopping rule, which sees scaled residuals).
    GridResult initial = floorGrid(sceneWith(panel("A", 0.3)), true);
    GridResult maintained =
        floorGrid(sceneWith(panel("A", 0.3), R"(, "maintenance_factor": 0.7)"), true);
    ASSERT_TRUE(initial.hasIndirect && maintained.hasIndirect);
    for (size_t k = 0; k < initial.E.size(); ++k) {
        ASSERT_GT(initial.indirect[k], 0.0) << k;  // the ceiling reflects light down
        EXPECT_NEAR(maintained.direct[k], 0.7 * initial.direct[k], 1e-12 * initial.direct[k]);
        EXPECT_NEAR(maintained.indirect[k], 0.7 * initial.indirect[k],
                    1e-9 * initial.indirect[k] + 1e-15);
    }
}

// What the CSVs' E_initial and maintenance_factor columns hold: the values before maintenance,
// checked against the same scene with no factor at all (an independent run). With one factor
// for every luminaire the reflected light's initial value is the maintained one over it; with
// factors that differ it comes from a second solution, and the factor in effect lies between
// them and varies from point to point.
TEST(Maintenance, InitialValuesEqualTheSceneWithoutFactors) {
    const std::string two =
        panel("A", 0.3) + "," + panel("B", -0.3, R"(, "maintenance_factor": 0.5)");
    GridResult none = floorGrid(sceneWith(panel("A", 0.3) + "," + panel("B", -0.3)), true);
    GridResult same = floorGrid(
        sceneWith(panel("A", 0.3) + "," + panel("B", -0.3), R"(, "maintenance_factor": 0.8)"),
        true);
    GridResult mixed = floorGrid(sceneWith(two, R"(, "maintenance_factor": 0.8)"), true);
    ASSERT_EQ(none.initial.size(), none.E.size());
    double lowest = 1.0, highest = 0.0;
    for (size_t k = 0; k < none.E.size(); ++k) {
        // Without factors the initial values are the values (the same sums, to rounding).
        EXPECT_NEAR(none.initial[k], none.E[k], 1e-12 * none.E[k]) << k;
        // 1e-9: the radiosity iteration's stopping rule sees scaled residuals (above).
        EXPECT_NEAR(same.initial[k], none.E[k], 1e-9 * none.E[k]) << k;
        EXPECT_NEAR(mixed.initial[k], none.E[k], 1e-9 * none.E[k]) << k;
        double f = effectiveMaintenanceFactor(same.E[k], same.initial[k], same.projectFactor);
        EXPECT_NEAR(f, 0.8, 1e-9) << k;
        double g = effectiveMaintenanceFactor(mixed.E[k], mixed.initial[k], mixed.projectFactor);
        EXPECT_GT(g, 0.5) << k;
        EXPECT_LT(g, 0.8) << k;
        lowest = std::min(lowest, g);
        highest = std::max(highest, g);
    }
    // Points nearer panel A (x > 0, factor 0.8) keep more of their light than those near B.
    EXPECT_GT(highest - lowest, 0.01);
    EXPECT_EQ(effectiveMaintenanceFactor(0.0, 0.0, 0.8), 0.8);  // no light: the project's factor
}

}  // namespace
}  // namespace candela
