// Mathematical constants shared by C++ and GLSL, valid as both (shaders/common.glsl includes it,
// so every shader has them). A `real` is 64-bit in C++ (the CPU reference works in 64-bit) and
// 32-bit in GLSL: the same literal gives each language its nearest value.
#ifdef __cplusplus
#pragma once
#include <glm/fwd.hpp>
namespace candela::gpu {
using real = glm::f64;
#ifndef CANDELA_CONST
#define CANDELA_CONST static constexpr
#endif
#else
#define real float
#ifndef CANDELA_CONST
#define CANDELA_CONST const
#endif
#endif

CANDELA_CONST real kPi = 3.14159265358979323846;

/// How far outside a luminaire body's bounds a light's emission point may be and still be the
/// body's own, metres (scene/Scene.h: insideBody): the body casts no shadow on that light.
CANDELA_CONST real kBodyMargin = 0.01;

/// Gauss-Legendre rule of 16 points on [-1, 1]: the nodes are +-kGaussLegendre16Node[i], both
/// weighted kGaussLegendre16Weight[i] (i = 0 .. 7), tabulated to 16 digits.
CANDELA_CONST real kGaussLegendre16Node[8] = {
    0.0950125098376374, 0.2816035507792589, 0.4580167776572274, 0.6178762444026438,
    0.7554044083550030, 0.8656312023878318, 0.9445750230732326, 0.9894009349916499};
CANDELA_CONST real kGaussLegendre16Weight[8] = {
    0.1894506104550685, 0.1826034150449236, 0.1691565193950025, 0.1495959888165767,
    0.1246289712555339, 0.0951585116824928, 0.0622535239386479, 0.0271524594117541};

#ifdef __cplusplus
}  // namespace candela::gpu
#else
#undef real
#endif
