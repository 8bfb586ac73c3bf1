#pragma once
// Camera navigation and viewport geometry for the editor: orbit, pan and zoom around the camera
// target, mouse rays from the renderer's view-projection, and projection of world points to
// viewport pixels. No ImGui and no GL here, so the maths can be tested on its own.

#include <glm/glm.hpp>
#include <optional>

#include "calculation/CalculationGrid.h"
#include "scene/Bvh.h"
#include "scene/Scene.h"

namespace candela {

/// A ray in world space (metres); dir is unit length.
struct Ray {
    glm::dvec3 origin{0.0};
    glm::dvec3 dir{0.0, 0.0, -1.0};
};

/// Ray through a render pixel (x right, y down, in render pixels, pixel centres at +0.5).
Ray pixelRay(const glm::mat4& viewProj, double x, double y, int width, int height);

/// The surface seen through a render pixel (x right, y down, centres at +0.5): the nearest
/// triangle along pixelRay, its normal turned towards the camera. Empty when the pixel sees
/// nothing. What the editor and `candela probe --pixel` pick.
std::optional<BvhHit> pickSurface(const Bvh& bvh, const glm::mat4& viewProj, double x, double y,
                                  int width, int height);

/// Where the ray meets the horizontal plane y = height (metres); empty when the ray is parallel
/// to it or points away from it.
std::optional<glm::dvec3> intersectHorizontal(const Ray& ray, double height);

/// Where the ray meets a calculation plane (its axis coordinate = offset, either side facing),
/// with that coordinate exact; empty when the ray is parallel to it or points away from it.
std::optional<glm::dvec3> intersectPlane(const Ray& ray, const CalcPlane& plane);

/// Projects a world point (metres) to render pixels (x right, y down). Empty when the point is
/// behind the camera.
std::optional<glm::dvec2> projectToPixels(const glm::mat4& viewProj, const glm::dvec3& point,
                                          int width, int height);

/// The zero of a luminaire's spin about its unit aim z: world +X made orthogonal to z (+Z when z
/// is along X), and refY = z x ref; spin s puts C0 at cos(s) ref + sin(s) refY.
void spinReference(const glm::dvec3& z, glm::dvec3& ref, glm::dvec3& refY);

/// Rotates the camera position about camera.target: yaw about world +Y, pitch about the camera's
/// right axis, both in degrees. Pitch stops 1 deg short of straight up or down.
void orbitCamera(Camera& camera, double yawDeg, double pitchDeg);

/// Moves position and target together by a screen-space offset in viewport pixels (x right,
/// y down), scaled so the point at the target follows the mouse. viewportHeight in pixels.
void panCamera(Camera& camera, double dxPixels, double dyPixels, double viewportHeight);

/// Moves the camera towards (steps > 0) or away from the target; each step scales the distance
/// by 0.85. The distance stays within [0.05, 1000] m.
void zoomCamera(Camera& camera, double steps);

}  // namespace candela
