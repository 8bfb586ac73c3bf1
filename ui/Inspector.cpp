// The inspector: pose, technique and kind-specific fields of the selected luminaire. Kind-specific
// fields are edited generically: the luminaire is written to its scene-file JSON, the numbers are
// edited, and the scene loader's parser rebuilds it, so every kind gets the same validation as
// when a scene file is loaded, and an invalid value is reported instead of applied.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <vector>

#include "luminaires/lightfield/LightField.h"
#include "luminaires/photometric/PhotometricLuminaire.h"
#include "renderer/ViewportMath.h"
#include "scene/SceneIo.h"
#include "ui/ImGuiUtil.h"
#include "ui/Panels.h"
#include "util/JsonRead.h"

namespace candela::ui {

namespace {

/// Fields every luminaire entry has; the inspector edits them with dedicated widgets.
bool isCommonField(const std::string& key) {
    for (const char* k : {"type", "kind", "name", "position", "aim", "c0", "technique"})
        if (key == k) return true;
    return false;
}

/// Drag speed per pixel proportional to the value, so a radiance of 40 and a size of 0.3 both
/// edit comfortably.
float dragSpeed(double value) {
    return float(std::max(0.001, std::abs(value) * 0.005));
}

bool dragVec3(const char* label, glm::dvec3& v, float speed) {
    return ImGui::DragScalarN(label, ImGuiDataType_Double, &v[0], 3, speed, nullptr, nullptr,
                              "%.3f");
}

/// Edits the numeric, string and boolean fields of a kind-specific entry in place.
bool editKindFields(EditorState& state, nlohmann::json& entry) {
    bool edited = false;
    for (auto it = entry.begin(); it != entry.end(); ++it) {
        const std::string& key = it.key();
        if (isCommonField(key)) continue;
        nlohmann::json& value = it.value();
        std::string label = key + fieldUnit(key);
        ImGui::PushID(key.c_str());
        if (value.is_number_integer()) {
            int64_t v = value.get<int64_t>();
            if (ImGui::DragScalar(label.c_str(), ImGuiDataType_S64, &v, 0.2f)) {
                value = v;
                edited = true;
            }
        } else if (value.is_number()) {
            double v = value.get<double>();
            if (ImGui::DragScalar(label.c_str(), ImGuiDataType_Double, &v, dragSpeed(v), nullptr,
                                  nullptr, "%.4g")) {
                value = v;
                edited = true;
            }
        } else if (value.is_array() && !value.empty() && value.size() <= 4 &&
                   std::all_of(value.begin(), value.end(),
                               [](const nlohmann::json& e) { return e.is_number(); })) {
            double v[4] = {0.0, 0.0, 0.0, 0.0};
            double largest = 0.0;
            for (size_t k = 0; k < value.size(); ++k) {
                v[k] = value[k].get<double>();
                largest = std::max(largest, std::abs(v[k]));
            }
            if (ImGui::DragScalarN(label.c_str(), ImGuiDataType_Double, v, int(value.size()),
                                   dragSpeed(largest), nullptr, nullptr, "%.4g")) {
                for (size_t k = 0; k < value.size(); ++k)
                    value[k] = value[k].is_number_integer() ? nlohmann::json(std::llround(v[k]))
                                                            : nlohmann::json(v[k]);
                edited = true;
            }
        } else if (value.is_string()) {
            std::string text = value.get<std::string>();
            // Applied on Enter: a file path should not be loaded at every keystroke.
            if (ImGui::InputText(label.c_str(), &text, ImGuiInputTextFlags_EnterReturnsTrue)) {
                value = text;
                edited = true;
            }
            recordRect(state, "inspector.field:" + key);
            itemTooltip("Press Enter to apply");
        } else if (value.is_boolean()) {
            bool b = value.get<bool>();
            if (ImGui::Checkbox(label.c_str(), &b)) {
                value = b;
                edited = true;
            }
        } else {
            ImGui::TextDisabled("%s: %s", label.c_str(), value.dump().c_str());
        }
        ImGui::PopID();
    }
    return edited;
}

bool techniqueCombo(EditorState& state, int index) {
    const Luminaire& lum = *state.scene.luminaires[size_t(index)];
    const TechniqueInfo* current = findTechnique(lum.kind(), lum.technique);
    bool changed = false;
    if (ImGui::BeginCombo("Technique", lum.technique.c_str())) {
        for (const TechniqueInfo& t : techniques()) {
            if (t.kind != lum.kind()) continue;
            std::string name(t.name);
            bool picked = ImGui::Selectable(name.c_str(), &t == current);
            recordRect(state, "inspector.technique:" + name);
            if (picked && name != lum.technique) {
                applyEdit(state, "Technique of " + lum.name, kChangeLuminaires,
                          [&](Scene& s) { s.luminaires[size_t(index)]->technique = name; });
                changed = true;
            }
            itemTooltip(std::string(t.description) + (t.progressive ? " (progressive)" : ""));
        }
        ImGui::EndCombo();
    } else {
        recordRect(state, "inspector.technique");  // the closed combo
    }
    if (current) itemTooltip(std::string(current->description));
    return changed;
}

bool poseFields(EditorState& state, int index) {
    Luminaire& lum = *state.scene.luminaires[size_t(index)];
    bool changed = false;
    auto setPose = [&](const char* what, const Pose& pose) {
        applyEdit(state, std::string(what) + " " + lum.name, kChangeLuminaires,
                  [&](Scene& s) { s.luminaires[size_t(index)]->pose = pose; });
        changed = true;
    };
    Pose pose = lum.pose;
    if (dragVec3("Position [m]", pose.position, 0.01f)) setPose("Move", pose);

    pose = lum.pose;
    if (dragVec3("Aim (direction)", pose.aim, 0.01f)) {
        if (glm::length(pose.aim) > 1e-9)
            setPose("Aim", pose);
        else
            state.inspectorError = "Aim: the direction must not be zero";
    }
    itemTooltip("Main emission axis (local +z); need not be unit length");

    // The same aim as angles: tilt away from straight down, azimuth about +Y from +X.
    glm::dvec3 a = glm::normalize(lum.pose.aim);
    double angles[2] = {glm::degrees(std::acos(std::clamp(-a.y, -1.0, 1.0))),
                        glm::degrees(std::atan2(a.z, a.x))};
    if (ImGui::DragScalarN("Tilt, azimuth [deg]", ImGuiDataType_Double, angles, 2, 0.5f, nullptr,
                           nullptr, "%.1f")) {
        double t = glm::radians(std::clamp(angles[0], 0.0, 180.0));
        double z = glm::radians(angles[1]);
        pose = lum.pose;
        pose.aim = glm::dvec3(std::sin(t) * std::cos(z), -std::cos(t), std::sin(t) * std::sin(z));
        setPose("Aim", pose);
    }
    itemTooltip("Tilt 0 deg aims straight down, 90 deg horizontal; azimuth from +X towards +Z");

    pose = lum.pose;
    if (dragVec3("C0 axis (direction)", pose.c0, 0.01f)) {
        if (glm::length(pose.c0) > 1e-9)
            setPose("Rotate", pose);
        else
            state.inspectorError = "C0: the direction must not be zero";
    }
    itemTooltip("Reference horizontal axis (local +x); made orthogonal to the aim");

    // Spin: the angle of C0 about the aim, from world +X projected onto the plane across the aim
    // (world +Z when the aim is along X), counter-clockwise seen from the front of the luminaire.
    glm::dvec3 ex, ey, ez;
    lum.pose.frame(ex, ey, ez);
    glm::dvec3 ref, refY;
    spinReference(ez, ref, refY);
    double spin = glm::degrees(std::atan2(glm::dot(ex, refY), glm::dot(ex, ref)));
    if (ImGui::DragScalar("Spin [deg]", ImGuiDataType_Double, &spin, 0.5f, nullptr, nullptr,
                          "%.1f")) {
        double s = glm::radians(spin);
        pose = lum.pose;
        pose.c0 = std::cos(s) * ref + std::sin(s) * refY;
        setPose("Spin", pose);
    }
    recordRect(state, "inspector.spin");
    itemTooltip("Rotation of the luminaire about its aim (where its C0 plane points)");
    return changed;
}

/// The luminaire's kind fields (and a rectangle's Emits switch), edited as its scene-file entry
/// and parsed again; an invalid value stays in the inspector's error and changes nothing.
bool kindFields(EditorState& state, int index) {
    bool changed = false;
    try {
        nlohmann::json entry = luminaireToJson(*state.scene.luminaires[size_t(index)]);
        bool edited = false;
        if (entry.contains("radiance") || entry.contains("luminance")) {
            // A Lambertian rectangle's emission is a radiance (W/(m2 sr)) or a luminance (cd/m2):
            // switching keeps the numbers and changes what they mean (and the scene's units).
            int luminous = entry.contains("luminance") ? 1 : 0;
            const char* items[] = {"radiance [W/(m2 sr)]", "luminance [cd/m2]"};
            if (ImGui::Combo("Emits", &luminous, items, 2)) {
                const char* from = luminous ? "radiance" : "luminance";
                entry[luminous ? "luminance" : "radiance"] = entry[from];
                entry.erase(from);
                edited = true;
            }
            itemTooltip(
                "Radiometric (W) or photometric (lm, lx) emission; a scene mixing both converts "
                "radiometric sources at 683 lm/W and says so");
        }
        edited = editKindFields(state, entry) || edited;
        if (edited) {
            json::Where where{state.scene.path.empty() ? "(editor)" : state.scene.path,
                              "luminaires[" + std::to_string(index) + "]"};
            // The same parser as scene loading: common fields, then the kind's own.
            replaceLuminaire(state, index, parseLuminaire(entry, where, size_t(index)));
            state.inspectorError.clear();
            changed = true;
        }
    } catch (const std::exception& e) {
        state.inspectorError = e.what();  // Shown in red; the luminaire keeps its valid values.
    }
    return changed;
}

/// Kind-specific details: a light field's images, a photometric file's polar diagram, else the
/// luminaire's power or flux.
void kindDetails(const Luminaire& shown) {
    if (const LightFieldLuminaire* lf = lightFieldModel(shown)) {
        static int shownImage = 0;  // UI state only: which image the panel shows
        lightFieldDetails(*lf, shownImage);
    } else if (const PhotometricLuminaire* ph = photometricModel(shown)) {
        photometricDetails(*ph);
    } else {
        glm::dvec3 power = shown.power();
        bool luminous = shown.quantities() == Quantities::Photometric;
        ImGui::Text("%s [%s]: %.4g  %.4g  %.4g", luminous ? "Flux" : "Power",
                    fluxUnit(shown.quantities()), power.x, power.y, power.z);
    }
}

bool luminaireInspector(EditorState& state, int index) {
    bool changed = false;
    const Luminaire& lum = *state.scene.luminaires[size_t(index)];
    ImGui::Text("Kind: %s", std::string(kindName(lum.kind())).c_str());
    ImGui::PushTextWrapPos(0.f);
    ImGui::TextDisabled("%s", describe(lum).c_str());
    ImGui::PopTextWrapPos();

    std::string name = lum.name;
    if (ImGui::InputText("Name", &name)) {
        if (name.empty()) {
            state.inspectorError = "Name: must not be empty";
        } else {
            applyEdit(state, "Rename " + lum.name, kChangeLuminaires,
                      [&](Scene& s) { s.luminaires[size_t(index)]->name = name; });
            changed = true;
        }
    }
    changed = techniqueCombo(state, index) || changed;
    ImGui::Separator();
    changed = poseFields(state, index) || changed;
    ImGui::Separator();

    changed = kindFields(state, index) || changed;
    // The body: a GLDF variant's L3D housing (drawn; all its placements alike: the same geometry
    // at the same insertion point) or the photometry's luminous box, blocking other light, or not.
    // (kindFields may have replaced the luminaire: `lum` is stale from here.)
    const Luminaire& current = *state.scene.luminaires[size_t(index)];
    if (const PhotometricLuminaire* ph = photometricModel(current);
        ph && (ph->geometry || ph->area() > 0.0)) {
        bool show = ph->showBody;
        if (ImGui::Checkbox(ph->geometry ? "Body (L3D geometry)" : "Body (luminous box)", &show)) {
            applyEdit(state, std::string(show ? "Show" : "Hide") + " body of " + current.name,
                      kChangeLuminaires, [&](Scene& s) {
                          // A new model for each luminaire whose body this is (models are shared
                          // and never changed in place).
                          const Luminaire& self = *s.luminaires[size_t(index)];
                          std::shared_ptr<const L3dLuminaire> geometry = ph->geometry;
                          for (auto& other : s.luminaires) {
                              const PhotometricLuminaire* p = photometricModel(*other);
                              if (!p || !(other.get() == &self ||
                                          (geometry && p->geometry == geometry &&
                                           other->pose.position == self.pose.position)))
                                  continue;
                              auto model = std::make_shared<PhotometricLuminaire>(*p);
                              model->showBody = show;
                              other->setModel(std::move(model));
                          }
                      });
            changed = true;
        }
        recordRect(state, "inspector.body");
        itemTooltip(
            "The luminaire's housing (its L3D geometry, drawn; or its photometry's luminous box, "
            "seen through): opaque and black, it blocks the light of every other luminaire and "
            "the reflected light (never its own, which its photometry already holds)");
    }

    kindDetails(*state.scene.luminaires[size_t(index)]);
    if (!state.inspectorError.empty()) errorText(state.inspectorError);

    ImGui::Spacing();
    if (ImGui::Button("Duplicate")) {
        duplicateLuminaire(state, index);
        changed = true;
    }
    ImGui::SameLine();
    if (ImGui::Button("Delete")) {
        deleteLuminaire(state, index);
        changed = true;
    }
    return changed;
}

void geometryInspector(const EditorState& state, int index) {
    const GeometryItem& item = state.scene.geometry[size_t(index)];
    ImGui::Text("Geometry entry #%d: %zu mesh(es)", index, item.meshes.size());
    size_t triangles = 0;
    for (uint32_t m : item.meshes)
        if (m < state.scene.meshes.size()) triangles += state.scene.meshes[m].triangleCount();
    ImGui::Text("Triangles: %zu", triangles);
    if (!item.meshes.empty() && item.meshes[0] < state.scene.meshes.size()) {
        const Mesh& mesh = state.scene.meshes[item.meshes[0]];
        ImGui::Text("Bounds min [m]: %.3f %.3f %.3f", mesh.boundsMin.x, mesh.boundsMin.y,
                    mesh.boundsMin.z);
        ImGui::Text("Bounds max [m]: %.3f %.3f %.3f", mesh.boundsMax.x, mesh.boundsMax.y,
                    mesh.boundsMax.z);
    }
    ImGui::TextDisabled("Scene-file entry (read-only in this version):");
    ImGui::PushTextWrapPos(0.f);
    ImGui::TextUnformatted(item.source.dump(2).c_str());
    ImGui::PopTextWrapPos();
}

}  // namespace

bool inspectorPanel(EditorState& state, const PanelRect& rect) {
    bool changed = false;
    placeNextWindow(rect);
    ImGui::Begin("Inspector", nullptr, kPanelFlags);
    recordPanelRect(state, "inspector");
    ImGui::PushItemWidth(-ImGui::GetFontSize() * 11.f);  // room for labels with units
    int lum = state.selectedLuminaire;
    int geo = state.selectedGeometry;
    if (lum >= 0 && lum < int(state.scene.luminaires.size())) {
        changed = luminaireInspector(state, lum);
    } else if (geo >= 0 && geo < int(state.scene.geometry.size())) {
        geometryInspector(state, geo);
    } else {
        ImGui::PushTextWrapPos(0.f);
        ImGui::TextDisabled(
            "Select a luminaire or a geometry entry in the outline, or click a luminaire in the "
            "viewport. Drag a luminaire to move it at its height.");
        ImGui::PopTextWrapPos();
    }
    ImGui::PopItemWidth();
    ImGui::End();
    return changed;
}

}  // namespace candela::ui
