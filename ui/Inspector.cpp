// The inspector: pose, technique and kind-specific fields of the selected luminaire. Kind-specific
// fields are edited generically: the luminaire is written to its scene-file JSON, the numbers are
// edited, and the scene loader's parser rebuilds it, so every kind gets the same validation as
// when a scene file is loaded, and an invalid value is reported instead of applied.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <optional>
#include <vector>

#include "formats/Gldf.h"
#include "luminaires/lightfield/LightField.h"
#include "luminaires/photometric/PhotometricLuminaire.h"
#include "renderer/ViewportMath.h"
#include "scene/SceneIo.h"
#include "ui/ImGuiUtil.h"
#include "ui/Panels.h"
#include "ui/RoomEditing.h"
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

/// Edits one value of a scene-file entry in place: a number (dragged), a short list of numbers,
/// a string (applied on Enter: a file path should not be loaded at every keystroke), a boolean,
/// and an object or a list as a tree of its own values (a room's reflectances, its openings).
bool editJsonValue(EditorState& state, const std::string& key, nlohmann::json& value,
                   int depth = 0) {
    bool edited = false;
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
    } else if ((value.is_object() || value.is_array()) && depth < 4 && !value.empty()) {
        if (ImGui::TreeNodeEx(key.c_str(), ImGuiTreeNodeFlags_DefaultOpen, "%s", label.c_str())) {
            if (value.is_object()) {
                for (auto it = value.begin(); it != value.end(); ++it)
                    edited = editJsonValue(state, it.key(), it.value(), depth + 1) || edited;
            } else {
                // A list's items are "key 1", "key 2", ...; objects in it (openings) can be
                // removed one by one.
                for (size_t k = 0; k < value.size(); ++k) {
                    std::string item = key + " " + std::to_string(k + 1);
                    if (value[k].is_object()) {
                        ImGui::PushID(int(k));
                        bool remove = ImGui::SmallButton("x");
                        itemTooltip("Remove " + item);
                        ImGui::PopID();
                        if (remove) {
                            value.erase(k);
                            edited = true;
                            break;
                        }
                        ImGui::SameLine();
                    }
                    edited = editJsonValue(state, item, value[k], depth + 1) || edited;
                }
            }
            ImGui::TreePop();
        }
    } else {
        ImGui::TextDisabled("%s: %s", label.c_str(), value.dump().c_str());
    }
    ImGui::PopID();
    return edited;
}

/// Edits the kind-specific fields of a luminaire's entry in place.
bool editKindFields(EditorState& state, nlohmann::json& entry) {
    bool edited = false;
    for (auto it = entry.begin(); it != entry.end(); ++it)
        if (!isCommonField(it.key())) edited = editJsonValue(state, it.key(), it.value()) || edited;
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
    recordRect(state, "inspector.position");

    // Typed distances: the height above the floor under the luminaire, and the clear distance
    // to the first surface along -x, +x, -z and +z at its height (walls, partitions).
    pose = lum.pose;
    if (std::optional<double> floor = floorBelow(state, pose.position)) {
        double height = pose.position.y - *floor;
        if (ImGui::DragScalar("Mounting height [m]", ImGuiDataType_Double, &height, 0.01f, nullptr,
                              nullptr, "%.3f")) {
            pose.position.y = *floor + height;
            setPose("Move", pose);
        }
        recordRect(state, "inspector.mounting_height");
        itemTooltip("Above the floor under the luminaire (double-click to type)");
    }
    for (int axis : {0, 2}) {
        pose = state.scene.luminaires[size_t(index)]->pose;
        glm::dvec3 dir(0.0);
        dir[axis] = 1.0;
        std::optional<double> back = clearDistance(state, pose.position, -dir);
        std::optional<double> ahead = clearDistance(state, pose.position, dir);
        if (!back || !ahead) continue;
        double d[2] = {*back, *ahead};
        const char* label = axis == 0 ? "From walls -x, +x [m]" : "From walls -z, +z [m]";
        if (ImGui::DragScalarN(label, ImGuiDataType_Double, d, 2, 0.01f, nullptr, nullptr,
                               "%.3f")) {
            // The side edited keeps the typed distance; the luminaire moves along the axis.
            pose.position[axis] += d[0] != *back ? d[0] - *back : *ahead - d[1];
            setPose("Move", pose);
        }
        recordRect(state, axis == 0 ? "inspector.walls_x" : "inspector.walls_z");
        itemTooltip(
            "The clear distance at the luminaire's height to the first surface on each side (a "
            "wall or a partition); double-click one to type it and the luminaire moves to it");
    }

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

/// A GLDF product's data as the manufacturer gives it: manufacturer, product and variant,
/// article number, description and picture (decoded once; a picture that cannot be read is a
/// line saying so).
void gldfProductDetails(EditorState& state, const PhotometricLuminaire& p) {
    if (!p.gldf) return;
    GldfProductInfo info = gldfProductInfo(*p.gldf, p.gldfVariant);
    ImGui::PushTextWrapPos(0.f);
    if (!info.manufacturer.empty()) ImGui::Text("Manufacturer: %s", info.manufacturer.c_str());
    std::string product = info.product;
    if (!info.variant.empty() && info.variant.find(product) == std::string::npos)
        product += (product.empty() ? "" : ", ") + info.variant;
    else if (!info.variant.empty())
        product = info.variant;
    if (!product.empty()) ImGui::Text("Product: %s", product.c_str());
    ImGui::Text("Article number: %s",
                info.articleNumber.empty() ? "(not given)" : info.articleNumber.c_str());
    if (!info.description.empty()) ImGui::TextDisabled("%s", info.description.c_str());
    ImGui::PopTextWrapPos();
    if (!info.picture || !state.images) return;
    std::string key = "gldf:" + p.gldf->path + ":" + info.picture->id;
    auto [note, fresh] = state.library.pictures.try_emplace(key);
    if (fresh) {
        std::vector<std::string> warnings;
        try {
            std::optional<GldfImage> picture =
                gldfPicture(readGldfBytes(p.gldf->path), *p.gldf, info, warnings);
            if (picture) state.images->upload(key, picture->width, picture->height, picture->rgb);
        } catch (const std::exception& e) {
            warnings.push_back(e.what());
        }
        for (const std::string& w : warnings)
            note->second += (note->second.empty() ? "" : "; ") + w;
    }
    ImageTextures::Shown shown = state.images->find(key);
    if (shown.id) {
        float side = ImGui::GetFontSize() * 8.f;
        float scale = side / float(std::max(shown.width, shown.height));
        ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(shown.id)),
                     ImVec2(float(shown.width) * scale, float(shown.height) * scale));
        itemTooltip("The product's picture from its GLDF container");
    } else if (!note->second.empty()) {
        ImGui::PushTextWrapPos(0.f);
        ImGui::TextDisabled("No picture: %s", note->second.c_str());
        ImGui::PopTextWrapPos();
    }
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

    if (const PhotometricLuminaire* ph = photometricModel(*state.scene.luminaires[size_t(index)]))
        gldfProductDetails(state, *ph);
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

/// A geometry entry: what it made, and its scene-file fields, edited in place (each change
/// rebuilds the geometry as one undo step; a value the parser refuses is shown and not applied).
/// A room can take openings; any entry can be deleted.
bool geometryInspector(EditorState& state, int index) {
    bool changed = false;
    const GeometryItem& item = state.scene.geometry[size_t(index)];
    size_t triangles = 0;
    for (uint32_t m : item.meshes)
        if (m < state.scene.meshes.size()) triangles += state.scene.meshes[m].triangleCount();
    ImGui::Text("Geometry entry #%d: %zu mesh(es), %zu triangles", index, item.meshes.size(),
                triangles);
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (uint32_t m : item.meshes)
        if (m < state.scene.meshes.size()) {
            lo = glm::min(lo, state.scene.meshes[m].boundsMin);
            hi = glm::max(hi, state.scene.meshes[m].boundsMax);
        }
    if (lo.x <= hi.x)
        ImGui::TextDisabled(
            "Extent %.2f x %.2f x %.2f m (x %.2f..%.2f, y %.2f..%.2f, z %.2f..%.2f)", hi.x - lo.x,
            hi.y - lo.y, hi.z - lo.z, lo.x, hi.x, lo.y, hi.y, lo.z, hi.z);
    nlohmann::json entry = item.source;
    bool edited = false;
    if (entry.is_object())
        for (auto it = entry.begin(); it != entry.end(); ++it)
            edited = editJsonValue(state, it.key(), it.value()) || edited;
    if (edited) {
        changed =
            replaceGeometryEntry(state, index, entry, "Edit " + geometryLabel(item, size_t(index)));
    }
    if (!state.inspectorError.empty()) errorText(state.inspectorError);

    ImGui::Spacing();
    if (entry.is_object() && entry.contains("room")) {
        int walls = int(entry["room"].value("floor", nlohmann::json::array()).size());
        for (const char* type : {"window", "door", "skylight"}) {
            std::string button = std::string("Add ") + type;
            if (ImGui::Button(button.c_str())) {
                OpeningDraft o;
                o.type = type;
                if (o.type == "door") o.wall = 2, o.width = 1.0, o.height = 2.1, o.offset = 0.5;
                changed = addOpening(state, index, o) || changed;
            }
            recordRect(state, std::string("inspector.add_") + type);
            itemTooltip(std::string(type) == "skylight"
                            ? std::string("A 1.2 x 1.2 m opening in the middle of the ceiling; "
                                          "edit its centre and size below")
                            : std::string("On wall ") + (std::string(type) == "door" ? "2" : "1") +
                                  " (wall N runs from corner N to N + 1; the room has " +
                                  std::to_string(walls) +
                                  " walls); edit its wall, offset, width and height below");
            ImGui::SameLine();
        }
        ImGui::NewLine();
    }
    if (ImGui::Button("Delete")) changed = removeGeometryEntry(state, index) || changed;
    recordRect(state, "inspector.delete_geometry");
    return changed;
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
        changed = geometryInspector(state, geo);
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
