// The photometric part of the inspector: what the file holds, the flux two ways (the table's
// exact quadrature and lamp flux x light output ratio), the emitting opening, what was assumed to
// read the file (its warnings), and the polar candela diagram (report/PolarDiagram.cpp).
#include <imgui.h>

#include <algorithm>
#include <filesystem>

#include "calculation/Plausibility.h"
#include "formats/Gldf.h"
#include "luminaires/photometric/PhotometricLuminaire.h"
#include "report/PolarDiagram.h"
#include "ui/Panels.h"
#include "util/TextEncoding.h"

namespace candela::ui {

namespace {

/// What the parser assumed to read the file (Photometry.h, "Leniency"), one line each, folded
/// under a highlighted line that counts them.
void photometryWarnings(const PhotometricData& d) {
    if (d.warnings.empty()) return;
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.75f, 0.3f, 1.0f));
    bool open = ImGui::TreeNode("photometry-warnings", "%zu warning%s reading the file",
                                d.warnings.size(), d.warnings.size() == 1 ? "" : "s");
    ImGui::PopStyleColor();
    if (!open) return;
    for (const std::string& w : d.warnings) ImGui::TextWrapped("%s", w.c_str());
    ImGui::TreePop();
}

/// A GLDF variant's product data: manufacturer, product, variant and its emitter's ratings.
void gldfDetails(const GldfProduct& product, const std::string& variantId) {
    const GldfVariant* variant = product.variant(variantId);
    ImGui::TextWrapped(
        "GLDF: %s %s, variant %s", product.manufacturer.c_str(), product.productName.c_str(),
        variant && !variant->name.empty() ? variant->name.c_str() : variantId.c_str());
    const GldfEmitter* emitter =
        variant && !variant->emitters.empty() ? product.emitter(variant->emitters[0]) : nullptr;
    if (!emitter || emitter->lights.empty()) return;
    const GldfLightEmitter& light = emitter->lights[0];
    if (light.ratedFlux >= 0.0) ImGui::TextWrapped("Rated flux: %.5g lm", light.ratedFlux);
    if (light.ratedPower > 0.0)
        ImGui::TextWrapped("Rated power: %.4g W%s", light.ratedPower,
                           light.ratedFlux >= 0.0 ? "" : " (no rated flux)");
    if (light.ratedFlux >= 0.0 && light.ratedPower > 0.0)
        ImGui::TextWrapped("Rated efficacy: %.4g lm/W", light.ratedFlux / light.ratedPower);
    for (const GldfMaintenance& m : light.maintenance)
        ImGui::TextWrapped("%s: %.3g", m.what.c_str(), m.factor);
}

/// Where the file's own figures disagree (calculation/Plausibility.h), highlighted, one line each.
/// Computed once per photometry shown (its UGR table takes milliseconds, too long for a frame).
void plausibility(const PhotometricLuminaire& light) {
    // Held, not only compared, so that a freed photometry's address cannot come back as another.
    static std::shared_ptr<const PhotometricData> shownData;
    static std::shared_ptr<const GldfProduct> shownProduct;
    static const GldfLightEmitter* shownEmitter = nullptr;
    static std::vector<std::string> notes;
    const GldfLightEmitter* emitter = light.gldf ? light.gldfLightEmitter() : nullptr;
    if (light.data != shownData || light.gldf != shownProduct || emitter != shownEmitter) {
        notes = plausibilityNotes(light);
        shownData = light.data;
        shownProduct = light.gldf;
        shownEmitter = emitter;
    }
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.75f, 0.3f, 1.0f));
    for (const std::string& n : notes) ImGui::TextWrapped("%s", n.c_str());
    ImGui::PopStyleColor();
}

}  // namespace

void photometricDetails(const PhotometricLuminaire& light) {
    const PhotometricData& d = *light.data;
    ImGui::TextWrapped("%s: %s, type %s",
                       toValidUtf8(std::filesystem::path(light.file).filename().string()).c_str(),
                       d.format.c_str(), d.goniometer == Goniometer::B ? "B" : "C");
    if (!d.name.empty()) ImGui::TextWrapped("%s", d.name.c_str());
    if (light.gldf) gldfDetails(*light.gldf, light.gldfVariant);
    double flux = light.scale * d.fluxFromTable();
    ImGui::TextWrapped("Flux: %.5g lm (exact quadrature of the table%s)", flux,
                       light.scale != 1.0 ? ", scaled" : "");
    if (double declared = d.declaredFlux(); declared > 0.0)
        ImGui::TextWrapped("Lamps %.5g lm x LOR %.3g = %.5g lm (table / declared %.3f)", d.lampFlux,
                           d.lightOutputRatio, declared, d.fluxFromTable() / declared);
    else if (d.lampFlux > 0.0)
        ImGui::TextWrapped("Lamps %.5g lm, LOR 0: no declared luminaire flux", d.lampFlux);
    else
        ImGui::TextDisabled("Absolute photometry (no lamp flux declared)");
    ImGui::TextWrapped("Peak %.5g cd; %zu x %zu angles", light.scale * d.maxIntensity(),
                       d.vertical.size(), d.horizontal.size());
    const auto& poly = light.polygon();
    if (poly.empty())
        ImGui::TextWrapped(
            "Opening: a point (the file gives no size): every technique is the point law");
    else
        ImGui::TextWrapped("Opening: %.3g m (C0-C180) x %.3g m (C90-C270), %s of %.4g m2%s",
                           d.opening.length, d.opening.width,
                           poly.size() == 2 ? "a segment" : "a polygon", light.area(),
                           light.openingOverride.x > 0.0 ? " (overridden in the scene)" : "");
    plausibility(light);
    photometryWarnings(d);
    float side = std::min(ImGui::GetContentRegionAvail().x, 260.f);
    drawPolarDiagram(d, side);
}

}  // namespace candela::ui
