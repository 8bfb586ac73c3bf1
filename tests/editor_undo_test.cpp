// Undo and redo of the editor's scene edits (ui/EditorState.h): every edit through applyEdit is
// a step, a gesture's edits with one label merge, camera navigation is not recorded, and undoing
// restores the scene exactly as it was (checked against the scene file's own serialisation).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "luminaires/Adapter.h"
#include "scene/SceneIo.h"
#include "ui/EditorState.h"
#include "ui/Project.h"

namespace candela::ui {
namespace {

EditorState demo() {
    // Opening a scene records it in the recent files: keep that out of the user's home.
    static const bool isolated = [] {
        return setenv("CANDELA_STATE_DIR",
                      (std::filesystem::temp_directory_path() / "candela-undo-test").c_str(),
                      1) == 0;
    }();
    EXPECT_TRUE(isolated);
    EditorState state;
    EXPECT_TRUE(openSceneFile(state, CANDELA_SOURCE_DIR "/resources/scenes/editor-room.json"));
    return state;
}

/// The scene as its file would hold it: what undo must bring back.
std::string text(const EditorState& state) {
    return sceneToJson(state.scene).dump();
}

void move(EditorState& state, int index, glm::dvec3 by) {
    applyEdit(state, "Move " + state.scene.luminaires[size_t(index)]->name, kChangeLuminaires,
              [&](Scene& s) { s.luminaires[size_t(index)]->pose.position += by; });
}

TEST(EditorUndo, ADragIsOneStepAndUndoRedoRestoreExactly) {
    EditorState state = demo();
    std::string original = text(state);
    ++state.history.gesture;  // mouse press
    for (int i = 0; i < 10; ++i) move(state, 1, {0.05, 0.0, 0.0});
    ++state.history.gesture;  // release
    std::string moved = text(state);
    ASSERT_NE(moved, original);
    EXPECT_EQ(state.history.undo.size(), 1u);
    EXPECT_EQ(state.history.undo.back().label, "Move LED spot");

    state.pendingChanges = kChangeNone;
    ASSERT_TRUE(undo(state));
    EXPECT_EQ(text(state), original);
    EXPECT_NE(state.pendingChanges & kChangeLuminaires, 0u);  // the renderer hears of it
    EXPECT_FALSE(undo(state));                                // nothing left
    ASSERT_TRUE(redo(state));
    EXPECT_EQ(text(state), moved);
    EXPECT_FALSE(redo(state));
}

TEST(EditorUndo, TaskAreasFromTheGridAreStepsAndSaveWithTheScene) {
    EditorState state = demo();
    std::string original = text(state);
    size_t before = state.scene.taskAreas.size();
    // No extent yet: refused, nothing recorded.
    EXPECT_FALSE(addTaskAreaFromGrid(state));
    EXPECT_EQ(text(state), original);
    state.measure.grid.plane = parsePlane("y=0.75");
    state.measure.grid.lo = {-0.8, -0.4};
    state.measure.grid.hi = {0.8, 0.4};
    state.measure.extentSet = true;
    state.measure.taskName = "Table";
    state.measure.taskRequired = {300.0, 0.4};
    ASSERT_TRUE(addTaskAreaFromGrid(state));
    ASSERT_EQ(state.scene.taskAreas.size(), before + 1);
    const TaskArea& a = state.scene.taskAreas.back();
    EXPECT_EQ(a.name, "Table");
    EXPECT_EQ(a.plane.offset, 0.75);
    EXPECT_EQ(a.lo, glm::dvec2(-0.8, -0.4));
    EXPECT_EQ(a.hi, glm::dvec2(0.8, 0.4));
    EXPECT_EQ(a.required, (Requirement{300.0, 0.4}));
    // It is in the scene file, and it evaluates: the table, its surrounding and background.
    Scene saved = parseScene(sceneToJson(state.scene), state.scene.path);
    ASSERT_EQ(saved.taskAreas.size(), before + 1);
    EXPECT_EQ(saved.taskAreas.back().name, "Table");
    EXPECT_EQ(layoutSurfaces(saved).size(), 3 * (before + 1));
    std::string added = text(state);
    ASSERT_TRUE(undo(state));
    EXPECT_EQ(text(state), original);
    ASSERT_TRUE(redo(state));
    EXPECT_EQ(text(state), added);
    removeTaskArea(state, state.scene.taskAreas.size() - 1);
    EXPECT_EQ(state.scene.taskAreas.size(), before);
    EXPECT_EQ(state.history.undo.back().label, "Remove task area Table");
}

// A task area drawn with the mouse: the rectangle between the drag's two points on the grid's
// plane, corners rounded to 1 cm, whichever way the drag went; one step that also sets the grid's
// extent; a drag under 5 cm on a side is refused with no step.
TEST(EditorUndo, DrawnTaskAreasAreStepsOnTheGridsPlane) {
    EditorState state = demo();
    std::string original = text(state);
    size_t before = state.scene.taskAreas.size(), steps = state.history.undo.size();
    state.measure.grid.plane = parsePlane("y=0.8");
    state.measure.taskName = "Bench";
    state.measure.taskRequired = {750.0, 0.7};
    // Too thin along z: refused, and the status says why.
    EXPECT_FALSE(addTaskAreaFromDrag(state, {0.2, 0.8, 1.0}, {1.4, 0.8, 1.03}));
    EXPECT_TRUE(state.statusIsError);
    EXPECT_NE(state.status.find("too small"), std::string::npos) << state.status;
    EXPECT_EQ(text(state), original);
    EXPECT_EQ(state.history.undo.size(), steps);
    // Dragged from the far corner back to the near one.
    ASSERT_TRUE(addTaskAreaFromDrag(state, {1.4037, 0.8, 1.2449}, {-0.3012, 0.8, 0.4951}));
    ASSERT_EQ(state.scene.taskAreas.size(), before + 1);
    const TaskArea& a = state.scene.taskAreas.back();
    EXPECT_EQ(a.name, "Bench");
    EXPECT_EQ(a.plane.axis, 1);
    EXPECT_EQ(a.plane.offset, 0.8);
    EXPECT_EQ(a.lo, glm::dvec2(-0.30, 0.50));  // (x, z), rounded to 1 cm
    EXPECT_EQ(a.hi, glm::dvec2(1.40, 1.24));
    EXPECT_EQ(a.required, (Requirement{750.0, 0.7}));
    EXPECT_EQ(state.measure.grid.lo, a.lo);  // the grid takes it as its extent
    EXPECT_EQ(state.measure.grid.hi, a.hi);
    EXPECT_TRUE(state.measure.extentSet);
    EXPECT_EQ(state.history.undo.size(), steps + 1);
    EXPECT_EQ(state.history.undo.back().label, "Draw task area Bench");
    ASSERT_TRUE(undo(state));
    EXPECT_EQ(text(state), original);
    // On a wall (x = 2.5 facing -x) the rectangle spans (y, z).
    state.measure.grid.plane = parsePlane("-x=2.5");
    ASSERT_TRUE(addTaskAreaFromDrag(state, {2.5, 0.5, -1.0}, {2.5, 2.0, 1.0}));
    EXPECT_EQ(state.scene.taskAreas.back().lo, glm::dvec2(0.5, -1.0));
    EXPECT_EQ(state.scene.taskAreas.back().hi, glm::dvec2(2.0, 1.0));
}

// The Measure panel's grid starts on the scene's first task area, moves to an area just added,
// back to the first when areas are removed or an edit undone, stays where the user put it while
// the areas stay as they are, and a scene opened without task areas starts it afresh.
TEST(EditorUndo, TheMeasureGridFollowsTheTaskAreas) {
    EditorState state = demo();
    state.measure.surfaces = SurfaceReport{};  // results of the scene about to be left
    ASSERT_TRUE(openSceneFile(state, CANDELA_SOURCE_DIR "/resources/scenes/office.json"));
    EXPECT_FALSE(state.measure.surfaces.has_value());
    // The office's desk: y=0.75, x -0.4..1.2 m, z -0.7..0.1 m (its scene file).
    GridSpec& g = state.measure.grid;
    EXPECT_EQ(planeText(g.plane), "y=0.75");
    EXPECT_EQ(g.lo, glm::dvec2(-0.4, -0.7));
    EXPECT_EQ(g.hi, glm::dvec2(1.2, 0.1));
    EXPECT_TRUE(state.measure.extentSet);
    // The user's own grid stays while the areas do.
    g.plane = parsePlane("y=0");
    g.lo = {-2.0, -2.0};
    EXPECT_FALSE(followTaskAreas(state));
    EXPECT_EQ(planeText(g.plane), "y=0");
    // An area added (here not through the grid): the grid shows it.
    TaskArea shelf;
    shelf.name = "Shelf";
    shelf.plane = parsePlane("-x=1.9");
    shelf.lo = {1.0, -1.0};
    shelf.hi = {1.8, 0.5};
    applyEdit(state, "Add task area Shelf", kChangeSettings,
              [&](Scene& s) { s.taskAreas.push_back(shelf); });
    EXPECT_TRUE(followTaskAreas(state));
    EXPECT_EQ(planeText(g.plane), planeText(shelf.plane));
    EXPECT_EQ(g.lo, shelf.lo);
    EXPECT_EQ(g.hi, shelf.hi);
    EXPECT_FALSE(followTaskAreas(state));  // once
    // The desk removed: the first left is the shelf; undone: the desk again.
    removeTaskArea(state, 0);
    followTaskAreas(state);
    EXPECT_EQ(planeText(g.plane), planeText(shelf.plane));
    ASSERT_TRUE(undo(state));
    EXPECT_TRUE(followTaskAreas(state));
    EXPECT_EQ(planeText(g.plane), "y=0.75");
    EXPECT_EQ(g.lo, glm::dvec2(-0.4, -0.7));
    // A scene without task areas: the floor, its extent the scene's bounds when computed.
    ASSERT_TRUE(openSceneFile(state, CANDELA_SOURCE_DIR "/resources/scenes/editor-room.json"));
    EXPECT_EQ(planeText(g.plane), "y=0");
    EXPECT_FALSE(state.measure.extentSet);
}

// A GLDF luminaire's body follows its luminaire through edits, undo and redo, and tells the
// renderer the geometry changed (its mesh moved).
TEST(EditorUndo, LuminaireBodiesFollowMovesAndUndo) {
    EditorState state = demo();
    size_t before = state.scene.bodyCount();
    nlohmann::json lamp = {{"type", "gldf"},
                           {"name", "Pendant"},
                           {"file", CANDELA_TEST_DATA "/gldf/PendantTwoEmitters.gldf"},
                           {"position", {0, 2.2, 0}}};
    applyEdit(state, "Add pendant", kChangeLuminaires, [&](Scene& s) {
        s.luminaires.push_back(parseLuminaire(lamp, json::Where{"test", "luminaires"}));
        for (auto& c : companions(*s.luminaires.back())) s.luminaires.push_back(std::move(c));
    });
    // The demo room's linear pendant has its luminous box; the GLDF pendant brings its housing.
    auto housingX = [&] {
        for (const Mesh& m : state.scene.meshes)
            if (m.luminaireBody && !m.hidden) return double(m.boundsMin.x);
        return -1e9;
    };
    ASSERT_EQ(state.scene.bodyCount(), before + 1);
    double x0 = housingX();
    state.pendingChanges = kChangeNone;
    int pendant = int(state.scene.luminaires.size()) - 2;
    move(state, pendant, {0.5, 0.0, 0.0});
    EXPECT_NEAR(housingX(), x0 + 0.5, 1e-6);  // its sibling emitter moved with it, and the body
    EXPECT_NE(state.pendingChanges & kChangeGeometry, 0u);
    state.pendingChanges = kChangeNone;
    ASSERT_TRUE(undo(state));
    EXPECT_NEAR(housingX(), x0, 1e-6);
    EXPECT_NE(state.pendingChanges & kChangeGeometry, 0u);
    ASSERT_TRUE(undo(state));  // the pendant itself
    EXPECT_EQ(state.scene.bodyCount(), before);
    ASSERT_TRUE(redo(state));
    EXPECT_EQ(state.scene.bodyCount(), before + 1);
    // The saved scene holds no body geometry: it is the luminaire's.
    Scene saved = parseScene(sceneToJson(state.scene), state.scene.path);
    EXPECT_EQ(saved.geometry.size(), state.scene.geometry.size());
    EXPECT_EQ(saved.bodyCount(), before + 1);
}

// A glare observer at the camera: its eye where the camera is, its line of sight the camera's
// made horizontal; one step, saved with the scene, refused when the camera looks straight down.
TEST(EditorUndo, GlareObserversAtTheCameraAreStepsAndSaveWithTheScene) {
    EditorState state = demo();
    std::string original = text(state);
    state.scene.camera.position = {1.0, 1.2, 3.0};
    state.scene.camera.target = {1.0, 0.2, 0.0};  // looking forward and down
    state.measure.observerName = "Desk";
    state.measure.observerLimit = 19.0;
    original = text(state);
    ASSERT_TRUE(addGlareObserverAtCamera(state));
    ASSERT_EQ(state.scene.glareObservers.size(), 1u);
    const GlareObserver& o = state.scene.glareObservers[0];
    EXPECT_EQ(o.name, "Desk");
    EXPECT_EQ(o.position, glm::dvec3(1.0, 1.2, 3.0));
    EXPECT_EQ(o.view, glm::dvec3(0.0, 0.0, -1.0));
    EXPECT_EQ(o.limit, 19.0);
    EXPECT_EQ(parseScene(sceneToJson(state.scene), state.scene.path).glareObservers,
              state.scene.glareObservers);
    ASSERT_TRUE(undo(state));
    EXPECT_EQ(text(state), original);
    ASSERT_TRUE(redo(state));
    removeGlareObserver(state, 0);
    EXPECT_TRUE(state.scene.glareObservers.empty());
    EXPECT_EQ(state.history.undo.back().label, "Remove glare observer Desk");
    state.scene.camera.target = {1.0, -1.0, 3.0};  // straight down
    std::string before = text(state);
    EXPECT_FALSE(addGlareObserverAtCamera(state));
    EXPECT_TRUE(state.statusIsError);
    EXPECT_EQ(text(state), before);
}

TEST(EditorUndo, StepsUndoInReverseOrderAndANewEditClearsRedo) {
    EditorState state = demo();
    std::vector<std::string> versions = {text(state)};
    ++state.history.gesture;
    move(state, 0, {0.0, 0.0, 0.5});
    versions.push_back(text(state));
    ++state.history.gesture;
    int added = addLuminaire(state, *findKind("photometric"));
    ASSERT_EQ(added, 3);
    EXPECT_EQ(state.selectedLuminaire, 3);
    versions.push_back(text(state));
    ++state.history.gesture;
    deleteLuminaire(state, 1);
    versions.push_back(text(state));

    for (int v = 2; v >= 0; --v) {
        ASSERT_TRUE(undo(state));
        EXPECT_EQ(text(state), versions[size_t(v)]) << "after undoing to version " << v;
    }
    EXPECT_LT(state.selectedLuminaire, int(state.scene.luminaires.size()));  // never dangling
    ASSERT_TRUE(redo(state));
    EXPECT_EQ(text(state), versions[1]);
    ++state.history.gesture;
    move(state, 2, {0.1, 0.0, 0.0});  // a new edit: the redo stack is gone
    EXPECT_FALSE(redo(state));
}

TEST(EditorUndo, CameraNavigationIsNotAStepButMarksTheSceneUnsaved) {
    EditorState state = demo();
    applyEdit(state, "Orbit camera", kChangeCamera, [](Scene& s) { s.camera.position.x += 1.0; });
    EXPECT_TRUE(state.history.undo.empty());
    EXPECT_TRUE(state.dirty);
}

TEST(EditorUndo, GeometryStepsRestoreTheMeshes) {
    EditorState state = demo();
    std::string original = text(state);
    size_t meshes = state.scene.meshes.size();
    ++state.history.gesture;
    applyEdit(state, "Delete geometry", kChangeGeometry, [](Scene& s) {
        // The last entry's one mesh (the luminaires' bodies come after it).
        s.meshes.erase(s.meshes.begin() + s.geometry.back().meshes.at(0));
        s.geometry.pop_back();
    });
    ASSERT_EQ(state.scene.meshes.size(), meshes - 1);
    ASSERT_TRUE(undo(state));
    EXPECT_EQ(state.scene.meshes.size(), meshes);
    EXPECT_EQ(text(state), original);
    EXPECT_NE(state.pendingChanges & kChangeGeometry, 0u);
}

TEST(EditorUndo, OpeningAnotherSceneForgetsTheHistory) {
    EditorState state = demo();
    ++state.history.gesture;
    move(state, 0, {0.1, 0.0, 0.0});
    ASSERT_TRUE(openSceneFile(state, CANDELA_SOURCE_DIR "/resources/scenes/demo.json"));
    EXPECT_FALSE(undo(state));
    // The unsaved move was kept in this session's autosave beside the shipped scene: not there.
    std::string left = CANDELA_SOURCE_DIR "/resources/scenes/editor-room.json";
    EXPECT_TRUE(std::filesystem::exists(autosavePath(left, state.project.session)));
    removeAutosave(left, state.project.session);
}

}  // namespace
}  // namespace candela::ui

namespace candela::ui {
namespace {

TEST(EditorUndo, MultiSelectionTogglesAndDeletesAsOneStep) {
    EditorState state = demo();  // three luminaires
    std::string original = text(state);
    state.selectedLuminaire = 0;
    toggleSelected(state, 2);
    EXPECT_EQ(selectedLuminaires(state), (std::vector<int>{0, 2}));
    EXPECT_EQ(state.selectedLuminaire, 2);  // the one added shows in the inspector
    toggleSelected(state, 2);
    EXPECT_EQ(selectedLuminaires(state), (std::vector<int>{0}));
    toggleSelected(state, 1);
    toggleSelected(state, 2);
    ASSERT_EQ(selectedLuminaires(state).size(), 3u);
    ++state.history.gesture;
    deleteSelected(state);
    EXPECT_TRUE(state.scene.luminaires.empty());
    EXPECT_TRUE(selectedLuminaires(state).empty());
    EXPECT_EQ(state.history.undo.back().label, "Delete 3 luminaires");
    ASSERT_TRUE(undo(state));
    EXPECT_EQ(text(state), original);
    EXPECT_TRUE(state.alsoSelected.empty());  // no stale indices after the list changed
}

}  // namespace
}  // namespace candela::ui
