// Add > Luminaire layout: a luminaire, a task area, a mounting height and a target; Propose
// computes the layout on a worker thread (each arrangement shown as it is computed), Accept
// applies the chosen grid as one undo step (ui/LayoutJob.h).
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cstdio>

#include "ui/ImGuiUtil.h"
#include "ui/Panels.h"

namespace candela::ui {

namespace {

/// The files a layout can use: the scene's and the library's photometries and GLDF containers.
std::vector<LibraryEntry> layoutFiles(const EditorState& state) {
    std::vector<LibraryEntry> out;
    for (const LibraryEntry& e : sceneLuminaireFiles(state.scene))
        if (e.kind != FileKind::LightField) out.push_back(e);
    for (const LibraryEntry& e : state.library.entries)
        if (e.kind != FileKind::LightField &&
            std::none_of(out.begin(), out.end(),
                         [&](const LibraryEntry& o) { return o.path == e.path; }))
            out.push_back(e);
    return out;
}

void resultTable(const LayoutResult& r) {
    ImGui::Text(
        "Lumen method: %d luminaires (room index %.2f, utilisation about %.2f, %.0f lm "
        "each, maintenance factor %.2f)",
        r.lumenMethodCount, r.roomIndex, r.utilisationGuess, r.flux, r.maintenanceFactor);
    ImGuiTableFlags flags =
        ImGuiTableFlags_RowBg | ImGuiTableFlags_Borders | ImGuiTableFlags_SizingFixedFit;
    if (!ImGui::BeginTable("tried", 5, flags)) return;
    ImGui::TableSetupColumn("Grid");
    ImGui::TableSetupColumn("Luminaires");
    ImGui::TableSetupColumn("Em [lx]");
    ImGui::TableSetupColumn("U0");
    ImGui::TableSetupColumn("Target");
    ImGui::TableHeadersRow();
    for (size_t k = 0; k < r.tried.size(); ++k) {
        const LayoutCandidate& c = r.tried[k];
        bool chosen = int(k) == r.chosen;
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::Text("%s%d x %d", chosen ? "> " : "", c.columns, c.rows);
        ImGui::TableNextColumn();
        ImGui::Text("%d", c.count());
        ImGui::TableNextColumn();
        ImGui::Text("%.1f", c.em);
        ImGui::TableNextColumn();
        ImGui::Text("%.3f", c.u0);
        ImGui::TableNextColumn();
        if (c.meets)
            ImGui::TextColored(ImVec4(0.4f, 0.9f, 0.4f, 1.f), chosen ? "met (chosen)" : "met");
        else
            ImGui::TextColored(ImVec4(1.f, 0.5f, 0.4f, 1.f), "not met");
    }
    ImGui::EndTable();
}

}  // namespace

bool layoutDialog(EditorState& state) {
    LayoutUi& ui = state.layoutDialog;
    const char* title = "Luminaire layout###layout_dialog";
    if (ui.requested) {
        ImGui::OpenPopup(title);
        ui.requested = false;
    }
    // Sized to what it shows (its results and lists come and go).
    if (!ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return false;
    bool changed = false;
    const std::vector<TaskArea>& areas = state.scene.taskAreas;
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40.f);
    ImGui::TextDisabled(
        "The fewest luminaires in a regular grid that reach the target on a task area: the lumen "
        "method's count first, then each arrangement computed with shadows and interreflected "
        "light, as the Measure panel's surfaces are.");
    ImGui::PopTextWrapPos();
    if (areas.empty()) {
        ImGui::TextColored(errorColour(),
                           "The scene has no task area: draw one in the Measure panel, or make a "
                           "room with one (File > New room).");
        if (ImGui::Button("Close")) ImGui::CloseCurrentPopup();
        ImGui::EndPopup();
        return false;
    }
    bool running = ui.job && !ui.job->done();
    ImGui::BeginDisabled(running);
    ImGui::PushItemWidth(ImGui::GetFontSize() * 22.f);
    std::vector<LibraryEntry> files = layoutFiles(state);
    if (ui.file.empty() && !files.empty()) ui.file = files.front().path;
    std::string shown = std::filesystem::path(ui.file).filename().string();
    if (ImGui::BeginCombo("Luminaire", shown.c_str())) {
        for (const LibraryEntry& f : files) {
            if (ImGui::Selectable(f.label.c_str(), f.path == ui.file)) ui.file = f.path;
            recordRect(state, "layout.file:" + std::filesystem::path(f.path).filename().string());
        }
        ImGui::EndCombo();
    }
    recordRect(state, "layout.luminaire");
    itemTooltip(ui.file + "\n(the scene's files first, then the library's)");
    if (std::filesystem::path(ui.file).extension() == ".gldf")
        ImGui::InputTextWithHint("Variant", "the first", &ui.variant);
    ui.area = std::clamp(ui.area, 0, int(areas.size()) - 1);
    if (ImGui::BeginCombo("Task area", areas[size_t(ui.area)].name.c_str())) {
        for (size_t i = 0; i < areas.size(); ++i)
            if (ImGui::Selectable(areas[i].name.c_str(), int(i) == ui.area)) ui.area = int(i);
        ImGui::EndCombo();
    }
    const TaskArea& area = areas[size_t(ui.area)];
    ImGui::DragScalar("Mounting height [m]", ImGuiDataType_Double, &ui.height, 0.01f, nullptr,
                      nullptr, "%.2f");
    recordRect(state, "layout.height");
    itemTooltip("The luminaires' light openings above the room's floor");
    ui.height = std::clamp(ui.height, 0.01, 1000.0);
    double em = ui.em > 0.0 ? ui.em : area.required.em;
    double u0 = ui.u0 > 0.0 ? ui.u0 : area.required.u0;
    if (ImGui::DragScalar("Target Em [lx]", ImGuiDataType_Double, &em, 5.f, nullptr, nullptr,
                          "%.0f"))
        ui.em = std::clamp(em, 0.0, 1e6);
    if (ImGui::DragScalar("Target U0", ImGuiDataType_Double, &u0, 0.01f, nullptr, nullptr, "%.2f"))
        ui.u0 = std::clamp(u0, 0.0, 1.0);
    itemTooltip("Maintained illuminance and uniformity; by default the task area's requirement");
    ImGui::PopItemWidth();
    if (ImGui::Button("Propose")) {
        LayoutRequest request;
        request.name = std::filesystem::path(ui.file).stem().string();
        request.area = area.name;
        request.luminaire = layoutLuminaireEntry(ui.file, ui.variant);
        request.mountingHeight = ui.height;
        request.targetEm = ui.em;
        request.targetU0 = ui.u0;
        ui.job.reset();  // a previous proposal's worker is cancelled and joined first
        ui.job = std::make_shared<LayoutJob>(state.scene, request);
    }
    recordRect(state, "layout.propose");
    ImGui::EndDisabled();

    if (ui.job) {
        ImGui::Separator();
        if (!ui.job->done()) {
            std::string status = ui.job->status();
            ImGui::Text("Computing... %s",
                        status.empty() ? "the lumen method's guess" : status.c_str());
            if (ImGui::Button("Stop")) ui.job.reset();
        } else if (ui.job->result()) {
            const LayoutResult& r = *ui.job->result();
            resultTable(r);
            ImGui::TextDisabled("%s", r.light.c_str());
            if (const LayoutCandidate* best = r.best()) {
                std::string accept = "Accept " + std::to_string(best->count()) + " luminaires (" +
                                     std::to_string(best->columns) + " x " +
                                     std::to_string(best->rows) + ")";
                if (ImGui::Button(accept.c_str())) {
                    changed = acceptLayout(state, ui.job->request(), r);
                    if (changed) {
                        ui.job.reset();
                        ImGui::CloseCurrentPopup();
                    }
                }
                recordRect(state, "layout.accept");
                itemTooltip("Replaces the luminaires over the room with this grid: one undo step");
            } else {
                ImGui::TextColored(errorColour(),
                                   "No arrangement met the target: raise the mounting height, "
                                   "take a brighter luminaire or lower the target.");
            }
        } else {
            errorText(ui.job->error());
        }
    }
    ImGui::SameLine();
    if (ImGui::Button("Close")) {
        ui.job.reset();
        ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
    return changed;
}

}  // namespace candela::ui
