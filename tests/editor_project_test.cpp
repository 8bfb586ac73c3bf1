// Projects (ui/Project.h): where autosaves go, that one newer than its scene is restored and an
// older one is not, that saving removes it, and the recent-files list. All state goes to a
// temporary CANDELA_STATE_DIR.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "scene/SceneIo.h"
#include "ui/EditorState.h"
#include "ui/Project.h"

namespace candela::ui {
namespace {

namespace fs = std::filesystem;

class EditorProject : public ::testing::Test {
  protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("candela-project-test-" + std::to_string(::getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir / "state");
        setenv("CANDELA_STATE_DIR", (dir / "state").c_str(), 1);
        scene = (dir / "room.json").string();
        fs::copy_file(CANDELA_SOURCE_DIR "/resources/scenes/demo.json", scene);
    }
    void TearDown() override {
        unsetenv("CANDELA_STATE_DIR");
        fs::remove_all(dir);
    }
    fs::path dir;
    std::string scene;
};

TEST_F(EditorProject, AutosaveSitsBesideTheSceneAndUntitledInTheStateFolder) {
    EXPECT_EQ(autosavePath(scene), dir / ".room.autosave.json");
    EXPECT_EQ(autosavePath(""), dir / "state" / "untitled.autosave.json");
    EXPECT_EQ(stateDir(), dir / "state");
}

TEST_F(EditorProject, AnAutosaveNewerThanTheSceneIsRestoredThenRemovedBySaving) {
    EditorState state;
    ASSERT_TRUE(openSceneFile(state, scene));
    std::string original = sceneToJson(state.scene).dump();
    applyEdit(state, "Move Ceiling panel", kChangeLuminaires,
              [](Scene& s) { s.luminaires[0]->pose.position.x += 0.75; });
    std::string edited = sceneToJson(state.scene).dump();
    ASSERT_TRUE(writeAutosave(state));
    ASSERT_TRUE(fs::exists(autosavePath(scene)));
    EXPECT_EQ(sceneToJson(loadScene(scene)).dump(), original);  // the scene file is untouched

    EditorState after;  // a new session, as after a crash
    ASSERT_TRUE(openSceneFile(after, scene));
    EXPECT_EQ(sceneToJson(after.scene).dump(), edited);
    EXPECT_TRUE(after.dirty);
    EXPECT_EQ(after.scene.path, scene);  // Save writes the scene, not the autosave
    EXPECT_NE(after.status.find("Restored"), std::string::npos);

    ASSERT_TRUE(saveSceneFile(after, ""));
    EXPECT_FALSE(fs::exists(autosavePath(scene)));
    EXPECT_EQ(sceneToJson(loadScene(scene)).dump(), edited);
}

TEST_F(EditorProject, AnAutosaveOlderThanTheSceneIsIgnored) {
    EditorState state;
    ASSERT_TRUE(openSceneFile(state, scene));
    applyEdit(state, "Move Ceiling panel", kChangeLuminaires,
              [](Scene& s) { s.luminaires[0]->pose.position.x += 0.75; });
    ASSERT_TRUE(writeAutosave(state));
    // The scene was saved (by another program) after the autosave.
    fs::last_write_time(autosavePath(scene), fs::last_write_time(scene) - std::chrono::seconds(10));
    EditorState after;
    ASSERT_TRUE(openSceneFile(after, scene));
    EXPECT_FALSE(after.dirty);
    EXPECT_EQ(sceneToJson(after.scene).dump(), sceneToJson(loadScene(scene)).dump());
}

TEST_F(EditorProject, ADamagedAutosaveIsReportedAndKept) {
    std::ofstream(autosavePath(scene)) << "{ not json";
    fs::last_write_time(autosavePath(scene), fs::last_write_time(scene) + std::chrono::seconds(10));
    EditorState state;
    ASSERT_TRUE(openSceneFile(state, scene));  // the scene itself opens
    EXPECT_TRUE(state.statusIsError);
    EXPECT_NE(state.status.find("autosave"), std::string::npos);
    EXPECT_TRUE(fs::exists(autosavePath(scene)));  // nothing lost: kept for the user to look at
}

TEST_F(EditorProject, RecentFilesNewestFirstWithoutDuplicatesOrMissingFiles) {
    std::string other = (dir / "other.json").string();
    fs::copy_file(scene, other);
    addRecentFile(scene);
    addRecentFile(other);
    addRecentFile(scene);
    std::vector<std::string> recent = recentFiles();
    ASSERT_EQ(recent.size(), 2u);
    EXPECT_EQ(recent[0], scene);
    EXPECT_EQ(recent[1], other);
    fs::remove(other);
    EXPECT_EQ(recentFiles(), std::vector<std::string>{scene});
}

}  // namespace
}  // namespace candela::ui
