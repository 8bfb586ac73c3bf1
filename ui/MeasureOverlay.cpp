// What the Measure panel draws over the viewport image: the computed surfaces' cells in false
// colour, their isolux lines with their values (calculation/Isolines.h), and the grid's and the
// surfaces' points with their illuminance.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "calculation/Isolines.h"
#include "renderer/ViewportMath.h"
#include "shaders/shared/FalseColour.h"
#include "ui/Panels.h"

namespace candela::ui {

namespace {

constexpr size_t kMaxLabelledPoints = 900;  ///< More grid points than this: dots only, no values.

/// Window pixels of world points through the shown view, clipped to the viewport panel.
class ViewportProjection {
  public:
    ViewportProjection(const EditorState& state, const Renderer& renderer)
        : mViewport(state.layout.viewport),
          mWidth(renderer.settings().width),
          mHeight(renderer.settings().height),
          mViewProj(renderer.viewProj()) {}
    /// Where the world point (m) shows, window pixels; none behind the camera.
    std::optional<ImVec2> operator()(const glm::dvec3& world) const {
        auto px = projectToPixels(mViewProj, world, mWidth, mHeight);
        if (!px) return std::nullopt;
        return ImVec2(mViewport.x + float(px->x) * mViewport.z / float(mWidth),
                      mViewport.y + float(px->y) * mViewport.w / float(mHeight));
    }
    void clip(ImDrawList* draw) const {
        draw->PushClipRect(ImVec2(mViewport.x, mViewport.y),
                           ImVec2(mViewport.x + mViewport.z, mViewport.y + mViewport.w), true);
    }

  private:
    glm::vec4 mViewport;
    int mWidth, mHeight;
    glm::mat4 mViewProj;
};

/// Label boxes drawn so far (x0, y0, x1, y1, window pixels): later labels keep out of them.
using LabelBoxes = std::vector<ImVec4>;

/// Writes text on a dark patch centred at x with its top at y, unless it would overlap a label
/// already drawn; true when drawn.
bool placeLabel(ImDrawList* draw, LabelBoxes& drawn, ImVec2 at, const char* text) {
    ImVec2 size = ImGui::CalcTextSize(text);
    ImVec4 box(at.x - 0.5f * size.x - 1.f, at.y, at.x + 0.5f * size.x + 1.f, at.y + size.y);
    bool overlaps = std::any_of(drawn.begin(), drawn.end(), [&](const ImVec4& o) {
        return box.x < o.z && o.x < box.z && box.y < o.w && o.y < box.w;
    });
    if (overlaps) return false;
    drawn.push_back(box);
    draw->AddRectFilled(ImVec2(box.x, box.y), ImVec2(box.z, box.w), IM_COL32(0, 0, 0, 150));
    draw->AddText(ImVec2(box.x + 1.f, box.y), IM_COL32(255, 255, 255, 255), text);
    return true;
}

/// Dots with their illuminance at world points over the viewport image.
void drawValues(const EditorState& state, const Renderer& renderer,
                const std::vector<glm::dvec3>& points, const std::vector<double>& values,
                LabelBoxes& drawn) {
    ViewportProjection project(state, renderer);
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    project.clip(draw);
    bool labels = values.size() <= kMaxLabelledPoints;
    char text[32];
    for (size_t k = 0; k < points.size(); ++k) {
        std::optional<ImVec2> at = project(points[k]);
        if (!at) continue;
        draw->AddCircleFilled(*at, 2.f, IM_COL32(255, 255, 255, 230));
        if (!labels) continue;
        std::snprintf(text, sizeof text, "%.3g", values[k]);
        // Far from the camera the labels crowd: keep the first of any that overlap.
        placeLabel(draw, drawn, ImVec2(at->x, at->y + 3.f), text);
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
    ViewportProjection project(state, renderer);
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    project.clip(draw);
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
                    std::optional<ImVec2> at = project(s.plane.point(corners[i].x, corners[i].y));
                    shown = at.has_value();
                    if (shown) quad[i] = *at;
                }
                if (shown) draw->AddQuadFilled(quad[0], quad[1], quad[2], quad[3], colour);
            }
        }
    }
    draw->PopClipRect();
}

/// The computed surfaces' isolux lines at the legend's levels (its isolux levels, or its ticks),
/// a dark line on a light edge so it reads on false colour and on the image alike, each with its
/// value written at its middle where no other label is. Task areas first: their labels win.
void drawSurfaceIsolines(EditorState& state, const SurfaceReport& report, const Renderer& renderer,
                         LabelBoxes& drawn) {
    ViewportProjection project(state, renderer);
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    project.clip(draw);
    FalseColourLegend legend = state.settings.legend;
    legend.contours = true;  // the surfaces' own checkbox says whether to draw them
    std::vector<double> levels;
    for (float level : contourLevels(legend)) levels.push_back(double(level));
    const char* unit = report.units.irradiance();
    char text[48];
    for (const SurfaceResult& s : report.surfaces) {
        for (const Isoline& line : isolines(surfaceNodes(s), levels)) {
            std::vector<std::optional<ImVec2>> at;
            for (const glm::dvec2& q : line.points) at.push_back(project(s.plane.point(q.x, q.y)));
            size_t n = at.size(), pieces = line.closed ? n : n - 1;
            for (float width : {3.f, 1.5f}) {
                ImU32 colour = width > 2.f ? IM_COL32(255, 255, 255, 140) : IM_COL32(0, 0, 0, 255);
                for (size_t k = 0; k < pieces; ++k)
                    if (at[k] && at[(k + 1) % n])
                        draw->AddLine(*at[k], *at[(k + 1) % n], colour, width);
            }
            // The value at the point halfway along the line (on screen).
            std::vector<float> along(n, 0.f);
            for (size_t k = 1; k < n; ++k) {
                float step = 0.f;
                if (at[k] && at[k - 1])
                    step = std::hypot(at[k]->x - at[k - 1]->x, at[k]->y - at[k - 1]->y);
                along[k] = along[k - 1] + step;
            }
            size_t middle = size_t(
                std::lower_bound(along.begin(), along.end(), 0.5f * along.back()) - along.begin());
            bool labelled = false;
            if (middle < n && at[middle]) {
                std::snprintf(text, sizeof text, "%g %s", line.level, unit);
                ImVec2 size = ImGui::CalcTextSize(text);
                labelled = placeLabel(draw, drawn,
                                      ImVec2(at[middle]->x, at[middle]->y - 0.5f * size.y), text);
            }
            state.measure.drawnIsolines.push_back({s.name, line.level, line.points[0], labelled});
        }
    }
    draw->PopClipRect();
}

}  // namespace

void drawMeasuredValues(EditorState& state, const Renderer& renderer) {
    const MeasureState& measure = state.measure;
    if (measure.colourSurfaces && measure.surfaces)
        drawSurfaceColours(state, *measure.surfaces, renderer);
    LabelBoxes drawn;
    if (measure.isolinesOnSurfaces && measure.surfaces)
        drawSurfaceIsolines(state, *measure.surfaces, renderer, drawn);
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
    if (!points.empty()) drawValues(state, renderer, points, values, drawn);
}

}  // namespace candela::ui
