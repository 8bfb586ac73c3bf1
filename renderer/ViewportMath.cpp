#include "renderer/ViewportMath.h"

#include <algorithm>
#include <cmath>

namespace candela {

namespace {

/// Camera basis: forward towards the target, right and up perpendicular to it (world Y-up).
void cameraBasis(const Camera& camera, glm::dvec3& forward, glm::dvec3& right, glm::dvec3& up) {
    forward = glm::normalize(camera.target - camera.position);
    glm::dvec3 worldUp(0.0, 1.0, 0.0);
    right = glm::cross(forward, worldUp);
    if (glm::length(right) < 1e-9) right = glm::dvec3(1.0, 0.0, 0.0);
    right = glm::normalize(right);
    up = glm::cross(right, forward);
}

}  // namespace

Ray pixelRay(const glm::mat4& viewProj, double x, double y, int width, int height) {
    glm::dmat4 inv = glm::inverse(glm::dmat4(viewProj));
    double ndcX = 2.0 * x / double(std::max(1, width)) - 1.0;
    double ndcY = 1.0 - 2.0 * y / double(std::max(1, height));
    glm::dvec4 nearPoint = inv * glm::dvec4(ndcX, ndcY, -1.0, 1.0);
    glm::dvec4 farPoint = inv * glm::dvec4(ndcX, ndcY, 1.0, 1.0);
    Ray ray;
    ray.origin = glm::dvec3(nearPoint) / nearPoint.w;
    ray.dir = glm::normalize(glm::dvec3(farPoint) / farPoint.w - ray.origin);
    return ray;
}

std::optional<BvhHit> pickSurface(const Bvh& bvh, const glm::mat4& viewProj, double x, double y,
                                  int width, int height) {
    Ray ray = pixelRay(viewProj, x, y, width, height);
    return bvh.closestHit(ray.origin, ray.dir);
}

std::optional<glm::dvec3> intersectHorizontal(const Ray& ray, double height) {
    if (std::abs(ray.dir.y) < 1e-9) return std::nullopt;
    double t = (height - ray.origin.y) / ray.dir.y;
    if (!(t > 0.0) || !std::isfinite(t)) return std::nullopt;
    glm::dvec3 p = ray.origin + t * ray.dir;
    p.y = height;  // exact, so a drag never drifts vertically through rounding
    return p;
}

std::optional<glm::dvec3> intersectPlane(const Ray& ray, const CalcPlane& plane) {
    int a = plane.axis;
    if (std::abs(ray.dir[a]) < 1e-9) return std::nullopt;
    double t = (plane.offset - ray.origin[a]) / ray.dir[a];
    if (!(t > 0.0) || !std::isfinite(t)) return std::nullopt;
    glm::dvec3 p = ray.origin + t * ray.dir;
    p[a] = plane.offset;
    return p;
}

std::optional<glm::dvec2> projectToPixels(const glm::mat4& viewProj, const glm::dvec3& point,
                                          int width, int height) {
    glm::dvec4 clip = glm::dmat4(viewProj) * glm::dvec4(point, 1.0);
    if (clip.w <= 1e-9) return std::nullopt;
    glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
    return glm::dvec2((ndc.x * 0.5 + 0.5) * width, (0.5 - ndc.y * 0.5) * height);
}

void orbitCamera(Camera& camera, double yawDeg, double pitchDeg) {
    glm::dvec3 offset = camera.position - camera.target;
    double distance = glm::length(offset);
    if (distance < 1e-9) return;
    // Spherical coordinates of the offset: azimuth about +Y, elevation above the horizon.
    double elevation = std::asin(std::clamp(offset.y / distance, -1.0, 1.0));
    double azimuth = std::atan2(offset.x, offset.z);
    const double limit = glm::radians(89.0);
    azimuth -= glm::radians(yawDeg);
    elevation = std::clamp(elevation + glm::radians(pitchDeg), -limit, limit);
    offset = distance * glm::dvec3(std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                                   std::cos(elevation) * std::cos(azimuth));
    camera.position = camera.target + offset;
}

void panCamera(Camera& camera, double dxPixels, double dyPixels, double viewportHeight) {
    glm::dvec3 forward, right, up;
    cameraBasis(camera, forward, right, up);
    double distance = glm::length(camera.target - camera.position);
    // Metres per pixel at the target's depth: the view spans 2 d tan(fov/2) over the height.
    double metresPerPixel = 2.0 * distance * std::tan(glm::radians(camera.fovDeg) * 0.5) /
                            std::max(1.0, viewportHeight);
    glm::dvec3 move = (-dxPixels * right + dyPixels * up) * metresPerPixel;
    camera.position += move;
    camera.target += move;
}

void zoomCamera(Camera& camera, double steps) {
    glm::dvec3 offset = camera.position - camera.target;
    double distance = glm::length(offset);
    if (distance < 1e-9) return;
    double next = std::clamp(distance * std::pow(0.85, steps), 0.05, 1000.0);
    camera.position = camera.target + offset * (next / distance);
}

void spinReference(const glm::dvec3& z, glm::dvec3& ref, glm::dvec3& refY) {
    ref = std::abs(z.x) > 0.99 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
    ref = glm::normalize(ref - glm::dot(ref, z) * z);
    refY = glm::cross(z, ref);
}

}  // namespace candela
