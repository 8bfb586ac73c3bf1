// What every Lambertian rectangle technique's shader shares; luminaires/Registry.cpp names one
// shader per technique, shaders/lambertian_rect_<technique>.frag, which defines
//   vec3 shadeTechnique(Surface s, LambertianRectGpu L, int spp, inout uint rng)
// (this pass's radiance estimate) between an include of this file and of
// lambertian_rect_main.glsl. Variants every technique honours:
//   SHADOWS             trace shadow rays through the scene BVH.
//   GLOSSY              the scene has glossy materials: add the Phong lobe by light sampling.
#include "shade_common.glsl"
#include "lambertian_rect.glsl"
#ifdef SHADOWS
#include "bvh_traverse.glsl"
#endif

layout(std430, binding = 1) readonly buffer Luminaires { LambertianRectGpu lights[]; };
layout(location = 0) uniform int uLuminaire;

layout(location = 0) out vec4 outRadiance;

float visibility(Surface s, vec3 wi, float dist) {
#ifdef SHADOWS
    vec3 from = shadowOrigin(s);
    return bvhOccluded(from, s.p + wi * dist) ? 0.0 : 1.0;
#else
    return 1.0;
#endif
}
