// The Environment section of the Render panel: the map's source, intensity and rotation, the
// sky's sun (directly or by time of day, with playback), a sequence's frame and playback, the
// environment technique, and the sample chart of Lu et al. (2013), Fig. 1-2. Every edit makes a
// new map; the renderer sees it and rebuilds its tables (Algorithm 1) that frame.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "luminaires/environment/Environment.h"
#include "luminaires/environment/EnvironmentSampling.h"
#include "renderer/passes/EnvironmentPass.h"
#include "ui/ImGuiUtil.h"
#include "ui/Panels.h"
#include "util/Error.h"

namespace candela::ui {

namespace {

constexpr const char* kChartImage =
    "environment:sample-chart";  ///< Its key in EditorState::images.

std::string baseDir(const Scene& scene) {
    return scene.path.empty() ? std::string(".")
                              : std::filesystem::path(scene.path).parent_path().string();
}

/// Replaces the scene's environment by `env` (a scene-file "environment" object). Files and
/// sequences keep their loaded texels; only the sky is made anew. Errors go to the status bar
/// and leave the scene as it was.
void setEnvironment(EditorState& state, const char* label, nlohmann::json env) {
    try {
        std::shared_ptr<const EnvironmentMap> map;
        std::shared_ptr<EnvironmentSequence> sequence;
        double intensity = env.value("intensity", 1.0), rotation = env.value("rotation_deg", 0.0);
        if (env.contains("file") && state.scene.environmentMap) {
            map = state.scene.environmentMap->adjusted(intensity, rotation);
        } else if (env.contains("sequence") && state.scene.environmentSequence) {
            const EnvironmentSequence& old = *state.scene.environmentSequence;
            sequence = std::make_shared<EnvironmentSequence>(
                env["sequence"].get<std::string>(), old.files(), old.fps(), intensity, rotation);
            map = sequence->frameAt(state.environment.sequenceSeconds);
        } else {
            EnvironmentSource source = parseEnvironment(
                env,
                json::Where{state.scene.path.empty() ? "scene" : state.scene.path, "environment"},
                baseDir(state.scene));
            map = source.map;
            sequence = source.sequence;
        }
        applyEdit(state, label, kChangeEnvironment, [&](Scene& s) {
            s.environment = std::move(env);
            s.environmentMap = std::move(map);
            s.environmentSequence = std::move(sequence);
        });
    } catch (const std::exception& e) {
        setStatus(state, std::string("Environment: ") + e.what(), true);
    }
}

/// A slider over the number object[key] (fallback when absent), written back when moved.
bool jsonSlider(const char* label, nlohmann::json& object, const char* key, double fallback,
                double lo, double hi, const char* tooltip = nullptr) {
    double value = object.value(key, fallback);
    bool moved = ImGui::SliderScalar(label, ImGuiDataType_Double, &value, &lo, &hi, "%.1f");
    if (moved) object[key] = value;
    if (tooltip) itemTooltip(tooltip);
    return moved;
}

/// Puts the sun where the time-of-day controls say (at the horizon while it is below).
void applyTimeOfDay(EditorState& state) {
    const EnvironmentUi& ui = state.environment;
    SunPosition sun = sunPosition(ui.latitudeDeg, ui.dayOfYear, ui.solarHours);
    nlohmann::json env = state.scene.environment;
    env["sky"]["sun_elevation_deg"] = std::max(0.0, sun.elevationDeg);
    env["sky"]["sun_azimuth_deg"] = sun.azimuthDeg;
    setEnvironment(state, "Time of day", std::move(env));
}

bool skyControls(EditorState& state) {
    EnvironmentUi& ui = state.environment;
    nlohmann::json env = state.scene.environment;
    nlohmann::json& sky = env["sky"];
    bool changed = false;
    changed |= jsonSlider("Sun elevation [deg]", sky, "sun_elevation_deg", 30.0, 0.0, 90.0);
    changed |= jsonSlider("Sun azimuth [deg]", sky, "sun_azimuth_deg", 120.0, -180.0, 180.0,
                          "phi of the sun, from +X (east) towards +Z (south)");
    changed |= jsonSlider(
        "Turbidity", sky, "turbidity", 3.0, 1.7, 10.0,
        "Atmospheric turbidity (Preetham et al. 1999): 2 very clear, 3 clear, 6 hazy, 10 "
        "overcast-like haze");
    if (changed) setEnvironment(state, "Sun", env);

    ImGui::TextDisabled("Time of day (north = -Z, east = +X)");
    bool timeChanged = false;
    const double l0 = -66.0, l1 = 66.0, h0 = 0.0, h1 = 24.0;
    timeChanged = ImGui::SliderScalar("Latitude [deg]", ImGuiDataType_Double, &ui.latitudeDeg, &l0,
                                      &l1, "%.1f") ||
                  timeChanged;
    timeChanged = ImGui::SliderInt("Day of year", &ui.dayOfYear, 1, 365) || timeChanged;
    int hh = int(ui.solarHours), mm = int((ui.solarHours - hh) * 60.0);
    char clock[32];
    std::snprintf(clock, sizeof clock, "%02d:%02d", hh, mm);
    float sliderWidth = ImGui::CalcItemWidth();
    timeChanged = ImGui::SliderScalar("Solar time [h]", ImGuiDataType_Double, &ui.solarHours, &h0,
                                      &h1, clock) ||
                  timeChanged;
    recordRect(state, "environment.time", sliderWidth);
    itemTooltip(
        "Apparent solar time at the site; the sun's position follows (declination and hour angle)");
    if (ImGui::Button(ui.playing ? "Pause##sky" : "Play##sky")) ui.playing = !ui.playing;
    recordRect(state, "environment.play");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.6f);
    ImGui::SliderFloat("h/s", &ui.hoursPerSecond, 0.05f, 4.f, "%.2f h/s",
                       ImGuiSliderFlags_Logarithmic);
    itemTooltip(
        "Playback: hours of sun motion per second of wall time; the sky is made anew every frame");
    if (ui.playing) {
        ui.solarHours =
            std::fmod(ui.solarHours + ui.hoursPerSecond * ImGui::GetIO().DeltaTime, 24.0);
        timeChanged = true;
    }
    if (timeChanged) {
        applyTimeOfDay(state);
        changed = true;
    }
    SunPosition sun = sunPosition(ui.latitudeDeg, ui.dayOfYear, ui.solarHours);
    if (sun.elevationDeg < 0.0) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.f, 0.75f, 0.3f, 1.f));
        ImGui::TextWrapped("Sun %.1f deg below the horizon: shown at the horizon",
                           -sun.elevationDeg);
        ImGui::PopStyleColor();
    }
    return changed;
}

bool sequenceControls(EditorState& state) {
    EnvironmentUi& ui = state.environment;
    EnvironmentSequence& seq = *state.scene.environmentSequence;
    int count = int(seq.frameCount());
    int frame = int(seq.frameIndex(ui.sequenceSeconds));
    bool changed = false;
    ImGui::Text("%d frames at %.3g fps", count, seq.fps());
    if (ImGui::SliderInt("Frame", &frame, 0, std::max(0, count - 1))) {
        ui.sequenceSeconds = (frame + 0.5) / seq.fps();
        changed = true;
    }
    if (ImGui::Button(ui.playing ? "Pause##seq" : "Play##seq")) ui.playing = !ui.playing;
    ImGui::SameLine();
    ImGui::TextDisabled("%s", std::filesystem::path(seq.files()[size_t(frame)]).filename().c_str());
    if (ui.playing) {
        ui.sequenceSeconds += ImGui::GetIO().DeltaTime;
        changed = true;
    }
    if (changed) {
        try {
            auto map = seq.frameAt(ui.sequenceSeconds);
            if (map != state.scene.environmentMap)
                applyEdit(state, "Sequence frame", kChangeEnvironment,
                          [&](Scene& s) { s.environmentMap = map; });
        } catch (const std::exception& e) {
            ui.playing = false;
            setStatus(state, std::string("Environment sequence: ") + e.what(), true);
        }
    }
    return changed;
}

/// The sample chart for the chosen normal, remade when the map, normal or count changes.
void sampleChartControls(EditorState& state) {
    EnvironmentUi& ui = state.environment;
    if (ImGui::Checkbox("Pick a pixel", &ui.pickingPixel) && ui.pickingPixel)
        setStatus(state,
                  "Click the viewport: the chart shows the samples of the surface seen there",
                  false);
    recordRect(state, "environment.pick_pixel");
    itemTooltip(
        "The next click on the viewport picks the surface seen through that pixel; the chart "
        "then shows that pixel's normal");
    if (ui.pixelPicked) {
        ImGui::TextDisabled("pixel (%.0f, %.0f) at (%.2f, %.2f, %.2f) m",
                            std::floor(ui.pickedPixel.x), std::floor(ui.pickedPixel.y),
                            ui.pickedPoint.x, ui.pickedPoint.y, ui.pickedPoint.z);
    }
    if (ImGui::SliderFloat("Normal elevation [deg]", &ui.normalElevationDeg, -90.f, 90.f, "%.0f"))
        ui.pixelPicked = false;
    if (ImGui::SliderFloat("Normal azimuth [deg]", &ui.normalAzimuthDeg, -180.f, 180.f, "%.0f"))
        ui.pixelPicked = false;
    ImGui::SliderInt("Samples N_s", &ui.chartSpp, 4, 512, "%d", ImGuiSliderFlags_Logarithmic);
    bool balanced = state.settings.environmentTechnique != "uniform-faces";
    char key[160];
    std::snprintf(key, sizeof key, "%p %.4f %.4f %d %d",
                  static_cast<const void*>(state.scene.environmentMap.get()), ui.normalElevationDeg,
                  ui.normalAzimuthDeg, ui.chartSpp, int(balanced));
    if (!state.images) return;
    if (ui.chartKey != key || !state.images->find(kChartImage).id) {
        const EnvironmentMap& map = *state.scene.environmentMap;
        CubeMapDistribution cube(map, EnvironmentPass::defaultFaceSize(map));  // as the renderer's
        glm::dvec3 n = ui.chartNormal();
        SampleChart chart = sampleChart(map, cube, n, ui.chartSpp, balanced, 1, 64);
        state.images->upload(kChartImage, chart.width, chart.height, chart.rgb);
        ui.chartKey = key;
        int drawn = 0, effective = 0;
        for (int f = 0; f < 6; ++f)
            drawn += chart.drawn[size_t(f)], effective += chart.effective[size_t(f)];
        char text[512];
        const auto& m = chart.mu;
        std::snprintf(text, sizeof text,
                      "%s: %d selected, %d effective (%.0f %%)\nshare +X %.2f -X %.2f +Y %.2f -Y "
                      "%.2f +Z %.2f -Z %.2f",
                      balanced ? "balanced" : "uniform-faces", drawn, effective,
                      drawn ? 100.0 * effective / drawn : 0.0, m[0], m[1], m[2], m[3], m[4], m[5]);
        ui.chartCounts = text;
    }
    ImageTextures::Shown chartImage = state.images->find(kChartImage);
    float w = ImGui::GetContentRegionAvail().x;
    ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(chartImage.id)),
                 ImVec2(w, w * float(chartImage.height) / float(chartImage.width)));
    itemTooltip(
        "Unfolded cube seen from inside (+Y on top, -X -Z +X +Z across, -Y below). Green: samples "
        "the normal selects that face it (effective); red: selected behind it (wasted); white "
        "cross: the normal. Faces dimmed further get no samples.");
    ImGui::TextUnformatted(ui.chartCounts.c_str());
}

/// No environment yet: "Add a sky" at the time of day of the section. True when it added one.
bool addSkyControls(EditorState& state) {
    ImGui::TextDisabled("No environment.");
    if (ImGui::Button("Add a sky")) {
        SunPosition sun = sunPosition(state.environment.latitudeDeg, state.environment.dayOfYear,
                                      state.environment.solarHours);
        setEnvironment(state, "Add sky",
                       {{"sky",
                         {{"sun_elevation_deg", std::max(0.0, sun.elevationDeg)},
                          {"sun_azimuth_deg", sun.azimuthDeg}}}});
        return true;
    }
    itemTooltip(
        "A clear sky with a sun (Preetham / Perez luminance, cd/m2) at the time of day below");
    return false;
}

/// The environment's intensity (dimensionless) and rotation (degrees about +Y), as one edit.
bool intensityAndRotation(EditorState& state) {
    nlohmann::json env = state.scene.environment;
    double intensity = env.value("intensity", 1.0);
    bool edited = false;
    if (ImGui::DragScalar("Intensity", ImGuiDataType_Double, &intensity, 0.01f, nullptr, nullptr,
                          "%.3g")) {
        env["intensity"] = std::max(0.0, intensity);
        edited = true;
    }
    itemTooltip("Multiplies every texel (dimensionless)");
    edited |= jsonSlider("Rotation [deg]", env, "rotation_deg", 0.0, -180.0, 180.0,
                         "Turns the map about +Y (added to phi)");
    if (edited) setEnvironment(state, "Environment", env);
    return edited;
}

}  // namespace

bool environmentControls(EditorState& state) {
    state.environment.chartOpen = false;
    if (!ImGui::CollapsingHeader("Environment", ImGuiTreeNodeFlags_DefaultOpen)) return false;
    Scene& scene = state.scene;
    if (!scene.environmentMap) return addSkyControls(state);
    bool changed = false;
    const EnvironmentMap& map = *scene.environmentMap;
    const char* kind = scene.environment.contains("sky")        ? "Sky"
                       : scene.environment.contains("sequence") ? "Sequence"
                                                                : "File";
    ImGui::Text("%s, %dx%d lat-long", kind, map.width(), map.height());
    itemTooltip(map.source());

    // The environment technique.
    RenderSettings& s = state.settings;
    std::string current = s.environmentTechnique.empty() ? "balanced" : s.environmentTechnique;
    if (ImGui::BeginCombo("Technique##env", current.c_str())) {
        for (const TechniqueInfo& t : techniquesOf(LuminaireKind::Environment)) {
            if (t.shader.empty()) continue;  // the exact reference is CPU-only
            if (ImGui::Selectable(std::string(t.name).c_str(), t.name == current)) {
                s.environmentTechnique = std::string(t.name);
                changed = true;
            }
            itemTooltip(std::string(t.description));
        }
        ImGui::EndCombo();
    }

    changed = intensityAndRotation(state) || changed;

    if (scene.environment.contains("sky"))
        changed = skyControls(state) || changed;
    else if (scene.environmentSequence)
        changed = sequenceControls(state) || changed;

    bool chartNode = ImGui::TreeNode("Samples for a pixel (Fig. 1-2)");
    recordRect(state, "environment.chart");
    if (chartNode) {
        state.environment.chartOpen = true;
        if (state.scene.environmentMap) sampleChartControls(state);
        ImGui::TreePop();
    }
    if (ImGui::Button("Remove environment")) {
        state.environment.playing = false;
        applyEdit(state, "Remove environment", kChangeEnvironment, [](Scene& sc) {
            sc.environment = nullptr;
            sc.environmentMap.reset();
            sc.environmentSequence.reset();
        });
        changed = true;
    }
    return changed;
}

}  // namespace candela::ui
