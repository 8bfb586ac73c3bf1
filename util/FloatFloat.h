// The float-float pairs that the shaders read where a table needs more digits than a float holds
// (shaders/ff.glsl): a 64-bit value v as hi, its nearest float, and lo, the nearest float of
// v - hi, about 48 significant bits in all.
#pragma once
#include <glm/vec2.hpp>

namespace candela {

inline glm::vec2 toFloatFloat(double v) {
    float hi = float(v);
    return {hi, float(v - double(hi))};
}

inline double fromFloatFloat(glm::vec2 p) {
    return double(p.x) + double(p.y);
}

}  // namespace candela
