// The room dialog (File > New, Add > Room): a room's shape, size, height, reflectances,
// openings, furniture and task area, with its plan drawn as it is typed; Create builds it through
// the scene file's parser (ui/RoomEditing.h).
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "scene/Procedural.h"
#include "ui/ImGuiUtil.h"
#include "ui/Panels.h"
#include "ui/RoomEditing.h"

namespace candela::ui {

namespace {

bool metres(const char* label, double& v, double lo, double hi) {
    bool changed = ImGui::DragScalar(label, ImGuiDataType_Double, &v, 0.01f, &lo, &hi, "%.2f");
    v = std::clamp(v, lo, hi);
    return changed;
}

bool ratio(const char* label, double& v) {
    const double lo = 0.0, hi = 0.95;  // no real surface reflects more (docs/scene-files.md)
    bool changed = ImGui::SliderScalar(label, ImGuiDataType_Double, &v, &lo, &hi, "%.2f");
    v = std::clamp(v, lo, hi);
    return changed;
}

/// The room's plan seen from above (x right, z down, as the report draws it): the outline with
/// each wall's number, the openings, the furniture and the task area.
void drawPlan(const RoomDraft& draft, float size) {
    std::vector<glm::dvec2> outline;
    try {
        outline = floorOutline(draft);
    } catch (const std::exception&) {
        ImGui::Dummy(ImVec2(size, size));
        return;
    }
    glm::dvec2 lo(1e300), hi(-1e300);
    for (const glm::dvec2& p : outline) lo = glm::min(lo, p), hi = glm::max(hi, p);
    glm::dvec2 extent = glm::max(hi - lo, glm::dvec2(1e-3));
    double scale = (size - 30.0) / std::max(extent.x, extent.y);
    ImVec2 origin = ImGui::GetCursorScreenPos();
    ImDrawList* draw = ImGui::GetWindowDrawList();
    draw->AddRectFilled(origin, ImVec2(origin.x + size, origin.y + size),
                        IM_COL32(30, 30, 34, 255));
    auto at = [&](glm::dvec2 p) {
        return ImVec2(origin.x + 15.f + float((p.x - lo.x) * scale),
                      origin.y + 15.f + float((p.y - lo.y) * scale));
    };
    nlohmann::json area = nullptr;
    try {
        area = taskAreaEntry(draft);
    } catch (const std::exception&) {
    }
    if (!area.is_null()) {
        const nlohmann::json& e = area["extent"];
        draw->AddRectFilled(at({e[0].get<double>(), e[1].get<double>()}),
                            at({e[2].get<double>(), e[3].get<double>()}),
                            IM_COL32(60, 90, 60, 255));
    }
    for (size_t i = 0; i < outline.size(); ++i) {
        glm::dvec2 a = outline[i], b = outline[(i + 1) % outline.size()];
        draw->AddLine(at(a), at(b), IM_COL32(230, 230, 230, 255), 2.f);
        ImVec2 mid = at(0.5 * (a + b));
        std::string n = std::to_string(i + 1);
        draw->AddText(ImVec2(mid.x + 3.f, mid.y + 2.f), IM_COL32(200, 200, 120, 255), n.c_str());
    }
    for (const OpeningDraft& o : draft.openings) {
        ImU32 colour = o.type == "door" ? IM_COL32(220, 140, 60, 255) : IM_COL32(90, 170, 255, 255);
        if (o.type == "skylight") {
            draw->AddRect(at(o.center - 0.5 * o.size), at(o.center + 0.5 * o.size), colour, 0.f, 0,
                          2.f);
            continue;
        }
        if (o.wall < 1 || o.wall > int(outline.size())) continue;
        glm::dvec2 a = outline[size_t(o.wall - 1)], b = outline[size_t(o.wall) % outline.size()];
        double length = glm::length(b - a);
        if (!(length > 0.0)) continue;
        glm::dvec2 along = (b - a) / length;
        draw->AddLine(at(a + along * o.offset), at(a + along * (o.offset + o.width)), colour, 5.f);
    }
    for (const FurnitureDraft& f : draft.furniture) {
        glm::dvec3 s(0.8);
        for (const FurnitureType& t : furnitureTypes())
            if (f.type == t.name) s = t.size;
        double r = glm::radians(f.rotateYDeg);
        glm::dvec2 u(std::cos(r), -std::sin(r)), v(std::sin(r), std::cos(r));
        ImVec2 q[4];
        int k = 0;
        for (glm::dvec2 c :
             {glm::dvec2(-1, -1), glm::dvec2(1, -1), glm::dvec2(1, 1), glm::dvec2(-1, 1)})
            q[k++] = at(f.position + 0.5 * (c.x * s.x * u + c.y * s.z * v));
        draw->AddQuad(q[0], q[1], q[2], q[3], IM_COL32(190, 160, 120, 255), 1.5f);
    }
    ImGui::Dummy(ImVec2(size, size));
}

/// A narrow number field of a table row.
bool cell(const char* id, double& v, double lo, double hi, const char* format = "%.2f") {
    ImGui::TableNextColumn();
    ImGui::SetNextItemWidth(-1.f);
    bool changed = ImGui::DragScalar(id, ImGuiDataType_Double, &v, 0.01f, &lo, &hi, format);
    v = std::clamp(v, lo, hi);
    return changed;
}

/// The openings, one row each: wall, offset, width, sill and height (a skylight: its centre's x
/// and z, its size along x and z).
void openingRows(EditorState& state, RoomDraft& draft) {
    ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchSame;
    if (!draft.openings.empty() && ImGui::BeginTable("openings", 8, flags)) {
        ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthFixed, ImGui::GetFontSize() * 1.5f);
        ImGui::TableSetupColumn("Opening", ImGuiTableColumnFlags_WidthFixed,
                                ImGui::GetFontSize() * 4.5f);
        ImGui::TableSetupColumn("Wall");
        ImGui::TableSetupColumn("Offset [m]");
        ImGui::TableSetupColumn("Width [m]");
        ImGui::TableSetupColumn("Sill [m]");
        ImGui::TableSetupColumn("Height [m]");
        ImGui::TableSetupColumn("Glazing");
        ImGui::TableHeadersRow();
        for (size_t i = 0; i < draft.openings.size(); ++i) {
            OpeningDraft& o = draft.openings[i];
            ImGui::PushID(int(i));
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            bool remove = ImGui::SmallButton("x");
            itemTooltip("Remove this opening");
            ImGui::TableNextColumn();
            ImGui::Text("%s", o.type.c_str());
            if (o.type == "skylight") {
                itemTooltip("In the ceiling: its centre x and z, its size along x and z, m");
                cell("##cx", o.center.x, -1e4, 1e4);
                cell("##cz", o.center.y, -1e4, 1e4);
                cell("##sx", o.size.x, 0.01, 1e4);
                cell("##sz", o.size.y, 0.01, 1e4);
                ImGui::TableNextColumn();
            } else {
                double wall = o.wall;
                cell("##wall", wall, 1.0, 1000.0, "%.0f");
                o.wall = int(std::lround(wall));
                cell("##offset", o.offset, 0.0, 1e4);
                cell("##width", o.width, 0.01, 1e4);
                ImGui::BeginDisabled(o.type != "window");
                cell("##sill", o.sill, 0.0, 100.0);
                ImGui::EndDisabled();
                cell("##height", o.height, 0.01, 100.0);
                ImGui::BeginDisabled(o.type != "window");
                cell("##glazing", o.glazing, 0.0, 1.0);
                ImGui::EndDisabled();
            }
            ImGui::PopID();
            if (remove) {
                draft.openings.erase(draft.openings.begin() + long(i));
                break;
            }
        }
        ImGui::EndTable();
    }
    auto add = [&](const char* type) {
        OpeningDraft o;
        o.type = type;
        // A door on wall 2 (windows go on wall 1 unless moved), windows one after another.
        if (o.type == "door") o.wall = 2, o.width = 1.0, o.height = 2.1, o.offset = 0.5;
        double next = 0.5;
        for (const OpeningDraft& p : draft.openings)
            if (p.type != "skylight" && p.wall == o.wall)
                next = std::max(next, p.offset + p.width + 0.5);
        o.offset = next;
        draft.openings.push_back(o);
    };
    if (ImGui::Button("Add window")) add("window");
    recordRect(state, "room.add_window");
    ImGui::SameLine();
    if (ImGui::Button("Add door")) add("door");
    recordRect(state, "room.add_door");
    ImGui::SameLine();
    if (ImGui::Button("Add skylight")) add("skylight");
    recordRect(state, "room.add_skylight");
    ImGui::SameLine();
    ImGui::TextDisabled("(wall N: from corner N to N + 1, see the plan)");
}

void furnitureRows(RoomDraft& draft) {
    const std::vector<FurnitureType>& types = furnitureTypes();
    for (size_t i = 0; i < draft.furniture.size(); ++i) {
        FurnitureDraft& f = draft.furniture[i];
        ImGui::PushID(1000 + int(i));
        if (ImGui::SmallButton("x")) {
            draft.furniture.erase(draft.furniture.begin() + long(i));
            ImGui::PopID();
            break;
        }
        ImGui::SameLine();
        int type = 0;
        for (size_t k = 0; k < types.size(); ++k)
            if (f.type == types[k].name) type = int(k);
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 7.f);
        if (ImGui::BeginCombo("##type", types[size_t(type)].label)) {
            for (const FurnitureType& t : types)
                if (ImGui::Selectable(t.label, f.type == t.name)) f.type = t.name;
            ImGui::EndCombo();
        }
        ImGui::SameLine();
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 9.f);
        ImGui::DragScalarN("x, z [m]", ImGuiDataType_Double, &f.position[0], 2, 0.01f, nullptr,
                           nullptr, "%.2f");
        ImGui::SameLine();
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 4.f);
        ImGui::DragScalar("turn [deg]", ImGuiDataType_Double, &f.rotateYDeg, 1.f, nullptr, nullptr,
                          "%.0f");
        ImGui::PopID();
    }
    if (ImGui::BeginCombo("##add_furniture", "Add furniture...")) {
        for (const FurnitureType& t : types)
            if (ImGui::Selectable(t.label)) {
                FurnitureDraft f;
                f.type = t.name;
                draft.furniture.push_back(f);
            }
        ImGui::EndCombo();
    }
}

}  // namespace

bool roomDialog(EditorState& state) {
    RoomDialogUi& ui = state.room;
    const char* title = "Room###room_dialog";
    if (ui.requested) {
        ImGui::OpenPopup(title);
        ui.requested = false;
    }
    // Sized to what it shows (its results and lists come and go).
    if (!ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return false;
    bool changed = false;
    RoomDraft& d = ui.draft;
    ImGui::TextUnformatted(ui.newScene ? "A new scene: a room, its openings and furniture"
                                       : "A room added to this scene");
    ImGui::Separator();
    ImGui::BeginGroup();
    ImGui::PushItemWidth(ImGui::GetFontSize() * 12.f);
    if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
    ImGui::InputText("Name", &d.name);
    recordRect(state, "room.name");
    int shape = int(d.shape);
    ImGui::RadioButton("Rectangle", &shape, int(RoomShape::Rectangle));
    ImGui::SameLine();
    ImGui::RadioButton("L-shaped", &shape, int(RoomShape::LShape));
    ImGui::SameLine();
    ImGui::RadioButton("Typed outline", &shape, int(RoomShape::Polygon));
    recordRect(state, "room.polygon");
    d.shape = RoomShape(shape);
    if (d.shape == RoomShape::Polygon) {
        ImGui::InputText("Corners x z [m]", &d.polygon);
        recordRect(state, "room.corners");
        itemTooltip(
            "The floor's corners in metres, x and z, in order round the room: "
            "\"0 0, 6 0, 6 4, 0 4\"");
    } else {
        metres("Width, along x [m]", d.width, 0.1, 1000.0);
        recordRect(state, "room.width");
        metres("Depth, along z [m]", d.depth, 0.1, 1000.0);
        recordRect(state, "room.depth");
        if (d.shape == RoomShape::LShape) {
            metres("Corner cut, x [m]", d.notchWidth, 0.05, 1000.0);
            metres("Corner cut, z [m]", d.notchDepth, 0.05, 1000.0);
            itemTooltip("The L loses this much of the room at its +x, +z corner");
        }
    }
    metres("Height [m]", d.height, 0.1, 100.0);
    recordRect(state, "room.height");
    ImGui::TextDisabled("Reflectances");
    ratio("Floor", d.floorReflectance);
    ratio("Walls", d.wallReflectance);
    ratio("Ceiling", d.ceilingReflectance);
    itemTooltip("EN 12464-1's usual values: ceiling 0.7, walls 0.5, floor 0.2");
    ImGui::Checkbox("Task area on the work plane", &d.taskArea);
    if (d.taskArea) {
        ImGui::Indent();
        metres("Work plane height [m]", d.workPlane, 0.0, 100.0);
        metres("Band left along the walls [m]", d.wallBand, 0.0, 10.0);
        ImGui::DragScalar("Required Em [lx]", ImGuiDataType_Double, &d.requiredEm, 5.f, nullptr,
                          nullptr, "%.0f");
        ImGui::DragScalar("Required U0", ImGuiDataType_Double, &d.requiredU0, 0.01f, nullptr,
                          nullptr, "%.2f");
        d.requiredEm = std::clamp(d.requiredEm, 0.0, 1e5);
        d.requiredU0 = std::clamp(d.requiredU0, 0.0, 1.0);
        if (d.shape == RoomShape::Polygon) ImGui::TextDisabled("(draw it in the Measure panel)");
        ImGui::Unindent();
    }
    if (ui.newScene) {
        ImGui::DragScalar("Maintenance factor", ImGuiDataType_Double, &d.maintenanceFactor, 0.01f,
                          nullptr, nullptr, "%.2f");
        d.maintenanceFactor = std::clamp(d.maintenanceFactor, 0.01, 1.0);
        ImGui::InputText("Project", &d.project.name);
        ImGui::InputText("Client", &d.project.client);
        ImGui::InputText("Designer", &d.project.designer);
    }
    ImGui::PopItemWidth();
    ImGui::EndGroup();
    ImGui::SameLine();
    ImGui::BeginGroup();
    drawPlan(d, ImGui::GetFontSize() * 20.f);
    ImGui::TextDisabled("Seen from above: x right, z down; wall numbers");
    ImGui::EndGroup();

    // The lists scroll in a region of their own, so Create stays in view.
    ImGui::BeginChild("lists", ImVec2(ImGui::GetFontSize() * 50.f, ImGui::GetFontSize() * 13.f),
                      true);
    ImGui::TextDisabled("Openings");
    openingRows(state, d);
    ImGui::Separator();
    ImGui::TextDisabled("Furniture");
    furnitureRows(d);
    ImGui::EndChild();

    ImGui::Separator();
    bool valid = false;
    std::string summary = roomDraftSummary(d, valid);
    if (valid)
        ImGui::TextUnformatted(summary.c_str());
    else
        errorText(summary);
    ImGui::BeginDisabled(!valid);
    if (ImGui::Button(ui.newScene ? "Create" : "Add to the scene")) {
        changed = ui.newScene ? newSceneFromRoom(state, d) : addRoom(state, d);
        if (changed) ImGui::CloseCurrentPopup();
    }
    recordRect(state, "room.create");
    ImGui::EndDisabled();
    ImGui::SameLine();
    if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)))
        ImGui::CloseCurrentPopup();
    recordRect(state, "room.cancel");
    ImGui::EndPopup();
    return changed;
}

}  // namespace candela::ui
