#include "report/PolarDiagram.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "formats/Photometry.h"
#include "shaders/shared/Constants.h"

namespace candela {

namespace {

constexpr ImU32 kColourC0 = IM_COL32(255, 150, 40, 255);   ///< C0-C180 curve.
constexpr ImU32 kColourC90 = IM_COL32(90, 170, 255, 255);  ///< C90-C270 curve.
constexpr ImU32 kGridColour = IM_COL32(255, 255, 255, 50);
constexpr ImU32 kLabelColour = IM_COL32(220, 220, 220, 200);

double intensityAt(const PhotometricData& data, double cDeg, double gammaDeg) {
    double c = cDeg * gpu::kPi / 180.0, g = gammaDeg * gpu::kPi / 180.0;
    return data.intensity({std::cos(c) * std::sin(g), std::sin(c) * std::sin(g), std::cos(g)});
}

/// Screen point of intensity `cd` at angle gamma on the right (side = 1) or left (-1) half.
ImVec2 polarPoint(ImVec2 centre, float pixelsPerCd, double cd, double gammaDeg, float side) {
    double g = gammaDeg * gpu::kPi / 180.0;
    float r = float(cd) * pixelsPerCd;
    return ImVec2(centre.x + side * r * float(std::sin(g)), centre.y + r * float(std::cos(g)));
}

/// One curve through both halves: `left` from gamma 180 down to 0, then `right` from 0 to 180.
void drawCurve(ImDrawList* draw, const PolarCurves& c, const std::vector<double>& left,
               const std::vector<double>& right, ImVec2 centre, float scale, ImU32 colour) {
    std::vector<ImVec2> points;
    for (size_t k = c.gamma.size(); k-- > 0;)
        points.push_back(polarPoint(centre, scale, left[k], c.gamma[k], -1.f));
    for (size_t k = 0; k < c.gamma.size(); ++k)
        points.push_back(polarPoint(centre, scale, right[k], c.gamma[k], 1.f));
    draw->AddPolyline(points.data(), int(points.size()), colour, ImDrawFlags_None, 2.f);
}

}  // namespace

PolarCurves polarCurves(const PhotometricData& data, const std::vector<double>& gammaDeg) {
    PolarCurves c;
    for (double g : gammaDeg) {
        c.gamma.push_back(g);
        c.c0.push_back(intensityAt(data, 0.0, g));
        c.c180.push_back(intensityAt(data, 180.0, g));
        c.c90.push_back(intensityAt(data, 90.0, g));
        c.c270.push_back(intensityAt(data, 270.0, g));
        c.peak = std::max({c.peak, c.c0.back(), c.c180.back(), c.c90.back(), c.c270.back()});
    }
    return c;
}

PolarCurves polarCurves(const PhotometricData& data, double stepDeg) {
    std::vector<double> gamma;
    int n = std::max(1, int(std::ceil(180.0 / std::max(stepDeg, 1e-3) - 1e-9)));
    for (int k = 0; k <= n; ++k) gamma.push_back(std::min(180.0, k * stepDeg));
    return polarCurves(data, gamma);
}

std::vector<double> polarRings(double peak) {
    if (!(peak > 0.0) || !std::isfinite(peak)) return {1.0};
    // The smallest 1-2-5 step that covers the peak in at most five rings.
    double decade = std::pow(10.0, std::floor(std::log10(peak / 5.0)));
    double step = decade;
    for (double m : {1.0, 2.0, 5.0, 10.0}) {
        step = m * decade;
        if (step * 5.0 >= peak * (1.0 - 1e-12)) break;
    }
    std::vector<double> rings;
    for (int k = 1; rings.empty() || rings.back() < peak * (1.0 - 1e-12); ++k)
        rings.push_back(k * step);
    return rings;
}

void drawPolarDiagram(const PhotometricData& data, float sizePx) {
    sizePx = std::max(sizePx, 120.f);
    PolarCurves curves = polarCurves(data, 1.0);
    std::vector<double> rings = polarRings(curves.peak);
    ImDrawList* draw = ImGui::GetWindowDrawList();
    ImVec2 origin = ImGui::GetCursorScreenPos();
    float lineHeight = ImGui::GetTextLineHeight();
    float margin = lineHeight * 1.6f;  // room for the angle labels
    float radius = 0.5f * sizePx - margin;
    ImVec2 centre(origin.x + 0.5f * sizePx, origin.y + 0.5f * sizePx);
    float scale = radius / float(rings.back());

    // Rings with their value on the upward spoke, spokes every 30 degrees with the angle.
    char label[64];
    for (double r : rings) {
        draw->AddCircle(centre, float(r) * scale, kGridColour, 64, 1.f);
        std::snprintf(label, sizeof label, "%g cd", r);
        draw->AddText(ImVec2(centre.x + 3.f, centre.y - float(r) * scale), kLabelColour, label);
    }
    for (int deg = 0; deg <= 180; deg += 30)
        for (float side : {-1.f, 1.f}) {
            if ((deg == 0 || deg == 180) && side < 0.f) continue;
            ImVec2 end = polarPoint(centre, scale, rings.back(), deg, side);
            draw->AddLine(centre, end, kGridColour, 1.f);
            std::snprintf(label, sizeof label, "%d\xC2\xB0", deg);  // degree sign, UTF-8
            ImVec2 size = ImGui::CalcTextSize(label);
            ImVec2 at = polarPoint(centre, scale, rings.back() + margin * 0.5f / scale, deg, side);
            draw->AddText(ImVec2(at.x - 0.5f * size.x, at.y - 0.5f * size.y), kLabelColour, label);
        }
    drawCurve(draw, curves, curves.c180, curves.c0, centre, scale, kColourC0);
    drawCurve(draw, curves, curves.c270, curves.c90, centre, scale, kColourC90);
    draw->AddText(ImVec2(origin.x, origin.y), kLabelColour, "C180 | C0");
    ImVec2 right = ImGui::CalcTextSize("C270 | C90");
    draw->AddText(ImVec2(origin.x + sizePx - right.x, origin.y), kLabelColour, "C270 | C90");
    ImGui::Dummy(ImVec2(sizePx, sizePx));

    // Legend: a line sample of each curve, and the peak.
    auto legendEntry = [&](ImU32 colour, const char* text) {
        ImVec2 p = ImGui::GetCursorScreenPos();
        float y = p.y + 0.5f * lineHeight;
        draw->AddLine(ImVec2(p.x, y), ImVec2(p.x + 2.f * lineHeight, y), colour, 2.f);
        ImGui::Dummy(ImVec2(2.2f * lineHeight, lineHeight));
        ImGui::SameLine();
        ImGui::TextUnformatted(text);
    };
    legendEntry(kColourC0, "C0-C180");
    ImGui::SameLine();
    legendEntry(kColourC90, "C90-C270");
    ImGui::Text("Luminous intensity [cd]; peak %.4g cd, table max %.4g cd", curves.peak,
                data.maxIntensity());
}

}  // namespace candela
