#pragma once
// The editor's panels: free functions over EditorState that return whether they changed it.
// They read the renderer and shader library (statistics, picking) but never own GL objects.

#include <imgui.h>

#include <string>

#include "renderer/Renderer.h"
#include "renderer/ShaderLibrary.h"
#include "ui/EditorState.h"

namespace candela {
class LightFieldLuminaire;
class PhotometricLuminaire;
}  // namespace candela

namespace candela::ui {

/// A fixed panel placement in window pixels (the layout is deterministic; no imgui.ini).
struct PanelRect {
    float x = 0.f, y = 0.f, w = 0.f, h = 0.f;
};

/// Test hook: the last item's screen rectangle under name, for the layout file. With a width,
/// only that much of it from the left (a slider's frame without its label).
void recordRect(EditorState& state, std::string name, float width = -1.f);
/// Records the current window's rectangle (inside ImGui::Begin/End) as "panel.NAME", so e2e
/// tests can tell whether a recorded widget is scrolled out of its panel.
void recordPanelRect(EditorState& state, const std::string& name);

/// File menu (Open, Save, Save As, Quit) and keyboard shortcuts (Ctrl+O, Ctrl+S, Delete).
/// barHeight receives the menu bar's height in pixels.
/// "plane #0", "Classroom (room) #1", "gltf chair.glb #7": the entry's name (its own or its
/// shape's), else its shape key and file, and its index.
std::string geometryLabel(const GeometryItem& item, size_t index);

bool mainMenuBar(EditorState& state, float& barHeight);
/// The project's dialogs: autosaves found when the scene was opened (restore, discard, later) and
/// a save that found the scene changed on disk (overwrite, save as, reload, cancel).
bool projectDialogs(EditorState& state);
/// The Open / Save As modals, the project's dialogs and the error modal.
bool fileDialogs(EditorState& state);
/// The room dialog (File > New, Add > Room; ui/RoomDialog.cpp).
bool roomDialog(EditorState& state);
/// Add > Luminaire layout (ui/LayoutDialog.cpp).
bool layoutDialog(EditorState& state);

/// Outline of geometry and luminaires (click to select) with Add / Duplicate / Delete.
bool outlinePanel(EditorState& state, const PanelRect& rect);
/// Luminaire files with thumbnails; Add (then click a surface) and Swap (ui/LibraryPanel.cpp).
bool libraryPanel(EditorState& state, const PanelRect& rect);
/// Fields of the selected luminaire (pose, technique, kind-specific values) or geometry.
bool inspectorPanel(EditorState& state, const PanelRect& rect);
/// Basis grid, one image and the flux of a light-field luminaire (ui/LightFieldPanel.cpp);
/// shownImage is the image index the user picked.
void lightFieldDetails(const LightFieldLuminaire& light, int& shownImage);
/// File, flux (table and lamps x LOR), opening and polar candela diagram of a photometric
/// luminaire (ui/PhotometricPanel.cpp).
void photometricDetails(const PhotometricLuminaire& light);
/// Screenshot button, tone mapping, camera and sampling settings.
bool renderPanel(EditorState& state, const PanelRect& rect);
/// The Environment section of the Render panel (ui/EnvironmentPanel.cpp).
bool environmentControls(EditorState& state);
/// Quantity (radiance / illuminance), false colour with its legend (range in lux, log or linear,
/// isolux levels) drawn as a colour bar, and the calculation grid (Emin, Eavg, Emax, U0) whose
/// values it writes over the viewport (ui/MeasurePanel.cpp); its own settings are state.measure.
bool measurePanel(EditorState& state, const Renderer& renderer, const PanelRect& rect);
/// Over the viewport (ui/MeasureOverlay.cpp): the computed surfaces in false colour and their
/// isolux lines with their values, and the grid's and surfaces' points with theirs, as the
/// Measure panel's checkboxes ask; the isolines drawn go to state.measure.drawnIsolines.
void drawMeasuredValues(EditorState& state, const Renderer& renderer);
/// Passes with GPU times, accumulation, compiled variants and the shader error log.
void statsPanel(const EditorState& state, const Renderer& renderer, const ShaderLibrary& shaders,
                const PanelRect& rect);
/// The rendered image; picking, luminaire dragging and camera orbit / pan / zoom.
/// With a comparison (state.compare.layout not Single) the panes instead, and only camera input.
bool viewportPanel(EditorState& state, const Renderer& renderer, const PanelRect& rect,
                   const Comparison* comparison = nullptr);
void statusBar(const EditorState& state, const Renderer& renderer, const PanelRect& rect);

/// The comparison (ui/ComparePanel.cpp). The panes a comparison renders for the layout (the
/// two either side of a wipe), and the letter of the pane it shows at that index.
std::vector<PaneSpec> comparedPanes(const CompareUi& ui);
std::string paneName(const CompareUi& ui, size_t pane);
/// The viewport's layout bar (Single, 2 panes, 4 panes, Wipe; error map, plot, export).
bool compareToolbar(EditorState& state);
/// Draws the panes (image or error map, labels, the wipe line, which it also drags).
void compareView(EditorState& state, const Comparison& comparison, ImVec2 origin, ImVec2 size,
                 bool hovered);
/// Each pane's techniques per kind and sample budget, the reference, results, export.
bool comparePanel(EditorState& state, const Comparison* comparison, const PanelRect& rect);
/// The accuracy-versus-time window (when state.compare.plotOpen), placed over the viewport.
void accuracyWindow(EditorState& state, const Comparison* comparison, const PanelRect& viewport);

/// " [unit]" for a scene-file field name ("radiance" -> " [W/(m2 sr)]"), or "" if unknown.
const char* fieldUnit(const std::string& key);

}  // namespace candela::ui
