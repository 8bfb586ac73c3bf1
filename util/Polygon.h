#pragma once
// The signed area of a plane polygon: a luminaire's opening (luminaires/photometric) and a room's
// floor (scene/Procedural.h) both ask which way their corners run.

#include <glm/glm.hpp>
#include <vector>

namespace candela {

/// Signed area of a polygon (shoelace), in the square of its coordinates' unit: positive when its
/// corners run counter-clockwise with the first coordinate to the right and the second up.
inline double signedArea(const std::vector<glm::dvec2>& polygon) {
    double twice = 0.0;
    for (size_t i = 0; i < polygon.size(); ++i) {
        const glm::dvec2& a = polygon[i];
        const glm::dvec2& b = polygon[(i + 1) % polygon.size()];
        twice += a.x * b.y - b.x * a.y;
    }
    return 0.5 * twice;
}

}  // namespace candela
