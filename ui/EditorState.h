#pragma once
// Everything the editor's panels read and write. Panels are free functions over this state; the
// scene changes only through applyEdit() (and the few helpers built on it), which is where undo
// will record its steps.

#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "calculation/CalculationGrid.h"
#include "calculation/CalculationSurfaces.h"
#include "calculation/Glare.h"
#include "luminaires/Registry.h"
#include "renderer/Comparison.h"
#include "renderer/ImageTextures.h"
#include "renderer/LivePreview.h"
#include "renderer/Renderer.h"
#include "report/Screenshot.h"
#include "scene/Bvh.h"
#include "scene/Scene.h"
#include "ui/AccuracyPlot.h"
#include "ui/EditorSession.h"
#include "ui/LayoutJob.h"
#include "ui/RoomEditing.h"

namespace candela::ui {

/// Aim and Spin: the rotation gizmo's handles of the selected luminaire (ui/Viewport.cpp).
/// The layout file names each (ui/Editor.cpp); Area is the last.
enum class DragMode { None, Orbit, Pan, Luminaire, Aim, Spin, Area };

/// A mouse interaction in the viewport that spans several frames.
struct ViewportDrag {
    DragMode mode = DragMode::None;
    int luminaire = -1;          ///< Luminaire being moved (DragMode::Luminaire).
    double height = 0.0;         ///< Height of the horizontal drag plane, metres.
    glm::dvec3 grabOffset{0.0};  ///< Luminaire position minus the grabbed plane point, metres.
    bool onSurfaces = false;     ///< The luminaire follows the surface under the mouse.
    /// DragMode::Area: the corners of the task area being drawn on the Measure grid's plane
    /// (world, metres): where the press met the plane and where the mouse meets it now.
    glm::dvec3 areaStart{0.0}, areaEnd{0.0};
};

/// Where things are on screen this frame, in window pixels (x right, y down).
struct ScreenLayout {
    glm::vec2 window{0.f};            ///< Window size.
    glm::vec4 viewport{0.f};          ///< Viewport image: x, y, width, height.
    glm::vec2 screenshotButton{0.f};  ///< Centre of the Screenshot button.
    bool gizmo = false;               ///< The rotation gizmo is drawn (a luminaire is selected).
    glm::vec2 aimKnob{0.f}, spinKnob{0.f};  ///< Its knobs.
};

/// The File menu's dialogs.
struct FileDialogs {
    bool openRequested = false;     ///< Open the "Open scene" modal next frame.
    bool saveAsRequested = false;   ///< Open the "Save scene as" modal next frame.
    bool reportRequested = false;   ///< Open the "Export report" modal next frame.
    bool projectRequested = false;  ///< Open the "Project data" modal next frame.
    ProjectInfo projectDraft;       ///< What that modal edits until OK.
    std::string openPath;
    std::string saveAsPath;
    std::string reportPath;
};

/// The scene file on disk and this session's autosaves of it (ui/Project.h).
struct ProjectFiles {
    EditorSession session = EditorSession::current();  ///< Whose autosaves this editor writes.
    /// The scene file as this editor last read or wrote it (fileFingerprint); empty when unknown
    /// (a restored autosave that may predate a change on disk): Save then asks first.
    std::string onDisk;
    /// Autosaves found when the scene was opened, offered in the "Unsaved edits found" dialog
    /// until restored, discarded or put off.
    std::vector<AutosaveFile> offers;
    /// Save found the file changed on disk since it was read: the "Changed on disk" dialog asks
    /// whether to overwrite, reload or save as.
    bool conflict = false;
};

/// File > Export report (report/Report.h, as `candela report` writes it): the editor renders the
/// view from the viewport's image and computes the rest on a thread of its own.
struct ReportExport {
    std::string requested;  ///< Set by the dialog: the PDF to write, started next frame.
    bool running = false;
    int written = 0;       ///< Reports written this session (the layout file's "reports").
    std::string lastPath;  ///< The last report written.
};

/// What the Measure panel keeps between frames: the calculation grid's settings and result, and
/// the operator that false colour replaced (the Render panel's operator combo switches it too).
struct MeasureState {
    GridSpec grid;                     ///< Plane, extent (m), spacing (m), samples per point.
    LightChoice light;                 ///< What the grid, surfaces and report include.
    bool extentSet = false;            ///< False: take the extent from the scene's bounds.
    std::optional<GridResult> result;  ///< Last computed grid (shown until recomputed).
    GridSummary summary;
    bool showValues = true;  ///< Draw each point's illuminance in the viewport.
    std::string levelsText;  ///< The isolux levels as typed, lux.
    std::string error;       ///< Why the last computation failed.
    /// The operator false colour replaced, restored when it is turned off (setFalseColour).
    ToneMapOperator previousOperator = ToneMapOperator::Exponential;
    // EN 12464-1 calculation surfaces (calculation/CalculationSurfaces.h).
    std::string taskName = "Task area";    ///< Name of the next task area added.
    Requirement taskRequired{500.0, 0.6};  ///< Its requirement (lx, U0).
    /// "Draw a task area": the next left drag in the viewport draws one on the grid's plane.
    bool drawingArea = false;
    std::optional<SurfaceReport> surfaces;  ///< Last computed surfaces and points.
    /// Each computed surface point's cell filled with its false colour in the viewport.
    bool colourSurfaces = false;
    /// The computed surfaces' isolux lines, at the legend's levels, with their values, in the
    /// viewport (calculation/Isolines.h).
    bool isolinesOnSurfaces = true;
    std::string surfacesError;  ///< Why the last computation failed.
    /// The scene's task areas as the grid last followed them (followTaskAreas), as text.
    std::string followedAreas;
    /// Test hook for the layout file: the isolines drawn over the viewport this frame.
    struct DrawnIsoline {
        std::string surface;
        double level = 0.0;     ///< In the surfaces' unit (lx).
        glm::dvec2 first{0.0};  ///< Its first point on the surface's plane (u, v), m.
        bool labelled = false;  ///< Its value is written beside it (not crowded out).
    };
    std::vector<DrawnIsoline> drawnIsolines;
    // Glare (calculation/Glare.h): the next observer's name and limit, the last UGR computed.
    std::string observerName = "Observer";
    double observerLimit = 19.0;  ///< UGR_L; EN 12464-1's for offices.
    std::optional<GlareReport> glare;
    std::string glareError;
};

/// The Environment section's controls that are not part of the scene file.
struct EnvironmentUi {
    double latitudeDeg = 48.1;    ///< Time of day: the site (default Munich).
    int dayOfYear = 172;          ///< 21 June.
    double solarHours = 14.0;     ///< Apparent solar time, hours.
    bool playing = false;         ///< The time of day (sky) or the sequence advances.
    float hoursPerSecond = 0.5f;  ///< Playback speed of the time of day.
    double sequenceSeconds = 0.0;
    // The sample chart (Fig. 1-2 of Lu et al. 2013) for a normal chosen by its angles.
    bool chartOpen = false;
    float normalElevationDeg = 90.f, normalAzimuthDeg = 0.f;
    /// The chart's unit normal from its elevation and azimuth (phi from +X towards +Z).
    glm::dvec3 chartNormal() const {
        double el = glm::radians(double(normalElevationDeg)),
               az = glm::radians(double(normalAzimuthDeg));
        return {std::cos(el) * std::cos(az), std::sin(el), std::cos(el) * std::sin(az)};
    }
    int chartSpp = 64;
    /// Picking the chart's normal from the viewport: armed by the panel, taken by the next left
    /// click on the viewport, which sets the normal to the surface seen through that pixel.
    bool pickingPixel = false;
    bool pixelPicked = false;
    glm::dvec2 pickedPixel{0.0};  ///< Render pixels (x right, y down), at the click.
    glm::dvec3 pickedPoint{0.0};  ///< World position seen there, metres.
    std::string chartKey;         ///< What the chart image shows (map, normal, spp)
    std::string chartCounts;      ///< Selected / effective per face, as text
};

/// The fallback while the user drags (renderer/LivePreview.h) and what it did last.
struct LivePreviewUi {
    bool enabled = true;        ///< Render the preview while a drag is under way.
    bool adaptive = true;       ///< Adjust the scale to hold targetMs per frame.
    float targetMs = 45.f;      ///< Frame time the adaptive scale aims for, ms (about 22 fps).
    PreviewPolicy policy;       ///< Its scale is the current one when adaptive.
    bool active = false;        ///< This frame rendered the preview.
    double frameMs = 0.0;       ///< Smoothed wall time of the editor's frames while previewing, ms.
    int width = 0, height = 0;  ///< Preview render size, pixels.
};

/// Interreflected light (calculation/InterreflectionWorker.h): the user's switch, and what the
/// editor's worker reported this frame (the panels read it from here).
struct InterreflectionUi {
    bool enabled = true;       ///< Off: no interreflection is computed or shown.
    bool busy = false;         ///< The worker is computing.
    bool present = false;      ///< The image holds interreflected light.
    bool converged = false;    ///< The shown solution is refined and nothing is left to do.
    std::string stage;         ///< What the worker does ("form factors", "direct light", ...).
    double progress = 0.0;     ///< Of that stage, 0..1.
    double lastSeconds = 0.0;  ///< Wall time of the worker's last job.
    std::string error;         ///< Its last failure, else empty.
    size_t patches = 0;        ///< Patches of the shown solution.
    uint64_t version = 0;      ///< Of the solution the renderer shows.
    int updates = 0;           ///< Solutions handed to the renderer so far.
};

/// How the viewport shows the comparison (renderer/Comparison.h): one image (no comparison),
/// 2 or 4 panes side by side, or two panes on either side of a wipe line.
enum class CompareLayout { Single, Two, Four, Wipe };
/// The comparison's controls (ui/ComparePanel.cpp); not part of the scene file (a sheet's
/// sidecar records them).
struct CompareUi {
    CompareLayout layout = CompareLayout::Single;
    /// Each pane's technique list and sample budget: A the scene's own techniques, B each kind's
    /// fast preview technique, C and D other estimators of the same kinds.
    std::array<PaneSpec, 4> panes = {
        PaneSpec{"", 64}, PaneSpec{"precomputed-global,scattered,analytic,balanced", 64},
        PaneSpec{"uniform-restricted,mc-poisson-24,reference,uniform-faces", 64},
        PaneSpec{"granier2003,point,analytic,global-cdf", 64}};
    int referenceSamples = 512;  ///< The reference's sample budget, samples per pixel.
    bool showError = false;      ///< Panes show their signed error map instead of the image.
    float errorScale =
        0.25f;          ///< Error map saturation, fraction of the reference's mean luminance.
    float wipe = 0.5f;  ///< Wipe line position, fraction of the viewport's width.
    int wipePanes[2] = {0, 1};  ///< The panes left and right of the wipe line.
    bool wipeDragging = false;  ///< The wipe line follows the mouse.
    // The accuracy-versus-time window.
    bool plotOpen = false;
    bool plotDeltaE = false;               ///< Plot mean Delta E instead of relative RMSE.
    float budgetMs = 5000.f;               ///< The time budget the plot names a winner at, GPU ms.
    std::vector<ErrorSeries> benchSeries;  ///< Curves read from `candela bench` CSV files.
    std::string benchPath;                 ///< The window's CSV path field.
    std::string winner;       ///< This view's series that wins at budgetMs (empty: none).
    std::string benchWinner;  ///< The bench curve that wins there.
    // Export.
    bool sheetRequested = false;  ///< Export the comparison sheet after this frame's render.
    int sheetsTaken = 0;
    std::string lastSheet;  ///< PNG of the last sheet written.
    /// Panes the layout shows.
    int paneCount() const {
        return layout == CompareLayout::Four ? 4 : layout == CompareLayout::Single ? 1 : 2;
    }
};
/// One luminaire file of the library panel.
enum class FileKind { Unknown, Photometric, Gldf, LightField, Environment, Geometry };

struct LibraryEntry {
    std::string path;   ///< Absolute.
    std::string label;  ///< File name.
    FileKind kind;      ///< Photometric, Gldf or LightField.
};

/// The luminaire files (photometry, GLDF, light field) the scene's luminaires are made from,
/// absolute, each once, sorted by name; the label says how many luminaires use it.
std::vector<LibraryEntry> sceneLuminaireFiles(const Scene& scene);

/// The Library panel: luminaire files under resources/luminaires and the folders the user adds
/// (kept in the state folder's library.json), each with a thumbnail of what it casts.
struct LibraryUi {
    std::vector<std::string> folders;  ///< Added by the user, absolute.
    std::vector<LibraryEntry> entries;
    bool scanned = false;
    std::string folderText;  ///< The "Add folder" field.
    struct Thumbnail {
        bool hasImage = false;  ///< Uploaded to EditorState::images (key: "library:PATH").
        std::string info;       ///< Flux and size, or why it failed.
        bool failed = false;
    };
    std::map<std::string, Thumbnail> thumbnails;  ///< By path.
    /// GLDF product pictures decoded for the inspector (key "gldf:PATH:FILE-ID", uploaded to
    /// EditorState::images): "" or why there is none.
    std::map<std::string, std::string> pictures;
};

/// Placing luminaires on the scene's surfaces (the outline's Placement row and the viewport).
struct PlacementUi {
    bool armed = false;  ///< The next left click on a surface places the selected luminaire.
    bool aimAlongNormal =
        true;  ///< Placed luminaires aim along the surface normal, else straight down.
    bool alongSurfaces =
        false;                ///< Dragging moves a luminaire over the surfaces, not in its plane.
    double clearance = 0.01;  ///< Distance from the surface, metres.
    /// Dragged and placed luminaires land on a grid of `snap` metres (Ctrl held: the other way).
    bool snapping = true;
    double snap = 0.1;           ///< The grid's step, metres.
    int arrayCount[2] = {3, 2};  ///< Array: luminaires along x and z.
    double arraySpacing[2] = {1.2,
                              1.2};  ///< Array: distance between neighbours along x and z, metres.
    /// The scene's BVH for picking surfaces, rebuilt when geometryVersion moves on.
    std::shared_ptr<const Bvh> surfaces;
    int surfacesVersion = -1;
    /// The same without the luminaires' bodies: distances to the walls (ui/RoomEditing.h).
    std::shared_ptr<const Bvh> walls;
    int wallsVersion = -1;
};

/// Add > Luminaire layout: a layout that reaches a task area's target (ui/LayoutJob.h).
struct LayoutUi {
    bool requested = false;          ///< Open the dialog next frame.
    std::string file;                ///< The luminaire file, absolute.
    std::string variant;             ///< GLDF only ("" for the first).
    int area = 0;                    ///< Index into the scene's task areas.
    double height = 2.5;             ///< Mounting height above the floor, m.
    double em = 0.0, u0 = 0.0;       ///< Targets; 0: the task area's requirement.
    std::shared_ptr<LayoutJob> job;  ///< Running or done; reset by a new proposal.
};

/// File > New's room dialog and Add > Room.
struct RoomDialogUi {
    bool requested = false;  ///< Open the dialog next frame.
    bool newScene = true;    ///< A new scene (File > New), else a room added to this one.
    RoomDraft draft;
};

/// What an undo step restores: the scene's editable state. Meshes and materials are kept only
/// for steps that changed geometry (a luminaire move does not copy the room).
struct SceneSnapshot {
    std::vector<std::unique_ptr<Luminaire>> luminaires;
    std::vector<LayoutItem> layouts;  ///< Small: kept by every step, as the luminaires are.
    ProjectInfo project;
    Camera camera;
    double maintenanceFactor = 1.0;
    std::vector<TaskArea> taskAreas;  ///< Small: kept by every step.
    std::vector<CalcPoint> calcPoints;
    std::vector<GlareObserver> glareObservers;
    nlohmann::json environment;
    std::shared_ptr<const EnvironmentMap> environmentMap;
    std::shared_ptr<EnvironmentSequence> environmentSequence;
    bool hasGeometry = false;
    std::vector<GeometryItem> geometry;
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    int selectedLuminaire = -1;
};

struct UndoStep {
    std::string label;     ///< "Move Ceiling panel"
    unsigned changes = 0;  ///< What restoring it changes (ChangeFlags).
    int gesture = 0;       ///< The input gesture that made it (edits of one gesture merge).
    SceneSnapshot before;  ///< The scene before the step (after it, on the redo stack).
};

/// Undo and redo of every scene edit but camera navigation (orbit, pan, zoom), as in most
/// modelling tools. Edits with the same label in one gesture (a drag, a slider held) are one step.
struct UndoHistory {
    std::vector<UndoStep> undo, redo;
    int gesture = 0;  ///< Incremented by the editor at each mouse press or release and key press.
    static constexpr size_t kMaxSteps = 200;
};

struct EditorState {
    Scene scene;
    int selectedLuminaire =
        -1;  ///< Index into scene.luminaires, or -1: the one the inspector shows.
    /// Further luminaires selected with Ctrl+click (outline or viewport); they move and are
    /// deleted with the primary one. Cleared whenever the list of luminaires changes.
    std::vector<int> alsoSelected;
    int selectedGeometry = -1;  ///< Index into scene.geometry, or -1.

    RenderSettings settings;  ///< What the renderer uses; the editor applies it every frame.
    /// The panels' pictures (library thumbnails, the sample chart) as GL textures: owned by the
    /// Editor, so the panels hold no GL object (null without a GL context).
    ImageTextures* images = nullptr;
    /// Render pixels per viewport pixel (1 = full resolution; less is faster on slow GPUs).
    float renderScale = 1.f;
    unsigned pendingChanges = kChangeAll;  ///< Scene changes not yet passed to the renderer.
    bool dirty = false;                    ///< Edits not yet saved.
    int edits = 0;                         ///< Counts edits (and undos), for the autosave.

    std::filesystem::path screenshotDir = "candela-screenshots";
    bool screenshotRequested = false;  ///< Set by the Screenshot button; the editor takes it.
    bool windowShotRequested =
        false;  ///< F12 or View > Save window image: the whole editor window.
    int windowShotsTaken = 0;
    int screenshotsTaken = 0;
    ReportExport report;

    std::string status;  ///< One line in the status bar.
    bool statusIsError = false;
    std::string modalError;      ///< Non-empty: shown in the error modal until dismissed.
    std::string inspectorError;  ///< Why the inspector rejected the last value.
    bool quitRequested = false;

    int addKind = 0;  ///< Index into luminaireKinds() for the Add button.
    FileDialogs files;
    ProjectFiles project;
    ViewportDrag drag;
    ScreenLayout layout;
    PassTotals passes;
    MeasureState measure;  ///< The Measure panel's grid and legend text; kept across scenes.
    EnvironmentUi environment;
    LivePreviewUi preview;
    InterreflectionUi interreflection;
    UndoHistory history;
    PlacementUi placement;
    LibraryUi library;
    CompareUi compare;
    RoomDialogUi room;
    LayoutUi layoutDialog;
    int geometryVersion = 0;  ///< Moves on whenever the scene's meshes may have changed.
    /// Test hook for --layout-file: screen rectangles (x0, y0, x1, y1, window pixels) of named
    /// widgets drawn this frame ("inspector.spin", "outline.add", ...), recorded by the panels
    /// and written out, then cleared, by the editor's layout writer each frame.
    std::vector<std::pair<std::string, glm::vec4>> widgetRects;
};

/// The one path by which the scene changes: runs edit on the scene, tells the renderer what
/// changed, marks the scene unsaved and records an undo step named label ("Move Ceiling panel";
/// camera-only changes are not recorded).
void applyEdit(EditorState& state, std::string_view label, unsigned changes,
               const std::function<void(Scene&)>& edit);

/// Undoes (redoes) the last step; false when there is none. The status bar names it.
bool undo(EditorState& state);
bool redo(EditorState& state);

void setStatus(EditorState& state, std::string message, bool error = false);
/// Turns the false-colour operator on (remembering the operator it replaces in
/// state.measure.previousOperator) or off (restoring that operator). The Measure panel's toggle
/// and the Render panel's operator combo both go through here.
void setFalseColour(EditorState& state, bool on);
/// Adds the Measure panel's grid (its plane and extent) to the scene as an EN 12464-1 task area
/// named measure.taskName with measure.taskRequired, as one undo step. False, with a status,
/// when the grid has no area.
bool addTaskAreaFromGrid(EditorState& state);
/// Smallest side of a task area drawn with the mouse, metres; shorter drags are refused.
constexpr double kMinDrawnSide = 0.05;
/// A task area drawn in the viewport: the rectangle on the Measure grid's plane with opposite
/// corners `a` and `b` (world, metres; their in-plane coordinates rounded to 1 cm) becomes a task
/// area named and required as the panel says, and the grid's extent, in one undo step. Refused,
/// with the status saying why, when a side is under kMinDrawnSide.
bool addTaskAreaFromDrag(EditorState& state, const glm::dvec3& a, const glm::dvec3& b);
/// Removes task area `index` as one undo step.
void removeTaskArea(EditorState& state, size_t index);
/// Keeps the Measure panel's grid on the scene's task areas: when they change (a scene opened or
/// restored, an area drawn, added, removed, undone), the grid takes the plane and extent of the
/// area just added, or else of the first. Without task areas the grid stays as it is. True when
/// it moved the grid.
bool followTaskAreas(EditorState& state);
/// Adds a UGR observer where the camera is, looking where it looks (made horizontal), named
/// measure.observerName with measure.observerLimit, as one undo step. False, with a status, when
/// the camera looks straight up or down.
bool addGlareObserverAtCamera(EditorState& state);
/// Removes glare observer `index` as one undo step.
void removeGlareObserver(EditorState& state, size_t index);
/// Sets the project's data (the report's cover: name, client, designer, date, description) as
/// one undo step; false when nothing changes.
bool setProjectInfo(EditorState& state, const ProjectInfo& project);
/// Shows message in the status bar and in the error modal.
void reportError(EditorState& state, const std::string& message);

/// Makes `scene` the editor's (opening a file, File > New): unsaved edits of the scene it replaces
/// go to the autosave first; selection, drag, undo history and the Measure panel's results start
/// afresh, the grid on the new scene's first task area. The caller sets path, dirty and status.
void takeScene(EditorState& state, Scene scene);
/// Loads a scene file into the state; on failure reports the error and keeps the current scene.
/// Unsaved edits of the scene it replaces go to this session's autosave first; autosaves of the
/// new scene left by other editors are offered (project.offers), not applied.
bool openSceneFile(EditorState& state, const std::string& path);
/// Saves atomically to path (the scene's own path when empty); reports errors, never throws.
/// Saving over the scene's own file when it changed on disk since this editor read or wrote it
/// saves nothing and sets project.conflict (the dialog asks) unless overwriteChanges.
bool saveSceneFile(EditorState& state, const std::string& path, bool overwriteChanges = false);

/// Adds a default luminaire of the kind 0.5 m below the top of the scene's bounds, centred,
/// aimed down; selects it and returns its index.
int addLuminaire(EditorState& state, const LuminaireKindInfo& kind);
/// Adds a luminaire made from a file (a drop onto the window): .ies / .ldt photometry or a
/// .lf.json light field, placed like Add and selected. A file that fails to load is reported and
/// nothing changes. Returns the new index or -1.
int addLuminaireFromFile(EditorState& state, const std::string& path);
/// What a file holds, by its extension (case-insensitive): FileKind::Photometric (.ies, .ldt,
/// and .xml or .iesxml for TM-33),
/// Gldf (.gldf), LightField (.lf.json), Environment (.hdr, .exr), Geometry (.gltf, .glb), else
/// Unknown.
FileKind fileKind(const std::string& path);
/// The scene-file luminaire type a file makes ("photometric", "gldf", "lightfield"), or null.
const char* luminaireKindOf(FileKind kind);

/// A file dropped onto the window: .ies / .ldt / .lf.json become a luminaire (then a click on a
/// surface places it), .hdr / .exr the environment map, .gltf / .glb added geometry. One undo
/// step; an unreadable or unsupported file is reported by name and changes nothing.
bool dropFile(EditorState& state, const std::string& path);
/// Builds a luminaire from a file (.ies, .ldt or .lf.json) through the scene-file parser; throws
/// InputError naming the file. Its name is the file's stem.
std::unique_ptr<Luminaire> luminaireFromFile(const std::string& path);
/// Swaps the luminaire behind an instance for one made from another file, keeping its pose and
/// name, and its technique when the new kind has it (else the kind's default). One undo step;
/// errors are reported and change nothing. Returns whether it swapped.
bool swapLuminaireFile(EditorState& state, int index, const std::string& path);
/// Makes the luminaire the first of a grid of nx x nz identical ones, dx and dz metres apart
/// along world x and z (at its height, same aim, spin and technique; names "NAME 2", ...), as one
/// undo step, as designers lay out offices. Returns how many were added (0 for a 1 x 1 grid or a
/// bad index; counts are clamped to 1..50 each).
int arrayLuminaire(EditorState& state, int index, int nx, int nz, double dx, double dz);
/// The selected luminaires: the primary one and alsoSelected, valid indices, ascending.
std::vector<int> selectedLuminaires(const EditorState& state);
/// Ctrl+click: adds the luminaire to the selection, or removes it (the primary moves on).
void toggleSelected(EditorState& state, int index);
/// Deletes every selected luminaire as one undo step.
void deleteSelected(EditorState& state);
/// Copies the luminaire 0.25 m along +x with a fresh name; selects and returns the copy.
int duplicateLuminaire(EditorState& state, int index);
void deleteLuminaire(EditorState& state, int index);
/// Replaces a luminaire by one built from edited fields, keeping its pose, name and technique.
void replaceLuminaire(EditorState& state, int index, std::unique_ptr<Luminaire> replacement);

/// The grid step a drag or placement lands on now (0: none): the placement's snap step while
/// snapping is on, Ctrl held turning it off (or on, while it is off).
double snapStep(const PlacementUi& placement);

/// The scene's BVH for surface picks (cached in state.placement until the geometry changes).
const Bvh& surfaceBvh(EditorState& state);
/// The pose of a luminaire put on a surface point: `clearance` off it along the normal, aimed
/// along the normal or straight down, its C0 kept (made orthogonal by Pose::frame). With a snap
/// step > 0 the position's coordinates across the surface's main axis are rounded to it.
Pose poseOnSurface(const Pose& pose, const glm::dvec3& point, const glm::dvec3& normal,
                   bool aimAlongNormal, double clearance, double snap);

/// base, or "base 2", "base 3", ... whichever no luminaire of the scene uses yet.
/// `alsoTaken` lists names about to be added (copies made in one step).
std::string uniqueLuminaireName(const Scene& scene, const std::string& base,
                                const std::vector<std::string>& alsoTaken = {});

}  // namespace candela::ui
