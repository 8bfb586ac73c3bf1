#pragma once
// Small Dear ImGui helpers shared by the panels.

#include <imgui.h>

#include <string>

#include "ui/Panels.h"

namespace candela::ui {

/// Panels sit where the layout puts them: no moving, resizing, collapsing or saved settings.
constexpr ImGuiWindowFlags kPanelFlags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                         ImGuiWindowFlags_NoCollapse |
                                         ImGuiWindowFlags_NoSavedSettings;

/// Colour of error messages.
inline ImVec4 errorColour() {
    return ImVec4(1.f, 0.35f, 0.3f, 1.f);
}

inline void placeNextWindow(const PanelRect& r) {
    ImGui::SetNextWindowPos(ImVec2(r.x, r.y), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(r.w, r.h), ImGuiCond_Always);
}

/// Wrapped red text.
inline void errorText(const std::string& text) {
    ImGui::PushStyleColor(ImGuiCol_Text, errorColour());
    ImGui::PushTextWrapPos(0.f);
    ImGui::TextUnformatted(text.c_str());
    ImGui::PopTextWrapPos();
    ImGui::PopStyleColor();
}

/// Tooltip for the previous item.
inline void itemTooltip(const std::string& text) {
    if (!text.empty() && ImGui::IsItemHovered()) {
        ImGui::BeginTooltip();
        ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30.f);
        ImGui::TextUnformatted(text.c_str());
        ImGui::PopTextWrapPos();
        ImGui::EndTooltip();
    }
}

}  // namespace candela::ui
