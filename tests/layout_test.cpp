// Layouts that reach their target (calculation/Layout.h): the arrangement chosen on the classroom
// and the office, applied to the scene and computed again by the surfaces calculation on its own,
// meets the target, and the next smaller arrangement tried does not; an L-shaped room gets no
// luminaire outside its outline; and what cannot be laid out says why.
#include "calculation/Layout.h"

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "calculation/CalculationSurfaces.h"
#include "scene/Procedural.h"
#include "scene/Scene.h"
#include "scene/SceneIo.h"
#include "util/Error.h"

namespace candela {
namespace {

/// The scene's task area `area` as the surfaces calculation computes it, on its own.
SurfaceResult taskArea(const Scene& scene, const std::string& area) {
    GridSpec how;
    applyLightChoice(scene, LightChoice{}, how);
    SurfaceReport r = computeSurfaces(scene, how);
    for (const SurfaceResult& s : r.surfaces)
        if (s.name == area) return s;
    throw std::runtime_error("no surface " + area);
}

void checkLayout(const std::string& sceneFile, const std::string& luminaireFile, double height,
                 const std::string& area) {
    const std::string path = test::sourceDir() + "/resources/scenes/" + sceneFile;
    Scene scene = loadScene(path);
    LayoutRequest request;
    request.luminaire = {{"type", "photometric"}, {"file", luminaireFile}};
    request.name = "Lamp";
    request.mountingHeight = height;
    LayoutResult r = proposeLayout(scene, request);
    ASSERT_NE(r.best(), nullptr) << sceneFile;
    EXPECT_EQ(r.targetEm, 500.0);
    EXPECT_EQ(r.targetU0, 0.6);
    const LayoutCandidate& best = *r.best();
    // Applied and computed again from its scene file: the target is met.
    Scene laidOut = parseScene(applyLayout(scene, request, r), path);
    EXPECT_EQ(laidOut.luminaires.size(), size_t(best.count()));
    SurfaceResult s = taskArea(laidOut, area);
    EXPECT_GE(s.summary.eAvg, 500.0) << sceneFile;
    EXPECT_GE(s.summary.u0, 0.6) << sceneFile;
    // The same values as the layout's own calculation (the same scene, the same method; the
    // adaptive gather's noise at a few points is below 0.5 %).
    EXPECT_NEAR(s.summary.eAvg, best.em, 0.005 * best.em);
    // Fewest: every arrangement tried with fewer luminaires fails.
    for (const LayoutCandidate& c : r.tried)
        if (c.count() < best.count()) {
            EXPECT_FALSE(c.meets) << c.columns << " x " << c.rows;
        }
    bool fewerTried = false;
    for (const LayoutCandidate& c : r.tried) fewerTried |= c.count() < best.count();
    EXPECT_TRUE(fewerTried) << "the search never looked below its answer";
}

TEST(Layout, TheClassroomMeetsItsTargetWithTheFewestTried) {
    checkLayout("classroom-project.json", "../luminaires/photometric/prolicht-e30.ldt", 2.4,
                "Classroom");
}

TEST(Layout, TheOfficeMeetsItsTargetWithTheFewestTried) {
    checkLayout("office.json", "../luminaires/photometric/halo-recessed-downlight.ies", 2.79,
                "Desk");
}

Scene lShaped() {
    return parseScene(nlohmann::json::parse(R"({
        "geometry": [{"room": {"name": "L", "height": 3,
                      "floor": [[0,0],[8,0],[8,4],[4,4],[4,8],[0,8]]}}],
        "task_areas": [{"name": "Floor", "plane": "y=0.8", "extent": [0.5, 0.5, 3.5, 3.5],
                        "required": {"em_lx": 300}}]})"),
                      test::sourceDir() + "/resources/scenes/l.json");
}

TEST(Layout, AnLShapedRoomGetsNoLuminaireOutsideItsOutline) {
    Scene scene = lShaped();
    LayoutRequest request;
    request.luminaire = {{"type", "photometric"},
                         {"file", "../luminaires/photometric/halo-recessed-downlight.ies"}};
    request.mountingHeight = 2.9;
    LayoutResult r = proposeLayout(scene, request);
    ASSERT_NE(r.best(), nullptr);
    EXPECT_EQ(r.lo, glm::dvec2(0, 0));
    EXPECT_EQ(r.hi, glm::dvec2(8, 8));
    const std::vector<glm::dvec2> outline = {{0, 0}, {8, 0}, {8, 4}, {4, 4}, {4, 8}, {0, 8}};
    for (const LayoutCandidate& c : r.tried) {
        EXPECT_LT(c.count(), c.columns * c.rows);  // the missing quarter holds none
        for (const glm::dvec3& p : c.positions) {
            EXPECT_TRUE(insidePolygon(outline, {p.x, p.z})) << p.x << ", " << p.z;
            EXPECT_DOUBLE_EQ(p.y, 2.9);
        }
    }
}

TEST(Layout, ASceneFilesLayoutPlacesItsGridAndSavesAsWritten) {
    const std::string path = test::sourceDir() + "/resources/scenes/classroom-project.json";
    Scene scene = loadScene(path);
    // The classroom's 5 x 3 layout over its 10 x 8 m room: 2 m and 2.667 m apart, half a
    // spacing from the walls, 2.4 m above the floor, named after the layout.
    ASSERT_EQ(scene.luminaires.size(), 15u);
    EXPECT_EQ(scene.luminaires[0]->name, "Linear 1");
    EXPECT_EQ(scene.luminaires[0]->pose.position, glm::dvec3(-4.0, 2.4, -2.667));
    EXPECT_EQ(scene.luminaires[14]->pose.position, glm::dvec3(4.0, 2.4, 2.667));
    nlohmann::json saved = sceneToJson(scene);
    ASSERT_EQ(saved["layouts"].size(), 1u);
    EXPECT_EQ(saved["layouts"][0], nlohmann::json::parse(R"({"name": "Linear", "area": "Classroom",
        "grid": [5, 3], "height": 2.4, "luminaire": {"type": "photometric",
        "file": "../luminaires/photometric/prolicht-e30.ldt"}})"));
    EXPECT_TRUE(saved["luminaires"].empty());
    // A copy (undo's) saves the same; once one luminaire moves, each is written on its own.
    Scene copy = scene.clone();
    EXPECT_EQ(sceneToJson(copy), saved);
    copy.luminaires[3]->pose.position.x += 0.5;
    nlohmann::json moved = sceneToJson(copy);
    EXPECT_FALSE(moved.contains("layouts"));
    ASSERT_EQ(moved["luminaires"].size(), 15u);
    EXPECT_EQ(moved["luminaires"][3]["position"][0], 2.5);
    EXPECT_EQ(parseScene(moved, path).luminaires.size(), 15u);
    // A removed luminaire: likewise.
    copy = scene.clone();
    copy.luminaires.erase(copy.luminaires.begin());
    EXPECT_EQ(sceneToJson(copy)["luminaires"].size(), 14u);
}

TEST(Layout, WhatCannotBeLaidOutSaysWhy) {
    Scene scene = lShaped();
    LayoutRequest request;
    request.luminaire = {{"type", "photometric"},
                         {"file", "../luminaires/photometric/halo-recessed-downlight.ies"}};
    request.mountingHeight = 2.9;
    request.area = "Desk";
    std::string e = test::inputError([&] { proposeLayout(scene, request); });
    EXPECT_NE(e.find("no task area \"Desk\" (it has \"Floor\")"), std::string::npos) << e;
    // A scene file's layout names the field.
    e = test::inputError([] {
        parseScene(nlohmann::json::parse(R"({"task_areas": [{"name": "A", "plane": "y=0.8",
            "extent": [0, 0, 1, 1]}], "layouts": [{"grid": [2, 0], "height": 2,
            "luminaire": {"type": "photometric", "file": "x.ies"}}]})"),
                   "s.json");
    });
    EXPECT_NE(e.find("s.json: layouts[0].grid[1]: expected a whole number"), std::string::npos)
        << e;
    request.area = "";
    request.mountingHeight = 0.5;
    e = test::inputError([&] { proposeLayout(scene, request); });
    EXPECT_NE(e.find("at or below task area"), std::string::npos) << e;
    request.mountingHeight = 2.9;
    request.luminaire = {
        {"type", "lambertian-rect"}, {"size", {0.5, 0.5}}, {"radiance", {10, 10, 10}}};
    e = test::inputError([&] { proposeLayout(scene, request); });
    EXPECT_NE(e.find("a photometry (IES, LDT, TM-33) or a GLDF variant"), std::string::npos) << e;
}

}  // namespace
}  // namespace candela
