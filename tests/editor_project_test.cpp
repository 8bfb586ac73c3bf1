// Projects (ui/Project.h): every editor autosaves to its own file, which no other editor removes;
// an autosave of an editor that is no longer running is offered (not applied) when the scene is
// opened, restored on request and removed by saving; a save over a file changed on disk asks
// first; and the recent-files list. Two editors are two EditorStates with the sessions of two
// processes: this one, and a child that sleeps (running) or has exited (crashed). All state goes
// to a temporary CANDELA_STATE_DIR.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

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

/// A child process: running until stop(), then gone (its session no longer runs).
class OtherProcess {
  public:
    OtherProcess() {
        mPid = ::fork();
        if (mPid == 0) {
            ::pause();  // until killed
            ::_exit(0);
        }
        // Wait until /proc shows it (its start time is what makes the session).
        for (int i = 0; i < 1000 && EditorSession::of(mPid).start == 0; ++i) ::usleep(1000);
        session = EditorSession::of(mPid);
    }
    ~OtherProcess() { stop(); }
    void stop() {
        if (mPid <= 0) return;
        ::kill(mPid, SIGKILL);
        ::waitpid(mPid, nullptr, 0);
        mPid = -1;
    }
    EditorSession session;

  private:
    pid_t mPid = -1;
};

class EditorProject : public ::testing::Test {
  protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("candela-project-test-" + std::to_string(::getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir / "state");
        setenv("CANDELA_STATE_DIR", (dir / "state").c_str(), 1);
        scene = (dir / "room.json").string();
        fs::copy_file(CANDELA_SOURCE_DIR "/resources/scenes/demo.json", scene);
        // Written well before any editor of the test started (whose start is known to 10 ms).
        fs::last_write_time(scene, fs::file_time_type::clock::now() - std::chrono::minutes(1));
    }
    void TearDown() override {
        unsetenv("CANDELA_STATE_DIR");
        fs::remove_all(dir);
    }
    /// Opens the scene as the editor `session` would.
    void open(EditorState& state, const EditorSession& session) {
        state.project.session = session;
        ASSERT_TRUE(openSceneFile(state, scene));
    }
    static void moveFirst(EditorState& state, double dx) {
        applyEdit(state, "Move Ceiling panel", kChangeLuminaires,
                  [dx](Scene& s) { s.luminaires[0]->pose.position.x += dx; });
    }
    static double firstX(const Scene& s) { return s.luminaires[0]->pose.position.x; }
    double savedX() const { return firstX(loadScene(scene)); }
    /// Autosave files beside the scene.
    size_t autosaves() const {
        size_t n = 0;
        for (const auto& entry : fs::directory_iterator(dir))
            n += entry.path().filename().string().rfind(".room.autosave", 0) == 0;
        return n;
    }
    fs::path dir;
    std::string scene;
};

TEST_F(EditorProject, EachEditorAutosavesBesideTheSceneUnderItsOwnName) {
    EditorSession self = EditorSession::current();
    EXPECT_GT(self.start, 0u);
    EXPECT_TRUE(self.running());
    EXPECT_EQ(autosavePath(scene, self), dir / (".room.autosave-" + self.tag() + ".json"));
    EXPECT_EQ(autosavePath("", self),
              dir / "state" / ("untitled.autosave-" + self.tag() + ".json"));
    OtherProcess other;
    EXPECT_TRUE(other.session.running());
    EXPECT_NE(autosavePath(scene, other.session), autosavePath(scene, self));
    other.stop();
    EXPECT_FALSE(other.session.running());  // gone: its process id no longer has that start
    EXPECT_EQ(stateDir(), dir / "state");
}

TEST_F(EditorProject, TwoEditorsOnOneSceneKeepEachOthersAutosaves) {
    OtherProcess otherEditor;
    EditorState a, b;
    open(a, otherEditor.session);
    open(b, EditorSession::current());
    moveFirst(a, 0.5);
    moveFirst(b, -0.25);
    ASSERT_TRUE(writeAutosave(a));
    ASSERT_TRUE(writeAutosave(b));
    EXPECT_EQ(autosaves(), 2u);
    // A saves: its own autosave goes, B's stays.
    ASSERT_TRUE(saveSceneFile(a, ""));
    EXPECT_FALSE(fs::exists(autosavePath(scene, a.project.session)));
    EXPECT_TRUE(fs::exists(autosavePath(scene, b.project.session)));
    // A third editor opening the scene is not offered B's autosave while B runs (this process).
    EditorState c;
    open(c, otherEditor.session);
    EXPECT_TRUE(c.project.offers.empty());
}

TEST_F(EditorProject, SavingOverAFileChangedOnDiskAsksFirst) {
    OtherProcess otherEditor;
    EditorState a, b;
    open(a, otherEditor.session);
    open(b, EditorSession::current());
    double original = savedX();
    moveFirst(a, 0.5);
    moveFirst(b, -0.25);
    ASSERT_TRUE(saveSceneFile(a, ""));
    EXPECT_DOUBLE_EQ(savedX(), original + 0.5);
    // B's save would replace A's: it saves nothing and asks.
    EXPECT_FALSE(saveSceneFile(b, ""));
    EXPECT_TRUE(b.project.conflict);
    EXPECT_TRUE(b.dirty);
    EXPECT_DOUBLE_EQ(savedX(), original + 0.5);
    // "Save mine as...": both edits are on disk.
    std::string mine = (dir / "room-b.json").string();
    ASSERT_TRUE(saveSceneFile(b, mine));
    EXPECT_DOUBLE_EQ(firstX(loadScene(mine)), original - 0.25);
    EXPECT_DOUBLE_EQ(savedX(), original + 0.5);
    // A saves again after editing more: the file is as A left it, so no question.
    moveFirst(a, 0.25);
    EXPECT_TRUE(saveSceneFile(a, ""));
    EXPECT_FALSE(a.project.conflict);
    // "Overwrite with my edits" (another editor, C, opened before A's last save).
    EditorState c;
    open(c, EditorSession::current());
    moveFirst(a, 0.25);
    ASSERT_TRUE(saveSceneFile(a, ""));
    moveFirst(c, 1.0);
    EXPECT_FALSE(saveSceneFile(c, ""));
    ASSERT_TRUE(saveSceneFile(c, "", true));
    EXPECT_DOUBLE_EQ(savedX(), original + 0.75 + 1.0);  // C's scene as C had it
}

TEST_F(EditorProject, ACrashedEditorsAutosaveIsOfferedRestoredAndRemovedBySaving) {
    OtherProcess crashed;
    EditorState state;
    open(state, crashed.session);
    std::string original = sceneToJson(state.scene).dump();
    moveFirst(state, 0.75);
    std::string edited = sceneToJson(state.scene).dump();
    ASSERT_TRUE(writeAutosave(state));
    EXPECT_EQ(sceneToJson(loadScene(scene)).dump(), original);  // the scene file is untouched
    crashed.stop();

    EditorState after;  // a new editor, after the crash
    open(after, EditorSession::current());
    EXPECT_FALSE(after.dirty);  // offered, not applied unasked
    EXPECT_EQ(sceneToJson(after.scene).dump(), original);
    ASSERT_EQ(after.project.offers.size(), 1u);
    EXPECT_TRUE(after.project.offers[0].newerThanScene);
    EXPECT_NE(after.project.offers[0].describe().find("no longer running"), std::string::npos);
    ASSERT_TRUE(restoreAutosave(after, after.project.offers[0]));
    EXPECT_EQ(sceneToJson(after.scene).dump(), edited);
    EXPECT_TRUE(after.dirty);
    EXPECT_EQ(after.scene.path, scene);  // Save writes the scene, not the autosave
    EXPECT_NE(after.status.find("Restored"), std::string::npos);
    // Adopted: it is now this editor's, and saving (no question: the file is as it was) removes it.
    EXPECT_TRUE(fs::exists(autosavePath(scene, after.project.session)));
    ASSERT_TRUE(saveSceneFile(after, ""));
    EXPECT_EQ(autosaves(), 0u);
    EXPECT_EQ(sceneToJson(loadScene(scene)).dump(), edited);
}

TEST_F(EditorProject, AnAutosaveOlderThanTheSavedFileIsStillOfferedAndItsSaveAsks) {
    OtherProcess crashed;
    EditorState b;
    open(b, crashed.session);
    moveFirst(b, -0.5);
    ASSERT_TRUE(writeAutosave(b));
    crashed.stop();
    // Another editor saved the scene after B's autosave.
    EditorState a;
    open(a, EditorSession::current());
    a.project.offers.clear();  // A put B's autosave off
    moveFirst(a, 0.5);
    fs::last_write_time(autosavePath(scene, b.project.session),
                        fs::last_write_time(scene) - std::chrono::seconds(10));
    ASSERT_TRUE(saveSceneFile(a, ""));
    double saved = savedX();

    EditorState restart;
    open(restart, EditorSession::current());
    ASSERT_EQ(restart.project.offers.size(), 1u);  // B's edits are not lost
    EXPECT_FALSE(restart.project.offers[0].newerThanScene);
    EXPECT_NE(restart.project.offers[0].describe().find("older"), std::string::npos);
    ASSERT_TRUE(restoreAutosave(restart, restart.project.offers[0]));
    // The file changed after B's editor read it: saving B's edits over it asks first.
    EXPECT_FALSE(saveSceneFile(restart, ""));
    EXPECT_TRUE(restart.project.conflict);
    EXPECT_DOUBLE_EQ(savedX(), saved);
}

TEST_F(EditorProject, DiscardingAnAutosaveRemovesIt) {
    OtherProcess crashed;
    EditorState b;
    open(b, crashed.session);
    moveFirst(b, -0.5);
    ASSERT_TRUE(writeAutosave(b));
    crashed.stop();
    EditorState a;
    open(a, EditorSession::current());
    ASSERT_EQ(a.project.offers.size(), 1u);
    discardAutosave(a.project.offers[0]);
    EXPECT_EQ(autosaves(), 0u);
}

TEST_F(EditorProject, AnOlderCandelasSharedAutosaveIsOffered) {
    EditorState edited;
    open(edited, EditorSession::current());
    moveFirst(edited, 0.75);
    saveScene(edited.scene, (dir / ".room.autosave.json").string());
    EditorState state;
    open(state, EditorSession::current());
    ASSERT_EQ(state.project.offers.size(), 1u);
    EXPECT_FALSE(state.project.offers[0].owner);
    ASSERT_TRUE(restoreAutosave(state, state.project.offers[0]));
    EXPECT_TRUE(state.project.onDisk.empty());  // who knows what it began from: Save asks
}

TEST_F(EditorProject, OpeningAnotherSceneKeepsUnsavedEditsInTheAutosave) {
    std::string other = (dir / "other.json").string();
    fs::copy_file(scene, other);
    EditorState state;
    open(state, EditorSession::current());
    moveFirst(state, 0.75);
    ASSERT_TRUE(openSceneFile(state, other));
    EXPECT_FALSE(state.dirty);
    ASSERT_TRUE(openSceneFile(state, scene));  // back: this session's own autosave is offered
    ASSERT_EQ(state.project.offers.size(), 1u);
    ASSERT_TRUE(restoreAutosave(state, state.project.offers[0]));
    EXPECT_DOUBLE_EQ(firstX(state.scene), savedX() + 0.75);
}

TEST_F(EditorProject, ADamagedAutosaveIsReportedAndKept) {
    OtherProcess crashed;
    fs::path damaged = autosavePath(scene, crashed.session);
    crashed.stop();
    std::ofstream(damaged) << "{ not json";
    EditorState state;
    open(state, EditorSession::current());  // the scene itself opens
    ASSERT_EQ(state.project.offers.size(), 1u);
    EXPECT_FALSE(restoreAutosave(state, state.project.offers[0]));
    EXPECT_TRUE(state.statusIsError);
    EXPECT_NE(state.status.find("autosave"), std::string::npos);
    EXPECT_FALSE(state.dirty);
    EXPECT_TRUE(fs::exists(damaged));  // nothing lost: kept for the user to look at
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
