// The viewport: the renderer's tone-mapped image, luminaire outlines, picking and dragging of
// luminaires in their horizontal plane, and camera orbit / pan / zoom around the target.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "renderer/ViewportMath.h"
#include "shaders/shared/Constants.h"
#include "ui/ImGuiUtil.h"
#include "ui/Panels.h"

namespace candela::ui {

namespace {

constexpr double kOrbitDegPerPixel = 0.3;   ///< Camera orbit per pixel of mouse motion, degrees.
constexpr double kMaxDragDistance = 200.0;  ///< Farthest a drag may place a luminaire, metres.

/// Maps between window pixels of the viewport image and render pixels.
struct ImageMapping {
    ImVec2 origin;  ///< Top-left of the image, window pixels.
    ImVec2 size;    ///< Image size, window pixels.
    int renderWidth = 1, renderHeight = 1;

    glm::dvec2 toRender(const ImVec2& p) const {
        return {(p.x - origin.x) * renderWidth / size.x, (p.y - origin.y) * renderHeight / size.y};
    }
    ImVec2 toWindow(const glm::dvec2& p) const {
        return ImVec2(origin.x + float(p.x) * size.x / float(renderWidth),
                      origin.y + float(p.y) * size.y / float(renderHeight));
    }
};

constexpr double kAimHandleM = 0.35;  ///< Length of the aim handle, metres.
constexpr double kSpinRingM = 0.22;   ///< Radius of the spin ring, metres.
constexpr float kGrabPx = 9.f;        ///< How close a press must be to a handle's knob, pixels.

/// Where the rotation gizmo's knobs of the selected luminaire are, in window pixels.
struct Gizmo {
    bool valid = false;
    ImVec2 centre, aimKnob, spinKnob;
    std::vector<ImVec2> ring;
};

Gizmo gizmo(const EditorState& state, const Renderer& renderer, const ImageMapping& map) {
    Gizmo g;
    int index = state.selectedLuminaire;
    if (index < 0 || index >= int(state.scene.luminaires.size())) return g;
    const Pose& pose = state.scene.luminaires[size_t(index)]->pose;
    glm::dvec3 x, y, z;
    pose.frame(x, y, z);
    glm::mat4 viewProj = renderer.viewProj();
    auto toWindow = [&](const glm::dvec3& p, ImVec2& out) {
        auto px = projectToPixels(viewProj, p, map.renderWidth, map.renderHeight);
        if (px) out = map.toWindow(*px);
        return px.has_value();
    };
    if (!toWindow(pose.position, g.centre) ||
        !toWindow(pose.position + kAimHandleM * z, g.aimKnob) ||
        !toWindow(pose.position + kSpinRingM * x, g.spinKnob))
        return g;
    for (int i = 0; i <= 48; ++i) {
        double a = 2.0 * gpu::kPi * i / 48;
        ImVec2 p;
        if (!toWindow(pose.position + kSpinRingM * (std::cos(a) * x + std::sin(a) * y), p))
            return g;
        g.ring.push_back(p);
    }
    g.valid = true;
    return g;
}

/// The rotation gizmo: an aim handle (drag its knob onto what the luminaire should light) and a
/// spin ring about the aim with a knob at C0 (drag it round; Ctrl snaps to 15 degrees).
void drawGizmo(const Gizmo& g) {
    if (!g.valid) return;
    ImDrawList* draw = ImGui::GetWindowDrawList();
    draw->AddPolyline(g.ring.data(), int(g.ring.size()), IM_COL32(90, 200, 255, 200),
                      ImDrawFlags_None, 1.5f);
    draw->AddLine(g.centre, g.aimKnob, IM_COL32(255, 120, 60, 230), 2.f);
    draw->AddCircleFilled(g.aimKnob, 6.f, IM_COL32(255, 120, 60, 255));
    draw->AddCircleFilled(g.spinKnob, 5.f, IM_COL32(90, 200, 255, 255));
}

float distance(const ImVec2& a, const ImVec2& b) {
    return std::hypot(a.x - b.x, a.y - b.y);
}

/// The gizmo knob under the mouse: DragMode::Aim, Spin, or None.
DragMode grabbed(const Gizmo& g, const ImVec2& mouse) {
    if (!g.valid) return DragMode::None;
    if (distance(mouse, g.aimKnob) <= kGrabPx) return DragMode::Aim;
    if (distance(mouse, g.spinKnob) <= kGrabPx) return DragMode::Spin;
    return DragMode::None;
}

void drawOutlines(const EditorState& state, const Renderer& renderer, const ImageMapping& map) {
    ImDrawList* draw = ImGui::GetWindowDrawList();
    glm::mat4 viewProj = renderer.viewProj();
    for (size_t i = 0; i < state.scene.luminaires.size(); ++i) {
        std::vector<glm::dvec3> outline = state.scene.luminaires[i]->outline();
        std::vector<ImVec2> points;
        for (const glm::dvec3& p : outline) {
            auto px = projectToPixels(viewProj, p, map.renderWidth, map.renderHeight);
            if (!px) break;
            points.push_back(map.toWindow(*px));
        }
        if (points.size() != outline.size() || points.size() < 2) continue;
        bool selected = int(i) == state.selectedLuminaire ||
                        std::find(state.alsoSelected.begin(), state.alsoSelected.end(), int(i)) !=
                            state.alsoSelected.end();
        ImU32 colour = selected ? IM_COL32(255, 210, 40, 255) : IM_COL32(255, 255, 255, 70);
        draw->AddPolyline(points.data(), int(points.size()), colour, ImDrawFlags_Closed,
                          selected ? 2.f : 1.f);
    }
}

/// Every task area's outline on its plane, named, and the one being drawn (DragMode::Area).
void drawTaskAreas(const EditorState& state, const Renderer& renderer, const ImageMapping& map) {
    ImDrawList* draw = ImGui::GetWindowDrawList();
    glm::mat4 viewProj = renderer.viewProj();
    auto rectangle = [&](const CalcPlane& plane, glm::dvec2 lo, glm::dvec2 hi, ImU32 colour,
                         const std::string& label) {
        ImVec2 corners[4];
        glm::dvec2 uv[4] = {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
        for (int k = 0; k < 4; ++k) {
            auto px = projectToPixels(viewProj, plane.point(uv[k].x, uv[k].y), map.renderWidth,
                                      map.renderHeight);
            if (!px) return;  // behind the camera
            corners[k] = map.toWindow(*px);
        }
        draw->AddPolyline(corners, 4, colour, ImDrawFlags_Closed, 2.f);
        if (!label.empty()) draw->AddText(corners[3], colour, label.c_str());
    };
    for (const TaskArea& a : state.scene.taskAreas)
        rectangle(a.plane, a.lo, a.hi, IM_COL32(80, 220, 255, 220), a.name);
    if (state.drag.mode != DragMode::Area) return;
    const CalcPlane& plane = state.measure.grid.plane;
    glm::dvec2 a = plane.inPlane(state.drag.areaStart), b = plane.inPlane(state.drag.areaEnd);
    glm::dvec2 lo = glm::min(a, b), hi = glm::max(a, b);
    char label[96];
    std::snprintf(label, sizeof label, "%.2f x %.2f m", hi.x - lo.x, hi.y - lo.y);
    rectangle(plane, lo, hi, IM_COL32(255, 210, 40, 255), label);
}

/// Where the mouse ray meets the Measure grid's plane, within kMaxDragDistance of the camera.
std::optional<glm::dvec3> onGridPlane(const EditorState& state, const Renderer& renderer,
                                      const ImageMapping& map, const ImVec2& mouse) {
    glm::dvec2 px = map.toRender(mouse);
    Ray ray = pixelRay(renderer.viewProj(), px.x, px.y, map.renderWidth, map.renderHeight);
    auto hit = intersectPlane(ray, state.measure.grid.plane);
    if (!hit || glm::length(*hit - ray.origin) > kMaxDragDistance) return std::nullopt;
    return hit;
}

/// Left press while "Draw a task area" is armed: the drag's first corner, on the grid's plane.
void beginAreaDrag(EditorState& state, const Renderer& renderer, const ImageMapping& map,
                   const ImVec2& mouse) {
    auto hit = onGridPlane(state, renderer, map, mouse);
    if (!hit) {
        setStatus(state,
                  "That pixel does not see the plane " + planeText(state.measure.grid.plane) +
                      ": press where the work plane is",
                  true);
        return;
    }
    state.drag = {};
    state.drag.mode = DragMode::Area;
    state.drag.areaStart = state.drag.areaEnd = *hit;
}

/// Left press: picks a luminaire (select it and start moving it) or starts an orbit.
void beginLeftDrag(EditorState& state, const Renderer& renderer, const ImageMapping& map,
                   const Gizmo& g, const ImVec2& mouse) {
    glm::dvec2 px = map.toRender(mouse);
    state.drag = {};
    if (DragMode knob = grabbed(g, mouse); knob != DragMode::None) {
        state.drag.mode = knob;
        state.drag.luminaire = state.selectedLuminaire;
        return;
    }
    int hit = renderer.pickLuminaire(state.scene, px.x, px.y);
    if (hit < 0) {
        state.drag.mode = DragMode::Orbit;
        return;
    }
    if (ImGui::GetIO().KeyCtrl) {
        toggleSelected(state, hit);  // Ctrl+click: add to or remove from the selection
        return;
    }
    std::vector<int> group = selectedLuminaires(state);
    bool inGroup = std::find(group.begin(), group.end(), hit) != group.end();
    if (state.selectedLuminaire != hit) state.inspectorError.clear();
    // A press inside the selection drags all of it (the pressed one becomes the primary); a press
    // outside selects that one alone.
    state.alsoSelected.clear();
    if (inGroup)
        for (int i : group)
            if (i != hit) state.alsoSelected.push_back(i);
    state.selectedLuminaire = hit;
    state.selectedGeometry = -1;
    const Luminaire& lum = *state.scene.luminaires[size_t(hit)];
    if (state.placement.alongSurfaces) {
        state.drag.mode = DragMode::Luminaire;
        state.drag.luminaire = hit;
        state.drag.onSurfaces = true;
        return;
    }
    Ray ray = pixelRay(renderer.viewProj(), px.x, px.y, map.renderWidth, map.renderHeight);
    auto grabbed = intersectHorizontal(ray, lum.pose.position.y);
    if (!grabbed) return;  // Seen exactly edge-on: selectable but not draggable from here.
    state.drag.mode = DragMode::Luminaire;
    state.drag.luminaire = hit;
    state.drag.height = lum.pose.position.y;
    state.drag.grabOffset = lum.pose.position - *grabbed;
    state.drag.grabOffset.y = 0.0;
}

/// Moves the dragged luminaire to where the mouse ray meets its horizontal plane.
bool continueLuminaireDrag(EditorState& state, const Renderer& renderer, const ImageMapping& map,
                           const ImVec2& mouse) {
    int index = state.drag.luminaire;
    if (index < 0 || index >= int(state.scene.luminaires.size())) return false;
    glm::dvec2 px = map.toRender(mouse);
    Luminaire& lum = *state.scene.luminaires[size_t(index)];
    double step = snapStep(state.placement);
    if (state.drag.onSurfaces) {
        const PlacementUi& p = state.placement;
        auto hit = pickSurface(surfaceBvh(state), renderer.viewProj(), px.x, px.y, map.renderWidth,
                               map.renderHeight);
        if (!hit) return false;
        Pose pose =
            poseOnSurface(lum.pose, hit->point, hit->normal, p.aimAlongNormal, p.clearance, step);
        if (pose.position == lum.pose.position && pose.aim == lum.pose.aim) return false;
        applyEdit(state, "Move " + lum.name, kChangeLuminaires,
                  [&](Scene& s) { s.luminaires[size_t(index)]->pose = pose; });
        return true;
    }
    Ray ray = pixelRay(renderer.viewProj(), px.x, px.y, map.renderWidth, map.renderHeight);
    auto hit = intersectHorizontal(ray, state.drag.height);
    if (!hit || glm::length(*hit - ray.origin) > kMaxDragDistance) return false;
    glm::dvec3 position = *hit + state.drag.grabOffset;
    if (step > 0.0) {
        position.x = std::round(position.x / step) * step;
        position.z = std::round(position.z / step) * step;
    }
    position.y = state.drag.height;
    if (position == lum.pose.position) return false;
    // The rest of the selection moves by the same step.
    glm::dvec3 shift = position - lum.pose.position;
    std::vector<int> group = selectedLuminaires(state);
    if (std::find(group.begin(), group.end(), index) == group.end()) group = {index};
    std::string label = group.size() > 1 ? "Move " + std::to_string(group.size()) + " luminaires"
                                         : "Move " + lum.name;
    applyEdit(state, label, kChangeLuminaires, [&](Scene& s) {
        for (int i : group) s.luminaires[size_t(i)]->pose.position += shift;
        s.luminaires[size_t(index)]->pose.position = position;  // exactly where the mouse put it
    });
    return true;
}

/// Aim handle: the luminaire turns to face the surface point under the mouse (or, over empty
/// space, the point of the mouse ray at the handle's distance); C0 is kept as far as it can be.
bool continueAimDrag(EditorState& state, const Renderer& renderer, const ImageMapping& map,
                     const ImVec2& mouse) {
    int index = state.drag.luminaire;
    if (index < 0 || index >= int(state.scene.luminaires.size())) return false;
    Luminaire& lum = *state.scene.luminaires[size_t(index)];
    glm::dvec2 px = map.toRender(mouse);
    Ray ray = pixelRay(renderer.viewProj(), px.x, px.y, map.renderWidth, map.renderHeight);
    auto hit = pickSurface(surfaceBvh(state), renderer.viewProj(), px.x, px.y, map.renderWidth,
                           map.renderHeight);
    glm::dvec3 target =
        hit ? hit->point : ray.origin + ray.dir * glm::length(lum.pose.position - ray.origin);
    glm::dvec3 aim = target - lum.pose.position;
    if (!(glm::length(aim) > 1e-6)) return false;
    aim = glm::normalize(aim);
    if (aim == lum.pose.aim) return false;
    applyEdit(state, "Aim " + lum.name, kChangeLuminaires,
              [&](Scene& s) { s.luminaires[size_t(index)]->pose.aim = aim; });
    return true;
}

/// Spin ring: C0 turns about the aim to follow the mouse around the ring (Ctrl: 15 degree steps).
bool continueSpinDrag(EditorState& state, const Renderer& renderer, const ImageMapping& map,
                      const ImVec2& mouse) {
    int index = state.drag.luminaire;
    if (index < 0 || index >= int(state.scene.luminaires.size())) return false;
    Luminaire& lum = *state.scene.luminaires[size_t(index)];
    glm::dvec3 x, y, z;
    lum.pose.frame(x, y, z);
    glm::dvec2 px = map.toRender(mouse);
    Ray ray = pixelRay(renderer.viewProj(), px.x, px.y, map.renderWidth, map.renderHeight);
    double denom = glm::dot(ray.dir, z);
    if (std::abs(denom) < 1e-9) return false;  // the ring seen edge-on
    double t = glm::dot(lum.pose.position - ray.origin, z) / denom;
    if (!(t > 0.0)) return false;
    glm::dvec3 d = ray.origin + t * ray.dir - lum.pose.position;
    // The angle from the current C0 in the ring's plane, then the new C0 at that angle.
    double angle = std::atan2(glm::dot(d, y), glm::dot(d, x));
    if (ImGui::GetIO().KeyCtrl) {
        // Snap the spin (the inspector's, from world +X across the aim) to 15 degrees.
        glm::dvec3 ref, refY;
        spinReference(z, ref, refY);
        glm::dvec3 c = std::cos(angle) * x + std::sin(angle) * y;
        double spin = std::atan2(glm::dot(c, refY), glm::dot(c, ref));
        double step = glm::radians(15.0);
        spin = std::round(spin / step) * step;
        glm::dvec3 c0 = std::cos(spin) * ref + std::sin(spin) * refY;
        if (c0 == lum.pose.c0) return false;
        applyEdit(state, "Spin " + lum.name, kChangeLuminaires,
                  [&](Scene& s) { s.luminaires[size_t(index)]->pose.c0 = c0; });
        return true;
    }
    if (std::abs(angle) < 1e-9) return false;
    glm::dvec3 c0 = std::cos(angle) * x + std::sin(angle) * y;
    applyEdit(state, "Spin " + lum.name, kChangeLuminaires,
              [&](Scene& s) { s.luminaires[size_t(index)]->pose.c0 = c0; });
    return true;
}

/// Left click while "Place on a surface" is armed: the selected luminaire moves onto the surface
/// seen through the pixel (Shift keeps placement armed for the next click).
void placeAtPixel(EditorState& state, const Renderer& renderer, const ImageMapping& map,
                  const ImVec2& mouse) {
    PlacementUi& p = state.placement;
    int index = state.selectedLuminaire;
    if (index < 0 || index >= int(state.scene.luminaires.size())) {
        p.armed = false;
        setStatus(state, "Select a luminaire to place first", true);
        return;
    }
    glm::dvec2 px = map.toRender(mouse);
    auto hit = pickSurface(surfaceBvh(state), renderer.viewProj(), px.x, px.y, map.renderWidth,
                           map.renderHeight);
    if (!hit) {
        setStatus(state, "That pixel sees no surface: click a surface to place the luminaire",
                  true);
        return;
    }
    const ImGuiIO& io = ImGui::GetIO();
    Luminaire& lum = *state.scene.luminaires[size_t(index)];
    Pose pose = poseOnSurface(lum.pose, hit->point, hit->normal, p.aimAlongNormal, p.clearance,
                              snapStep(p));
    applyEdit(state, "Place " + lum.name, kChangeLuminaires,
              [&](Scene& s) { s.luminaires[size_t(index)]->pose = pose; });
    p.armed = io.KeyShift;
    char text[200];
    std::snprintf(text, sizeof text, "Placed %s at (%.2f, %.2f, %.2f) m, aimed (%.2f, %.2f, %.2f)",
                  lum.name.c_str(), pose.position.x, pose.position.y, pose.position.z, pose.aim.x,
                  pose.aim.y, pose.aim.z);
    setStatus(state, text);
}

/// Left click while the Environment panel's "Pick a pixel" is armed: the chart's normal becomes
/// the one of the surface seen through that pixel (Fig. 1-2 of Lu et al. 2013 for a pixel).
void pickChartPixel(EditorState& state, const Renderer& renderer, const ImageMapping& map,
                    const ImVec2& mouse) {
    EnvironmentUi& ui = state.environment;
    ui.pickingPixel = false;
    glm::dvec2 px = map.toRender(mouse);
    Bvh bvh = Bvh::build(state.scene);
    std::optional<BvhHit> hit =
        pickSurface(bvh, renderer.viewProj(), px.x, px.y, map.renderWidth, map.renderHeight);
    if (!hit) {
        setStatus(state, "That pixel sees no surface: pick another", true);
        ui.pickingPixel = true;
        return;
    }
    ui.pixelPicked = true;
    ui.pickedPixel = px;
    ui.pickedPoint = hit->point;
    ui.normalElevationDeg = float(glm::degrees(std::asin(std::clamp(hit->normal.y, -1.0, 1.0))));
    ui.normalAzimuthDeg = float(glm::degrees(std::atan2(hit->normal.z, hit->normal.x)));
    char text[160];
    std::snprintf(text, sizeof text, "Sample chart: pixel (%.0f, %.0f), normal (%.3f, %.3f, %.3f)",
                  std::floor(px.x), std::floor(px.y), hit->normal.x, hit->normal.y, hit->normal.z);
    setStatus(state, text, false);
}

/// A cross where the sample chart's pixel was picked, while the chart is shown.
void drawPickedPixel(const EditorState& state, const ImageMapping& map) {
    const EnvironmentUi& ui = state.environment;
    if (!ui.pixelPicked || !ui.chartOpen) return;
    ImVec2 c = map.toWindow(ui.pickedPixel);
    ImDrawList* draw = ImGui::GetWindowDrawList();
    for (auto [colour, width] :
         {std::pair{IM_COL32(0, 0, 0, 200), 3.f}, std::pair{IM_COL32(80, 255, 120, 255), 1.5f}}) {
        draw->AddLine(ImVec2(c.x - 9.f, c.y), ImVec2(c.x - 3.f, c.y), colour, width);
        draw->AddLine(ImVec2(c.x + 3.f, c.y), ImVec2(c.x + 9.f, c.y), colour, width);
        draw->AddLine(ImVec2(c.x, c.y - 9.f), ImVec2(c.x, c.y - 3.f), colour, width);
        draw->AddLine(ImVec2(c.x, c.y + 3.f), ImVec2(c.x, c.y + 9.f), colour, width);
    }
}

/// A press over the image starts what it means: an orbit (cameraOnly), a chart pixel pick, a
/// placement, a left drag (luminaire, gizmo or orbit), or a pan (right or middle button).
bool beginGesture(EditorState& state, const Renderer& renderer, const ImageMapping& map,
                  const Gizmo& g, bool hovered, bool cameraOnly) {
    const ImGuiIO& io = ImGui::GetIO();
    bool changed = false;
    if (cameraOnly && hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
        state.drag = {};
        if (!state.compare.wipeDragging) state.drag.mode = DragMode::Orbit;
    } else if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left) &&
               state.environment.pickingPixel && state.environment.chartOpen) {
        pickChartPixel(state, renderer, map, io.MouseClickedPos[ImGuiMouseButton_Left]);
    } else if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left) &&
               state.measure.drawingArea) {
        beginAreaDrag(state, renderer, map, io.MouseClickedPos[ImGuiMouseButton_Left]);
    } else if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left) && state.placement.armed) {
        placeAtPixel(state, renderer, map, io.MouseClickedPos[ImGuiMouseButton_Left]);
        changed = true;
    } else if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
        beginLeftDrag(state, renderer, map, g, io.MouseClickedPos[ImGuiMouseButton_Left]);
        changed = true;
    } else if (hovered && (ImGui::IsMouseClicked(ImGuiMouseButton_Right) ||
                           ImGui::IsMouseClicked(ImGuiMouseButton_Middle))) {
        state.drag = {};
        state.drag.mode = DragMode::Pan;
    }
    return changed;
}

/// The drag under way follows the mouse, or ends when its button is up.
bool continueDrag(EditorState& state, const Renderer& renderer, const ImageMapping& map) {
    const ImGuiIO& io = ImGui::GetIO();
    bool changed = false;
    ImVec2 delta = io.MouseDelta;
    bool moved = delta.x != 0.f || delta.y != 0.f;
    switch (state.drag.mode) {
        case DragMode::Luminaire:
            if (!ImGui::IsMouseDown(ImGuiMouseButton_Left))
                state.drag = {};
            else
                changed = continueLuminaireDrag(state, renderer, map, io.MousePos);
            break;
        case DragMode::Aim:
        case DragMode::Spin:
            if (!ImGui::IsMouseDown(ImGuiMouseButton_Left))
                state.drag = {};
            else if (moved)
                changed = state.drag.mode == DragMode::Aim
                              ? continueAimDrag(state, renderer, map, io.MousePos)
                              : continueSpinDrag(state, renderer, map, io.MousePos);
            break;
        case DragMode::Area:
            if (auto hit = onGridPlane(state, renderer, map, io.MousePos))
                state.drag.areaEnd = *hit;
            if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
                changed = addTaskAreaFromDrag(state, state.drag.areaStart, state.drag.areaEnd);
                state.measure.drawingArea = false;
                state.drag = {};
            }
            break;
        case DragMode::Orbit:
            if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
                state.drag = {};
            } else if (moved) {
                applyEdit(state, "Orbit camera", kChangeCamera, [&](Scene& s) {
                    orbitCamera(s.camera, delta.x * kOrbitDegPerPixel, delta.y * kOrbitDegPerPixel);
                });
                changed = true;
            }
            break;
        case DragMode::Pan:
            if (!ImGui::IsMouseDown(ImGuiMouseButton_Right) &&
                !ImGui::IsMouseDown(ImGuiMouseButton_Middle)) {
                state.drag = {};
            } else if (moved) {
                applyEdit(state, "Pan camera", kChangeCamera,
                          [&](Scene& s) { panCamera(s.camera, delta.x, delta.y, map.size.y); });
                changed = true;
            }
            break;
        case DragMode::None:
            break;
    }
    return changed;
}

/// The cursor over the image: a resize arrow on the wipe, a hand where a click picks, places or
/// grabs something.
void setCursor(const EditorState& state, const Renderer& renderer, const ImageMapping& map,
               const Gizmo& g, bool hovered, bool cameraOnly) {
    const ImGuiIO& io = ImGui::GetIO();
    if (cameraOnly) {
        if (hovered && state.compare.wipeDragging) ImGui::SetMouseCursor(ImGuiMouseCursor_ResizeEW);
    } else if (hovered && ((state.environment.pickingPixel && state.environment.chartOpen) ||
                           state.placement.armed)) {
        ImGui::SetMouseCursor(ImGuiMouseCursor_Hand);
    } else if (hovered && (state.measure.drawingArea || state.drag.mode == DragMode::Area)) {
        ImGui::SetMouseCursor(ImGuiMouseCursor_ResizeNWSE);
    } else if (hovered && state.drag.mode == DragMode::None) {
        glm::dvec2 px = map.toRender(io.MousePos);
        if (grabbed(g, io.MousePos) != DragMode::None ||
            renderer.pickLuminaire(state.scene, px.x, px.y) >= 0)
            ImGui::SetMouseCursor(ImGuiMouseCursor_Hand);
    }
}

/// Mouse input over the image. cameraOnly (comparison panes): a left press orbits, nothing is
/// picked or placed.
bool handleInput(EditorState& state, const Renderer& renderer, const ImageMapping& map,
                 const Gizmo& g, bool hovered, bool cameraOnly = false) {
    const ImGuiIO& io = ImGui::GetIO();
    bool changed = beginGesture(state, renderer, map, g, hovered, cameraOnly);
    changed = continueDrag(state, renderer, map) || changed;
    if (hovered && io.MouseWheel != 0.f) {
        applyEdit(state, "Zoom camera", kChangeCamera,
                  [&](Scene& s) { zoomCamera(s.camera, io.MouseWheel); });
        changed = true;
    }
    setCursor(state, renderer, map, g, hovered, cameraOnly);
    return changed;
}

}  // namespace

bool viewportPanel(EditorState& state, const Renderer& renderer, const PanelRect& rect,
                   const Comparison* comparison) {
    placeNextWindow(rect);
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0.f, 0.f));
    ImGui::PushStyleVar(ImGuiStyleVar_WindowBorderSize, 0.f);
    ImGui::Begin("Viewport", nullptr,
                 kPanelFlags | ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoScrollbar |
                     ImGuiWindowFlags_NoScrollWithMouse | ImGuiWindowFlags_NoBringToFrontOnFocus);
    ImGui::PopStyleVar(2);
    bool changed = compareToolbar(state);
    ImGui::SetCursorPos(ImVec2(0.f, ImGui::GetFrameHeight() + 4.f));

    ImVec2 avail = ImGui::GetContentRegionAvail();
    ImVec2 size(std::max(1.f, std::floor(avail.x)), std::max(1.f, std::floor(avail.y)));
    ImVec2 origin = ImGui::GetCursorScreenPos();
    origin = ImVec2(std::floor(origin.x), std::floor(origin.y));
    state.layout.viewport = glm::vec4(origin.x, origin.y, size.x, size.y);
    // The render resolution follows the panel (scaled down on request); applied next frame.
    state.settings.width = std::max(1, int(std::lround(size.x * state.renderScale)));
    state.settings.height = std::max(1, int(std::lround(size.y * state.renderScale)));

    ImGui::InvisibleButton("##viewport", size,
                           ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight |
                               ImGuiButtonFlags_MouseButtonMiddle);
    bool hovered = ImGui::IsItemHovered();

    if (comparison && state.compare.layout != CompareLayout::Single) {
        compareView(state, *comparison, origin, size, hovered);
        state.layout.gizmo = false;
        ImageMapping map{origin, size, renderer.settings().width, renderer.settings().height};
        changed = handleInput(state, renderer, map, Gizmo{}, hovered, true) || changed;
        ImGui::End();
        return changed;
    }
    ImDrawList* draw = ImGui::GetWindowDrawList();
    ImVec2 corner(origin.x + size.x, origin.y + size.y);
    GLuint texture = renderer.displayTexture().id();
    if (texture) {
        // Row 0 of the display texture is the bottom row: flip v.
        draw->AddImage(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(texture)), origin,
                       corner, ImVec2(0.f, 1.f), ImVec2(1.f, 0.f));
    } else {
        draw->AddRectFilled(origin, corner, IM_COL32(20, 20, 24, 255));
    }

    ImageMapping map{origin, size, renderer.settings().width, renderer.settings().height};
    drawOutlines(state, renderer, map);
    drawTaskAreas(state, renderer, map);
    Gizmo handles = gizmo(state, renderer, map);
    drawGizmo(handles);
    state.layout.gizmo = handles.valid;
    state.layout.aimKnob = glm::vec2(handles.aimKnob.x, handles.aimKnob.y);
    state.layout.spinKnob = glm::vec2(handles.spinKnob.x, handles.spinKnob.y);
    drawPickedPixel(state, map);
    changed = handleInput(state, renderer, map, handles, hovered) || changed;
    ImGui::End();
    return changed;
}

}  // namespace candela::ui
