// Menu bar, file dialogs, scene outline and status bar.
#include "ui/Panels.h"

#include <GLFW/glfw3.h>  // key codes only (GLFW_INCLUDE_NONE is set for the whole build)
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cstring>
#include <filesystem>

#include "ui/ImGuiUtil.h"
#include "ui/Project.h"

namespace candela::ui {

namespace {

void requestSave(EditorState& state) {
    if (state.scene.path.empty())
        state.files.saveAsRequested = true;
    else
        saveSceneFile(state, {});
}

}  // namespace

std::string geometryLabel(const GeometryItem& item, size_t index) {
    std::string label;
    const nlohmann::json& src = item.source;
    if (src.is_object()) {
        auto name = src.find("name");
        if (name != src.end() && name->is_string()) label = name->get<std::string>();
        for (auto it = src.begin(); label.empty() && it != src.end(); ++it) {
            static const char* kMaterialKeys[] = {"albedo", "specular", "roughness", "material"};
            bool material = false;
            for (const char* k : kMaterialKeys) material = material || it.key() == k;
            if (material) continue;
            label = it.key();
            // {"room": {"name": "Classroom", ...}}: "Classroom (room)".
            if (it.value().is_object() && it.value().contains("name") &&
                it.value()["name"].is_string())
                label = it.value()["name"].get<std::string>() + " (" + it.key() + ")";
            if (it.value().is_string()) {
                std::filesystem::path file = it.value().get<std::string>();
                label.append(" ").append(file.filename().string());
            }
        }
    }
    if (label.empty()) label = "geometry";
    return label + " #" + std::to_string(index);
}

const char* fieldUnit(const std::string& key) {
    struct Unit {
        const char* key;
        const char* unit;
    };
    static const Unit kUnits[] = {
        {"size", " [m]"},          {"width", " [m]"},
        {"height", " [m]"},        {"length", " [m]"},
        {"radius", " [m]"},        {"diameter", " [m]"},
        {"distance", " [m]"},      {"radiance", " [W/(m2 sr)]"},
        {"luminance", " [cd/m2]"}, {"power", " [W]"},
        {"irradiance", " [W/m2]"}, {"intensity", " [cd]"},
        {"lumens", " [lm]"},       {"flux", " [lm]"},
        {"illuminance", " [lx]"},  {"opening", " [m]"},
        {"scale", " [x]"},         {"offset", " [m]"},
        {"sill", " [m]"},          {"elevation", " [m]"},
        {"position", " [m]"},      {"center", " [m]"},
    };
    for (const Unit& u : kUnits)
        if (key == u.key) return u.unit;
    auto endsWith = [&](const char* suffix) {
        size_t n = std::strlen(suffix);
        return key.size() > n && key.compare(key.size() - n, n, suffix) == 0;
    };
    if (endsWith("_deg")) return " [deg]";
    if (endsWith("_m")) return " [m]";
    if (endsWith("_mm")) return " [mm]";
    return "";
}

bool mainMenuBar(EditorState& state, float& barHeight) {
    bool changed = false;
    barHeight = 0.f;
    if (ImGui::BeginMainMenuBar()) {
        if (ImGui::BeginMenu("File")) {
            if (ImGui::MenuItem("New room...", "Ctrl+N")) {
                state.room.requested = true;
                state.room.newScene = true;
            }
            if (ImGui::MenuItem("Open...", "Ctrl+O")) state.files.openRequested = true;
            if (ImGui::MenuItem("Save", "Ctrl+S")) requestSave(state);
            if (ImGui::MenuItem("Save As...")) state.files.saveAsRequested = true;
            if (ImGui::MenuItem("Project data...")) state.files.projectRequested = true;
            if (ImGui::MenuItem("Export report...", "Ctrl+E", false, !state.report.running))
                state.files.reportRequested = true;
            if (ImGui::BeginMenu("Open Recent")) {
                std::vector<std::string> recent = recentFiles();
                if (recent.empty()) ImGui::TextDisabled("(none yet)");
                for (const std::string& path : recent)
                    if (ImGui::MenuItem(path.c_str()))
                        changed = openSceneFile(state, path) || changed;
                ImGui::EndMenu();
            }
            if (ImGui::MenuItem("Revert to Saved", nullptr, false,
                                state.dirty && !state.scene.path.empty())) {
                std::string path = state.scene.path;
                removeAutosave(path, state.project.session);
                state.dirty = false;  // discarded: not kept in an autosave by openSceneFile
                changed = openSceneFile(state, path) || changed;
            }
            ImGui::Separator();
            if (ImGui::MenuItem("Quit")) state.quitRequested = true;
            ImGui::EndMenu();
        }
        if (ImGui::BeginMenu("Edit")) {
            const auto& h = state.history;
            std::string undoLabel = h.undo.empty() ? "Undo" : "Undo " + h.undo.back().label;
            std::string redoLabel = h.redo.empty() ? "Redo" : "Redo " + h.redo.back().label;
            if (ImGui::MenuItem(undoLabel.c_str(), "Ctrl+Z", false, !h.undo.empty()))
                changed = undo(state) || changed;
            if (ImGui::MenuItem(redoLabel.c_str(), "Ctrl+Y", false, !h.redo.empty()))
                changed = redo(state) || changed;
            ImGui::EndMenu();
        }
        if (ImGui::BeginMenu("Add")) {
            if (ImGui::MenuItem("Room...")) {
                state.room.requested = true;
                state.room.newScene = false;
            }
            itemTooltip("A room beside the scene's others (move its floor's corners to place it)");
            if (ImGui::MenuItem("Luminaire layout...", "Ctrl+L"))
                state.layoutDialog.requested = true;
            itemTooltip(
                "The fewest luminaires in a grid that reach a task area's target, computed");
            if (ImGui::BeginMenu("Furniture")) {
                for (const FurnitureType& t : furnitureTypes())
                    if (ImGui::MenuItem(t.label)) {
                        // Where the camera looks, on the floor of the room there.
                        glm::dvec3 target = state.scene.camera.target;
                        glm::dvec2 at(target.x, target.z);
                        double floorY = roomFloorAt(state.scene, at)
                                            .value_or(double(state.scene.boundsMin().y));
                        if (state.scene.geometry.empty()) floorY = 0.0;
                        changed = addFurniture(state, t.name, at, floorY) >= 0 || changed;
                    }
                ImGui::EndMenu();
            }
            ImGui::EndMenu();
        }
        if (ImGui::BeginMenu("View")) {
            if (ImGui::MenuItem("Save window image", "F12")) state.windowShotRequested = true;
            ImGui::EndMenu();
        }
        barHeight = ImGui::GetWindowSize().y;
        ImGui::EndMainMenuBar();
    }
    const ImGuiIO& io = ImGui::GetIO();
    if (!io.WantTextInput && !ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId)) {
        // GLFW key codes equal ASCII for letters (the 1.86 backend indexes KeysDown by them).
        if (io.KeyCtrl && ImGui::IsKeyPressed('S', false)) requestSave(state);
        if (io.KeyCtrl && ImGui::IsKeyPressed('O', false)) state.files.openRequested = true;
        if (io.KeyCtrl && ImGui::IsKeyPressed('L', false)) state.layoutDialog.requested = true;
        if (io.KeyCtrl && ImGui::IsKeyPressed('N', false)) {
            state.room.requested = true;
            state.room.newScene = true;
        }
        if (io.KeyCtrl && ImGui::IsKeyPressed('E', false) && !state.report.running)
            state.files.reportRequested = true;
        if (io.KeyCtrl && !io.KeyShift && ImGui::IsKeyPressed('Z', false))
            changed = undo(state) || changed;
        if (ImGui::IsKeyPressed(GLFW_KEY_F12, false)) state.windowShotRequested = true;
        if (io.KeyCtrl &&
            (ImGui::IsKeyPressed('Y', false) || (io.KeyShift && ImGui::IsKeyPressed('Z', false))))
            changed = redo(state) || changed;
        if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Delete), false) &&
            state.selectedLuminaire >= 0) {
            deleteSelected(state);
            changed = true;
        }
    }
    return changed;
}

namespace {

/// The scene file's name for a dialog ("untitled scene" without one).
std::string sceneName(const EditorState& state) {
    return state.scene.path.empty() ? std::string("the untitled scene")
                                    : std::filesystem::path(state.scene.path).filename().string();
}

}  // namespace

bool projectDialogs(EditorState& state) {
    bool changed = false;
    ProjectFiles& project = state.project;
    // Autosaves left by editors that crashed or quit with unsaved edits (ui/Project.h).
    if (!project.offers.empty() && !ImGui::IsPopupOpen("Unsaved edits found"))
        ImGui::OpenPopup("Unsaved edits found");
    if (ImGui::BeginPopupModal("Unsaved edits found", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::Text("Unsaved edits of %s were kept in %s:", sceneName(state).c_str(),
                    project.offers.size() > 1 ? "these autosaves" : "an autosave");
        if (project.offers.size() > 1)
            ImGui::TextDisabled("Restore one to go on with it; the others stay until you decide.");
        for (size_t i = 0; i < project.offers.size(); ++i) {
            const AutosaveFile& offer = project.offers[i];
            ImGui::PushID(int(i));
            ImGui::TextUnformatted(offer.describe().c_str());
            if (ImGui::Button("Restore")) {
                AutosaveFile chosen = offer;
                project.offers.clear();
                changed = restoreAutosave(state, chosen);
                ImGui::CloseCurrentPopup();
                recordRect(state, "autosave.restore" + std::to_string(i));
                ImGui::PopID();
                break;
            }
            recordRect(state, "autosave.restore" + std::to_string(i));
            ImGui::SameLine();
            if (ImGui::Button("Discard")) {
                discardAutosave(offer);
                setStatus(state, "Discarded the autosave " + offer.path.filename().string());
                project.offers.erase(project.offers.begin() + long(i));
                recordRect(state, "autosave.discard" + std::to_string(i));
                ImGui::PopID();
                break;
            }
            recordRect(state, "autosave.discard" + std::to_string(i));
            ImGui::PopID();
        }
        if (project.offers.empty()) ImGui::CloseCurrentPopup();
        if (!project.offers.empty() && ImGui::Button("Decide later")) {
            setStatus(state, "Autosaves kept: they are offered again when " + sceneName(state) +
                                 " is next opened");
            project.offers.clear();
            ImGui::CloseCurrentPopup();
        }
        recordRect(state, "autosave.later");
        ImGui::EndPopup();
    }

    // Save found the scene file changed on disk since this editor read or wrote it.
    if (project.conflict && !ImGui::IsPopupOpen("Changed on disk"))
        ImGui::OpenPopup("Changed on disk");
    if (ImGui::BeginPopupModal("Changed on disk", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40.f);
        ImGui::Text(
            "%s changed on disk since this editor opened or saved it (another editor or program "
            "saved it). Saving now would replace those changes with yours.",
            sceneName(state).c_str());
        ImGui::PopTextWrapPos();
        if (ImGui::Button("Overwrite with my edits")) {
            project.conflict = false;
            changed = saveSceneFile(state, {}, true) || changed;
            ImGui::CloseCurrentPopup();
        }
        recordRect(state, "conflict.overwrite");
        ImGui::SameLine();
        if (ImGui::Button("Save mine as...")) {
            project.conflict = false;
            state.files.saveAsRequested = true;
            state.files.saveAsPath.clear();
            ImGui::CloseCurrentPopup();
        }
        recordRect(state, "conflict.save_as");
        ImGui::SameLine();
        if (ImGui::Button("Reload from disk (discard mine)")) {
            project.conflict = false;
            std::string path = state.scene.path;
            removeAutosave(path, state.project.session);
            state.dirty = false;  // discarded by choice: not kept in an autosave
            changed = openSceneFile(state, path) || changed;
            ImGui::CloseCurrentPopup();
        }
        recordRect(state, "conflict.reload");
        ImGui::SameLine();
        if (ImGui::Button("Cancel")) {
            project.conflict = false;
            setStatus(state, "Not saved: " + sceneName(state) + " changed on disk");
            ImGui::CloseCurrentPopup();
        }
        recordRect(state, "conflict.cancel");
        ImGui::EndPopup();
    }
    return changed;
}

bool fileDialogs(EditorState& state) {
    bool changed = false;
    if (state.files.openRequested) {
        if (state.files.openPath.empty()) state.files.openPath = state.scene.path;
        ImGui::OpenPopup("Open scene");
        state.files.openRequested = false;
    }
    if (state.files.saveAsRequested) {
        if (state.files.saveAsPath.empty()) state.files.saveAsPath = state.scene.path;
        ImGui::OpenPopup("Save scene as");
        state.files.saveAsRequested = false;
    }
    if (state.files.reportRequested) {
        if (state.files.reportPath.empty()) {
            std::filesystem::path scene =
                state.scene.path.empty() ? "untitled.json" : state.scene.path;
            state.files.reportPath =
                (scene.parent_path() / (scene.stem().string() + "-report.pdf")).string();
        }
        ImGui::OpenPopup("Export report");
        state.files.reportRequested = false;
    }
    auto pathDialog = [&](const char* title, const char* action, std::string& path,
                          bool (*run)(EditorState&, const std::string&),
                          const char* prompt =
                              "Scene file (.json), absolute or relative to the working folder:") {
        if (!ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
        ImGui::TextUnformatted(prompt);
        ImGui::SetNextItemWidth(520.f);
        if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
        bool enter = ImGui::InputText("##path", &path, ImGuiInputTextFlags_EnterReturnsTrue);
        if (ImGui::Button(action) || enter) {
            changed = run(state, path) || changed;
            ImGui::CloseCurrentPopup();
        }
        ImGui::SameLine();
        if (ImGui::Button("Cancel")) ImGui::CloseCurrentPopup();
        ImGui::EndPopup();
    };
    pathDialog("Open scene", "Open", state.files.openPath, &openSceneFile);
    pathDialog("Save scene as", "Save", state.files.saveAsPath,
               [](EditorState& s, const std::string& path) { return saveSceneFile(s, path); });
    pathDialog(
        "Export report", "Export", state.files.reportPath,
        [](EditorState& s, const std::string& path) {
            s.report.requested = path;
            return false;
        },
        "Report (.pdf): luminaire schedule, polar diagrams, the calculation surfaces, UGR and "
        "this view:");

    // The project's data for the report's cover, edited as one undo step.
    if (state.files.projectRequested) {
        state.files.projectDraft = state.scene.project;
        ImGui::OpenPopup("Project data");
        state.files.projectRequested = false;
    }
    if (ImGui::BeginPopupModal("Project data", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ProjectInfo& p = state.files.projectDraft;
        ImGui::TextUnformatted("What the report's cover says about the project:");
        ImGui::PushItemWidth(ImGui::GetFontSize() * 28.f);
        ImGui::InputText("Project", &p.name);
        ImGui::InputText("Client", &p.client);
        ImGui::InputText("Lighting designer", &p.designer);
        ImGui::InputTextWithHint("Date", "the day the report is made", &p.date);
        ImGui::InputTextMultiline("Description", &p.description,
                                  ImVec2(ImGui::GetFontSize() * 28.f, ImGui::GetFontSize() * 4.f));
        ImGui::PopItemWidth();
        if (ImGui::Button("OK")) {
            changed = setProjectInfo(state, p) || changed;
            ImGui::CloseCurrentPopup();
        }
        ImGui::SameLine();
        if (ImGui::Button("Cancel")) ImGui::CloseCurrentPopup();
        ImGui::EndPopup();
    }

    changed = projectDialogs(state) || changed;

    if (!state.modalError.empty() && !ImGui::IsPopupOpen("Error")) ImGui::OpenPopup("Error");
    if (ImGui::BeginPopupModal("Error", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40.f);
        ImGui::TextColored(errorColour(), "%s", state.modalError.c_str());
        ImGui::PopTextWrapPos();
        if (ImGui::Button("OK") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)) ||
            ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Enter))) {
            state.modalError.clear();
            ImGui::CloseCurrentPopup();
        }
        ImGui::EndPopup();
    }
    return changed;
}

/// The Placement rows under the luminaire list: place the selection on a clicked surface, how it
/// is aimed there, dragging over surfaces, and the snap step (Ctrl).
static void placementControls(EditorState& state, bool noSelection) {
    PlacementUi& p = state.placement;
    ImGui::BeginDisabled(noSelection);
    if (ImGui::Button(p.armed ? "Click a surface..." : "Place on a surface")) p.armed = !p.armed;
    recordRect(state, "outline.place");
    itemTooltip(
        "The next left click on a surface in the viewport puts the selected luminaire "
        "there (Shift+click to place it again, Ctrl to turn snapping off or on, Escape to "
        "cancel)");
    ImGui::EndDisabled();
    if (noSelection) p.armed = false;
    if (p.armed && ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false)) p.armed = false;
    ImGui::SameLine();
    ImGui::Checkbox("Over surfaces", &p.alongSurfaces);
    recordRect(state, "outline.over_surfaces");
    itemTooltip(
        "Dragging a luminaire moves it over the surface under the mouse (aimed as "
        "below) instead of in its horizontal plane");
    int aim = p.aimAlongNormal ? 0 : 1;
    ImGui::TextUnformatted("Aim:");
    ImGui::SameLine();
    if (ImGui::RadioButton("surface normal", aim == 0)) p.aimAlongNormal = true;
    recordRect(state, "outline.aim_normal");
    ImGui::SameLine();
    if (ImGui::RadioButton("down", aim == 1)) p.aimAlongNormal = false;
    recordRect(state, "outline.aim_down");
    ImGui::SetNextItemWidth(80.f);
    double minClear = 0.0, maxClear = 1.0, minSnap = 0.01, maxSnap = 2.0;
    ImGui::SliderScalar("Clearance [m]", ImGuiDataType_Double, &p.clearance, &minClear, &maxClear,
                        "%.3f");
    ImGui::SameLine();
    ImGui::Checkbox("Snap", &p.snapping);
    recordRect(state, "outline.snap");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(70.f);
    ImGui::SliderScalar("grid [m]", ImGuiDataType_Double, &p.snap, &minSnap, &maxSnap, "%.2f");
    itemTooltip(
        "Dragged and placed luminaires land on a grid of this step (hold Ctrl for the other "
        "way); type exact positions, mounting heights and distances from the walls in the "
        "inspector");
    ImGui::SetNextItemWidth(90.f);
    ImGui::InputInt2("##arraycount", p.arrayCount);
    recordRect(state, "outline.array_count");
    itemTooltip("Luminaires along x and along z");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(100.f);
    double minSpacing = 0.05, maxSpacing = 20.0;
    ImGui::DragScalarN("##arrayspacing", ImGuiDataType_Double, p.arraySpacing, 2, 0.01f,
                       &minSpacing, &maxSpacing, "%.2f");
    itemTooltip("Spacing along x and along z, metres");
    ImGui::SameLine();
    ImGui::BeginDisabled(noSelection);
    if (ImGui::Button("Array"))
        arrayLuminaire(state, state.selectedLuminaire, p.arrayCount[0], p.arrayCount[1],
                       p.arraySpacing[0], p.arraySpacing[1]);
    recordRect(state, "outline.array");
    ImGui::EndDisabled();
    itemTooltip(
        "Copies the selected luminaire into a grid (a row with one count 1), as one undo step");
}

/// The scene's luminaires, each selectable (Ctrl+click adds to the selection). True on a click.
static bool luminaireList(EditorState& state) {
    bool changed = false;
    const Scene& scene = state.scene;
    for (size_t i = 0; i < scene.luminaires.size(); ++i) {
        const Luminaire& lum = *scene.luminaires[i];
        ImGui::PushID(int(i));
        std::vector<int> group = selectedLuminaires(state);
        bool selected = std::find(group.begin(), group.end(), int(i)) != group.end();
        std::string label = lum.name + "  [" + lum.technique + "]";
        bool clicked = ImGui::Selectable(label.c_str(), selected);
        recordRect(state, "outline.luminaire:" + lum.name);
        if (clicked && ImGui::GetIO().KeyCtrl) {
            toggleSelected(state, int(i));  // Ctrl+click: add to or remove from the selection
            changed = true;
        } else if (clicked) {
            state.selectedLuminaire = int(i);
            state.alsoSelected.clear();
            state.selectedGeometry = -1;
            state.inspectorError.clear();
            changed = true;
        }
        itemTooltip(std::string(kindName(lum.kind())) + ": " + describe(lum));
        ImGui::PopID();
    }
    return changed;
}

/// The kind to add and Add. True when a luminaire was added.
static bool addLuminaireControls(EditorState& state) {
    auto kinds = luminaireKinds();
    if (kinds.empty()) return false;
    state.addKind = std::clamp(state.addKind, 0, int(kinds.size()) - 1);
    ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x - 60.f);
    std::string current(kinds[size_t(state.addKind)].name);
    if (ImGui::BeginCombo("##addkind", current.c_str())) {
        for (size_t k = 0; k < kinds.size(); ++k) {
            std::string name(kinds[k].name);
            if (ImGui::Selectable(name.c_str(), int(k) == state.addKind)) state.addKind = int(k);
            recordRect(state, "outline.add_kind:" + name);
            itemTooltip(std::string(kinds[k].description));
        }
        ImGui::EndCombo();
    } else {
        recordRect(state, "outline.add_kind");  // the closed combo
    }
    ImGui::SameLine();
    bool added = false;
    if (ImGui::Button("Add", ImVec2(-1.f, 0.f)))
        added = addLuminaire(state, kinds[size_t(state.addKind)]) >= 0;
    recordRect(state, "outline.add");
    itemTooltip(
        "Adds a luminaire of this kind 0.5 m below the top of the scene, aimed "
        "down");
    return added;
}

/// The Luminaires section: the list, Add, Duplicate, Delete and the placement rows.
static bool luminairesSection(EditorState& state) {
    bool changed = luminaireList(state);
    changed = addLuminaireControls(state) || changed;
    bool none = state.selectedLuminaire < 0;
    ImGui::BeginDisabled(none);
    if (ImGui::Button("Duplicate")) {
        duplicateLuminaire(state, state.selectedLuminaire);
        changed = true;
    }
    ImGui::SameLine();
    if (ImGui::Button("Delete")) {
        deleteSelected(state);
        changed = true;
    }
    ImGui::EndDisabled();
    placementControls(state, none);
    return changed;
}

/// The Geometry section: each item, selectable.
static bool geometryList(EditorState& state) {
    bool changed = false;
    const Scene& scene = state.scene;
    for (size_t i = 0; i < scene.geometry.size(); ++i) {
        ImGui::PushID(int(i));
        bool selected = state.selectedGeometry == int(i);
        if (ImGui::Selectable(geometryLabel(scene.geometry[i], i).c_str(), selected)) {
            state.selectedGeometry = int(i);
            state.selectedLuminaire = -1;
            state.inspectorError.clear();
            changed = true;
        }
        ImGui::PopID();
    }
    return changed;
}

bool outlinePanel(EditorState& state, const PanelRect& rect) {
    bool changed = false;
    placeNextWindow(rect);
    ImGui::Begin("Scene", nullptr, kPanelFlags);
    recordPanelRect(state, "scene");
    const Scene& scene = state.scene;
    std::string luminairesHeader =
        "Luminaires (" + std::to_string(scene.luminaires.size()) + ")###luminaires";
    if (ImGui::CollapsingHeader(luminairesHeader.c_str(), ImGuiTreeNodeFlags_DefaultOpen))
        changed = luminairesSection(state) || changed;
    std::string geometryHeader =
        "Geometry (" + std::to_string(scene.geometry.size()) + ")###geometry";
    if (ImGui::CollapsingHeader(geometryHeader.c_str(), ImGuiTreeNodeFlags_DefaultOpen))
        changed = geometryList(state) || changed;
    ImGui::End();
    return changed;
}

void statusBar(const EditorState& state, const Renderer& renderer, const PanelRect& rect) {
    placeNextWindow(rect);
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(8.f, 3.f));
    ImGui::Begin("##status", nullptr,
                 kPanelFlags | ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoScrollbar);
    ImGui::PopStyleVar();
    const FrameStats& stats = renderer.stats();
    std::string right =
        (state.scene.path.empty() ? std::string("(unsaved scene)") : state.scene.path) +
        (state.dirty ? " *" : "") + "   |   " + std::to_string(stats.samplesPerPixel) + " spp   " +
        (ImGui::GetIO().WantTextInput ? "paused while typing"
         : stats.converged            ? "converged"
                                      : "refining");
    float rightWidth = ImGui::CalcTextSize(right.c_str()).x;
    ImGui::PushClipRect(ImGui::GetCursorScreenPos(),
                        ImVec2(rect.x + rect.w - rightWidth - 24.f, rect.y + rect.h), true);
    if (state.statusIsError)
        ImGui::TextColored(errorColour(), "%s", state.status.c_str());
    else
        ImGui::TextUnformatted(state.status.c_str());
    ImGui::PopClipRect();
    ImGui::SameLine(std::max(0.f, rect.w - rightWidth - 12.f));
    ImGui::TextUnformatted(right.c_str());
    ImGui::End();
}

void recordPanelRect(EditorState& state, const std::string& name) {
    ImVec2 lo = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    state.widgetRects.emplace_back("panel." + name,
                                   glm::vec4(lo.x, lo.y, lo.x + size.x, lo.y + size.y));
}

void recordRect(EditorState& state, std::string name, float width) {
    ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
    if (width > 0.f) hi.x = std::min(hi.x, lo.x + width);
    state.widgetRects.emplace_back(std::move(name), glm::vec4(lo.x, lo.y, hi.x, hi.y));
}

}  // namespace candela::ui
