// The editor's rooms (ui/RoomEditing.h): the room dialog's draft of the classroom gives the very
// entries of the hand-written classroom scene file (resources/scenes/classroom-project.json, an
// independent reference), an L's floor area is its closed form, typed outlines are checked, and
// adding, editing and removing geometry are undo steps that restore the scene file exactly, with
// refused values changing nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

#include "TempDir.h"
#include "scene/Procedural.h"
#include "scene/SceneIo.h"
#include "ui/EditorState.h"
#include "ui/LayoutJob.h"
#include "ui/RoomEditing.h"
#include "util/Error.h"
#include "util/Polygon.h"

namespace candela::ui {
namespace {

void isolate() {
    // Opening or replacing a scene touches the recent files and autosaves: keep them out of the
    // user's home.
    static const bool isolated = [] {
        return setenv("CANDELA_STATE_DIR",
                      (std::filesystem::temp_directory_path() / "candela-room-test").c_str(),
                      1) == 0;
    }();
    EXPECT_TRUE(isolated);
}

/// The classroom as a designer fills in the dialog: the room, three windows, a door, furniture.
RoomDraft classroomDraft() {
    RoomDraft d;
    d.name = "Classroom";
    d.width = 10.0, d.depth = 8.0, d.height = 3.0;
    d.floorReflectance = 0.2, d.wallReflectance = 0.5, d.ceilingReflectance = 0.7;
    for (double offset : {0.5, 3.0, 5.5}) {
        OpeningDraft w;
        w.type = "window";
        w.wall = 4, w.offset = offset, w.width = 2.0, w.sill = 0.9, w.height = 1.6;
        w.glazing = 0.7;
        d.openings.push_back(w);
    }
    OpeningDraft door;
    door.type = "door";
    door.wall = 2, door.offset = 6.5, door.width = 1.0, door.height = 2.1;
    d.openings.push_back(door);
    d.furniture = {{"desk", {0.0, -3.0}, 0.0}, {"shelf", {-1.0, 3.8}, 180.0}};
    d.taskArea = true;
    d.workPlane = 0.75, d.wallBand = 0.0, d.requiredEm = 500.0, d.requiredU0 = 0.6;
    return d;
}

nlohmann::json shippedClassroom() {
    std::ifstream in(CANDELA_SOURCE_DIR "/resources/scenes/classroom-project.json");
    return nlohmann::json::parse(in);
}

TEST(EditorRoom, TheDialogsClassroomIsTheHandWrittenOne) {
    RoomDraft d = classroomDraft();
    nlohmann::json shipped = shippedClassroom();
    // Numbers compare by value: 3 and 3.0 are the same length.
    EXPECT_EQ(roomEntry(d), shipped["geometry"][0]);
    EXPECT_EQ(taskAreaEntry(d), shipped["task_areas"][0]);
    std::vector<nlohmann::json> furniture = furnitureEntries(d);
    ASSERT_EQ(furniture.size(), 2u);
    EXPECT_EQ(furniture[0]["furniture"]["position"],
              shipped["geometry"][1]["furniture"]["position"]);
    EXPECT_EQ(furniture[1]["furniture"]["rotate_y_deg"],
              shipped["geometry"][3]["furniture"]["rotate_y_deg"]);

    // Built, the room's surfaces are those of the file's room: same meshes, same triangles.
    Scene fromDraft = parseScene(newSceneDocument(d), "draft");
    Scene fromFile = loadScene(CANDELA_SOURCE_DIR "/resources/scenes/classroom-project.json");
    ASSERT_GE(fromFile.geometry.size(), 1u);
    ASSERT_EQ(fromDraft.geometry[0].meshes.size(), fromFile.geometry[0].meshes.size());
    for (size_t k = 0; k < fromDraft.geometry[0].meshes.size(); ++k) {
        const Mesh& a = fromDraft.meshes[fromDraft.geometry[0].meshes[k]];
        const Mesh& b = fromFile.meshes[fromFile.geometry[0].meshes[k]];
        EXPECT_EQ(a.name, b.name);
        EXPECT_EQ(a.positions, b.positions);
    }
    ASSERT_EQ(fromDraft.taskAreas.size(), 1u);
    EXPECT_EQ(fromDraft.taskAreas[0].lo, fromFile.taskAreas[0].lo);
    EXPECT_EQ(fromDraft.taskAreas[0].hi, fromFile.taskAreas[0].hi);
    // The camera stands inside the room.
    const glm::dvec3& eye = fromDraft.camera.position;
    EXPECT_TRUE(insidePolygon(floorOutline(d), {eye.x, eye.z}));
    EXPECT_GT(eye.y, 0.0);
    EXPECT_LT(eye.y, d.height);
}

TEST(EditorRoom, AnLsFloorIsTheRectangleLessItsCorner) {
    RoomDraft d;
    d.shape = RoomShape::LShape;
    d.width = 12.0, d.depth = 9.0, d.notchWidth = 5.0, d.notchDepth = 4.0;
    std::vector<glm::dvec2> outline = floorOutline(d);
    EXPECT_EQ(outline.size(), 6u);
    EXPECT_NEAR(std::abs(signedArea(outline)), 12.0 * 9.0 - 5.0 * 4.0, 1e-12);
    EXPECT_EQ(polygonDefect(outline), "");
    // Its task area is the part that spans the whole width: 12 x 5 m.
    nlohmann::json area = taskAreaEntry(d);
    const nlohmann::json& e = area["extent"];
    EXPECT_DOUBLE_EQ(e[2].get<double>() - e[0].get<double>(), 12.0);
    EXPECT_DOUBLE_EQ(e[3].get<double>() - e[1].get<double>(), 5.0);
    bool valid = false;
    std::string summary = roomDraftSummary(d, valid);
    EXPECT_TRUE(valid) << summary;
    EXPECT_NE(summary.find("88.0 m² floor, 6 walls"), std::string::npos) << summary;

    // A cut as large as the room leaves no L.
    d.notchWidth = 12.0;
    EXPECT_THROW(floorOutline(d), InputError);
}

TEST(EditorRoom, TypedOutlinesAreCheckedCornerByCorner) {
    RoomDraft d;
    d.shape = RoomShape::Polygon;
    d.polygon = "0 0; 6 0, 6 4 , 0 4";
    EXPECT_EQ(floorOutline(d).size(), 4u);
    d.polygon = "0 0, 6, 6 4, 0 4";
    try {
        floorOutline(d);
        ADD_FAILURE() << "a corner of one number was taken";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("corner 2"), std::string::npos) << e.what();
    }
    d.polygon = "0 0, 6 0";
    EXPECT_THROW(floorOutline(d), InputError);
    // A crossing outline is the scene parser's to refuse, and the summary says so.
    d.polygon = "0 0, 4 4, 4 0, 0 4";
    bool valid = true;
    std::string summary = roomDraftSummary(d, valid);
    EXPECT_FALSE(valid);
    EXPECT_NE(summary.find("floor"), std::string::npos) << summary;
}

TEST(EditorRoom, FileNewMakesAnUntitledSceneThatSavesAndLoadsBack) {
    isolate();
    EditorState state;
    ASSERT_TRUE(newSceneFromRoom(state, classroomDraft()));
    EXPECT_TRUE(state.scene.path.empty());
    EXPECT_TRUE(state.dirty);
    EXPECT_TRUE(state.history.undo.empty());
    EXPECT_EQ(state.scene.taskAreas.size(), 1u);
    EXPECT_EQ(state.scene.geometry.size(), 3u);  // the room and two pieces of furniture
    test::TempDir dir;
    std::string path = (dir.path() / "classroom.json").string();
    ASSERT_TRUE(saveSceneFile(state, path));
    Scene back = loadScene(path);
    EXPECT_EQ(sceneToJson(back).dump(), sceneToJson(state.scene).dump());

    // A draft the parser refuses changes nothing.
    RoomDraft bad = classroomDraft();
    bad.openings[0].wall = 9;  // the room has 4 walls
    std::string before = sceneToJson(state.scene).dump();
    EXPECT_FALSE(newSceneFromRoom(state, bad));
    EXPECT_FALSE(state.modalError.empty());
    EXPECT_EQ(sceneToJson(state.scene).dump(), before);
}

TEST(EditorRoom, AddingEditingAndRemovingGeometryAreUndoSteps) {
    isolate();
    EditorState state;
    ASSERT_TRUE(newSceneFromRoom(state, classroomDraft()));
    std::string original = sceneToJson(state.scene).dump();
    size_t meshes = state.scene.meshes.size();

    // A skylight: one more opening, undone exactly.
    OpeningDraft sky;
    sky.type = "skylight";
    sky.center = {0.0, 0.0}, sky.size = {1.2, 1.2};
    ASSERT_TRUE(addOpening(state, 0, sky));
    EXPECT_EQ(state.scene.geometry[0].source["room"]["openings"].size(), 5u);
    ASSERT_TRUE(undo(state));
    EXPECT_EQ(sceneToJson(state.scene).dump(), original);
    EXPECT_EQ(state.scene.meshes.size(), meshes);

    // The inspector's edit of the height: the walls grow with it.
    nlohmann::json entry = state.scene.geometry[0].source;
    entry["room"]["height"] = 3.5;
    ASSERT_TRUE(replaceGeometryEntry(state, 0, entry, "Edit Classroom"));
    EXPECT_NEAR(state.scene.boundsMax().y, 3.5, 1e-6);
    // A refused value (a negative height) changes nothing and says why.
    size_t steps = state.history.undo.size();
    std::string edited = sceneToJson(state.scene).dump();
    entry["room"]["height"] = -1.0;
    EXPECT_FALSE(replaceGeometryEntry(state, 0, entry, "Edit Classroom"));
    EXPECT_NE(state.inspectorError.find("height"), std::string::npos) << state.inspectorError;
    EXPECT_EQ(sceneToJson(state.scene).dump(), edited);
    EXPECT_EQ(state.history.undo.size(), steps);

    // Furniture where the camera looks, on the room's floor; then removed; all undone.
    ASSERT_EQ(roomFloorAt(state.scene, {1.0, 1.0}).value_or(-1.0), 0.0);
    EXPECT_FALSE(roomFloorAt(state.scene, {20.0, 0.0}).has_value());
    int chair = addFurniture(state, "chair", {1.0, 1.0}, 0.0);
    ASSERT_GE(chair, 0);
    EXPECT_EQ(state.selectedGeometry, chair);
    EXPECT_EQ(state.scene.geometry[size_t(chair)].source["furniture"]["type"], "chair");
    ASSERT_TRUE(removeGeometryEntry(state, 0));  // the room itself
    EXPECT_EQ(state.scene.geometry.size(), 3u);
    while (undo(state)) {
    }
    EXPECT_EQ(sceneToJson(state.scene).dump(), original);
    EXPECT_EQ(state.scene.meshes.size(), meshes);
    EXPECT_EQ(addFurniture(state, "piano", {0.0, 0.0}, 0.0), -1);
}

TEST(EditorRoom, AddingARoomToAScenePutsItsTaskAreaWithIt) {
    isolate();
    EditorState state;
    ASSERT_TRUE(newSceneFromRoom(state, classroomDraft()));
    RoomDraft next;
    next.name = "Office";
    next.shape = RoomShape::Polygon;
    next.polygon = "6 -4, 10 -4, 10 0, 6 0";
    next.taskArea = true;  // none for a typed outline: drawn in the Measure panel
    ASSERT_TRUE(addRoom(state, next));
    EXPECT_EQ(state.scene.taskAreas.size(), 1u);
    EXPECT_EQ(state.history.undo.size(), 1u);
    EXPECT_EQ(state.scene.geometry.back().source["room"]["name"], "Office");
    next.shape = RoomShape::Rectangle;
    next.width = 4.0, next.depth = 4.0;
    ASSERT_TRUE(addRoom(state, next));
    EXPECT_EQ(state.scene.taskAreas.size(), 2u);
    ASSERT_TRUE(undo(state));
    EXPECT_EQ(state.scene.taskAreas.size(), 1u);
}

TEST(EditorRoom, TheProjectsDataIsAnUndoStepSavedWithTheScene) {
    isolate();
    EditorState state;
    ASSERT_TRUE(newSceneFromRoom(state, classroomDraft()));
    std::string original = sceneToJson(state.scene).dump();
    ProjectInfo p;
    p.name = "Primary school";
    p.client = "Town of Riverside";
    ASSERT_TRUE(setProjectInfo(state, p));
    EXPECT_FALSE(setProjectInfo(state, p));  // nothing changes: no step
    EXPECT_EQ(state.history.undo.size(), 1u);
    EXPECT_EQ(sceneToJson(state.scene)["project"],
              nlohmann::json({{"name", "Primary school"}, {"client", "Town of Riverside"}}));
    ASSERT_TRUE(undo(state));
    EXPECT_EQ(sceneToJson(state.scene).dump(), original);
}

TEST(EditorRoom, TypedDistancesAreTheRoomsOwn) {
    isolate();
    EditorState state;
    ASSERT_TRUE(newSceneFromRoom(state, classroomDraft()));
    // Above the windows (their tops at 2.5 m): the 10 x 8 m room's walls at x = -5, 5 and
    // z = -4, 4. The walls are float triangles: a few micrometres.
    glm::dvec3 p(1.0, 2.7, -1.0);
    EXPECT_NEAR(floorBelow(state, p).value_or(-1.0), 0.0, 1e-12);
    EXPECT_NEAR(clearDistance(state, p, {-1, 0, 0}).value_or(0.0), 6.0, 1e-5);
    EXPECT_NEAR(clearDistance(state, p, {1, 0, 0}).value_or(0.0), 4.0, 1e-5);
    EXPECT_NEAR(clearDistance(state, p, {0, 0, -1}).value_or(0.0), 3.0, 1e-5);
    EXPECT_NEAR(clearDistance(state, p, {0, 0, 1}).value_or(0.0), 5.0, 1e-5);
    // Through a window (wall 4 is x = -5; the middle window spans z = 1 .. -1, sill 0.9 m to
    // 2.5 m): nothing to meet.
    EXPECT_FALSE(clearDistance(state, {1.0, 1.5, 0.0}, {-1, 0, 0}).has_value());
    // A luminaire's own housing does not stop the ray: one added at p measures the same.
    ASSERT_GE(addLuminaireFromFile(
                  state, CANDELA_SOURCE_DIR "/resources/luminaires/photometric/prolicht-e30.ldt"),
              0);
    applyEdit(state, "Move", kChangeLuminaires,
              [&](Scene& s) { s.luminaires.back()->pose.position = p; });
    EXPECT_NEAR(clearDistance(state, p, {1, 0, 0}).value_or(0.0), 4.0, 1e-5);
}

TEST(EditorLayout, AProposalRunsApartAndIsAcceptedAsOneUndoStep) {
    isolate();
    EditorState state;
    RoomDraft small;
    small.name = "Office";
    small.width = 4.0, small.depth = 4.0, small.height = 2.8;
    small.requiredEm = 300.0;
    ASSERT_TRUE(newSceneFromRoom(state, small));
    std::string original = sceneToJson(state.scene).dump();
    const std::string file =
        CANDELA_SOURCE_DIR "/resources/luminaires/photometric/prolicht-e30.ldt";
    LayoutRequest request;
    request.name = "Linear";
    request.luminaire = layoutLuminaireEntry(file, "");
    request.mountingHeight = 2.5;
    auto job = std::make_shared<LayoutJob>(state.scene, request);
    // The editor goes on while it runs: the scene may change under it.
    applyEdit(state, "Maintenance factor", kChangeLuminaires,
              [](Scene& s) { s.maintenanceFactor = 0.7; });
    while (!job->done()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ASSERT_TRUE(job->result().has_value()) << job->error();
    const LayoutResult& result = *job->result();
    const LayoutCandidate* best = result.best();
    ASSERT_NE(best, nullptr);
    EXPECT_GE(best->em, 300.0);
    size_t steps = state.history.undo.size();
    ASSERT_TRUE(acceptLayout(state, job->request(), result));
    EXPECT_EQ(state.history.undo.size(), steps + 1);
    EXPECT_EQ(int(state.scene.luminaires.size()), best->count());
    EXPECT_EQ(state.scene.maintenanceFactor, 0.7);  // applied to the scene as it is now
    nlohmann::json doc = sceneToJson(state.scene);
    ASSERT_EQ(doc["layouts"].size(), 1u);
    EXPECT_EQ(doc["layouts"][0]["grid"], nlohmann::json({best->columns, best->rows}));
    // The Library lists the file the scene now uses, with its count.
    std::vector<LibraryEntry> used = sceneLuminaireFiles(state.scene);
    ASSERT_EQ(used.size(), 1u);
    EXPECT_EQ(used[0].label, "prolicht-e30.ldt (" + std::to_string(best->count()) +
                                 (best->count() == 1 ? " luminaire)" : " luminaires)"));
    ASSERT_TRUE(undo(state));
    ASSERT_TRUE(undo(state));
    EXPECT_EQ(sceneToJson(state.scene).dump(), original);

    // A proposal no longer wanted stops at its next arrangement; dropping it waits for that.
    auto cancelled = std::make_shared<LayoutJob>(state.scene, request);
    cancelled.reset();
    // One that cannot be: the error says why.
    request.mountingHeight = 0.5;  // below the work plane
    LayoutJob low(state.scene, request);
    while (!low.done()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    EXPECT_FALSE(low.result().has_value());
    EXPECT_FALSE(low.error().empty());
}

}  // namespace
}  // namespace candela::ui
