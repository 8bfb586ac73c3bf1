// GL function declarations first: nothing below may pull in GL/gl.h before them.
// clang-format off
#include "renderer/gl/GlFunctions.h"
// clang-format on
#include "ui/Editor.h"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "calculation/InterreflectionWorker.h"
#include "renderer/Comparison.h"
#include "renderer/ImageFile.h"
#include "renderer/LivePreview.h"
#include "renderer/Renderer.h"
#include "renderer/ShaderLibrary.h"
#include "renderer/ViewportMath.h"
#include "renderer/context/GlContext.h"
#include "report/ComparisonExport.h"
#include "report/Report.h"
#include "report/Screenshot.h"
#include "scene/SceneIo.h"
#include "ui/EditorState.h"
#include "ui/KeyLatch.h"
#include "ui/Panels.h"
#include "ui/Project.h"
#include "util/FileOutput.h"

namespace {

/// Paths dropped onto the window since the last frame (GLFW calls back on the main thread).
std::vector<std::string> gDropped;

void onDrop(GLFWwindow*, int count, const char** paths) {
    for (int i = 0; i < count; ++i) gDropped.emplace_back(paths[i]);
}

}  // namespace

namespace candela::ui {

namespace {

constexpr double kReloadIntervalS = 0.5;  ///< How often shader files are checked, seconds.
constexpr double kIdleWaitS = 0.1;        ///< Longest sleep of an idle editor, seconds.
constexpr int kBusyFramesAfterInput = 3;  ///< Frames drawn after input before sleeping.
constexpr double kBandBudgetMs = 40.0;    ///< Longest shading work per editor frame, ms.
constexpr float kLeftWidth = 330.f;       ///< Outline and inspector column, pixels.
constexpr float kRightWidth = 330.f;      ///< Render and statistics column, pixels.

/// True when this frame saw mouse motion, a wheel turn, or a button or key held down.
double now0() {
    return glfwGetTime();
}

bool hadInput() {
    const ImGuiIO& io = ImGui::GetIO();
    if (io.MouseDelta.x != 0.f || io.MouseDelta.y != 0.f || io.MouseWheel != 0.f ||
        io.MouseWheelH != 0.f)
        return true;
    for (bool down : io.MouseDown)
        if (down) return true;
    for (bool down : io.KeysDown)
        if (down) return true;
    return false;
}

nlohmann::json vec2Json(float x, float y) {
    return nlohmann::json::array({x, y});
}

}  // namespace

Editor::Editor(const EditorOptions& options) : mOptions(options) {
    mContext = std::make_unique<WindowContext>(options.width, options.height, "Candela");
    mShaders = std::make_unique<ShaderLibrary>();
    mRenderer = std::make_unique<Renderer>(*mShaders);
    mState = std::make_unique<EditorState>();
    mImages = std::make_unique<ImageTextures>();
    mState->images = mImages.get();
    mState->screenshotDir = options.screenshotDir;
    // Many samples per pass: a pass pays a fixed cost per pixel (the light field's box
    // integrals) that more samples share, and banding keeps the editor responsive anyway.
    mState->settings.samplesPerFrame = 16;
    mState->settings.maxSamples = 256;
    // A pass over the image can take seconds on a software rasterizer: shade it in bands of
    // about this long, so input is read between them.
    mState->settings.bandBudgetMs = kBandBudgetMs;
    if (!options.scenePath.empty())
        openSceneFile(*mState, options.scenePath);
    else
        mState->project.offers = findAutosaves("", mState->project.session);
    protectInputs();
    mAutosavedEdits = mState->edits;

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // deterministic layout: no imgui.ini
    io.LogFilename = nullptr;
    ImGui::StyleColorsDark();
    // Dear ImGui's built-in font, with the Greek capital delta of "Delta E" merged in from DejaVu
    // Sans (fonts-dejavu-core) when it is installed.
    io.Fonts->AddFontDefault();
    const char* dejaVu = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
    if (std::filesystem::is_regular_file(dejaVu)) {
        ImFontConfig merge;
        merge.MergeMode = true;
        static const ImWchar kDelta[] = {0x0394, 0x0394, 0};
        io.Fonts->AddFontFromFileTTF(dejaVu, 13.f, &merge, kDelta);
    }
    ImGui::GetStyle().WindowRounding = 0.f;
    mKeyLatch = std::make_unique<KeyLatch>();
    mKeyLatch->install(mContext->window());  // before the backend, which chains to it
    ImGui_ImplGlfw_InitForOpenGL(mContext->window(), true);
    ImGui_ImplOpenGL3_Init("#version 450 core");
    mImGuiReady = true;
    glfwSetDropCallback(mContext->window(), onDrop);
    updateTitle();
}

Editor::~Editor() {
    // A clean quit keeps unsaved edits in the autosave (restored next time) and drops a stale one.
    if (mState) {
        if (mState->dirty && mState->edits != mAutosavedEdits)
            writeAutosave(*mState);
        else if (!mState->dirty)
            removeAutosave(mState->scene.path, mState->project.session);
    }
    if (mImGuiReady) {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
    if (mContext) {
        glfwSetKeyCallback(mContext->window(), nullptr);
        glfwSetDropCallback(mContext->window(), nullptr);
        glfwSetWindowUserPointer(mContext->window(), nullptr);
    }
    mInterreflection.reset();  // stops its thread
    // GL objects go before the context that owns them.
    mComparison.reset();
    mImages.reset();
    mPreviewRenderer.reset();
    mRenderer.reset();
    mShaders.reset();
    mState.reset();
    mContext.reset();
}

int Editor::run() {
    GLFWwindow* window = mContext->window();
    while (!glfwWindowShouldClose(window) && !mState->quitRequested) {
        frame();
        ++mFrame;
        if (mOptions.quitAfterFrames > 0 && mFrame >= mOptions.quitAfterFrames) break;
    }
    return 0;
}

Editor::FrameMode Editor::frameMode() {
    const EditorState& state = *mState;
    FrameMode mode;
    // While a text field has the keyboard, refinement pauses: Dear ImGui 1.86 sees a key only if
    // it is still down at the next frame, and a slow GPU's frames would lose keystrokes.
    mode.typing = ImGui::GetIO().WantTextInput;
    // While the camera is dragged over split panes, the viewport shows the live preview of the
    // single view (the panes would restart every frame and show nothing); letting go splits it
    // again and the panes refine the new view.
    bool split = state.compare.layout != CompareLayout::Single;
    mode.navigating = split && mComparison && state.preview.enabled &&
                      (state.drag.mode == DragMode::Orbit || state.drag.mode == DragMode::Pan);
    mPreviewingSplit = mode.navigating;
    mode.comparing = split && !mode.navigating;
    return mode;
}

void Editor::waitForEvents(const FrameMode& mode) {
    const EditorState& state = *mState;
    bool settled =
        (mode.comparing ? mComparison && mComparison->done() : shownRenderer().converged()) ||
        mRenderFailed || mode.typing;
    bool idle = settled && mIdleFrames >= kBusyFramesAfterInput &&
                state.pendingChanges == kChangeNone && !state.screenshotRequested;
    if (idle)
        glfwWaitEventsTimeout(kIdleWaitS);
    else
        glfwPollEvents();
}

void Editor::autosaveIfDue() {
    EditorState& state = *mState;
    if (!state.dirty || state.edits == mAutosavedEdits ||
        now0() - mLastAutosave < mOptions.autosaveSeconds)
        return;
    if (writeAutosave(state))
        std::fprintf(stderr, "candela edit: autosaved to %s\n",
                     autosavePath(state.scene.path, state.project.session).c_str());
    mAutosavedEdits = state.edits;
    mLastAutosave = now0();
}

void Editor::protectInputs() {
    // Every file the open scene reads, the scene itself included: no writer of the editor
    // (screenshots, sheets, reports, the autosave, the layout file) may replace one. Save writes
    // the scene through an InputReplacement (saveSceneFile).
    std::vector<std::string> inputs = mState->scene.inputFiles();
    if (mInputs && inputs == mProtected) return;
    mInputs.reset();
    mInputs = std::make_unique<ProtectedInputs>(inputs);
    mProtected = std::move(inputs);
}

void Editor::reloadShadersIfDue() {
    EditorState& state = *mState;
    double now = glfwGetTime();
    if (now - mLastReloadCheck < kReloadIntervalS) return;
    mLastReloadCheck = now;
    bool reloaded = mShaders->reloadChanged();
    if (reloaded) state.pendingChanges |= kChangeSettings;
    const std::string& log = mShaders->errorLog();
    if (log != mLastShaderLog && !log.empty())
        setStatus(state,
                  "Shader compile failed (log under Frame statistics); keeping the "
                  "last good program",
                  true);
    else if (reloaded)
        setStatus(state, "Shaders reloaded");
    mLastShaderLog = log;
}

void Editor::routeChanges(const FrameMode& mode) {
    EditorState& state = *mState;
    if (mode.comparing) {
        state.pendingChanges |= mComparisonOwed;  // what changed while navigating
        mComparisonOwed = kChangeNone;
        if (state.preview.active) {
            // Navigation ended: the single view owes the full renderer what changed meanwhile.
            state.preview.active = false;
            mComparisonChanges |= mFullOwed;
            mFullOwed = kChangeNone;
        }
        prepareComparison();
        return;
    }
    if (mode.navigating) {
        // The single view catches up on what changed while it waited, and the panes are owed
        // what changes now.
        state.pendingChanges |= mComparisonChanges;
        mComparisonChanges = kChangeNone;
        mComparisonOwed |= state.pendingChanges;
    }
    prepareRender();
}

void Editor::refineImage(const FrameMode& mode) {
    EditorState& state = *mState;
    glDisable(GL_SCISSOR_TEST);
    try {
        // Frame 0 only lays out the UI, which sets the render size from the viewport panel.
        if (mFrame > 0 && !mode.typing && mode.comparing) {
            mComparison->step(kBandBudgetMs);
        } else if (mFrame > 0 && !mode.typing) {
            shownRenderer().renderFrame();
            state.passes.add(shownRenderer().stats());
        }
        mRenderFailed = false;
    } catch (const std::exception& e) {
        std::string message = std::string("Render failed: ") + e.what();
        if (state.status != message) {
            std::fprintf(stderr, "candela edit: %s\n", message.c_str());
            setStatus(state, message, true);
        }
        mRenderFailed = true;
    }
}

void Editor::drawUi() {
    EditorState& state = *mState;
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    mKeyLatch->apply(mContext->window());
    ImGui::NewFrame();
    {
        // A new input gesture at each press or release: the edits of one drag are one undo step.
        const ImGuiIO& io = ImGui::GetIO();
        bool gesture = false;
        for (int b = 0; b < 3; ++b)
            gesture = gesture || ImGui::IsMouseClicked(b) || ImGui::IsMouseReleased(b);
        for (int k = 0; k < IM_ARRAYSIZE(io.KeysDown); ++k)
            gesture = gesture || ImGui::IsKeyPressed(k, false);
        if (gesture) ++state.history.gesture;
    }
    buildUi();
    ImGui::Render();

    int fbWidth = 0, fbHeight = 0;
    glfwGetFramebufferSize(mContext->window(), &fbWidth, &fbHeight);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fbWidth, fbHeight);
    glClearColor(0.08f, 0.08f, 0.09f, 1.f);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (state.windowShotRequested) takeWindowShot(fbWidth, fbHeight);
    glfwSwapBuffers(mContext->window());
}

void Editor::frame() {
    EditorState& state = *mState;
    FrameMode mode = frameMode();
    waitForEvents(mode);
    protectInputs();
    autosaveIfDue();
    // Files dropped onto the window: luminaires, an environment map, geometry (dropFile).
    for (const std::string& path : gDropped) dropFile(state, path);
    gDropped.clear();
    reloadShadersIfDue();
    updateInterreflection();
    routeChanges(mode);
    refineImage(mode);
    // Requested last frame; taken now that the image shows the scene as it is.
    if (state.screenshotRequested) takeScreenshot();
    if (state.compare.sheetRequested) exportSheet();
    updateReport();
    drawUi();
    if (state.quitRequested) glfwSetWindowShouldClose(mContext->window(), GLFW_TRUE);
    mIdleFrames = hadInput() ? 0 : mIdleFrames + 1;
    updateTitle();
    protectInputs();  // before the layout file is written: the scene may have changed this frame
    writeLayout();
}

void Editor::updateInterreflection() {
    EditorState& state = *mState;
    InterreflectionUi& ui = state.interreflection;
    if (!mInterreflection) mInterreflection = std::make_unique<InterreflectionWorker>();
    if (ui.enabled != mIndirectEnabled) {
        mInterreflection->setEnabled(ui.enabled);
        mIndirectEnabled = ui.enabled;
    }
    // What its light depends on: the surfaces (geometry, materials), the luminaires and the
    // environment; the camera and the render settings change nothing of it.
    unsigned mask = kChangeGeometry | kChangeLuminaires | kChangeEnvironment;
    if (!mInterreflectionStarted || (state.pendingChanges & mask) != 0) {
        mInterreflection->update(
            state.scene, !mInterreflectionStarted || (state.pendingChanges & kChangeGeometry) != 0);
        mInterreflectionStarted = true;
    }
    if (mInterreflection->version() != mIndirectVersion) {
        InterreflectionWorker::Snapshot s = mInterreflection->latest();
        if (s.version != mIndirectVersion) {
            mRenderer->setIndirect(s.mesh, s.vertexIrradiance);
            if (mPreviewRenderer) mPreviewRenderer->setIndirect(s.mesh, s.vertexIrradiance);
            mIndirectVersion = s.version;
            ui.present = s.mesh != nullptr;
            ui.converged = s.converged;
            ui.patches = s.patches;
            ui.version = s.version;
            ++ui.updates;
        }
    }
    InterreflectionWorker::Status st = mInterreflection->status();
    ui.busy = st.busy;
    ui.stage = st.stage;
    ui.progress = st.progress;
    ui.lastSeconds = st.lastSeconds;
    ui.error = st.error;
}

Renderer& Editor::shownRenderer() {
    return mState->preview.active && mPreviewRenderer ? *mPreviewRenderer : *mRenderer;
}

void Editor::prepareComparison() {
    EditorState& state = *mState;
    CompareUi& ui = state.compare;
    if (!mComparison) {
        mComparison = std::make_unique<Comparison>(*mShaders);
        state.pendingChanges |= kChangeAll;
    }
    // Scene changes seen here are owed to the single view too, for when the comparison ends.
    mComparisonChanges |= state.pendingChanges;
    // Panes split the viewport (the wipe shows two at its full size).
    RenderSettings shared = state.settings;
    const glm::vec4& v = state.layout.viewport;
    float w = v.z * state.renderScale, h = v.w * state.renderScale;
    if (ui.layout != CompareLayout::Wipe) w *= 0.5f;
    if (ui.layout == CompareLayout::Four) h *= 0.5f;
    shared.width = std::max(1, int(std::lround(w)));
    shared.height = std::max(1, int(std::lround(h)));
    mComparison->configure(comparedPanes(ui), shared, ui.referenceSamples);
    mComparison->setErrorScale(ui.errorScale);
    mComparison->update(state.scene, state.pendingChanges);
    state.pendingChanges = kChangeNone;
}

void Editor::exportSheet() {
    EditorState& state = *mState;
    CompareUi& ui = state.compare;
    ui.sheetRequested = false;
    if (!mComparison || ui.layout == CompareLayout::Single) {
        setStatus(state, "Split the viewport into panes to export a comparison sheet", true);
        return;
    }
    if (!mComparison->measurable()) {
        // Taken as soon as every pane and the reference have a pass over the image.
        ui.sheetRequested = true;
        setStatus(state,
                  "The comparison sheet is written when the reference and every pane have a pass");
        return;
    }
    try {
        std::vector<std::string> names;
        for (size_t i = 0; i < mComparison->paneCount(); ++i) names.push_back(paneName(ui, i));
        SheetFiles files = exportComparisonSheet(state.screenshotDir, *mComparison, state.scene,
                                                 names, ui.showError);
        std::printf("sheet: %s\nsheet: %s\nsheet: %s\n", files.png.c_str(), files.exr.c_str(),
                    files.json.c_str());
        std::fflush(stdout);
        ++ui.sheetsTaken;
        ui.lastSheet = files.png;
        setStatus(state, "Comparison sheet written: " + files.png + " (+ .exr, .json)");
    } catch (const std::exception& e) {
        reportError(state, std::string("Comparison sheet failed: ") + e.what());
    }
}

void Editor::prepareRender() {
    EditorState& state = *mState;
    LivePreviewUi& preview = state.preview;
    auto now = std::chrono::steady_clock::now();
    double frameMs = std::chrono::duration<double, std::milli>(now - mLastFrame).count();
    mLastFrame = now;
    // A drag that has changed something (a click alone does not restart the refinement).
    bool dragging = state.drag.mode != DragMode::None && preview.enabled &&
                    (preview.active || state.pendingChanges != kChangeNone);
    if (dragging) {
        unsigned changes = state.pendingChanges;
        if (!preview.active) {
            // The preview starts: one frame's time is not the preview's yet.
            preview.frameMs = preview.targetMs;
        } else {
            preview.frameMs = 0.7 * preview.frameMs + 0.3 * frameMs;
            // Render time goes with the pixel count, the square of the scale.
            if (preview.adaptive && (preview.frameMs > 1.15 * preview.targetMs ||
                                     preview.frameMs < 0.7 * preview.targetMs))
                preview.policy.scale =
                    std::clamp(float(preview.policy.scale *
                                     std::sqrt(preview.targetMs / std::max(1.0, preview.frameMs))),
                               0.15f, 0.5f);
        }
        if (!mPreviewScene || !syncPreviewScene(*mPreviewScene, state.scene)) {
            try {
                mPreviewScene = std::make_unique<Scene>(previewScene(state.scene));
            } catch (const std::exception& e) {
                setStatus(state, std::string("Live preview off: ") + e.what(), true);
                preview.enabled = false;
                mPreviewScene.reset();
                prepareRender();
                return;
            }
            changes = kChangeAll;
        } else if (!preview.active) {
            changes |= kChangeAll & ~kChangeGeometry;
        }
        RenderSettings settings = previewSettings(state.settings, preview.policy);
        preview.width = settings.width;
        preview.height = settings.height;
        // The preview has its own renderer: the full one keeps every luminaire's accumulation,
        // and after the drag refines only what the drag changed.
        if (!mPreviewRenderer) {
            mPreviewRenderer = std::make_unique<Renderer>(*mShaders);
            changes = kChangeAll;
            InterreflectionWorker::Snapshot s = mInterreflection->latest();
            mPreviewRenderer->setIndirect(s.mesh, s.vertexIrradiance);
        }
        mPreviewRenderer->setSettings(settings);
        if (changes != kChangeNone)
            mPreviewRenderer->update(*mPreviewScene, changes | kChangeLuminaires);
        mFullOwed |= state.pendingChanges;
        state.pendingChanges = kChangeNone;
        preview.active = true;
        return;
    }
    mRenderer->setSettings(state.settings);
    if (mComparison && state.compare.layout == CompareLayout::Single) {
        // The comparison ended: its memory goes, and the single view catches up on the edits.
        mComparison.reset();
        state.pendingChanges |= mComparisonChanges;
        mComparisonChanges = kChangeNone;
    }
    if (preview.active) {
        // Released: the full renderer takes what the drag changed (a moved luminaire refines
        // alone; a moved camera refines everything).
        state.pendingChanges |= mFullOwed;
        mFullOwed = kChangeNone;
        preview.active = false;
    }
    if (state.pendingChanges != kChangeNone) {
        mRenderer->update(state.scene, state.pendingChanges);
        state.pendingChanges = kChangeNone;
    }
    mPreviewScene.reset();  // the renderer no longer points at it
}

void Editor::buildUi() {
    EditorState& state = *mState;
    float menuHeight = 0.f;
    mainMenuBar(state, menuHeight);

    ImVec2 display = ImGui::GetIO().DisplaySize;
    float statusHeight = ImGui::GetFrameHeight() + 6.f;
    float top = menuHeight;
    float middle = std::max(1.f, display.y - statusHeight - top);
    float left = std::min(kLeftWidth, display.x * 0.27f);
    float right = std::min(kRightWidth, display.x * 0.28f);
    PanelRect viewport{left, top, std::max(1.f, display.x - left - right), middle};
    PanelRect outline{0.f, top, left, std::floor(middle * 0.34f)};
    PanelRect library{0.f, top + outline.h, left, std::floor(middle * 0.24f)};
    PanelRect inspector{0.f, top + outline.h + library.h, left, middle - outline.h - library.h};
    // With an environment the Render panel holds its section too and takes more of the column.
    bool environment = state.scene.environmentMap != nullptr;
    PanelRect render{display.x - right, top, right,
                     std::floor(middle * (environment ? 0.58f : 0.36f))};
    PanelRect measure{display.x - right, top + render.h, right,
                      std::floor(middle * (environment ? 0.26f : 0.4f))};
    PanelRect stats{display.x - right, top + render.h + measure.h, right,
                    middle - render.h - measure.h};
    PanelRect status{0.f, top + middle, display.x, statusHeight};

    state.measure.drawnIsolines.clear();  // the Measure panel's overlay records this frame's
    bool comparing = state.compare.layout != CompareLayout::Single && !mPreviewingSplit;
    viewportPanel(state, shownRenderer(), viewport, comparing ? mComparison.get() : nullptr);
    outlinePanel(state, outline);
    libraryPanel(state, library);
    inspectorPanel(state, inspector);
    renderPanel(state, render);
    // While comparing, the Compare panel takes the Measure panel's place.
    if (state.compare.layout != CompareLayout::Single)
        comparePanel(state, mComparison.get(), measure);
    else
        measurePanel(state, shownRenderer(), measure);
    accuracyWindow(state,
                   state.compare.layout != CompareLayout::Single ? mComparison.get() : nullptr,
                   viewport);
    statsPanel(state, shownRenderer(), *mShaders, stats);
    statusBar(state, shownRenderer(), status);
    fileDialogs(state);
    roomDialog(state);
    layoutDialog(state);
}

void Editor::takeScreenshot() {
    EditorState& state = *mState;
    state.screenshotRequested = false;
    if (state.compare.layout != CompareLayout::Single) {
        exportSheet();  // what the viewport shows is the comparison: its sheet
        return;
    }
    try {
        ScreenshotFiles files =
            writeScreenshot(state.screenshotDir, state.scene, *mRenderer, state.passes);
        std::printf("screenshot: %s\nscreenshot: %s\nscreenshot: %s\n", files.png.c_str(),
                    files.exr.c_str(), files.json.c_str());
        std::fflush(stdout);
        ++state.screenshotsTaken;
        setStatus(state, "Screenshot written: " + files.png + " (+ .exr, .json)");
    } catch (const std::exception& e) {
        reportError(state, std::string("Screenshot failed: ") + e.what());
    }
}

void Editor::updateReport() {
    EditorState& state = *mState;
    ReportExport& r = state.report;
    if (r.running && mReportJob.valid() &&
        mReportJob.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
        r.running = false;
        std::string error = mReportJob.get();
        if (error.empty()) {
            ++r.written;
            std::printf("report: %s\n", r.lastPath.c_str());
            std::fflush(stdout);
            setStatus(state, "Report written: " + r.lastPath);
        } else {
            reportError(state, "Export report: " + error);
        }
    }
    if (r.requested.empty() || r.running) return;
    std::string path = r.requested;
    r.requested.clear();
    if (std::filesystem::path(path).extension() != ".pdf") {
        reportError(state, "Export report: " + path + ": the report is a PDF: name it NAME.pdf");
        return;
    }
    // The view as the viewport shows it now; the scene as it is now (the export works on a copy,
    // so editing goes on meanwhile).
    ReportInput in;
    in.view = mRenderer->readDisplay();
    in.viewWidth = mRenderer->settings().width;
    in.viewHeight = mRenderer->settings().height;
    in.viewNote = "the editor's viewport as shown when the report was exported (" +
                  std::to_string(mRenderer->stats().samplesPerPixel) + " samples per pixel)";
    auto scene = std::make_shared<Scene>(state.scene.clone());
    GridSpec how;
    how.spp = state.measure.grid.spp;
    applyLightChoice(*scene, state.measure.light, how);
    std::string title = state.scene.path.empty()
                            ? std::string("untitled")
                            : std::filesystem::path(state.scene.path).stem().string();
    r.running = true;
    r.lastPath = path;
    setStatus(state, "Exporting report to " + path + " ...");
    mReportJob = std::async(
        std::launch::async, [scene, how, title, path, in = std::move(in)]() mutable -> std::string {
            try {
                std::vector<std::string> inputs = scene->inputFiles();
                ProtectedInputs protect(inputs);
                checkNotAnInput(path, "Export report");
                computeReportContents(in, *scene, title, how);
                writeFileAtomically(path, reportPdf(in), "cannot write the report");
                return "";
            } catch (const std::exception& e) {
                return e.what();
            }
        });
}

void Editor::takeWindowShot(int width, int height) {
    EditorState& state = *mState;
    state.windowShotRequested = false;
    // The back buffer as drawn this frame, panels included (the guide images of docs/editor.md).
    std::vector<unsigned char> rgba(size_t(width) * size_t(height) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    char name[64];
    std::snprintf(name, sizeof name, "window-%03d.png", state.windowShotsTaken);
    std::string path = (state.screenshotDir / name).string();
    try {
        std::filesystem::create_directories(state.screenshotDir);
        writeImage8(path, width, height, rgbTopDown(rgba, width, height));
        ++state.windowShotsTaken;
        std::printf("window image: %s\n", path.c_str());
        std::fflush(stdout);
        setStatus(state, "Window image written: " + path);
    } catch (const std::exception& e) {
        reportError(state, std::string("Window image failed: ") + e.what());
    }
}

void Editor::updateTitle() {
    const EditorState& state = *mState;
    std::string name = state.scene.path.empty()
                           ? std::string("untitled")
                           : std::filesystem::path(state.scene.path).filename().string();
    std::string title = "Candela - " + name + (state.dirty ? " *" : "");
    if (title != mTitle) {
        glfwSetWindowTitle(mContext->window(), title.c_str());
        mTitle = title;
    }
}

/// The Environment section's state for the layout file: time of day, playback, and the sample
/// chart's picked pixel (window pixels) and normal.
static nlohmann::json environmentUiJson(const EditorState& state) {
    const EnvironmentUi& ui = state.environment;
    const glm::vec4& v = state.layout.viewport;
    const RenderSettings& s = state.settings;
    glm::dvec3 normal = ui.chartNormal();
    nlohmann::json chart = {
        {"open", ui.chartOpen},
        {"picking", ui.pickingPixel},
        {"picked", ui.pixelPicked},
        {"normal", {normal.x, normal.y, normal.z}},
        {"point", {ui.pickedPoint.x, ui.pickedPoint.y, ui.pickedPoint.z}},
        {"pixel", vec2Json(v.x + float(ui.pickedPixel.x) * v.z / float(std::max(1, s.width)),
                           v.y + float(ui.pickedPixel.y) * v.w / float(std::max(1, s.height)))},
        {"counts", ui.chartCounts},
    };
    return {{"latitude_deg", ui.latitudeDeg},
            {"day_of_year", ui.dayOfYear},
            {"solar_hours", ui.solarHours},
            {"playing", ui.playing},
            {"chart", std::move(chart)}};
}

/// The technique of each shading step of the renderer's plan ("Ceiling panel": "analytic"); the
/// preview scene has the edited scene's luminaires in the same order.
static nlohmann::json planTechniques(const Scene& scene, const Renderer& renderer) {
    nlohmann::json out = nlohmann::json::object();
    size_t k = 0;  // the steps of luminaires follow the scene's luminaires
    for (const ShadeStep& step : renderer.plan().shading)
        if (!step.atInfinity && k < scene.luminaires.size())
            out[scene.luminaires[k++]->name] = std::string(step.technique->name);
    return out;
}

/// The comparison's layout, panes, results and exports (a sheet's sidecar has the same panes).
static nlohmann::json compareState(const EditorState& state, const Comparison* comparison) {
    const CompareUi& ui = state.compare;
    const char* layouts[] = {"single", "two", "four", "wipe"};
    nlohmann::json j = {{"layout", layouts[int(ui.layout)]},
                        {"error_map", ui.showError},
                        {"wipe", ui.wipe},
                        {"sheets", ui.sheetsTaken},
                        {"last_sheet", ui.lastSheet},
                        {"plot_open", ui.plotOpen},
                        {"bench_series", ui.benchSeries.size()},
                        {"budget_ms", ui.budgetMs},
                        {"winner", ui.winner},
                        {"bench_winner", ui.benchWinner}};
    if (comparison && ui.layout != CompareLayout::Single) {
        std::vector<std::string> names;
        for (size_t i = 0; i < comparison->paneCount(); ++i) names.push_back(paneName(ui, i));
        j.update(comparisonJson(*comparison, names));
        j["done"] = comparison->done();
    }
    return j;
}

/// The passes of the last rendered frame with their times, ms.
static nlohmann::json passTimes(const FrameStats& stats) {
    nlohmann::json out = nlohmann::json::object();
    for (const PassTiming& p : stats.passes) out[p.name] = std::round(p.gpuMs * 100.0) / 100.0;
    return out;
}

/// Each luminaire's scene-file entry (type, name, position, aim, c0, technique, kind fields such
/// as file), plus where its position is on screen (window pixels; null when behind the camera).
static nlohmann::json luminairesJson(const Scene& scene, const Renderer& shown,
                                     const glm::vec4& viewport) {
    const RenderSettings& settings = shown.settings();
    glm::mat4 viewProj = shown.viewProj();
    const glm::vec4& v = viewport;
    nlohmann::json lums = nlohmann::json::array();
    for (const auto& lum : scene.luminaires) {
        nlohmann::json entry = luminaireToJson(*lum);
        auto px = projectToPixels(viewProj, lum->pose.position, settings.width, settings.height);
        if (px)
            entry["screen"] = vec2Json(v.x + float(px->x) * v.z / float(settings.width),
                                       v.y + float(px->y) * v.w / float(settings.height));
        else
            entry["screen"] = nullptr;
        lums.push_back(std::move(entry));
    }
    return lums;
}

/// The interreflection worker's state as the panels see it.
static nlohmann::json interreflectionJson(const InterreflectionUi& ir) {
    return {{"enabled", ir.enabled},     {"busy", ir.busy},       {"present", ir.present},
            {"converged", ir.converged}, {"version", ir.version}, {"updates", ir.updates},
            {"patches", ir.patches},     {"stage", ir.stage}};
}

void Editor::writeLayout() {
    // The panels record named widgets' rectangles every frame; taken here so they never pile up.
    std::vector<std::pair<std::string, glm::vec4>> widgets;
    widgets.swap(mState->widgetRects);
    if (mOptions.layoutFile.empty()) return;
    const EditorState& state = *mState;
    const ScreenLayout& layout = state.layout;
    int width = 0, height = 0;
    glfwGetWindowSize(mContext->window(), &width, &height);
    const Renderer& shown = shownRenderer();
    const RenderSettings& settings = shown.settings();
    const glm::vec4& v = layout.viewport;
    const ImGuiIO& io = ImGui::GetIO();
    const FrameStats& stats = shown.stats();
    int selected = state.selectedLuminaire;
    // Named widgets drawn this frame (see EditorState::widgetRects): x0, y0, x1, y1.
    nlohmann::json widgetJson = nlohmann::json::object();
    for (const auto& [name, r] : widgets) widgetJson[name] = {r.x, r.y, r.z, r.w};
    nlohmann::json j = {
        {"window", {width, height}},
        {"viewport", {v.x, v.y, v.z, v.w}},
        {"render_size", {settings.width, settings.height}},
        {"screenshot_button", vec2Json(layout.screenshotButton.x, layout.screenshotButton.y)},
        {"gizmo", layout.gizmo
                      ? nlohmann::json{{"aim", vec2Json(layout.aimKnob.x, layout.aimKnob.y)},
                                       {"spin", vec2Json(layout.spinKnob.x, layout.spinKnob.y)}}
                      : nlohmann::json(nullptr)},
        {"luminaires", luminairesJson(state.scene, shown, v)},
        {"selected", selected >= 0 && selected < int(state.scene.luminaires.size())
                         ? nlohmann::json(state.scene.luminaires[size_t(selected)]->name)
                         : nlohmann::json(nullptr)},
        {"dragging", state.drag.mode == DragMode::Luminaire},
        {"drag_mode",
         std::array<const char*, size_t(DragMode::Area) + 1>{
             "none", "orbit", "pan", "luminaire", "aim", "spin", "area"}[size_t(state.drag.mode)]},
        {"mouse", io.MousePos.x > -FLT_MAX / 2 ? vec2Json(io.MousePos.x, io.MousePos.y)
                                               : nlohmann::json(nullptr)},
        {"samples_per_pixel", stats.samplesPerPixel},
        {"converged", stats.converged},
        {"screenshots", state.screenshotsTaken},
        {"window_images", state.windowShotsTaken},
        {"reports", state.report.written},
        {"report_running", state.report.running},
        {"mouse_down", io.MouseDown[ImGuiMouseButton_Left]},  // as this frame's widgets saw it
        {"typing", io.WantTextInput},                         // a text field has the keyboard
        {"dirty", state.dirty},
        {"undo", state.history.undo.empty() ? nlohmann::json(nullptr)
                                            : nlohmann::json(state.history.undo.back().label)},
        {"undo_steps", state.history.undo.size()},
        {"redo_steps", state.history.redo.size()},
        {"status", state.status},
        {"error", state.modalError},
        {"widgets", std::move(widgetJson)},
        {"environment", state.scene.environment},
        {"environment_ui", environmentUiJson(state)},
        {"preview",
         {{"active", state.preview.active},
          {"size", {state.preview.width, state.preview.height}},
          {"frame_ms", std::round(state.preview.frameMs * 10.0) / 10.0}}},
        {"interreflection", interreflectionJson(state.interreflection)},
        {"techniques", planTechniques(state.scene, shown)},
        {"compare", compareState(state, mComparison.get())},
        {"passes", passTimes(stats)},
    };
    // The Measure panel's last computed calculation surfaces and points (null before).
    j["surfaces"] = nullptr;
    if (state.measure.surfaces) {
        j["surfaces"] = nlohmann::json::array();
        for (const SurfaceResult& s : state.measure.surfaces->surfaces)
            j["surfaces"].push_back({{"name", s.name},
                                     {"points", s.points.size()},
                                     {"em", s.summary.eAvg},
                                     {"u0", s.summary.u0},
                                     {"emin", s.summary.eMin},
                                     {"emax", s.summary.eMax},
                                     {"passes", s.passes},
                                     {"verdict", verdictText(s.verdict)}});
        for (const PointResult& p : state.measure.surfaces->points)
            j["surfaces"].push_back({{"name", p.point.name},
                                     {"points", 1},
                                     {"em", p.E},
                                     {"passes", p.passes},
                                     {"verdict", verdictText(p.verdict)}});
    }
    // The scene's task areas (metres on their planes) and the camera, for tests that draw one.
    j["task_areas"] = nlohmann::json::array();
    for (const TaskArea& a : state.scene.taskAreas)
        j["task_areas"].push_back({{"name", a.name},
                                   {"plane", planeText(a.plane)},
                                   {"lo", {a.lo.x, a.lo.y}},
                                   {"hi", {a.hi.x, a.hi.y}}});
    // The geometry entries (File > New, Add), and the layout dialog's proposal.
    j["geometry"] = nlohmann::json::array();
    for (size_t i = 0; i < state.scene.geometry.size(); ++i)
        j["geometry"].push_back(geometryLabel(state.scene.geometry[i], i));
    j["scene_path"] = state.scene.path;
    j["layout_job"] = nullptr;
    if (const LayoutJob* job = state.layoutDialog.job.get()) {
        const LayoutCandidate* best =
            job->done() && job->result() ? job->result()->best() : nullptr;
        j["layout_job"] = {
            {"done", job->done()}, {"error", job->error()}, {"count", best ? best->count() : 0}};
    }
    j["drawing_area"] = state.measure.drawingArea;
    j["grid_plane"] = planeText(state.measure.grid.plane);
    const GridSpec& grid = state.measure.grid;
    j["grid"] = {{"plane", planeText(grid.plane)},
                 {"lo", {grid.lo.x, grid.lo.y}},
                 {"hi", {grid.hi.x, grid.hi.y}},
                 {"extent_set", state.measure.extentSet}};
    // The isolux lines drawn over the computed surfaces this frame (each one's first point on
    // its surface's plane, u and v in metres).
    j["isolines"] = nlohmann::json::array();
    for (const MeasureState::DrawnIsoline& line : state.measure.drawnIsolines)
        j["isolines"].push_back({{"surface", line.surface},
                                 {"level", line.level},
                                 {"first", {line.first.x, line.first.y}},
                                 {"labelled", line.labelled}});
    const Camera& camera = state.scene.camera;
    j["camera"] = {{"position", {camera.position.x, camera.position.y, camera.position.z}},
                   {"target", {camera.target.x, camera.target.y, camera.target.z}},
                   {"fov_deg", camera.fovDeg}};
    j["glare"] = nullptr;
    if (state.measure.glare) {
        j["glare"] = nlohmann::json::array();
        for (const GlareResult& g : state.measure.glare->observers)
            j["glare"].push_back({{"name", g.observer.name},
                                  {"ugr", g.ugr},
                                  {"lb", g.background},
                                  {"passes", g.passes}});
    }
    // Written every frame (an idle editor draws ten a second), so a test waiting for "N more
    // frames" after its input always sees them come.
    j["frame"] = mFrame;
    j["conflict"] = state.project.conflict;
    j["autosave_offers"] = state.project.offers.size();
    try {
        writeFileAtomically(mOptions.layoutFile.string(), j.dump(2) + "\n");
        mLayoutError.clear();
    } catch (const std::exception& e) {
        if (mLayoutError != e.what())  // once, not every frame
            std::fprintf(stderr, "candela edit: layout file: %s\n", e.what());
        mLayoutError = e.what();
    }
}

}  // namespace candela::ui
