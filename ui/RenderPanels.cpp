// The Render panel (screenshot, tone mapping, sampling, camera) and the frame statistics.
#include <imgui.h>

#include <algorithm>
#include <set>
#include <string>

#include "ui/ImGuiUtil.h"
#include "ui/Panels.h"

namespace candela::ui {

namespace {

bool toneMappingControls(EditorState& state) {
    bool changed = false;
    ImGui::TextDisabled("Tone mapping");
    // In ToneMapOperator order. Picking False colour does what the Measure panel's toggle does
    // (setFalseColour), so that toggle, turned off, restores the operator it replaced.
    const char* operators[] = {"Exponential", "Reinhard", "False colour"};
    static_assert(int(ToneMapOperator::FalseColour) == 2, "operators[] follows ToneMapOperator");
    int op = int(state.settings.toneMap);
    if (ImGui::Combo("Operator", &op, operators, IM_ARRAYSIZE(operators))) {
        if (ToneMapOperator(op) == ToneMapOperator::FalseColour)
            setFalseColour(state, true);
        else
            state.settings.toneMap = ToneMapOperator(op);
        changed = true;
    }
    itemTooltip(
        "Exponential: 1 - exp(-k L / Lavg) (Lu et al. 2015). Reinhard (2002): "
        "0.18 k L / Lavg mapped by x / (1 + x). Lavg is the frame's mean luminance. "
        "False colour: the Measure panel's scale and legend (lx in illuminance mode).");
    changed = ImGui::SliderFloat("Exposure k", &state.settings.exposure, 0.01f, 100.f, "%.3g",
                                 ImGuiSliderFlags_Logarithmic) ||
              changed;
    state.settings.exposure = std::clamp(state.settings.exposure, 1e-4f, 1e4f);
    return changed;
}

/// "Interreflection: ..." for the panels: what the worker does or what the image holds.
std::string interreflectionLine(const InterreflectionUi& ir) {
    char text[200];
    if (!ir.enabled) return "Interreflection: off";
    if (!ir.error.empty()) return "Interreflection failed: " + ir.error;
    if (ir.busy) {
        std::snprintf(text, sizeof text, "Interreflection: %s %.0f %%", ir.stage.c_str(),
                      100.0 * ir.progress);
        return text;
    }
    if (!ir.present) return "Interreflection: none (no surface reflects onto another)";
    std::snprintf(text, sizeof text, "Interreflection: %zu patches, %s (%.1f s)", ir.patches,
                  ir.converged ? "converged" : "refining", ir.lastSeconds);
    return text;
}

bool interreflectionControls(EditorState& state) {
    InterreflectionUi& ir = state.interreflection;
    bool changed = ImGui::Checkbox("Interreflected light", &ir.enabled);
    recordRect(state, "render.indirect");
    itemTooltip(
        "Diffuse light the surfaces reflect onto each other, all bounces (radiosity over patches, "
        "each "
        "luminaire through its own estimator; computed on the CPU in the background). Not "
        "modelled: "
        "specular interreflection, transmission.");
    ImGui::TextDisabled("%s", interreflectionLine(ir).c_str());
    return changed;
}

/// Samples per frame, the sample budget and the render resolution.
bool sampleBudgetControls(EditorState& state) {
    bool changed = false;
    RenderSettings& s = state.settings;
    changed = ImGui::SliderInt("Samples / frame", &s.samplesPerFrame, 1, 64) || changed;
    itemTooltip("Light samples per pixel per luminaire in each progressive frame");
    if (ImGui::InputInt("Max spp", &s.maxSamples, 16, 256)) {
        s.maxSamples = std::max(0, s.maxSamples);
        changed = true;
    }
    itemTooltip(
        "Stop refining at this many samples per pixel; 0 refines for ever (exact "
        "techniques without occlusion finish in one frame)");

    const float scales[] = {1.f, 0.5f, 0.25f};
    const char* scaleNames[] = {"100 %", "50 %", "25 %"};
    int current = 0;
    for (int i = 0; i < 3; ++i)
        if (state.renderScale == scales[i]) current = i;
    if (ImGui::Combo("Resolution", &current, scaleNames, 3)) {
        state.renderScale = scales[current];
        changed = true;
    }
    itemTooltip("Render pixels per viewport pixel (lower is faster on a slow GPU)");
    return changed;
}

/// Technique override: every luminaire whose kind has the named technique uses it.
bool techniqueOverrideControl(RenderSettings& s) {
    bool changed = false;
    std::set<std::string> names;
    for (const TechniqueInfo& t : techniques()) names.insert(std::string(t.name));
    const char* preview =
        s.techniqueOverride.empty() ? "(each luminaire's own)" : s.techniqueOverride.c_str();
    if (ImGui::BeginCombo("Technique", preview)) {
        if (ImGui::Selectable("(each luminaire's own)", s.techniqueOverride.empty())) {
            s.techniqueOverride.clear();
            changed = true;
        }
        for (const std::string& n : names)
            if (ImGui::Selectable(n.c_str(), n == s.techniqueOverride)) {
                s.techniqueOverride = n;
                changed = true;
            }
        ImGui::EndCombo();
    }
    itemTooltip("Renders every luminaire whose kind has this technique with it");
    return changed;
}

/// Shadow maps (renderer/passes/ShadowMapPass.h): what the light-field, photometric and
/// Havran techniques read when an occluder can block them.
bool shadowMapControls(ShadowMapSettings& maps) {
    bool changed = false;
    if (ImGui::InputInt("Shadow maps", &maps.count, 1, 16)) {
        maps.count = std::clamp(maps.count, 0, 4096);
        changed = true;
    }
    itemTooltip(
        "Per-cell shadow maps per light-field luminaire (Lu et al. 2015, Sec. 6.2); 0 = one per "
        "cell of U, (W + 2) x (H + 2) for W x H images. The *-raytraced techniques trace a "
        "shadow ray per sample instead, the exact visibility the maps approximate.");
    const int sizes[] = {64, 128, 192, 256, 512, 1024};
    const char* sizeNames[] = {"64^2", "128^2", "192^2", "256^2", "512^2", "1024^2"};
    int size = 2;
    for (int i = 0; i < 6; ++i)
        if (maps.resolution == sizes[i]) size = i;
    if (ImGui::Combo("Shadow-map faces", &size, sizeNames, 6)) {
        maps.resolution = sizes[size];
        changed = true;
    }
    itemTooltip(
        "Texels per cube-map face of each shadow map; the edges of shadows move by about "
        "a texel (the bias), so finer faces are closer to the ray-traced truth");
    return changed;
}

/// The fallback while dragging (renderer/LivePreview.h); settings of the editor only: they
/// change nothing of the image once the drag ends.
void livePreviewControls(EditorState& state) {
    LivePreviewUi& live = state.preview;
    ImGui::Checkbox("Live preview while dragging", &live.enabled);
    recordRect(state, "render.preview");
    itemTooltip(
        "While a luminaire or the camera is dragged: light fields as their far field, Prost's "
        "scattered sampling for photometric lights, one small shadow map each, one sample per "
        "pixel at a reduced resolution. Letting go refines the chosen techniques again.");
    if (!live.enabled) return;
    ImGui::Checkbox("Hold the frame rate", &live.adaptive);
    itemTooltip("Lower the preview's resolution until a frame takes the target time");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(90.f);
    ImGui::SliderFloat("##target", &live.targetMs, 20.f, 200.f, "%.0f ms");
    if (!live.adaptive) {
        ImGui::SliderFloat("Preview scale", &live.policy.scale, 0.1f, 1.f, "%.2f");
        itemTooltip("Preview pixels per render pixel, per axis");
    }
    if (live.width > 0)
        ImGui::TextDisabled("Last preview: %d x %d, %.0f ms per frame (%.1f fps)", live.width,
                            live.height, live.frameMs,
                            live.frameMs > 0.0 ? 1000.0 / live.frameMs : 0.0);
}

bool samplingControls(EditorState& state) {
    ImGui::TextDisabled("Sampling");
    bool changed = sampleBudgetControls(state);
    changed = techniqueOverrideControl(state.settings) || changed;
    changed = shadowMapControls(state.settings.shadowMaps) || changed;
    livePreviewControls(state);
    return changed;
}

bool cameraControls(EditorState& state) {
    ImGui::TextDisabled("Camera");
    itemTooltip(
        "In the viewport: left-drag on empty space orbits about the target, right- or "
        "middle-drag pans, the wheel zooms; left-drag on a luminaire moves it.");
    Camera camera = state.scene.camera;
    bool edited = false;
    edited = ImGui::DragScalarN("Position [m]", ImGuiDataType_Double, &camera.position[0], 3, 0.01f,
                                nullptr, nullptr, "%.2f") ||
             edited;
    edited = ImGui::DragScalarN("Target [m]", ImGuiDataType_Double, &camera.target[0], 3, 0.01f,
                                nullptr, nullptr, "%.2f") ||
             edited;
    const double minFov = 5.0, maxFov = 150.0;
    edited = ImGui::SliderScalar("Vertical FOV [deg]", ImGuiDataType_Double, &camera.fovDeg,
                                 &minFov, &maxFov, "%.1f") ||
             edited;
    if (edited && glm::length(camera.target - camera.position) > 1e-6) {
        applyEdit(state, "Camera", kChangeCamera, [&](Scene& s) { s.camera = camera; });
        return true;
    }
    return false;
}

}  // namespace

bool renderPanel(EditorState& state, const PanelRect& rect) {
    bool changed = false;
    placeNextWindow(rect);
    ImGui::Begin("Render", nullptr, kPanelFlags);
    recordPanelRect(state, "render");
    if (ImGui::Button("Screenshot", ImVec2(-1.f, ImGui::GetFrameHeight() * 1.5f))) {
        state.screenshotRequested = true;
        changed = true;
    }
    ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
    state.layout.screenshotButton = glm::vec2(0.5f * (lo.x + hi.x), 0.5f * (lo.y + hi.y));
    std::string folder = state.screenshotDir.string();
    itemTooltip("Writes shot-NNN.png (tone-mapped), shot-NNN.exr (linear) and shot-NNN.json into " +
                folder);
    ImGui::PushItemWidth(-ImGui::GetFontSize() * 10.5f);  // room for labels with units
    ImGui::Spacing();
    changed = toneMappingControls(state) || changed;
    ImGui::Spacing();
    changed = samplingControls(state) || changed;
    ImGui::Spacing();
    changed = interreflectionControls(state) || changed;
    ImGui::Spacing();
    changed = cameraControls(state) || changed;
    ImGui::Spacing();
    changed = environmentControls(state) || changed;
    ImGui::PopItemWidth();
    ImGui::End();
    return changed;
}

void statsPanel(const EditorState& state, const Renderer& renderer, const ShaderLibrary& shaders,
                const PanelRect& rect) {
    placeNextWindow(rect);
    ImGui::Begin("Frame statistics", nullptr, kPanelFlags);
    if (state.compare.layout != CompareLayout::Single) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.f, 0.8f, 0.3f, 1.f));
        ImGui::TextWrapped(
            "The single view waits while the viewport is split: each pane's samples, GPU time "
            "and errors are in the Compare panel and on the pane.");
        ImGui::PopStyleColor();
    }
    const FrameStats& stats = renderer.stats();
    const RenderSettings& settings = renderer.settings();
    ImGui::Text("Render size: %d x %d px", settings.width, settings.height);
    if (renderer.plan().progressive())
        ImGui::Text("Accumulated: %d frames, %d spp", stats.accumulatedFrames,
                    stats.samplesPerPixel);
    else
        ImGui::Text("Accumulated: %d frame(s), exact techniques", stats.accumulatedFrames);
    ImGui::TextUnformatted("Converged:");
    ImGui::SameLine();
    if (stats.converged)
        ImGui::TextColored(ImVec4(0.4f, 0.9f, 0.4f, 1.f), "yes (idle)");
    else
        ImGui::TextColored(ImVec4(1.f, 0.8f, 0.3f, 1.f), "no (refining)");

    const std::vector<PassTiming>& shown =
        stats.passes.empty() ? state.passes.lastFrame() : stats.passes;
    ImGui::Spacing();
    ImGui::TextDisabled(stats.passes.empty() ? "Last frame with passes (this one: none)"
                                             : "Passes this frame");
    if (ImGui::BeginTable("passes", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV)) {
        ImGui::TableSetupColumn("Pass");
        ImGui::TableSetupColumn("GPU [ms]", ImGuiTableColumnFlags_WidthFixed,
                                ImGui::GetFontSize() * 5.f);
        ImGui::TableHeadersRow();
        double total = 0.0;
        for (const PassTiming& p : shown) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(p.name.c_str());
            ImGui::TableNextColumn();
            ImGui::Text("%.3f", p.gpuMs);
            total += p.gpuMs;
        }
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextDisabled("total");
        ImGui::TableNextColumn();
        ImGui::TextDisabled("%.3f", total);
        ImGui::EndTable();
    }
    ImGui::Text("GPU time of this accumulation: %.1f ms", state.passes.totalGpuMs());
    // The CPU's share: the interreflection worker (nothing when off or when nothing changed).
    ImGui::TextUnformatted(interreflectionLine(state.interreflection).c_str());

    std::vector<std::string> variants = shaders.compiledVariants();
    ImGui::Spacing();
    std::string header =
        "Compiled shader variants (" + std::to_string(variants.size()) + ")###variants";
    if (ImGui::CollapsingHeader(header.c_str(), ImGuiTreeNodeFlags_DefaultOpen)) {
        for (const std::string& v : variants) {
            ImGui::Bullet();
            ImGui::TextWrapped("%s", v.c_str());
        }
    }
    if (!shaders.errorLog().empty()) {
        ImGui::Spacing();
        ImGui::TextColored(errorColour(), "Shader errors (last good program kept):");
        errorText(shaders.errorLog());
    }
    ImGui::End();
}

}  // namespace candela::ui
