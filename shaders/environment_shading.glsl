// What every environment technique's shader shares (Algorithm 2 of Lu et al. 2013);
// luminaires/Registry.cpp names one shader per technique, shaders/environment_<technique>.frag,
// which defines
//   vec3 shadeTechnique(Surface s, int ns, inout uint rng)
// (this pass's radiance estimate from ns samples) between an include of this file and of
// environment_main.glsl. Variants every technique honours:
//   SHADOWS                  a shadow ray per sample through the scene BVH;
//   SHADOW_MAPS              havran2005: one directional shadow map per light;
//   GLOSSY                   the scene has glossy materials: add the Phong lobe.
#include "shade_common.glsl"
#include "environment.glsl"
#ifdef SHADOWS
#include "bvh_traverse.glsl"
#endif
#ifdef SHADOW_MAPS
#include "shadow_directional.glsl"
#endif

layout(location = 0) out vec4 outRadiance;

float envVisibility(Surface s, vec3 w) {
#ifdef SHADOWS
    vec3 from = shadowOrigin(s);
    return bvhOccludedToward(from, w) ? 0.0 : 1.0;
#else
    return 1.0;
#endif
}

/// radiance x BRDF x cosine x visibility for a direction with a positive cosine, else 0.
vec3 integrand(Surface s, vec3 w, vec3 radiance) {
    float c = dot(s.n, w);
    if (!(c > 0.0)) return vec3(0.0);
    return radiance * brdf(s, w) * c * envVisibility(s, w);
}

/// Sample i of face f's pool, starting at `start`.
EnvironmentSampleGpu poolSample(int f, int start, int i) {
    int pool = env.dims.w;
    return envSamples[f * pool + (start + i) % pool];
}
