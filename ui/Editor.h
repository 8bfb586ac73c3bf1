#pragma once
// The interactive editor: a GLFW window with Dear ImGui panels around the progressive renderer's
// viewport. One frame: poll events, refine the image (nothing when converged), build the UI,
// draw, swap. A converged editor with no input sleeps in glfwWaitEventsTimeout.

#include <chrono>
#include <filesystem>
#include <future>
#include <memory>
#include <string>
#include <vector>

namespace candela {

struct Scene;
class WindowContext;
class ShaderLibrary;
class Renderer;
class Comparison;
class ImageTextures;
class InterreflectionWorker;
class ProtectedInputs;

namespace ui {

struct EditorState;
class KeyLatch;

struct EditorOptions {
    std::string scenePath;  ///< Scene file to open.
    int width = 1280;       ///< Window width, screen pixels.
    int height = 800;       ///< Window height, screen pixels.
    std::filesystem::path screenshotDir = "candela-screenshots";
    /// Test hook: after every frame, the window, viewport, Screenshot button, widgets and
    /// luminaire positions (window pixels) are written here as JSON (atomically). Empty: off.
    std::filesystem::path layoutFile;
    int quitAfterFrames = 0;  ///< Test hook: exit after this many frames; 0 runs until closed.
    double autosaveSeconds = 60.0;  ///< Unsaved edits are autosaved this often (ui/Project.h).
};

class Editor {
  public:
    /// Opens the window and loads the scene (a scene that fails to load leaves the editor open
    /// with an empty scene and the error shown). Throws RuntimeError when no window can be made.
    explicit Editor(const EditorOptions& options);
    ~Editor();
    Editor(const Editor&) = delete;
    Editor& operator=(const Editor&) = delete;

    /// Runs until the window closes, Quit, or the frame limit. Returns the exit code.
    int run();

  private:
    /// What this frame does with the viewport.
    struct FrameMode {
        bool typing = false;      ///< A text field has the keyboard: refinement pauses.
        bool navigating = false;  ///< The camera moves over split panes: the preview shows.
        bool comparing = false;   ///< The split panes refine.
    };
    void frame();
    FrameMode frameMode();
    /// Sleeps (up to kIdleWaitS) while nothing refines and no input comes, else polls.
    void waitForEvents(const FrameMode& mode);
    /// Writes the autosave when there are unsaved edits and its interval has passed.
    void autosaveIfDue();
    /// Reloads changed shader files (every kReloadIntervalS) and says so in the status bar.
    void reloadShadersIfDue();
    /// Keeps every file the open scene reads protected from the editor's writers.
    void protectInputs();
    /// Hands this frame's scene changes to the comparison or to the single view (preview or full).
    void routeChanges(const FrameMode& mode);
    /// One refinement step of what the viewport shows; a failure is shown, not thrown.
    void refineImage(const FrameMode& mode);
    /// Builds the panels and draws them over the window, then swaps.
    void drawUi();
    /// Hands the renderer the scene and settings of this frame: the preview scene and settings
    /// while a drag is under way (renderer/LivePreview.h), else the edited scene.
    void prepareRender();
    /// Hands the comparison its panes, size and the scene's changes (state.compare.layout is
    /// not Single); the main renderer waits.
    void prepareComparison();
    /// The renderer whose image the viewport shows: the preview's while a drag is previewed.
    Renderer& shownRenderer();
    /// Writes the comparison sheet (report/ComparisonExport.h) into the screenshot folder.
    void exportSheet();
    void buildUi();
    void takeScreenshot();
    /// Writes the whole window as drawn (screenshotDir/window-NNN.png).
    void takeWindowShot(int width, int height);
    void updateTitle();
    void writeLayout();
    /// File > Export report: starts the export asked for (the view is this frame's image; the
    /// surfaces, the UGR and the PDF on a thread) and reports it when it is done.
    void updateReport();
    /// Hands the interreflection worker this frame's scene changes, and its newest solution to
    /// the renderers; mirrors its state into EditorState::interreflection for the panels.
    void updateInterreflection();

    EditorOptions mOptions;
    std::unique_ptr<WindowContext> mContext;
    std::unique_ptr<ShaderLibrary> mShaders;
    std::unique_ptr<Renderer> mRenderer;
    std::unique_ptr<EditorState> mState;
    std::unique_ptr<KeyLatch> mKeyLatch;
    std::unique_ptr<Scene> mPreviewScene;  ///< What the preview renderer shows while dragging.
    std::unique_ptr<Renderer>
        mPreviewRenderer;    ///< Renders the live preview (renderer/LivePreview.h).
    unsigned mFullOwed = 0;  ///< Changes made during a drag, owed to mRenderer (ChangeFlags).
    std::unique_ptr<Comparison> mComparison;  ///< The panes, while the viewport is split.
    std::unique_ptr<ImageTextures> mImages;   ///< The panels' pictures (EditorState::images).
    /// Interreflected light, computed on its own thread (calculation/InterreflectionWorker.h).
    std::unique_ptr<InterreflectionWorker> mInterreflection;
    /// The report being written: "" when it was, else why it was not.
    std::future<std::string> mReportJob;
    uint64_t mIndirectVersion = 0;  ///< The solution the renderers were handed (0: none yet).
    bool mInterreflectionStarted = false;  ///< The worker was handed a scene.
    bool mIndirectEnabled = true;          ///< The worker's switch as last set.
    unsigned mComparisonChanges = 0;       ///< Scene changes the comparison took (ChangeFlags).
    unsigned mComparisonOwed = 0;          ///< Changes made while navigating the split view.
    bool mPreviewingSplit = false;         ///< The split view shows the preview while navigating.
    std::chrono::steady_clock::time_point mLastFrame;
    double mLastAutosave = 0.0;  ///< glfwGetTime() of the last autosave check that wrote, s.
    int mAutosavedEdits = 0;     ///< EditorState::edits at the last autosave.
    bool mImGuiReady = false;
    bool mRenderFailed = false;  ///< The last renderFrame() threw; shown, not spun on.
    int mFrame = 0;
    int mIdleFrames = 0;            ///< Consecutive frames without input.
    double mLastReloadCheck = 0.0;  ///< glfwGetTime() of the last shader reload check, s.
    std::string mTitle;
    std::string mLastShaderLog;  ///< Shader error log at the last reload check.
    std::string mLayoutError;    ///< Why the layout file could not be written (printed once).
    std::unique_ptr<ProtectedInputs> mInputs;  ///< The open scene's files (protectInputs).
    std::vector<std::string> mProtected;       ///< What mInputs holds.
};

}  // namespace ui
}  // namespace candela
