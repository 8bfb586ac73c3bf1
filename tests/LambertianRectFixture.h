#pragma once
// The Lambertian rectangle tests' light and its frame (lambertian_rect_test.cpp,
// lambertian_rect_geometry_test.cpp), written from the definition in Luminaire.h (not with
// Pose::frame).

#include <glm/glm.hpp>
#include <memory>

#include "luminaires/Luminaire.h"
#include "luminaires/lambertian/LambertianRect.h"

namespace candela::test {

/// The light's local axes in world space: x along c0, z along aim.
struct Frame {
    glm::dvec3 x, y, z;
};

/// The frame of `pose`: z = aim, x = c0's part orthogonal to it, y = z x x.
inline Frame frameOf(const Pose& pose) {
    Frame f;
    f.z = glm::normalize(pose.aim);
    f.x = glm::normalize(pose.c0 - glm::dot(pose.c0, f.z) * f.z);
    f.y = glm::cross(f.z, f.x);
    return f;
}

/// A tilted light, so that no test relies on axis alignment: a placed luminaire whose model is a
/// LambertianRect.
inline Luminaire makeLight() {
    auto model = std::make_shared<LambertianRect>();
    model->size = {1.2, 0.6};
    model->emitted = {10.0, 5.0, 2.0};
    Luminaire light(model);
    light.pose.position = {0.3, 2.0, -0.2};
    light.pose.aim = {0.2, -1.0, 0.1};
    light.pose.c0 = {1.0, 0.0, 0.3};
    return light;
}

/// A point given in the light's local frame (metres), in world space.
inline glm::dvec3 toWorld(const Luminaire& light, const glm::dvec3& local) {
    Frame f = frameOf(light.pose);
    return light.pose.position + local.x * f.x + local.y * f.y + local.z * f.z;
}

/// A direction given in the light's local frame, in world space (unit).
inline glm::dvec3 dirToWorld(const Luminaire& light, const glm::dvec3& local) {
    Frame f = frameOf(light.pose);
    return glm::normalize(local.x * f.x + local.y * f.y + local.z * f.z);
}

}  // namespace candela::test
