// The false-colour scale of illuminance pictures and its legend mapping, valid as both C++ and
// GLSL: shaders/tonemap.frag, the editor's legend (ui/MeasurePanel.cpp) and the tests evaluate
// the same stops, so the legend always shows the colours the image uses.
//
// The scale runs from dark indigo through blue, teal, green and yellow to pale yellow. The stops
// were picked for this project so that CIE L* (of the sRGB colour) rises by 8.6 to 14 at every
// stop, from 7.5 to 96.3: the scale is perceptually ordered (brighter means more light, also when
// printed in grey) and its hue order is the familiar "cold to warm" one of lighting reports.
// Stops are sRGB-encoded display colours, interpolated linearly in that encoding.
#ifdef __cplusplus
#pragma once
#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
namespace candela::gpu {
using vec3 = glm::vec3;
using glm::clamp;
using glm::mix;
using std::log;
using std::max;
using std::min;
#define CANDELA_FN inline
#ifndef CANDELA_CONST
#define CANDELA_CONST static constexpr
#endif
#else
#define CANDELA_FN
#ifndef CANDELA_CONST
#define CANDELA_CONST const
#endif
#endif

/// Number of colour stops of the scale, spread evenly over t in [0, 1].
CANDELA_CONST int kFalseColourStops = 9;

/// Most isolux contour levels the picture takes (renderer/passes/TonemapPass.h contourLevels,
/// the uniform array of shaders/tonemap.frag).
CANDELA_CONST int kMaxContourLevels = 16;

/// Stop i (0 .. kFalseColourStops - 1) of the scale, sRGB-encoded.
CANDELA_FN vec3 falseColourStop(int i) {
    if (i <= 0) return vec3(0.08f, 0.04f, 0.28f);  // L* 7.5, dark indigo
    if (i == 1) return vec3(0.24f, 0.10f, 0.52f);  // L* 21.6, violet
    if (i == 2) return vec3(0.16f, 0.28f, 0.70f);  // L* 34.5, blue
    if (i == 3) return vec3(0.05f, 0.47f, 0.72f);  // L* 48.2, cyan-blue
    if (i == 4) return vec3(0.08f, 0.62f, 0.58f);  // L* 58.8, teal
    if (i == 5) return vec3(0.32f, 0.74f, 0.36f);  // L* 68.6, green
    if (i == 6) return vec3(0.66f, 0.82f, 0.18f);  // L* 78.6, yellow-green
    if (i == 7) return vec3(0.96f, 0.86f, 0.16f);  // L* 87.2, yellow
    return vec3(1.00f, 0.97f, 0.66f);              // L* 96.3, pale yellow
}

/// The scale at t in [0, 1] (clamped), sRGB-encoded.
CANDELA_FN vec3 falseColour(float t) {
    float x = clamp(t, 0.0f, 1.0f) * float(kFalseColourStops - 1);
    int i = min(int(x), kFalseColourStops - 2);
    return mix(falseColourStop(i), falseColourStop(i + 1), x - float(i));
}

/// Position on the legend (0 at lo, 1 at hi, not clamped) of the value v, in the legend's unit
/// (lux for illuminance). Log scale: log(v / lo) / log(hi / lo), with v floored at 1e-6 lo so a
/// dark pixel maps far below 0 instead of to -infinity; lo must then be > 0.
CANDELA_FN float legendPosition(float v, float lo, float hi, int logScale) {
    if (logScale != 0) return log(max(v, 1e-6f * lo) / lo) / log(hi / lo);
    return (v - lo) / (hi - lo);
}

#ifdef __cplusplus
}  // namespace candela::gpu
#endif
#undef CANDELA_FN
