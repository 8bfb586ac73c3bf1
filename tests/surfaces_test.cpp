// EN 12464-1 calculation surfaces (calculation/CalculationSurfaces.h): the grid rule and Table 1
// against the standard's own formulas worked by hand, the layout of a desk's surroundings, and
// the illuminance of task areas and calculation points against the closed form of a small
// Lambertian source (a patch of area A and luminance L: E = L A cos(emission) cos(incidence) /
// r^2, cylindrical Ez = L A cos(emission) sin(theta) / (pi r^2)).
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "TestUtil.h"
#include "calculation/CalculationSurfaces.h"
#include "scene/Scene.h"
#include "scene/SceneIo.h"
#include "shaders/shared/Constants.h"
#include "util/Error.h"

namespace candela {
namespace {

using gpu::kPi;

TEST(CalculationSurfaces, GridRuleIsTheStandardsFormula) {
    // p = 0.2 x 5^log10(d): 0.2 m at 1 m, 1 m at 10 m, 5 m at 100 m, capped at 10 m.
    EXPECT_NEAR(standardGridCell(1.0, 0.9), 0.2, 1e-12);
    EXPECT_NEAR(standardGridCell(10.0, 6.0), 1.0, 1e-12);
    EXPECT_NEAR(standardGridCell(100.0, 60.0), 5.0, 1e-12);
    EXPECT_EQ(standardGridCell(1000.0, 600.0), 10.0);
    // Twice as long as wide or more: d is the shorter side.
    EXPECT_NEAR(standardGridCell(4.0, 1.0), 0.2, 1e-12);
    EXPECT_NEAR(standardGridCell(1.6, 0.8), 0.2 * std::pow(5.0, std::log10(0.8)), 1e-12);
    // The next whole number at or above length / p: an exact multiple adds no point.
    EXPECT_EQ(standardPointCount(1.6, 0.2), 8);
    EXPECT_EQ(standardPointCount(1.7, 0.2), 9);
    EXPECT_EQ(standardPointCount(0.05, 0.2), 1);
}

TEST(CalculationSurfaces, SurroundingFollowsTable1) {
    EXPECT_EQ(surroundingIlluminance(1000.0), 500.0);
    EXPECT_EQ(surroundingIlluminance(750.0), 500.0);
    EXPECT_EQ(surroundingIlluminance(500.0), 300.0);
    EXPECT_EQ(surroundingIlluminance(300.0), 200.0);
    EXPECT_EQ(surroundingIlluminance(200.0), 150.0);
    EXPECT_EQ(surroundingIlluminance(150.0), 150.0);  // at or below 150 lx: the task's own
    EXPECT_EQ(surroundingIlluminance(600.0), 300.0);  // between rows: the lower row
}

// A 6 x 6 m floor, a desk 1.6 x 0.8 m at 0.75 m, and a 1 mm square of luminance L 3 m up.
constexpr double kL = 2.5e9, kSide = 1e-3, kLightY = 3.0;

Scene deskScene(const std::string& tasks, const std::string& points = "[]") {
    std::string text = R"({"geometry": [{"plane": {"center": [0,0,0], "normal": [0,1,0],
        "size": [6,6]}}], "luminaires": [{"type": "lambertian-rect", "name": "Spot",
        "size": [0.001, 0.001], "luminance": [2.5e9, 2.5e9, 2.5e9], "position": [0, 3, 0],
        "aim": [0, -1, 0], "technique": "analytic"}], "task_areas": )" +
                       tasks + R"(, "calculation_points": )" + points + "}";
    return parseScene(nlohmann::json::parse(text), "desk.json");
}

const std::string kDesk =
    R"([{"name": "Desk", "plane": "y=0.75", "extent": [-0.8, -0.4, 0.8, 0.4],
         "required": {"em_lx": 500, "u0": 0.6}}])";

/// Closed form of the 1 mm source at p for a unit normal n.
double closedForm(const glm::dvec3& p, const glm::dvec3& n) {
    glm::dvec3 w = glm::dvec3(0, kLightY, 0) - p;
    double r = glm::length(w);
    double emission = w.y / r, incidence = glm::dot(n, w) / r;
    return incidence > 0.0 ? kL * kSide * kSide * emission * incidence / (r * r) : 0.0;
}

TEST(CalculationSurfaces, DeskSurroundingAndBackgroundLayout) {
    std::vector<SurfaceResult> s = layoutSurfaces(deskScene(kDesk));
    ASSERT_EQ(s.size(), 3u);
    // Worked by hand: the desk is twice as long as wide, so d = 0.8 m, p = 0.1711 m: 10 x 5
    // cells of 0.16 m. Its surrounding, 2.6 x 1.8 m: d = 2.6 m, p = 0.3900 m, more than a third
    // of the 0.5 m band, so p = 0.5 / 3 m: 16 x 11 cells (2.6 / 0.1667 = 15.6, 1.8 / 0.1667 =
    // 10.8), 176 points of which 10 x 5 lie on the desk. The background, 3 m beyond that but inside
    // the room less its 0.5 m wall band (-2.5..2.5 m): d = 5 m, p = 0.616 m, 9 x 9 cells, 15 of
    // them inside the surrounding.
    EXPECT_EQ(s[0].role, "task area");
    EXPECT_EQ(s[0].cells, glm::ivec2(10, 5));
    EXPECT_NEAR(s[0].spacing.x, 0.16, 1e-12);
    EXPECT_EQ(s[0].points.size(), 50u);
    EXPECT_EQ(s[1].role, "immediate surrounding");
    EXPECT_EQ(s[1].cells, glm::ivec2(16, 11));
    EXPECT_EQ(s[1].points.size(), 126u);
    // Three rings of points across the band on every side, not one: the columns left of the desk
    // and the rows in front of it.
    std::set<double> left, front;
    for (const glm::dvec2& q : s[1].points) {
        if (q.x < -0.8) left.insert(q.x);
        if (q.y < -0.4) front.insert(q.y);
    }
    EXPECT_EQ(left.size(), 3u);
    EXPECT_EQ(front.size(), 3u);
    EXPECT_NEAR(s[1].lo.x, -1.3, 1e-12);
    EXPECT_NEAR(s[1].hi.y, 0.9, 1e-12);
    EXPECT_EQ(s[2].role, "background");
    EXPECT_EQ(s[2].cells, glm::ivec2(9, 9));
    EXPECT_EQ(s[2].points.size(), 66u);
    EXPECT_NEAR(s[2].lo.x, -2.5, 1e-12);
    EXPECT_NEAR(s[2].hi.y, 2.5, 1e-12);
    // The requirements the standard derives: Table 1 for 500 lx, U0 0.40; a third of that, 0.10.
    EXPECT_EQ(s[0].required, (Requirement{500.0, 0.6}));
    EXPECT_EQ(s[1].required, (Requirement{300.0, 0.4}));
    EXPECT_NEAR(s[2].required.em, 100.0, 1e-12);
    EXPECT_EQ(s[2].required.u0, 0.1);
    // No surroundings when the area asks for none; its own spacing when it gives one.
    std::vector<SurfaceResult> alone = layoutSurfaces(deskScene(
        R"([{"plane": "y=0.75", "extent": [0, 0, 1, 0.5], "spacing": 0.25, "surroundings": false}])"));
    ASSERT_EQ(alone.size(), 1u);
    EXPECT_EQ(alone[0].cells, glm::ivec2(4, 2));
}

TEST(CalculationSurfaces, SummariesAreTheClosedFormsMeans) {
    Scene scene = deskScene(kDesk);
    SurfaceReport r = computeSurfaces(scene, GridSpec{});
    ASSERT_EQ(r.surfaces.size(), 3u);
    EXPECT_TRUE(r.units.photometric);
    for (const SurfaceResult& s : r.surfaces) {
        double sum = 0.0, lo = 1e300, hi = 0.0;
        for (size_t k = 0; k < s.points.size(); ++k) {
            double e = closedForm(s.plane.point(s.points[k].x, s.points[k].y), {0, 1, 0});
            // The analytic polygon against the point-source closed form: the 1 mm patch's
            // finite size changes E by (size / r)^2 ~ 1e-7 relative at 2.25 m and more.
            EXPECT_NEAR(s.E[k], e, 1e-5 * e) << s.name << " " << k;
            sum += e, lo = std::min(lo, e), hi = std::max(hi, e);
        }
        double mean = sum / double(s.points.size());
        EXPECT_NEAR(s.summary.eAvg, mean, 1e-5 * mean) << s.name;
        EXPECT_NEAR(s.summary.eMin, lo, 1e-5 * lo) << s.name;
        EXPECT_NEAR(s.summary.eMax, hi, 1e-5 * hi) << s.name;
        EXPECT_NEAR(s.summary.u0, lo / mean, 1e-5) << s.name;
    }
    // The desk: Em about 487 lx under a point 2.25 m above its centre, U0 about 0.90.
    const SurfaceResult& desk = r.surfaces[0];
    EXPECT_FALSE(desk.passes);  // Em < 500 lx
    EXPECT_TRUE(r.surfaces[1].passes);
    EXPECT_TRUE(r.surfaces[2].passes);  // Em >= 100 lx, U0 >= 0.10
    // The same desk asking for 1 % below its Em passes; 1 % above fails.
    for (double f : {0.99, 1.01}) {
        scene.taskAreas[0].required.em = f * desk.summary.eAvg;
        scene.taskAreas[0].surroundings = false;
        SurfaceReport again = computeSurfaces(scene, GridSpec{});
        EXPECT_EQ(again.surfaces[0].passes, f < 1.0) << f;
    }
    // A uniformity it cannot reach fails though Em passes.
    scene.taskAreas[0].required = {100.0, 0.95};
    EXPECT_FALSE(computeSurfaces(scene, GridSpec{}).surfaces[0].passes);
}

TEST(CalculationSurfaces, ASurfaceWithoutPointsHasNothingToFail) {
    // The classroom's task area covers its floor: no immediate surrounding or background is
    // left. They have "no points": neither met nor failed (passes only says "not failed"), as
    // the CLI, the report and the editor say; the task area itself is judged.
    Scene classroom = loadScene(test::sourceDir() + "/resources/scenes/classroom.json");
    SurfaceReport r = computeSurfaces(classroom, GridSpec{});
    ASSERT_EQ(r.surfaces.size(), 3u);
    EXPECT_EQ(r.surfaces[0].points.size(), 80u);
    EXPECT_FALSE(r.surfaces[0].passes);  // direct light alone is far from 500 lx
    EXPECT_EQ(r.surfaces[0].verdict, Verdict::Fail);
    for (size_t k : {1u, 2u}) {
        EXPECT_TRUE(r.surfaces[k].points.empty()) << r.surfaces[k].name;
        EXPECT_TRUE(r.surfaces[k].required.any()) << r.surfaces[k].name;
        EXPECT_EQ(r.surfaces[k].verdict, Verdict::NoPoints) << r.surfaces[k].name;
        EXPECT_TRUE(r.surfaces[k].passes) << r.surfaces[k].name;
    }
}

TEST(CalculationSurfaces, SurroundingsOutsideTheRoomHaveNoPoints) {
    // A task area over the whole 6 x 6 m floor: its immediate surrounding, kept inside the room,
    // is the task area itself, all hole; its background, inside the wall band, lies within that
    // hole too. Both have "no points" whatever they require; the task area is judged on its own.
    Scene scene = deskScene(R"([{"name": "Floor", "plane": "y=0.75", "extent": [-3, -3, 3, 3],
        "required": {"em_lx": 50, "u0": 0.01}}])");
    SurfaceReport r = computeSurfaces(scene, GridSpec{});
    ASSERT_EQ(r.surfaces.size(), 3u);
    EXPECT_FALSE(r.surfaces[0].points.empty());
    // Em over the floor: about 150 lx (494 lx 2.25 m below the source, 24 lx in the corners),
    // U0 about 0.16: it meets 50 lx and 0.01.
    EXPECT_GT(r.surfaces[0].summary.eAvg, 50.0);
    EXPECT_EQ(r.surfaces[0].verdict, Verdict::Pass);
    EXPECT_STREQ(verdictText(r.surfaces[0].verdict), "PASS");
    for (size_t k : {1u, 2u}) {
        const SurfaceResult& s = r.surfaces[k];
        EXPECT_TRUE(s.points.empty()) << s.name;
        EXPECT_EQ(s.summary.count, 0u) << s.name;
        EXPECT_GT(s.required.em, 0.0) << s.name;  // Table 1 still asks for something
        EXPECT_EQ(s.verdict, Verdict::NoPoints) << s.name;
        EXPECT_STREQ(verdictText(s.verdict), "no points") << s.name;
        EXPECT_TRUE(s.passes) << s.name;  // nothing failed
    }
    // Asking for more than it reaches fails the task area, not its empty surroundings.
    scene.taskAreas[0].required.em = 1000.0;
    r = computeSurfaces(scene, GridSpec{});
    EXPECT_EQ(r.surfaces[0].verdict, Verdict::Fail);
    EXPECT_STREQ(verdictText(r.surfaces[0].verdict), "FAIL");
    EXPECT_EQ(r.surfaces[1].verdict, Verdict::NoPoints);
    EXPECT_EQ(r.surfaces[2].verdict, Verdict::NoPoints);
    // Without a requirement, a surface with points has "no requirement".
    scene.taskAreas[0].required = {};
    scene.taskAreas[0].surroundings = false;
    r = computeSurfaces(scene, GridSpec{});
    EXPECT_EQ(r.surfaces[0].verdict, Verdict::NoRequirement);
    EXPECT_STREQ(verdictText(r.surfaces[0].verdict), "no requirement");
}

TEST(CalculationSurfaces, VerticalAndCylindricalPoints) {
    Scene scene = deskScene("[]", R"([
        {"name": "Board", "position": [-1, 1.2, 0], "normal": [1, 0, 0], "required_lx": 50},
        {"name": "Face", "position": [1.5, 1.2, 0.5], "type": "cylindrical"},
        {"name": "Behind", "position": [-1, 1.2, 0], "normal": [-1, 0, 0]}])");
    SurfaceReport r = computeSurfaces(scene, GridSpec{});
    ASSERT_EQ(r.points.size(), 3u);
    double board = closedForm({-1, 1.2, 0}, {1, 0, 0});
    EXPECT_NEAR(r.points[0].E, board, 1e-5 * board);
    EXPECT_EQ(r.points[0].passes, board >= 50.0);
    EXPECT_EQ(r.points[0].verdict, board >= 50.0 ? Verdict::Pass : Verdict::Fail);
    // Cylindrical: Ez = L A cos(emission) sin(theta) / (pi r^2), theta from the vertical. The mean
    // over 32 horizontal directions weights one direction within 0.33 % of 1/pi.
    glm::dvec3 p(1.5, 1.2, 0.5), w = glm::dvec3(0, kLightY, 0) - p;
    double r2 = glm::dot(w, w), rr = std::sqrt(r2);
    double ez = kL * kSide * kSide * (w.y / rr) * (std::hypot(w.x, w.z) / rr) / (kPi * r2);
    EXPECT_NEAR(r.points[1].E, ez, 0.0034 * ez);
    EXPECT_EQ(r.points[2].E, 0.0);  // facing away
}

TEST(CalculationSurfaces, CylindricalGridIsEachPointsClosedForm) {
    Scene scene = deskScene(R"([{"name": "Seats", "plane": "y=1.2", "extent": [1, -1, 2, 1],
        "spacing": 0.5, "illuminance": "cylindrical", "required": {"em_lx": 50}}])");
    SurfaceReport r = computeSurfaces(scene, GridSpec{});
    ASSERT_EQ(r.surfaces.size(), 1u);  // no surroundings: Table 1 is for planar task areas
    const SurfaceResult& s = r.surfaces[0];
    EXPECT_TRUE(s.cylindrical);
    ASSERT_EQ(s.points.size(), 8u);  // 2 x 4 cells of 0.5 m
    for (size_t k = 0; k < s.points.size(); ++k) {
        glm::dvec3 p = s.plane.point(s.points[k].x, s.points[k].y);
        glm::dvec3 w = glm::dvec3(0, kLightY, 0) - p;
        double r2 = glm::dot(w, w), rr = std::sqrt(r2);
        double ez = kL * kSide * kSide * (w.y / rr) * (std::hypot(w.x, w.z) / rr) / (kPi * r2);
        // 32 azimuths: within 0.33 % of the exact weight 1/pi for one direction.
        EXPECT_NEAR(s.E[k], ez, 0.0034 * ez) << k;
    }
    // Cylindrical illuminance needs a horizontal plane and takes no surroundings.
    EXPECT_THROW(deskScene(R"([{"plane": "x=1", "extent": [0, 0, 1, 1],
                                "illuminance": "cylindrical"}])"),
                 InputError);
    EXPECT_THROW(deskScene(R"([{"plane": "y=1.2", "extent": [0, 0, 1, 1],
                                "illuminance": "cylindrical", "surroundings": true}])"),
                 InputError);
    Scene again = parseScene(sceneToJson(scene), "again.json");
    EXPECT_TRUE(again.taskAreas.at(0).cylindrical);
    EXPECT_FALSE(again.taskAreas.at(0).surroundings);
}

TEST(CalculationSurfaces, SceneFileEntriesRoundTripAndRefuseBadValues) {
    Scene scene = deskScene(kDesk, R"([{"name": "Face", "position": [1, 1.2, 0],
                                         "type": "cylindrical", "required_lx": 150}])");
    nlohmann::json saved = sceneToJson(scene);
    Scene again = parseScene(saved, "again.json");
    ASSERT_EQ(again.taskAreas.size(), 1u);
    EXPECT_EQ(again.taskAreas[0].name, "Desk");
    EXPECT_EQ(again.taskAreas[0].lo, scene.taskAreas[0].lo);
    EXPECT_EQ(again.taskAreas[0].hi, scene.taskAreas[0].hi);
    EXPECT_EQ(again.taskAreas[0].plane.offset, 0.75);
    EXPECT_EQ(again.taskAreas[0].required, scene.taskAreas[0].required);
    ASSERT_EQ(again.calcPoints.size(), 1u);
    EXPECT_TRUE(again.calcPoints[0].cylindrical);
    EXPECT_EQ(again.calcPoints[0].requiredLux, 150.0);
    auto refuses = [](const std::string& tasks, const std::string& points, const char* says) {
        try {
            deskScene(tasks, points);
            ADD_FAILURE() << "accepted " << tasks << points;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
        }
    };
    refuses(R"([{"plane": "y=0.75", "extent": [0, 0, 1]}])", "[]", "task_areas[0].extent");
    refuses(R"([{"plane": "y=0.75", "extent": [0, 0, 1, 0]}])", "[]", "not a line");
    refuses(R"([{"plane": "w=0.75", "extent": [0, 0, 1, 1]}])", "[]", "task_areas[0].plane");
    refuses(R"([{"plane": "y=0.75", "extent": [0, 0, 1, 1], "required": {"u0": 1.5}}])", "[]",
            "u0");
    refuses(R"([{"plane": "y=0.75", "extent": [0, 0, 1, 1], "required": {"em": 500}}])", "[]",
            "em");
    refuses("[]", R"([{"position": [0, 1, 0], "type": "round"}])", "cylindrical");
    refuses("[]", R"([{"position": [0, 1, 0], "type": "cylindrical", "normal": [1, 0, 0]}])",
            "normal");
    refuses("[]", R"([{"position": [0, 1, 0], "normal": [0, 0, 0]}])", "normal");
}

TEST(CalculationSurfaces, RefusesASceneWithNothingToEvaluate) {
    EXPECT_THROW(computeSurfaces(deskScene("[]"), GridSpec{}), InputError);
}

}  // namespace
}  // namespace candela
