// The Measure panel: what the image shows (radiance or illuminance), the false-colour legend
// (range in lux, log or linear, isolux levels) with its colour bar, and the calculation grid on a
// plane, whose summary it lists and whose values it writes over the viewport.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <sstream>

#include "renderer/ViewportMath.h"
#include "shaders/shared/FalseColour.h"
#include "ui/ImGuiUtil.h"
#include "ui/Panels.h"

namespace candela::ui {

namespace {

constexpr int kBarSegments = 96;  ///< Quads of the colour bar (the scale is piecewise linear).
constexpr size_t kMaxLabelledPoints = 900;  ///< More grid points than this: dots only, no values.

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
    itemTooltip("For stochastic techniques; exact ones ignore it");
    // What a light meter would read unless switched off, as on the command line.
    ImGui::Checkbox("Shadows", &measure.light.shadows);
    itemTooltip("Surfaces and luminaire bodies block light (where the scene has any)");
    ImGui::Checkbox("Interreflected light##grid", &measure.light.interreflection);
    recordRect(state, "measure.indirect");
    itemTooltip(
        "The light the surfaces reflect onto each other (where any surface reflects): the "
        "patches' solution, traced point by point where it is not accurate enough. Uncheck for "
        "direct light alone.");
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
    if (r.hasIndirect && ImGui::BeginTable("parts", 3, ImGuiTableFlags_RowBg)) {
        ImGui::TableSetupColumn("Light");
        ImGui::TableSetupColumn((std::string("Em [") + r.units.irradiance() + "]").c_str());
        ImGui::TableSetupColumn("U0");
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
            ImGui::Text("%.4g", p.eAvg);
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

/// The scene's task areas (add the grid as one, remove), and the surfaces' and points' results
/// against their requirements (calculation/CalculationSurfaces.h), computed on demand.
void surfaceControls(EditorState& state, MeasureState& measure) {
    ImGui::InputText("Task name", &measure.taskName);
    ImGui::DragScalar("Required Em [lx]", ImGuiDataType_Double, &measure.taskRequired.em, 5.0f,
                      nullptr, nullptr, "%.0f");
    const double zero = 0.0, one = 1.0;
    ImGui::SliderScalar("Required U0", ImGuiDataType_Double, &measure.taskRequired.u0, &zero, &one,
                        "%.2f");
    measure.taskRequired.em = std::max(0.0, measure.taskRequired.em);
    if (ImGui::Button("Add the grid as a task area", ImVec2(-1.f, 0.f))) addTaskAreaFromGrid(state);
    recordRect(state, "measure.add_task");
    std::string drawLabel = measure.drawingArea
                                ? "Drag across the viewport (click here to cancel)"
                                : "Draw a task area on " + planeText(measure.grid.plane);
    if (ImGui::Button(drawLabel.c_str(), ImVec2(-1.f, 0.f)))
        measure.drawingArea = !measure.drawingArea;
    recordRect(state, "measure.draw_task");
    itemTooltip(
        "Then drag a rectangle in the viewport: it is drawn on the grid's plane (set it above) "
        "and becomes a task area with this name and requirement, and the grid's extent "
        "(corners rounded to 1 cm; one undo step)");
    itemTooltip(
        "The grid's plane and extent become a task area of the scene (saved with it); its "
        "immediate surrounding (0.5 m) and background (3 m) are evaluated with it, on the "
        "standard's grid (p = 0.2 x 5^log10(d))");
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
        ImGui::Text("%s: %s, %.2f x %.2f m", a.name.c_str(), planeText(a.plane).c_str(),
                    a.hi.x - a.lo.x, a.hi.y - a.lo.y);
        ImGui::PopID();
    }
    if (state.scene.taskAreas.empty() && state.scene.calcPoints.empty()) return;
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
    ImGui::Checkbox("False colour on the surfaces", &measure.colourSurfaces);
    recordRect(state, "measure.colour_surfaces");
    itemTooltip(
        "Fills each computed point's cell of the grid in the viewport with the colour of its "
        "value on the false-colour legend (its range: tick False colour above)");
    if (!measure.surfacesError.empty()) errorText(measure.surfacesError);
    if (!measure.surfaces) return;
    const SurfaceReport& r = *measure.surfaces;
    const char* unit = r.units.irradiance();
    if (ImGui::BeginTable("surfaces", 5, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) {
        ImGui::TableSetupColumn("Surface");
        ImGui::TableSetupColumn((std::string("Em [") + unit + "]").c_str());
        ImGui::TableSetupColumn("U0");
        ImGui::TableSetupColumn("Required");
        ImGui::TableSetupColumn("");
        ImGui::TableHeadersRow();
        auto verdict = [](bool any, bool passes) {
            if (!any)
                ImGui::TextDisabled("-");
            else if (passes)
                ImGui::TextColored(ImVec4(0.4f, 0.9f, 0.4f, 1.f), "pass");
            else
                ImGui::TextColored(ImVec4(1.f, 0.4f, 0.4f, 1.f), "FAIL");
        };
        for (const SurfaceResult& s : r.surfaces) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(s.name.c_str());
            itemTooltip(s.role + (s.cylindrical ? " (cylindrical illuminance)" : "") + ", " +
                        std::to_string(s.points.size()) + " points; Emin " +
                        std::to_string(s.summary.eMin) + " " + unit + ", Emax " +
                        std::to_string(s.summary.eMax) + " " + unit);
            ImGui::TableNextColumn();
            ImGui::Text("%.4g", s.summary.eAvg);
            ImGui::TableNextColumn();
            ImGui::Text("%.2f", s.summary.u0);
            ImGui::TableNextColumn();
            if (s.required.any())
                ImGui::Text("%.0f / %.2f", s.required.em, s.required.u0);
            else
                ImGui::TextDisabled("-");
            ImGui::TableNextColumn();
            verdict(s.required.any(), s.passes);
        }
        for (const PointResult& p : r.points) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::Text("%s (%s)", p.point.name.c_str(), p.point.cylindrical ? "Ez" : "point");
            ImGui::TableNextColumn();
            ImGui::Text("%.4g", p.E);
            ImGui::TableNextColumn();
            ImGui::TextDisabled("-");
            ImGui::TableNextColumn();
            if (p.point.requiredLux > 0.0)
                ImGui::Text("%.0f", p.point.requiredLux);
            else
                ImGui::TextDisabled("-");
            ImGui::TableNextColumn();
            verdict(p.point.requiredLux > 0.0, p.passes);
        }
        ImGui::EndTable();
    }
    ImGui::TextDisabled("%s", r.maintenance.c_str());
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
        ImGui::Text("%s: eye (%.2f, %.2f, %.2f) m", o.name.c_str(), o.position.x, o.position.y,
                    o.position.z);
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
    if (ImGui::BeginTable("glare", 4, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) {
        ImGui::TableSetupColumn("Observer");
        ImGui::TableSetupColumn("Lb [cd/m2]");
        ImGui::TableSetupColumn("UGR");
        ImGui::TableSetupColumn("Limit");
        ImGui::TableHeadersRow();
        for (const GlareResult& g : measure.glare->observers) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(g.observer.name.c_str());
            int counted = 0;
            for (const GlareSource& s : g.sources) counted += s.excluded.empty();
            itemTooltip(std::to_string(counted) + " of " + std::to_string(g.sources.size()) +
                        " luminaires in view; background " +
                        (g.backgroundFromIndirect ? "from the interreflected light" : "given"));
            ImGui::TableNextColumn();
            ImGui::Text("%.3g", g.background);
            ImGui::TableNextColumn();
            ImGui::Text("%.1f", g.ugr);
            ImGui::TableNextColumn();
            if (g.observer.limit <= 0.0)
                ImGui::TextDisabled("-");
            else if (g.passes)
                ImGui::TextColored(ImVec4(0.4f, 0.9f, 0.4f, 1.f), "%.0f pass", g.observer.limit);
            else
                ImGui::TextColored(ImVec4(1.f, 0.4f, 0.4f, 1.f), "%.0f FAIL", g.observer.limit);
        }
        ImGui::EndTable();
    }
    ImGui::TextDisabled("%s", measure.glare->maintenance.c_str());
}

/// Dots with their illuminance at world points over the viewport image.
void drawValues(const EditorState& state, const Renderer& renderer,
                const std::vector<glm::dvec3>& points, const std::vector<double>& values) {
    const glm::vec4& v = state.layout.viewport;
    int width = renderer.settings().width, height = renderer.settings().height;
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    draw->PushClipRect(ImVec2(v.x, v.y), ImVec2(v.x + v.z, v.y + v.w), true);
    bool labels = values.size() <= kMaxLabelledPoints;
    char text[32];
    std::vector<ImVec4> drawn;  ///< Label boxes drawn so far: x0, y0, x1, y1 in window pixels.
    glm::mat4 viewProj = renderer.viewProj();
    for (size_t k = 0; k < points.size(); ++k) {
        auto px = projectToPixels(viewProj, points[k], width, height);
        if (!px) continue;
        ImVec2 at(v.x + float(px->x) * v.z / float(width),
                  v.y + float(px->y) * v.w / float(height));
        draw->AddCircleFilled(at, 2.f, IM_COL32(255, 255, 255, 230));
        if (!labels) continue;
        std::snprintf(text, sizeof text, "%.3g", values[k]);
        ImVec2 size = ImGui::CalcTextSize(text);
        ImVec2 lo(at.x - 0.5f * size.x - 1.f, at.y + 3.f);
        ImVec4 box(lo.x, lo.y, lo.x + size.x + 2.f, lo.y + size.y);
        // Far from the camera the labels crowd: keep the first of any that overlap.
        bool overlaps = std::any_of(drawn.begin(), drawn.end(), [&](const ImVec4& o) {
            return box.x < o.z && o.x < box.z && box.y < o.w && o.y < box.w;
        });
        if (overlaps) continue;
        drawn.push_back(box);
        draw->AddRectFilled(lo, ImVec2(lo.x + size.x + 2.f, lo.y + size.y), IM_COL32(0, 0, 0, 150));
        draw->AddText(ImVec2(lo.x + 1.f, lo.y), IM_COL32(255, 255, 255, 255), text);
    }
    draw->PopClipRect();
}

/// The rectangle [lo, hi] less [holeLo, holeHi]: up to four rectangles (left, right, then the
/// parts below and above the hole between them), as lo, hi pairs.
std::vector<std::pair<glm::dvec2, glm::dvec2>> minusHole(glm::dvec2 lo, glm::dvec2 hi,
                                                         glm::dvec2 holeLo, glm::dvec2 holeHi) {
    std::vector<std::pair<glm::dvec2, glm::dvec2>> out;
    bool overlaps = lo.x < holeHi.x && holeLo.x < hi.x && lo.y < holeHi.y && holeLo.y < hi.y;
    if (!overlaps) return {{lo, hi}};
    if (lo.x < holeLo.x) out.push_back({lo, {holeLo.x, hi.y}});
    if (hi.x > holeHi.x) out.push_back({{holeHi.x, lo.y}, hi});
    double x0 = std::max(lo.x, holeLo.x), x1 = std::min(hi.x, holeHi.x);
    if (lo.y < holeLo.y) out.push_back({{x0, lo.y}, {x1, holeLo.y}});
    if (hi.y > holeHi.y) out.push_back({{x0, holeHi.y}, {x1, hi.y}});
    return out;
}

/// Each computed surface point's grid cell (the rectangle of its spacing around it, on its plane,
/// less its surface's hole) filled with its value's colour on the false-colour legend, opaque,
/// under the values. Backgrounds first, task areas last, so inner surfaces show where cells meet.
void drawSurfaceColours(const EditorState& state, const SurfaceReport& report,
                        const Renderer& renderer) {
    const glm::vec4& v = state.layout.viewport;
    int width = renderer.settings().width, height = renderer.settings().height;
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    draw->PushClipRect(ImVec2(v.x, v.y), ImVec2(v.x + v.z, v.y + v.w), true);
    glm::mat4 viewProj = renderer.viewProj();
    FalseColourLegend legend = sanitizedLegend(state.settings.legend);
    auto byte = [](float x) { return int(std::lround(std::clamp(x, 0.f, 1.f) * 255.f)); };
    for (auto it = report.surfaces.rbegin(); it != report.surfaces.rend(); ++it) {
        const SurfaceResult& s = *it;
        for (size_t k = 0; k < s.points.size(); ++k) {
            glm::dvec2 c = s.points[k], h = 0.5 * s.spacing;
            glm::vec3 rgb = gpu::falseColour(gpu::legendPosition(
                float(s.E[k]), legend.min, legend.max, legend.logScale ? 1 : 0));
            ImU32 colour = IM_COL32(byte(rgb.x), byte(rgb.y), byte(rgb.z), 255);
            for (auto [lo, hi] : minusHole(c - h, c + h, s.holeLo, s.holeHi)) {
                glm::dvec2 corners[4] = {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
                ImVec2 quad[4];
                bool shown = true;
                for (int i = 0; i < 4 && shown; ++i) {
                    auto px = projectToPixels(viewProj, s.plane.point(corners[i].x, corners[i].y),
                                              width, height);
                    shown = px.has_value();
                    if (shown)
                        quad[i] = ImVec2(v.x + float(px->x) * v.z / float(width),
                                         v.y + float(px->y) * v.w / float(height));
                }
                if (shown) draw->AddQuadFilled(quad[0], quad[1], quad[2], quad[3], colour);
            }
        }
    }
    draw->PopClipRect();
}

/// The grid's points, and the computed surfaces' points, with their values in the viewport.
void drawMeasuredValues(const EditorState& state, const MeasureState& measure,
                        const Renderer& renderer) {
    if (measure.colourSurfaces && measure.surfaces)
        drawSurfaceColours(state, *measure.surfaces, renderer);
    if (!measure.showValues) return;
    std::vector<glm::dvec3> points;
    std::vector<double> values;
    if (measure.result) {
        const GridResult& r = *measure.result;
        for (size_t j = 0; j < r.v.size(); ++j)
            for (size_t i = 0; i < r.u.size(); ++i) {
                points.push_back(r.spec.plane.point(r.u[i], r.v[j]));
                values.push_back(r.E[j * r.u.size() + i]);
            }
    }
    if (measure.surfaces)
        for (const SurfaceResult& s : measure.surfaces->surfaces)
            for (size_t k = 0; k < s.points.size(); ++k) {
                points.push_back(s.plane.point(s.points[k].x, s.points[k].y));
                values.push_back(s.E[k]);
            }
    if (!points.empty()) drawValues(state, renderer, points, values);
}

}  // namespace

bool measurePanel(EditorState& state, const Renderer& renderer, const PanelRect& rect) {
    RenderSettings& s = state.settings;
    MeasureState& measure = state.measure;
    bool changed = false;
    placeNextWindow(rect);
    ImGui::Begin("Measure", nullptr, kPanelFlags);
    recordPanelRect(state, "measure");
    ImGui::PushItemWidth(-ImGui::GetFontSize() * 8.5f);
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
        ImGui::SameLine();
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
    ImGui::TextDisabled("Calculation grid");
    gridControls(state, measure);
    ImGui::Separator();
    ImGui::TextDisabled("Calculation surfaces (EN 12464-1)");
    surfaceControls(state, measure);
    ImGui::Separator();
    ImGui::TextDisabled("Glare: UGR (CIE 117)");
    glareControls(state, measure);
    ImGui::PopItemWidth();
    ImGui::End();
    drawMeasuredValues(state, measure, renderer);
    return changed;
}

}  // namespace candela::ui
