// The light-field part of the inspector: the basis grid on U with each image's energy, one image
// C_m drawn as a grid of cells, and the flux. Drawn with ImGui's draw lists: the UI owns no GL
// objects.
#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "luminaires/lightfield/LightField.h"
#include "ui/ImGuiUtil.h"
#include "ui/Panels.h"

namespace candela::ui {

namespace {

ImU32 grey(double v) {
    int g = std::clamp(int(std::lround(255.0 * v)), 0, 255);
    return IM_COL32(g, g, g, 255);
}

}  // namespace

void lightFieldDetails(const LightFieldLuminaire& light, int& shownImage) {
    const LightFieldData& lf = *light.data;
    bool photometric = lf.unit == "cd/m2";
    glm::dvec3 flux = lf.cachedPower();
    double total = 0.2126 * flux.x + 0.7152 * flux.y + 0.0722 * flux.z;
    ImGui::TextWrapped("Flux: %.4g %s (from the model, by quadrature)", total,
                       photometric ? "lm" : "W");
    ImGui::TextWrapped("Basis %d x %d, spacing %.2f x %.2f mm, delta %.2f mm", lf.count.x,
                       lf.count.y, 1e3 * lf.spacing.x, 1e3 * lf.spacing.y, 1e3 * lf.delta);
    ImGui::TextWrapped("Images %d x %d px over %.1f x %.1f mm; precomputed in %.1f ms", lf.width,
                       lf.height, 1e3 * (lf.imageMax.x - lf.imageMin.x),
                       1e3 * (lf.imageMax.y - lf.imageMin.y), lf.precomputeMs);

    // Basis grid: one disc per node, its brightness the image's share of the energy; the image
    // shown below is outlined.
    double most = 0.0;
    for (const auto& t : lf.tables) most = std::max(most, t.total);
    float side = std::min(ImGui::GetContentRegionAvail().x, 220.f);
    ImVec2 origin = ImGui::GetCursorScreenPos();
    ImDrawList* draw = ImGui::GetWindowDrawList();
    float cell = side / float(std::max(lf.count.x, lf.count.y));
    draw->AddRectFilled(origin, ImVec2(origin.x + cell * lf.count.x, origin.y + cell * lf.count.y),
                        IM_COL32(20, 20, 24, 255));
    for (int m = 0; m < lf.imageCount(); ++m) {
        int i = m % lf.count.x, j = m / lf.count.x;
        // Row 0 of the grid (smallest y) at the bottom, as seen from the front of the luminaire.
        ImVec2 c(origin.x + (float(i) + 0.5f) * cell,
                 origin.y + (float(lf.count.y - 1 - j) + 0.5f) * cell);
        double share = most > 0.0 ? lf.tables[size_t(m)].total / most : 0.0;
        draw->AddCircleFilled(c, 0.4f * cell, grey(std::sqrt(share)));
        if (m == shownImage) draw->AddCircle(c, 0.45f * cell, IM_COL32(255, 170, 0, 255), 0, 2.f);
    }
    ImGui::InvisibleButton("##basisgrid", ImVec2(cell * lf.count.x, cell * lf.count.y));
    if (ImGui::IsItemClicked()) {
        ImVec2 mouse = ImGui::GetIO().MousePos;
        int i = std::clamp(int((mouse.x - origin.x) / cell), 0, lf.count.x - 1);
        int j = lf.count.y - 1 - std::clamp(int((mouse.y - origin.y) / cell), 0, lf.count.y - 1);
        shownImage = j * lf.count.x + i;
    }
    itemTooltip(
        "Basis functions on U (brightness: energy of their image C_m). Click one to show its "
        "image.");

    shownImage = std::clamp(shownImage, 0, lf.imageCount() - 1);
    ImGui::SliderInt("Image", &shownImage, 0, lf.imageCount() - 1);
    const LightFieldImage& img = lf.images[size_t(shownImage)];
    // The image at up to 64 x 64 cells (the mean of the pixels each covers), normalised to its
    // peak.
    int cw = std::min(lf.width, 64), ch = std::min(lf.height, 64);
    std::vector<double> cells(size_t(cw * ch), 0.0);
    for (int y = 0; y < lf.height; ++y)
        for (int x = 0; x < lf.width; ++x)
            cells[size_t((y * ch / lf.height) * cw + x * cw / lf.width)] +=
                img.luminance[size_t(y * lf.width + x)];
    double peak = *std::max_element(cells.begin(), cells.end());
    ImVec2 o2 = ImGui::GetCursorScreenPos();
    float px = side / float(std::max(cw, ch));
    for (int y = 0; y < ch; ++y)
        for (int x = 0; x < cw; ++x) {
            ImVec2 a(o2.x + float(x) * px, o2.y + float(ch - 1 - y) * px);
            draw->AddRectFilled(
                a, ImVec2(a.x + px, a.y + px),
                grey(peak > 0.0 ? std::sqrt(cells[size_t(y * cw + x)] / peak) : 0.0));
        }
    ImGui::Dummy(ImVec2(px * float(cw), px * float(ch)));
    ImGui::TextDisabled("C_%d: %.4g %s m2 in all (square-root scale)", shownImage,
                        lf.tables[size_t(shownImage)].total, photometric ? "cd" : "W/sr");
}

}  // namespace candela::ui
