// The comparison in the editor (renderer/Comparison.h): the viewport's layout bar (one image,
// 2 or 4 panes, a wipe between two), the panes with their labels and error maps, the Compare
// panel (each pane's techniques per luminaire kind and sample budget, the reference, export)
// and the accuracy-versus-time window.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "luminaires/environment/EnvironmentSampling.h"
#include "report/ComparisonExport.h"
#include "ui/ImGuiUtil.h"
#include "ui/Panels.h"

namespace candela::ui {

namespace {

constexpr const char* kLetters[] = {"A", "B", "C", "D"};
constexpr float kWipeGrabPx = 8.f;  ///< How close a press must be to the wipe line, pixels.

ImTextureID textureId(GLuint id) {
    return reinterpret_cast<ImTextureID>(static_cast<intptr_t>(id));
}

/// The kinds a pane can choose a technique for: the scene's luminaire kinds in registry order,
/// then the environment when the scene has a map.
std::vector<LuminaireKind> sceneKinds(const Scene& scene) {
    std::vector<LuminaireKind> kinds;
    for (const LuminaireKindInfo& k : luminaireKinds())
        for (const auto& lum : scene.luminaires)
            if (lum->kind() == k.kind) {
                kinds.push_back(k.kind);
                break;
            }
    if (scene.environmentMap) kinds.push_back(LuminaireKind::Environment);
    return kinds;
}

/// The list with kind's choice set to name (empty: its own), as "KIND=NAME" items for the kinds.
std::string withChoice(const std::string& list, const std::vector<LuminaireKind>& kinds,
                       LuminaireKind kind, const std::string& name) {
    std::string out;
    for (LuminaireKind k : kinds) {
        std::string chosen = k == kind ? name : overrideFor(list, k);
        if (chosen.empty()) continue;
        if (!out.empty()) out += ',';
        out.append(kindName(k)).append("=").append(chosen);
    }
    return out;
}

/// Techniques of a kind that render on the GPU.
std::vector<std::string> gpuTechniques(LuminaireKind kind) {
    std::vector<std::string> out;
    for (const TechniqueInfo& t : techniquesOf(kind))
        if (!t.shader.empty()) out.emplace_back(t.name);
    return out;
}

/// The pane's label: its techniques, its samples and time, its errors (or what it waits for).
std::vector<std::string> paneLabel(const CompareUi& ui, const Comparison& c, size_t i) {
    const PaneResult& r = c.result(i);
    const Renderer& renderer = c.paneRenderer(i);
    std::string spp = renderer.plan().progressive()
                          ? std::to_string(r.spp) +
                                (r.done ? "" : " / " + std::to_string(c.spec(i).samples)) + " spp"
                          : std::string("exact");
    std::vector<std::string> lines = {paneName(ui, i) + "  " + techniqueSummary(renderer.plan()),
                                      spp + " \xc2\xb7 " + formatMs(r.gpuMs, 0) + " GPU"};
    char text[96];
    if (r.measured)
        std::snprintf(text, sizeof text,
                      "\xce\x94"
                      "E %.2f \xc2\xb7 rel. RMSE %.2f %%",
                      r.latest.deltaE, 100.0 * r.latest.relRmse);
    else
        std::snprintf(text, sizeof text, "measuring...");
    lines.emplace_back(text);
    return lines;
}

/// The reference's progress: samples, noise, time.
std::string referenceLine(const Comparison& c) {
    char noise[32], text[160];
    if (std::isfinite(c.referenceNoise()))
        std::snprintf(noise, sizeof noise, "%.2f %%", 100.0 * c.referenceNoise());
    else
        std::snprintf(noise, sizeof noise, "(after 2 passes)");
    std::snprintf(text, sizeof text, "Reference %d / %d spp \xc2\xb7 %s \xc2\xb7 noise %s",
                  c.referenceSpp(), c.referenceSamples(), formatMs(c.referenceGpuMs(), 0).c_str(),
                  noise);
    return text;
}

/// A label box: lines of text on a dark translucent background, anchored at a corner.
void labelBox(ImDrawList* draw, ImVec2 anchor, bool alignRight, bool alignBottom,
              const std::vector<std::string>& lines, ImU32 accent) {
    float pad = 4.f, lineH = ImGui::GetTextLineHeight();
    float w = 0.f;
    for (const std::string& l : lines) w = std::max(w, ImGui::CalcTextSize(l.c_str()).x);
    float h = lineH * float(lines.size());
    ImVec2 lo(alignRight ? anchor.x - w - 2.f * pad : anchor.x,
              alignBottom ? anchor.y - h - 2.f * pad : anchor.y);
    ImVec2 hi(lo.x + w + 2.f * pad, lo.y + h + 2.f * pad);
    draw->AddRectFilled(lo, hi, IM_COL32(0, 0, 0, 170));
    draw->AddRectFilled(lo, ImVec2(lo.x + 3.f, hi.y), accent);
    for (size_t k = 0; k < lines.size(); ++k)
        draw->AddText(ImVec2(lo.x + pad + 2.f, lo.y + pad + lineH * float(k)),
                      IM_COL32(235, 235, 235, 255), lines[k].c_str());
}

/// The diverging scale of the error maps, with its range as a fraction of the mean luminance.
void errorLegend(ImDrawList* draw, ImVec2 corner, float scale) {
    float w = 160.f, h = 10.f;
    ImVec2 lo(corner.x - w - 12.f, corner.y - h - 30.f);
    const ImU32 below = IM_COL32(124, 194, 255, 255), above = IM_COL32(255, 179, 89, 255),
                zero = IM_COL32(0, 0, 0, 255);
    draw->AddRectFilled(ImVec2(lo.x - 6.f, lo.y - 4.f), ImVec2(lo.x + w + 6.f, lo.y + h + 22.f),
                        IM_COL32(0, 0, 0, 170));
    draw->AddRectFilledMultiColor(lo, ImVec2(lo.x + w / 2, lo.y + h), below, zero, zero, below);
    draw->AddRectFilledMultiColor(ImVec2(lo.x + w / 2, lo.y), ImVec2(lo.x + w, lo.y + h), zero,
                                  above, above, zero);
    char text[64];
    std::snprintf(text, sizeof text, "-%g%%", 100.0 * scale);
    draw->AddText(ImVec2(lo.x, lo.y + h + 2.f), IM_COL32(220, 220, 220, 255), text);
    draw->AddText(ImVec2(lo.x + w / 2 - 4.f, lo.y + h + 2.f), IM_COL32(220, 220, 220, 255), "0");
    std::snprintf(text, sizeof text, "+%g%%", 100.0 * scale);
    draw->AddText(ImVec2(lo.x + w - ImGui::CalcTextSize(text).x, lo.y + h + 2.f),
                  IM_COL32(220, 220, 220, 255), text);
    draw->AddText(ImVec2(lo.x, lo.y - 4.f - ImGui::GetTextLineHeight()),
                  IM_COL32(220, 220, 220, 255), "pane - reference, of mean luminance");
}

}  // namespace

std::vector<PaneSpec> comparedPanes(const CompareUi& ui) {
    std::vector<PaneSpec> panes(ui.panes.begin(), ui.panes.begin() + ui.paneCount());
    if (ui.layout == CompareLayout::Wipe)
        panes = {ui.panes[size_t(ui.wipePanes[0])], ui.panes[size_t(ui.wipePanes[1])]};
    return panes;
}

std::string paneName(const CompareUi& ui, size_t pane) {
    size_t index =
        ui.layout == CompareLayout::Wipe ? size_t(ui.wipePanes[std::min<size_t>(pane, 1)]) : pane;
    return kLetters[std::min<size_t>(index, 3)];
}

bool compareToolbar(EditorState& state) {
    CompareUi& ui = state.compare;
    bool changed = false;
    const char* names[] = {"Single", "2 panes", "4 panes", "Wipe"};
    const char* ids[] = {"viewport.single", "viewport.two", "viewport.four", "viewport.wipe"};
    ImGui::SetCursorPos(ImVec2(6.f, 3.f));
    for (int k = 0; k < 4; ++k) {
        if (k) ImGui::SameLine();
        bool on = int(ui.layout) == k;
        if (on)
            ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetStyleColorVec4(ImGuiCol_ButtonActive));
        if (ImGui::SmallButton(names[k]) && !on) {
            ui.layout = CompareLayout(k);
            changed = true;
        }
        if (on) ImGui::PopStyleColor();
        recordRect(state, ids[k]);
    }
    itemTooltip(
        "Compare techniques: panes with the same camera, each with its own techniques and sample "
        "budget, measured against a progressive reference (the Compare panel sets them)");
    if (ui.layout != CompareLayout::Single) {
        ImGui::SameLine(0.f, 18.f);
        changed = ImGui::Checkbox("Error map", &ui.showError) || changed;
        recordRect(state, "viewport.error_map");
        itemTooltip("Each pane's signed error against the reference instead of its image");
        ImGui::SameLine();
        if (ImGui::SmallButton("Accuracy plot")) ui.plotOpen = !ui.plotOpen;
        recordRect(state, "viewport.plot");
        ImGui::SameLine();
        if (ImGui::SmallButton("Export sheet")) ui.sheetRequested = true;
        recordRect(state, "viewport.export_sheet");
        itemTooltip(
            "Writes sheet-NNN.png (labelled), sheet-NNN.exr (linear) and sheet-NNN.json (how to "
            "reproduce it) into " +
            state.screenshotDir.string());
    }
    return changed;
}

void compareView(EditorState& state, const Comparison& c, ImVec2 origin, ImVec2 size,
                 bool hovered) {
    CompareUi& ui = state.compare;
    ImDrawList* draw = ImGui::GetWindowDrawList();
    ImVec2 corner(origin.x + size.x, origin.y + size.y);
    draw->AddRectFilled(origin, corner, IM_COL32(20, 20, 24, 255));
    auto texture = [&](size_t i) {
        GLuint error = c.errorMap(i).id();
        return textureId(ui.showError && error ? error : c.paneRenderer(i).displayTexture().id());
    };
    auto labels = [&](size_t i) { return paneLabel(ui, c, i); };
    const ImU32 accent = IM_COL32(255, 200, 60, 255);
    if (ui.layout == CompareLayout::Wipe && c.paneCount() >= 2) {
        const ImGuiIO& io = ImGui::GetIO();
        float x = origin.x + ui.wipe * size.x;
        if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left) &&
            std::abs(io.MousePos.x - x) <= kWipeGrabPx)
            ui.wipeDragging = true;
        if (ui.wipeDragging) {
            if (!ImGui::IsMouseDown(ImGuiMouseButton_Left))
                ui.wipeDragging = false;
            else
                ui.wipe =
                    std::clamp((io.MousePos.x - origin.x) / std::max(1.f, size.x), 0.02f, 0.98f);
            x = origin.x + ui.wipe * size.x;
        }
        // Row 0 of the textures is the bottom row: v runs from 1 at the top to 0.
        draw->AddImage(texture(0), origin, ImVec2(x, corner.y), ImVec2(0.f, 1.f),
                       ImVec2(ui.wipe, 0.f));
        draw->AddImage(texture(1), ImVec2(x, origin.y), corner, ImVec2(ui.wipe, 1.f),
                       ImVec2(1.f, 0.f));
        draw->AddLine(ImVec2(x, origin.y), ImVec2(x, corner.y), IM_COL32(255, 255, 255, 220), 2.f);
        draw->AddCircleFilled(ImVec2(x, origin.y + 0.5f * size.y), 7.f,
                              IM_COL32(255, 255, 255, 230));
        state.widgetRects.emplace_back("compare.wipe",
                                       glm::vec4(x - 2.f, origin.y, x + 2.f, corner.y));
        labelBox(draw, ImVec2(origin.x + 6.f, origin.y + 6.f), false, false, labels(0), accent);
        labelBox(draw, ImVec2(corner.x - 6.f, origin.y + 6.f), true, false, labels(1), accent);
        for (size_t i = 0; i < 2; ++i)
            state.widgetRects.emplace_back("compare.pane" + std::to_string(i),
                                           glm::vec4(origin.x, origin.y, corner.x, corner.y));
    } else {
        int columns = 2, rows = c.paneCount() > 2 ? 2 : 1;
        float w = size.x / float(columns), h = size.y / float(rows);
        for (size_t i = 0; i < c.paneCount(); ++i) {
            ImVec2 lo(std::floor(origin.x + w * float(i % 2)),
                      std::floor(origin.y + h * float(i / 2)));
            ImVec2 hi(std::floor(lo.x + w), std::floor(lo.y + h));
            draw->AddImage(texture(i), lo, hi, ImVec2(0.f, 1.f), ImVec2(1.f, 0.f));
            draw->AddRect(lo, hi, IM_COL32(10, 10, 12, 255), 0.f, 0, 2.f);
            labelBox(draw, ImVec2(lo.x + 6.f, lo.y + 6.f), false, false, labels(i), accent);
            state.widgetRects.emplace_back("compare.pane" + std::to_string(i),
                                           glm::vec4(lo.x, lo.y, hi.x, hi.y));
        }
    }
    labelBox(draw, ImVec2(corner.x - 6.f, corner.y - 6.f), true, true, {referenceLine(c)},
             IM_COL32(120, 200, 255, 255));
    if (ui.showError) errorLegend(draw, ImVec2(corner.x, corner.y - 20.f), ui.errorScale);
}

namespace {

/// The reference's sample budget, the error maps' range and the wipe's panes.
bool referenceControls(CompareUi& ui, const Comparison* c) {
    bool changed = false;
    if (ImGui::InputInt("Reference spp", &ui.referenceSamples, 64, 512)) {
        ui.referenceSamples = std::clamp(ui.referenceSamples, 16, 1 << 16);
        changed = true;
    }
    itemTooltip(std::string("Each kind's unbiased technique with exact (ray-traced) visibility: ") +
                Comparison::kReferenceTechniques +
                ". Every pane's error is measured against it, its own "
                "noise (from the image at half its samples) removed from the relative RMSE.");
    if (c) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
        ImGui::TextWrapped("%s", referenceLine(*c).c_str());
        ImGui::PopStyleColor();
    }
    changed = ImGui::SliderFloat("Error map range", &ui.errorScale, 0.01f, 2.f, "+-%.2f",
                                 ImGuiSliderFlags_Logarithmic) ||
              changed;
    itemTooltip("The error maps saturate at this fraction of the reference's mean luminance");
    if (ui.layout == CompareLayout::Wipe) {
        const char* letters[] = {"A", "B", "C", "D"};
        changed = ImGui::Combo("Left of the wipe", &ui.wipePanes[0], letters, 4) || changed;
        changed = ImGui::Combo("Right of the wipe", &ui.wipePanes[1], letters, 4) || changed;
    }
    return changed;
}

/// Pane p's technique per kind of the scene ("(its own)": the luminaire's) and its budget.
bool paneControls(EditorState& state, PaneSpec& spec, int p,
                  const std::vector<LuminaireKind>& kinds) {
    bool changed = false;
    ImGui::PushID(p);
    ImGui::Separator();
    ImGui::Text("Pane %s", kLetters[p]);
    for (LuminaireKind kind : kinds) {
        // The technique the pane's list gives the kind; empty: the luminaire's own.
        std::string chosen = overrideFor(spec.technique, kind);
        std::string label(kindName(kind));
        std::string id = "compare.pane" + std::to_string(p) + "." + label;
        if (ImGui::BeginCombo(label.c_str(), chosen.empty() ? "(its own)" : chosen.c_str())) {
            if (ImGui::Selectable("(its own)", chosen.empty())) {
                spec.technique = withChoice(spec.technique, kinds, kind, "");
                changed = true;
            }
            for (const std::string& t : gpuTechniques(kind)) {
                if (ImGui::Selectable(t.c_str(), t == chosen)) {
                    spec.technique = withChoice(spec.technique, kinds, kind, t);
                    changed = true;
                }
                recordRect(state, id + "." + t);
            }
            ImGui::EndCombo();
        }
        recordRect(state, id);
    }
    if (ImGui::InputInt("Sample budget", &spec.samples, 16, 256)) {
        spec.samples = std::clamp(spec.samples, 1, 1 << 16);
        changed = true;
    }
    itemTooltip("Samples per pixel this pane refines to (exact techniques finish in one pass)");
    ImGui::PopID();
    return changed;
}

/// Each pane's GPU time and errors against the reference.
void resultsTable(const CompareUi& ui, const Comparison& c) {
    if (!ImGui::BeginTable("results", 4, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV))
        return;
    ImGui::TableSetupColumn("Pane");
    ImGui::TableSetupColumn("GPU");
    ImGui::TableSetupColumn(
        "\xce\x94"
        "E");
    ImGui::TableSetupColumn("RMSE");
    ImGui::TableHeadersRow();
    for (size_t i = 0; i < c.paneCount(); ++i) {
        const PaneResult& r = c.result(i);
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::Text("%s %s", paneName(ui, i).c_str(), r.done ? "" : "...");
        itemTooltip(techniqueSummary(c.paneRenderer(i).plan()));
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(formatMs(r.gpuMs, 0).c_str());
        ImGui::TableNextColumn();
        if (r.measured) ImGui::Text("%.2f", r.latest.deltaE);
        ImGui::TableNextColumn();
        if (r.measured) ImGui::Text("%.2f %%", 100.0 * r.latest.relRmse);
    }
    ImGui::EndTable();
}

}  // namespace

bool comparePanel(EditorState& state, const Comparison* c, const PanelRect& rect) {
    CompareUi& ui = state.compare;
    placeNextWindow(rect);
    ImGui::Begin("Compare", nullptr, kPanelFlags);
    recordPanelRect(state, "compare");
    ImGui::PushItemWidth(-ImGui::GetFontSize() * 8.f);
    bool changed = referenceControls(ui, c);
    std::vector<LuminaireKind> kinds = sceneKinds(state.scene);
    int shown = ui.layout == CompareLayout::Wipe ? 4 : ui.paneCount();
    for (int p = 0; p < shown; ++p)
        changed = paneControls(state, ui.panes[size_t(p)], p, kinds) || changed;
    if (c) {
        ImGui::Separator();
        resultsTable(ui, *c);
    }
    if (ImGui::Button("Export sheet")) ui.sheetRequested = true;
    recordRect(state, "compare.export");
    ImGui::SameLine();
    if (ImGui::Button("Accuracy plot")) ui.plotOpen = !ui.plotOpen;
    if (!ui.lastSheet.empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
        ImGui::TextWrapped("Last sheet: %s", ui.lastSheet.c_str());
        ImGui::PopStyleColor();
    }
    ImGui::PopItemWidth();
    ImGui::End();
    return changed;
}

namespace {

/// The winner on this view, and separately among the bench curves (measured on their own
/// scenes, they rank techniques but are not errors of this image), at the plot's budget.
void announceWinners(CompareUi& ui, const std::vector<ErrorSeries>& series, ErrorMetric metric) {
    size_t viewCount = series.size() - ui.benchSeries.size();
    std::vector<ErrorSeries> view(series.begin(), series.begin() + std::ptrdiff_t(viewCount));
    auto announce = [&](const std::vector<ErrorSeries>& among, const char* where,
                        std::string& winner) {
        Winner w = winnerAt(among, ui.budgetMs, metric);
        winner = w.series >= 0 ? among[size_t(w.series)].label : std::string();
        if (w.series >= 0)
            ImGui::Text("At %s %s: %s wins, %s %.3g%s", formatMs(ui.budgetMs, 0).c_str(), where,
                        winner.c_str(),
                        ui.plotDeltaE ? "\xce\x94"
                                        "E"
                                      : "rel. RMSE",
                        ui.plotDeltaE ? w.error : 100.0 * w.error, ui.plotDeltaE ? "" : " %");
        else
            ImGui::TextDisabled("%s: no technique has a measurement within %s yet", where,
                                formatMs(ui.budgetMs, 0).c_str());
    };
    announce(view, "on this view", ui.winner);
    if (!ui.benchSeries.empty()) announce(ui.benchSeries, "in the bench CSVs", ui.benchWinner);
}

/// A bench CSV's path and Add CSV (its curves join the plot, dashed), and Clear.
void benchCsvControls(EditorState& state) {
    CompareUi& ui = state.compare;
    ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x - 130.f);
    bool enter = ImGui::InputTextWithHint("##csv", "bench.csv of `candela bench`", &ui.benchPath,
                                          ImGuiInputTextFlags_EnterReturnsTrue);
    recordRect(state, "plot.csv");
    itemTooltip(
        "Adds the curves of a `candela bench` CSV (dashed); they were measured on their own scene, "
        "so they compare techniques, not this view");
    ImGui::SameLine();
    if (ImGui::Button("Add CSV") || enter) {
        try {
            std::vector<ErrorSeries> read = readBenchCsv(ui.benchPath);
            ui.benchSeries.insert(ui.benchSeries.end(), read.begin(), read.end());
            setStatus(state, "Bench curves added from " + ui.benchPath);
        } catch (const std::exception& e) {
            reportError(state, e.what());
        }
    }
    recordRect(state, "plot.add_csv");
    ImGui::SameLine();
    if (ImGui::Button("Clear")) ui.benchSeries.clear();
}

}  // namespace

void accuracyWindow(EditorState& state, const Comparison* c, const PanelRect& viewport) {
    CompareUi& ui = state.compare;
    if (!ui.plotOpen) return;
    ImGui::SetNextWindowPos(ImVec2(viewport.x + 12.f, viewport.y + viewport.h - 372.f),
                            ImGuiCond_Appearing);
    ImGui::SetNextWindowSize(ImVec2(std::min(560.f, viewport.w - 24.f), 360.f),
                             ImGuiCond_Appearing);
    if (!ImGui::Begin("Accuracy vs time", &ui.plotOpen, ImGuiWindowFlags_NoSavedSettings)) {
        ImGui::End();
        return;
    }
    recordPanelRect(state, "plot");
    std::vector<ErrorSeries> series;
    if (c)
        for (size_t i = 0; i < c->paneCount(); ++i)
            series.push_back({paneName(ui, i) + " " + techniqueSummary(c->paneRenderer(i).plan()),
                              c->result(i).series, false});
    series.insert(series.end(), ui.benchSeries.begin(), ui.benchSeries.end());
    ErrorMetric metric = ui.plotDeltaE ? ErrorMetric::DeltaE : ErrorMetric::RelRmse;
    int m = ui.plotDeltaE ? 1 : 0;
    ImGui::RadioButton("rel. RMSE", &m, 0);
    ImGui::SameLine();
    ImGui::RadioButton(
        "mean \xce\x94"
        "E",
        &m, 1);
    ui.plotDeltaE = m == 1;
    ImGui::SameLine(0.f, 20.f);
    ImGui::SetNextItemWidth(150.f);
    ImGui::SliderFloat("Budget", &ui.budgetMs, 1.f, 100000.f, "%.0f ms",
                       ImGuiSliderFlags_Logarithmic);
    recordRect(state, "plot.budget");
    itemTooltip(
        "GPU time you can spend on the image: the plot names the technique with the lowest error "
        "there");
    announceWinners(ui, series, metric);
    float csvHeight = ImGui::GetFrameHeightWithSpacing() + 4.f;
    accuracyPlot("##accuracy", series, metric, ui.budgetMs,
                 ImVec2(-1.f, ImGui::GetContentRegionAvail().y - csvHeight));
    recordRect(state, "plot.area");
    benchCsvControls(state);
    ImGui::End();
}

}  // namespace candela::ui
