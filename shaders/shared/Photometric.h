// What the photometric techniques share between C++ (luminaires/SphericalPolygon.*,
// luminaires/photometric/PhotometricEstimators.cpp) and GLSL (shaders/photometric*.glsl), valid as
// both. A `real` is 64-bit in C++ and 32-bit in GLSL.
#ifdef __cplusplus
#pragma once
#include <glm/glm.hpp>
namespace candela::gpu {
using real = glm::f64;
using glm::clamp;
#define CANDELA_FN inline
#ifndef CANDELA_CONST
#define CANDELA_CONST static constexpr
#endif
#else
#define real float
#define CANDELA_FN
#ifndef CANDELA_CONST
#define CANDELA_CONST const
#endif
#endif

/// Most vertices of the opening's polygon seen from a receiver (spherical::Polygon, the GLSL
/// PhPolygon): enough for a 16-gon cut by one plane, plus rounding slack.
CANDELA_CONST int kMaxPolygon = 20;

/// The adaptive technique (photometric `adaptive`, PhotometricEstimators.cpp) splits its worst
/// spherical triangle until the errors its triangles estimate sum to this fraction of its value
/// (the estimate is the disagreement of a triangle's vertex rule with its children's, some two to
/// four times the children's own error)...
CANDELA_CONST real kAdaptiveTolerance = 3e-3;
/// ...or it has split this often: on the CPU (grids, surfaces, probe: 12 intensity lookups a
/// split, at most some 2000 a point)...
CANDELA_CONST int kAdaptiveCpuSplits = 160;
/// ...and on the GPU, which holds every triangle of a pixel's cubature in its local memory (at
/// most the initial triangulation's kMaxPolygon + 1 and three more a split; llvmpipe's compile
/// time grows with it: about 5 s at 40 splits, 11 s at 80).
CANDELA_CONST int kAdaptiveGpuSplits = 40;
CANDELA_CONST int kAdaptiveGpuTriangles = kMaxPolygon + 1 + 3 * kAdaptiveGpuSplits;

/// The hybrid technique's Monte Carlo weight at `distance` (m) from an opening whose largest
/// extent is `size` (m): 0 within half an opening size, 1 beyond one and a half, smoothstep in
/// between (where the 24-point set's light bumps fade in `candela bench --prost`; Prost Sec. 6.6
/// suggests the blend, not the distances). 1 for an opening of no size.
CANDELA_FN real hybridWeight(real distance, real size) {
    if (!(size > 0.0)) return 1.0;
    real t = clamp(distance / size - 0.5, 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

#ifdef __cplusplus
}  // namespace candela::gpu
#else
#undef real
#endif
#undef CANDELA_FN
