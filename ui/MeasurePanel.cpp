// The Measure panel: what the image shows (radiance or illuminance), the false-colour legend
// (range in lux, log or linear, isolux levels) with its colour bar, then the scene's task areas
// with their surroundings' and points' results against EN 12464-1, the calculation grid on a
// plane (it starts on the first task area) with its summary, and the UGR at glare observers.
// What it draws over the viewport is ui/MeasureOverlay.cpp's.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <initializer_list>
#include <sstream>

#include "shaders/shared/FalseColour.h"
#include "ui/ImGuiUtil.h"
#include "ui/Panels.h"

namespace candela::ui {

namespace {

constexpr int kBarSegments = 96;  ///< Quads of the colour bar (the scale is piecewise linear).

ImU32 toImColour(const glm::vec3& c) {
    return ImGui::ColorConvertFloat4ToU32(ImVec4(c.x, c.y, c.z, 1.f));
}

/// "100, 200, 500" from levels in lux.
std::string levelsToText(const std::vector<float>& levels) {
    std::string out;
    char item[32];
    for (float v : levels) {
        std::snprintf(item, sizeof item, "%s%g", out.empty() ? "" : ", ", double(v));
        out += item;
    }
    return out;
}

/// Comma- or space-separated numbers; false if any item is not a finite number.
bool textToLevels(const std::string& text, std::vector<float>& levels) {
    std::string t = text;
    std::replace(t.begin(), t.end(), ',', ' ');
    std::istringstream in(t);
    std::vector<float> out;
    std::string item;
    while (in >> item) {
        char* end = nullptr;
        double v = std::strtod(item.c_str(), &end);
        if (*end != '\0' || !std::isfinite(v)) return false;
        out.push_back(float(v));
    }
    levels = out;
    return true;
}

/// The colour bar of the legend with its ticks labelled in the image's unit.
void colourBar(const FalseColourLegend& raw, const char* unit) {
    FalseColourLegend legend = sanitizedLegend(raw);
    ImDrawList* draw = ImGui::GetWindowDrawList();
    ImVec2 p = ImGui::GetCursorScreenPos();
    float width = std::max(40.f, ImGui::GetContentRegionAvail().x - 8.f);
    float height = ImGui::GetFrameHeight() * 0.8f;
    float x0 = p.x + 4.f;
    for (int k = 0; k < kBarSegments; ++k) {
        float t0 = float(k) / kBarSegments, t1 = float(k + 1) / kBarSegments;
        ImU32 a = toImColour(gpu::falseColour(t0)), b = toImColour(gpu::falseColour(t1));
        draw->AddRectFilledMultiColor(ImVec2(x0 + t0 * width, p.y),
                                      ImVec2(x0 + t1 * width, p.y + height), a, b, b, a);
    }
    std::vector<float> contours = contourLevels(legend);
    for (float level : contours) {
        float t = gpu::legendPosition(level, legend.min, legend.max, legend.logScale ? 1 : 0);
        if (t < 0.f || t > 1.f) continue;
        draw->AddLine(ImVec2(x0 + t * width, p.y), ImVec2(x0 + t * width, p.y + height),
                      IM_COL32(0, 0, 0, 200), 1.f);
    }
    float labelY = p.y + height + 2.f, lastRight = -1e9f;
    char text[32];
    for (float tick : legendTicks(legend)) {
        float t = gpu::legendPosition(tick, legend.min, legend.max, legend.logScale ? 1 : 0);
        float x = x0 + t * width;
        draw->AddLine(ImVec2(x, p.y + height), ImVec2(x, p.y + height + 3.f),
                      IM_COL32(220, 220, 220, 255));
        std::snprintf(text, sizeof text, "%g", double(tick));
        ImVec2 size = ImGui::CalcTextSize(text);
        float left = std::clamp(x - 0.5f * size.x, x0 - 4.f, x0 + width + 4.f - size.x);
        if (left < lastRight + 4.f) continue;  // would overlap the previous label
        draw->AddText(ImVec2(left, labelY + 2.f), IM_COL32(220, 220, 220, 255), text);
        lastRight = left + size.x;
    }
    ImGui::Dummy(ImVec2(width + 8.f, height + ImGui::GetTextLineHeight() + 6.f));
    ImGui::TextDisabled("[%s], %s scale; lines: isolux", unit, legend.logScale ? "log" : "linear");
}

bool legendControls(EditorState& state, MeasureState& measure, const Renderer& renderer) {
    RenderSettings& s = state.settings;
    FalseColourLegend& legend = s.legend;
    bool changed = false;
    bool illuminance = s.quantity == Quantity::Illuminance;
    UnitSystem units = state.scene.units();
    const char* unit = illuminance ? units.irradiance() : units.radiance();
    std::string minLabel = std::string("Min [") + unit + "]",
                maxLabel = std::string("Max [") + unit + "]";
    float speed = std::max(0.01f, 0.005f * (legend.max - legend.min));
    changed = ImGui::DragFloat(minLabel.c_str(), &legend.min, speed, 0.f, 1e9f, "%.4g") || changed;
    changed = ImGui::DragFloat(maxLabel.c_str(), &legend.max, speed, 0.f, 1e9f, "%.4g") || changed;
    changed = ImGui::Checkbox("Log scale", &legend.logScale) || changed;
    ImGui::SameLine();
    changed = ImGui::Checkbox("Isolux lines", &legend.contours) || changed;
    std::string levelsLabel = std::string("Levels [") + unit + "]";
    if (ImGui::InputTextWithHint(levelsLabel.c_str(), "at the legend's ticks",
                                 &measure.levelsText)) {
        std::vector<float> levels;
        if (textToLevels(measure.levelsText, levels)) {
            legend.levels = levels;
            changed = true;
        }
    }
    itemTooltip("Isolux levels, comma-separated (at most 16); empty: at the legend's ticks");
    if (ImGui::Button("Fit to image")) {
        std::vector<float> rgb = renderer.readLinear();
        float peak = 0.f;
        for (size_t i = 0; i + 2 < rgb.size(); i += 3)
            peak = std::max(peak, 0.2126f * rgb[i] + 0.7152f * rgb[i + 1] + 0.0722f * rgb[i + 2]);
        fitLegend(legend, peak);
        changed = true;
    }
    itemTooltip("Range from 0 (log: 3 decades below) to a round value above the brightest pixel");
    if (measure.result) ImGui::SameLine();
    if (measure.result && ImGui::Button("Range from grid")) {
        legend.min = legend.logScale ? float(std::max(measure.summary.eMin, 1e-3)) : 0.f;
        legend.max = float(std::max(measure.summary.eMax, double(legend.min) * 1.01 + 1e-6));
        changed = true;
    }
    legend = sanitizedLegend(legend);
    colourBar(legend, unit);
    if (!illuminance)
        ImGui::TextDisabled("Radiance mode: the scale shows %s",
                            units.photometric ? "luminance" : "radiance");
    if (units.converted) ImGui::TextDisabled("Mixed scene: %s", units.note().c_str());
    return changed;
}

/// Takes plane, height and extent from the selected geometry if it is an axis-aligned plane.
bool pickSelectedPlane(const EditorState& state, GridSpec& grid, std::string& error) {
    int index = state.selectedGeometry;
    if (index < 0 || index >= int(state.scene.geometry.size())) {
        error = "Select a plane in the outline first";
        return false;
    }
    const GeometryItem& item = state.scene.geometry[size_t(index)];
    if (item.meshes.size() != 1 || state.scene.meshes[item.meshes[0]].shape != MeshShape::Plane) {
        error = "The selected geometry is not a plane";
        return false;
    }
    const Mesh& mesh = state.scene.meshes[item.meshes[0]];
    glm::vec3 n = mesh.normals.empty() ? glm::vec3(0.f) : mesh.normals[0];
    int axis = 0;
    for (int a = 1; a < 3; ++a)
        if (std::abs(n[a]) > std::abs(n[axis])) axis = a;
    if (std::abs(n[axis]) < 0.999f) {
        error = "The selected plane is not axis-aligned";
        return false;
    }
    grid.plane.axis = axis;
    grid.plane.sign = n[axis] > 0.f ? 1.0 : -1.0;
    grid.plane.offset = 0.5 * double(mesh.boundsMin[axis] + mesh.boundsMax[axis]);
    grid.lo = grid.plane.inPlane(glm::dvec3(mesh.boundsMin));
    grid.hi = grid.plane.inPlane(glm::dvec3(mesh.boundsMax));
    error.clear();
    return true;
}

void computeNow(const EditorState& state, MeasureState& measure) {
    try {
        if (!measure.extentSet) defaultGridExtent(state.scene, measure.grid);
        measure.extentSet = true;
        GridSpec spec = measure.grid;
        applyLightChoice(state.scene, measure.light, spec);  // as `candela grid` does
        measure.result = computeGrid(state.scene, spec);
        measure.summary = summariseGrid(measure.result->E);
        measure.error.clear();
    } catch (const std::exception& e) {
        measure.error = e.what();
    }
}

/// The grid's plane, extent, spacing, samples and what it includes.
/// The project's maintenance factor (EN 12464-1): every luminaire without its own takes it, and
/// every illuminance the editor shows is maintained by it. An undoable edit.
bool maintenanceControl(EditorState& state) {
    double factor = state.scene.maintenanceFactor;
    bool dragged = ImGui::DragScalar("Maintenance factor", ImGuiDataType_Double, &factor, 0.005f,
                                     nullptr, nullptr, "%.3f");
    itemTooltip(
        "EN 12464-1: maintained over initial output, in (0, 1]. Every luminaire without a "
        "maintenance_factor of its own (Inspector) takes this one; illuminance, radiance and the "
        "grid show maintained values");
    factor = std::clamp(factor, 0.01, 1.0);
    if (!dragged || factor == state.scene.maintenanceFactor) return false;
    applyEdit(state, "Maintenance factor", kChangeLuminaires,
              [factor](Scene& scene) { scene.maintenanceFactor = factor; });
    return true;
}

void gridSpecControls(EditorState& state, MeasureState& measure) {
    GridSpec& g = measure.grid;
    const char* axes[] = {"x (wall)", "y (horizontal)", "z (wall)"};
    int axis = g.plane.axis;
    if (ImGui::Combo("Plane normal", &axis, axes, 3)) {
        g.plane.axis = axis;
        measure.extentSet = false;
    }
    bool down = g.plane.sign < 0.0;
    if (ImGui::Checkbox("Faces -axis", &down)) g.plane.sign = down ? -1.0 : 1.0;
    itemTooltip(
        "Receiving side: off = towards +axis (a floor or desk), on = towards -axis (a ceiling)");
    ImGui::DragScalar("Plane at [m]", ImGuiDataType_Double, &g.plane.offset, 0.01f, nullptr,
                      nullptr, "%.3f");
    double extent[4] = {g.lo.x, g.lo.y, g.hi.x, g.hi.y};
    if (ImGui::DragScalarN("Extent [m]", ImGuiDataType_Double, extent, 4, 0.01f, nullptr, nullptr,
                           "%.2f")) {
        g.lo = {extent[0], extent[1]};
        g.hi = {extent[2], extent[3]};
        measure.extentSet = true;
    }
    itemTooltip("Corners " + g.plane.uName() + "0, " + g.plane.vName() + "0, " + g.plane.uName() +
                "1, " + g.plane.vName() + "1 of the grid on the plane, metres");
    if (ImGui::Button("Scene bounds")) {
        measure.extentSet = false;
        try {
            defaultGridExtent(state.scene, g);
            measure.extentSet = true;
        } catch (const std::exception& e) {
            measure.error = e.what();
        }
    }
    ImGui::SameLine();
    if (ImGui::Button("Selected plane"))
        measure.extentSet = pickSelectedPlane(state, g, measure.error);
    const double minSpacing = 0.01, maxSpacing = 10.0;
    ImGui::SliderScalar("Spacing [m]", ImGuiDataType_Double, &g.spacing, &minSpacing, &maxSpacing,
                        "%.3f", ImGuiSliderFlags_Logarithmic);
    ImGui::SliderInt("Samples / point", &g.spp, 16, 4096, "%d", ImGuiSliderFlags_Logarithmic);
    itemTooltip(
        "For stochastic techniques (the grid, the surfaces and the UGR); exact ones "
        "ignore it");
}

/// What the grid, the surfaces and the UGR include: what a light meter would read unless switched
/// off, as on the command line.
void lightChoiceControls(EditorState& state, MeasureState& measure) {
    ImGui::Checkbox("Shadows", &measure.light.shadows);
    itemTooltip("Surfaces and luminaire bodies block light (where the scene has any)");
    ImGui::SameLine();
    ImGui::Checkbox("Interreflected light##grid", &measure.light.interreflection);
    recordRect(state, "measure.indirect");
    itemTooltip(
        "The light the surfaces reflect onto each other (where any surface reflects): the "
        "patches' solution, traced point by point where it is not accurate enough. Uncheck for "
        "direct light alone.");
}

/// A column of a results table that is never squeezed: as wide as its header and the widest of
/// the texts it shows (`widest`), so a value never reads "4 0 5 F".
void fixedColumn(const char* header, std::initializer_list<const char*> widest) {
    float width = ImGui::CalcTextSize(header).x;
    for (const char* text : widest) width = std::max(width, ImGui::CalcTextSize(text).x);
    ImGui::TableSetupColumn(header, ImGuiTableColumnFlags_WidthFixed, width);
}

/// Flags of the panel's results tables: rows told apart; the first column (names) takes the width
/// the fixed ones leave, and its names wrap.
constexpr ImGuiTableFlags kResultTable = ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerH;

/// The first cell of a row: a name over a grey second line (what it is), both wrapped in their
/// column; `detail` is its tooltip.
void nameCell(const std::string& name, const std::string& kind, const std::string& detail) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::PushTextWrapPos(0.f);
    ImGui::TextUnformatted(name.c_str());
    itemTooltip(detail);
    if (!kind.empty()) {
        ImGui::TextDisabled("%s", kind.c_str());
        itemTooltip(detail);
    }
    ImGui::PopTextWrapPos();
}

/// A list entry after its remove button: "name: details" on one line where it fits, else the
/// name (wrapped at its spaces) over the details in grey (numbers are never split).
void listEntry(const std::string& name, const std::string& details) {
    std::string line = name + ": " + details;
    if (ImGui::CalcTextSize(line.c_str()).x <= ImGui::GetContentRegionAvail().x) {
        ImGui::TextUnformatted(line.c_str());
        return;
    }
    ImGui::PushTextWrapPos(0.f);
    ImGui::TextUnformatted(name.c_str());
    ImGui::PopTextWrapPos();
    ImGui::TextDisabled("%s", details.c_str());
}

/// An illuminance in a column whose header gives the unit: 412, 12.3, 0.0123, 1.2e-05; at most
/// seven characters below 10^7 (the columns are sized for seven).
std::string compactNumber(double value) {
    char text[32];
    double a = std::abs(value);
    if (a == 0.0 || a >= 100.0)
        std::snprintf(text, sizeof text, "%.0f", value);
    else if (a >= 0.01)
        std::snprintf(text, sizeof text, "%.3g", value);
    else
        std::snprintf(text, sizeof text, "%.1e", value);
    return text;
}

/// A value over the grey requirement it is held to (">= 500"), in one cell.
void valueCell(const std::string& value, const std::string& required) {
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(value.c_str());
    if (!required.empty()) ImGui::TextDisabled("%s", required.c_str());
}

/// The verdict as every output words it (verdictText): PASS green, FAIL red, "no points" grey;
/// a dash where nothing is required.
void verdictCell(Verdict verdict) {
    ImGui::TableNextColumn();
    if (verdict == Verdict::Pass)
        ImGui::TextColored(ImVec4(0.4f, 0.9f, 0.4f, 1.f), "%s", verdictText(verdict));
    else if (verdict == Verdict::Fail)
        ImGui::TextColored(ImVec4(1.f, 0.4f, 0.4f, 1.f), "%s", verdictText(verdict));
    else if (verdict == Verdict::NoPoints)
        ImGui::TextDisabled("%s", verdictText(verdict));
    else
        ImGui::TextDisabled("-");
    itemTooltip(verdict == Verdict::NoPoints
                    ? "The room leaves no points of this surface: nothing to judge"
                    : std::string(verdictText(verdict)));
}

/// "Desk" for "Desk: immediate surrounding" (the second line names the role).
std::string ownerName(const SurfaceResult& s) {
    std::string suffix = ": " + s.role;
    if (s.name.size() > suffix.size() &&
        s.name.compare(s.name.size() - suffix.size(), suffix.size(), suffix) == 0)
        return s.name.substr(0, s.name.size() - suffix.size());
    return s.name;
}

/// Emin, Eavg, Emax and the uniformities of the computed grid; with interreflected light, Em
/// and U0 of the direct, interreflected and total light, as design tools report them.
void gridResultTables(const GridResult& r, const GridSummary& s) {
    ImGui::Text("%zu points (%zu x %zu), %c = %.3g m", s.count, r.u.size(), r.v.size(),
                "xyz"[r.spec.plane.axis], r.spec.plane.offset);
    if (ImGui::BeginTable("summary", 2, ImGuiTableFlags_RowBg)) {
        auto row = [](const char* name, const char* format, double value) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(name);
            ImGui::TableNextColumn();
            ImGui::Text(format, value);
        };
        std::string format = std::string("%.4g ") + r.units.irradiance();
        row("Emin", format.c_str(), s.eMin);
        row("Eavg", format.c_str(), s.eAvg);
        row("Emax", format.c_str(), s.eMax);
        row("U0 = Emin/Eavg", "%.3f", s.u0);
        row("Emin/Emax", "%.3f", s.minOverMax);
        ImGui::EndTable();
    }
    std::string em = std::string("Em [") + r.units.irradiance() + "]";
    if (r.hasIndirect && ImGui::BeginTable("parts", 3, kResultTable)) {
        ImGui::TableSetupColumn("Light", ImGuiTableColumnFlags_WidthStretch);
        fixedColumn(em.c_str(), {"8888888"});
        fixedColumn("U0", {"0.888"});
        ImGui::TableHeadersRow();
        for (auto [name, values] :
             {std::pair<const char*, const std::vector<double>*>{"direct", &r.direct},
              {"interreflected", &r.indirect},
              {"total", &r.E}}) {
            GridSummary p = summariseGrid(*values);
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(name);
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(compactNumber(p.eAvg).c_str());
            ImGui::TableNextColumn();
            ImGui::Text("%.3f", p.u0);
        }
        ImGui::EndTable();
    }
    if (r.units.converted) ImGui::TextDisabled("(%s)", r.units.note().c_str());
    ImGui::TextDisabled("%s", r.maintenance.c_str());
}

void gridControls(EditorState& state, MeasureState& measure) {
    gridSpecControls(state, measure);
    if (ImGui::Button("Compute grid", ImVec2(-1.f, 0.f))) computeNow(state, measure);
    if (!measure.error.empty()) errorText(measure.error);
    if (!measure.result) return;
    gridResultTables(*measure.result, measure.summary);
    ImGui::Checkbox("Values in the viewport", &measure.showValues);
}

/// The surfaces' and points' results: what each reached over what it needs, and the verdict.
void surfaceTable(const SurfaceReport& r) {
    const char* unit = r.units.irradiance();
    std::string em = std::string("Em [") + unit + "]";
    if (!ImGui::BeginTable("surfaces", 4, kResultTable)) return;
    ImGui::TableSetupColumn("Surface", ImGuiTableColumnFlags_WidthStretch);
    fixedColumn(em.c_str(), {"8888888", ">= 8888"});
    fixedColumn("U0", {"0.88", ">= 0.88"});
    fixedColumn("Result", {verdictText(Verdict::NoPoints), verdictText(Verdict::Fail)});
    ImGui::TableHeadersRow();
    char text[160];
    for (const SurfaceResult& s : r.surfaces) {
        std::snprintf(text, sizeof text, ": %s%s, %zu points", s.role.c_str(),
                      s.cylindrical ? " (cylindrical illuminance)" : "", s.points.size());
        std::string detail = s.name + text;
        if (!s.points.empty()) {
            std::snprintf(text, sizeof text, "; Em %.4g %s, U0 %.3f, Emin %.4g %s, Emax %.4g %s",
                          s.summary.eAvg, unit, s.summary.u0, s.summary.eMin, unit, s.summary.eMax,
                          unit);
            detail += text;
        }
        nameCell(ownerName(s), s.role, detail);
        std::string needU0;
        if (s.required.u0 > 0.0) {
            std::snprintf(text, sizeof text, ">= %.2f", s.required.u0);
            needU0 = text;
        }
        bool any = !s.points.empty();
        valueCell(any ? compactNumber(s.summary.eAvg) : "-",
                  s.required.em > 0.0 ? ">= " + compactNumber(s.required.em) : "");
        std::snprintf(text, sizeof text, "%.2f", s.summary.u0);
        valueCell(any ? text : "-", needU0);
        verdictCell(s.verdict);
    }
    for (const PointResult& p : r.points) {
        const CalcPoint& c = p.point;
        std::snprintf(text, sizeof text, " at (%.2f, %.2f, %.2f) m: %s %.4g %s", c.position.x,
                      c.position.y, c.position.z, c.cylindrical ? "cylindrical Ez" : "E", p.E,
                      unit);
        nameCell(c.name, c.cylindrical ? "point, cylindrical" : "point", c.name + text);
        valueCell(compactNumber(p.E),
                  c.requiredLux > 0.0 ? ">= " + compactNumber(c.requiredLux) : "");
        valueCell("", "");
        verdictCell(p.verdict);
    }
    ImGui::EndTable();
}

/// The scene's task areas (remove one), and the surfaces' and points' results against their
/// requirements (calculation/CalculationSurfaces.h), computed on demand; then a new task area
/// from the grid or drawn in the viewport.
void surfaceControls(EditorState& state, MeasureState& measure) {
    for (size_t i = 0; i < state.scene.taskAreas.size(); ++i) {
        const TaskArea& a = state.scene.taskAreas[i];
        ImGui::PushID(int(i));
        if (ImGui::SmallButton("x")) {
            removeTaskArea(state, i);
            ImGui::PopID();
            break;
        }
        itemTooltip("Remove this task area");
        ImGui::SameLine();
        char text[96];
        std::snprintf(text, sizeof text, "%s m, %.2f x %.2f m", planeText(a.plane).c_str(),
                      a.hi.x - a.lo.x, a.hi.y - a.lo.y);
        listEntry(a.name, text);
        ImGui::PopID();
    }
    if (state.scene.taskAreas.empty())
        ImGui::TextWrapped("No task areas yet: draw one in the viewport or add the grid (below).");
    if (!state.scene.taskAreas.empty() || !state.scene.calcPoints.empty()) {
        if (ImGui::Button("Compute surfaces", ImVec2(-1.f, 0.f))) {
            try {
                GridSpec how = measure.grid;
                applyLightChoice(state.scene, measure.light, how);  // as the command line does
                measure.surfaces = computeSurfaces(state.scene, how);
                measure.surfacesError.clear();
            } catch (const std::exception& e) {
                measure.surfacesError = e.what();
            }
        }
        recordRect(state, "measure.compute_surfaces");
        itemTooltip(
            "Each task area with its immediate surrounding (0.5 m) and background (3 m) on the "
            "standard's grid (p = 0.2 x 5^log10(d)), and the calculation points, against their "
            "requirements");
        ImGui::Checkbox("False colour on the surfaces", &measure.colourSurfaces);
        recordRect(state, "measure.colour_surfaces");
        itemTooltip(
            "Fills each computed point's cell of the grid in the viewport with the colour of its "
            "value on the false-colour legend (its range: tick False colour above)");
        ImGui::Checkbox("Isolux lines on the surfaces", &measure.isolinesOnSurfaces);
        recordRect(state, "measure.isolines");
        itemTooltip(
            "Lines of equal illuminance over the computed surfaces in the viewport, each with its "
            "value, at the legend's isolux levels (its ticks unless levels are typed)");
        if (!measure.surfacesError.empty()) errorText(measure.surfacesError);
        if (measure.surfaces) {
            surfaceTable(*measure.surfaces);
            recordRect(state, "measure.surfaces_table");
            ImGui::PushTextWrapPos(0.f);
            ImGui::TextDisabled("%s", measure.surfaces->maintenance.c_str());
            ImGui::PopTextWrapPos();
        }
    }
    ImGui::TextDisabled("New task area");
    ImGui::InputText("Task name", &measure.taskName);
    ImGui::DragScalar("Required Em [lx]", ImGuiDataType_Double, &measure.taskRequired.em, 5.0f,
                      nullptr, nullptr, "%.0f");
    const double zero = 0.0, one = 1.0;
    ImGui::SliderScalar("Required U0", ImGuiDataType_Double, &measure.taskRequired.u0, &zero, &one,
                        "%.2f");
    measure.taskRequired.em = std::max(0.0, measure.taskRequired.em);
    std::string drawLabel = measure.drawingArea
                                ? "Drag across the viewport (click here to cancel)"
                                : "Draw a task area on " + planeText(measure.grid.plane) + " m";
    if (ImGui::Button(drawLabel.c_str(), ImVec2(-1.f, 0.f)))
        measure.drawingArea = !measure.drawingArea;
    recordRect(state, "measure.draw_task");
    itemTooltip(
        "Then drag a rectangle in the viewport: it is drawn on the grid's plane (set it below) "
        "and becomes a task area with this name and requirement, and the grid's extent "
        "(corners rounded to 1 cm; one undo step)");
    if (ImGui::Button("Add the grid as a task area", ImVec2(-1.f, 0.f))) addTaskAreaFromGrid(state);
    recordRect(state, "measure.add_task");
    itemTooltip(
        "The grid's plane and extent (below) become a task area of the scene (saved with it); "
        "its immediate surrounding (0.5 m) and background (3 m) are evaluated with it");
}

/// The scene's glare observers (add one at the camera, remove), and the UGR at each against its
/// limit (calculation/Glare.h), computed on demand with the background from the interreflected
/// light.
void glareControls(EditorState& state, MeasureState& measure) {
    ImGui::InputText("Observer name", &measure.observerName);
    ImGui::DragScalar("Limit UGR_L", ImGuiDataType_Double, &measure.observerLimit, 0.1f, nullptr,
                      nullptr, "%.0f");
    measure.observerLimit = std::clamp(measure.observerLimit, 0.0, 40.0);
    if (ImGui::Button("Add an observer at the camera", ImVec2(-1.f, 0.f)))
        addGlareObserverAtCamera(state);
    recordRect(state, "measure.add_observer");
    itemTooltip(
        "An eye where the camera is, looking where it looks (made horizontal): place the camera "
        "at a seat's eye height (1.2 m seated) and look along the task");
    for (size_t i = 0; i < state.scene.glareObservers.size(); ++i) {
        const GlareObserver& o = state.scene.glareObservers[i];
        ImGui::PushID(1000 + int(i));
        if (ImGui::SmallButton("x")) {
            removeGlareObserver(state, i);
            ImGui::PopID();
            break;
        }
        itemTooltip("Remove this observer");
        ImGui::SameLine();
        char text[96];
        std::snprintf(text, sizeof text, "eye at (%.2f, %.2f, %.2f) m", o.position.x, o.position.y,
                      o.position.z);
        listEntry(o.name, text);
        ImGui::PopID();
    }
    if (state.scene.glareObservers.empty()) return;
    if (ImGui::Button("Compute UGR", ImVec2(-1.f, 0.f))) {
        try {
            GridSpec how = measure.grid;
            applyLightChoice(state.scene, measure.light, how);  // as the command line does
            measure.glare = computeGlare(state.scene, how);
            measure.glareError.clear();
        } catch (const std::exception& e) {
            measure.glareError = e.what();
        }
    }
    recordRect(state, "measure.compute_glare");
    if (!measure.glareError.empty()) errorText(measure.glareError);
    if (!measure.glare) return;
    if (ImGui::BeginTable("glare", 4, kResultTable)) {
        ImGui::TableSetupColumn("Observer", ImGuiTableColumnFlags_WidthStretch);
        fixedColumn("Lb [cd/m2]", {"8888888"});
        fixedColumn("UGR", {"88.8", "<= 88"});
        fixedColumn("Result", {verdictText(Verdict::Fail)});
        ImGui::TableHeadersRow();
        char text[64];
        for (const GlareResult& g : measure.glare->observers) {
            int counted = 0;
            for (const GlareSource& s : g.sources) counted += s.excluded.empty();
            nameCell(g.observer.name, "",
                     std::to_string(counted) + " of " + std::to_string(g.sources.size()) +
                         " luminaires in view; background " +
                         (g.backgroundFromIndirect ? "from the interreflected light" : "given"));
            valueCell(compactNumber(g.background), "");
            std::snprintf(text, sizeof text, "%.1f", g.ugr);
            std::string limit;
            if (g.observer.limit > 0.0) limit = "<= " + compactNumber(g.observer.limit);
            valueCell(text, limit);
            verdictCell(g.observer.limit <= 0.0 ? Verdict::NoRequirement
                        : g.passes              ? Verdict::Pass
                                                : Verdict::Fail);
        }
        ImGui::EndTable();
        recordRect(state, "measure.glare_table");
    }
    ImGui::PushTextWrapPos(0.f);
    ImGui::TextDisabled("%s", measure.glare->maintenance.c_str());
    ImGui::PopTextWrapPos();
}

}  // namespace

bool measurePanel(EditorState& state, const Renderer& renderer, const PanelRect& rect) {
    RenderSettings& s = state.settings;
    MeasureState& measure = state.measure;
    bool changed = false;
    followTaskAreas(state);  // a scene opened, an area added or removed: the grid goes there
    placeNextWindow(rect);
    ImGui::Begin("Measure", nullptr, kPanelFlags);
    recordPanelRect(state, "measure");
    ImGui::PushItemWidth(-ImGui::GetFontSize() * 10.f);  // room for "Maintenance factor"
    int quantity = int(s.quantity);
    changed = ImGui::RadioButton("Radiance", &quantity, 0) || changed;
    ImGui::SameLine();
    changed = ImGui::RadioButton("Illuminance", &quantity, 1) || changed;
    s.quantity = Quantity(quantity);
    itemTooltip(
        "Illuminance: every surface becomes a white Lambertian receiver and each pixel "
        "shows the illuminance on it, lx (W/m2 in a scene of radiometric sources only)");
    bool falseColour = s.toneMap == ToneMapOperator::FalseColour;
    if (ImGui::Checkbox("False colour", &falseColour)) {
        setFalseColour(state, falseColour);
        changed = true;
    }
    if (state.interreflection.present) {
        // The image may show each part alone (false colour of the interreflected light, say).
        int parts = int(s.parts);
        ImGui::TextUnformatted("Light:");
        // The choices beside their label where they fit, else on the next line (never clipped).
        const ImGuiStyle& style = ImGui::GetStyle();
        float choices = 0.f;
        for (const char* label : {"total", "direct", "interreflected"})
            choices += ImGui::GetFrameHeight() + style.ItemInnerSpacing.x +
                       ImGui::CalcTextSize(label).x + style.ItemSpacing.x;
        ImGui::SameLine();
        if (ImGui::GetContentRegionAvail().x < choices) ImGui::NewLine();
        changed = ImGui::RadioButton("total", &parts, 0) || changed;
        ImGui::SameLine();
        changed = ImGui::RadioButton("direct", &parts, 1) || changed;
        ImGui::SameLine();
        changed = ImGui::RadioButton("interreflected", &parts, 2) || changed;
        s.parts = LightParts(parts);
    }
    if (falseColour) {
        if (measure.levelsText.empty() && !s.legend.levels.empty())
            measure.levelsText = levelsToText(s.legend.levels);
        changed = legendControls(state, measure, renderer) || changed;
    }
    ImGui::Separator();
    changed = maintenanceControl(state) || changed;
    lightChoiceControls(state, measure);
    // The task areas first: the panel opens on them, and the grid below starts on the first.
    if (ImGui::CollapsingHeader("Calculation surfaces (EN 12464-1)",
                                ImGuiTreeNodeFlags_DefaultOpen))
        surfaceControls(state, measure);
    if (ImGui::CollapsingHeader("Calculation grid", ImGuiTreeNodeFlags_DefaultOpen))
        gridControls(state, measure);
    if (ImGui::CollapsingHeader("Glare: UGR (CIE 117)", ImGuiTreeNodeFlags_DefaultOpen))
        glareControls(state, measure);
    ImGui::PopItemWidth();
    ImGui::End();
    drawMeasuredValues(state, renderer);
    return changed;
}

}  // namespace candela::ui
