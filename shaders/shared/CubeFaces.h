// The frames of the environment's cube-map faces, valid as both C++ and GLSL: the CPU sampler
// (luminaires/environment/EnvironmentSampling.cpp) and the GPU tables (shaders/environment.glsl)
// use these. Faces follow the OpenEXR envmap=cube layout (ImfEnvmap.h;
// luminaires/environment/EnvironmentSampling.h says how texels map to face coordinates): texel (a,
// b) of face f looks along centre_f + a right_f + b down_f, the OpenEXR orientation (seen from
// inside the cube):
//
//   face  centre      right (+col)   down (+row)
//   +X    (+1, 0, 0)  (0, 0, +1)     (0, -1, 0)
//   -X    (-1, 0, 0)  (0, 0, -1)     (0, -1, 0)
//   +Y    (0, +1, 0)  (+1, 0, 0)     (0, 0, -1)
//   -Y    (0, -1, 0)  (+1, 0, 0)     (0, 0, +1)
//   +Z    (0, 0, +1)  (-1, 0, 0)     (0, -1, 0)
//   -Z    (0, 0, -1)  (+1, 0, 0)     (0, -1, 0)
#ifdef __cplusplus
#pragma once
#include <glm/glm.hpp>
namespace candela::gpu {
using vec3 = glm::vec3;
#ifndef CANDELA_CONST
#define CANDELA_CONST static constexpr
#endif
#else
#ifndef CANDELA_CONST
#define CANDELA_CONST const
#endif
#endif

/// Face f's direction through its centre, unit.
CANDELA_CONST vec3 kCubeFaceCentre[6] = {vec3(1, 0, 0),  vec3(-1, 0, 0), vec3(0, 1, 0),
                                         vec3(0, -1, 0), vec3(0, 0, 1),  vec3(0, 0, -1)};
/// Face f's axis of increasing column (face coordinate a), unit.
CANDELA_CONST vec3 kCubeFaceRight[6] = {vec3(0, 0, 1), vec3(0, 0, -1), vec3(1, 0, 0),
                                        vec3(1, 0, 0), vec3(-1, 0, 0), vec3(1, 0, 0)};
/// Face f's axis of increasing row (face coordinate b, row 0 at the face's top), unit.
CANDELA_CONST vec3 kCubeFaceDown[6] = {vec3(0, -1, 0), vec3(0, -1, 0), vec3(0, 0, -1),
                                       vec3(0, 0, 1),  vec3(0, -1, 0), vec3(0, -1, 0)};

#ifdef __cplusplus
}  // namespace candela::gpu
#endif
