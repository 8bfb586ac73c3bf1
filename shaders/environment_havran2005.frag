// environment `havran2005` (and `havran2005-raytraced`, its SHADOWS variant): the filtered
// directional lights of Havran et al. 2005 (built on the CPU); with SHADOW_MAPS one directional
// shadow map per light.
#include "environment_shading.glsl"

// Per light: direction (xyz), then power (rgb irradiance at normal incidence, W/m2).
layout(std430, binding = 13) readonly buffer EnvExtra { vec4 envLights[]; };

vec3 shadeTechnique(Surface s, int ns, inout uint rng) {
    vec3 result = vec3(0.0);
    for (int k = 0; k < env.extra.x; ++k) {
        vec3 w = envLights[2 * k].xyz;
        float c = dot(s.n, w);
        if (!(c > 0.0)) continue;
#ifdef SHADOW_MAPS
        float v = directionalVisibility(k, s.p, s.n, w);
#else
        float v = envVisibility(s, w);
#endif
        result += envLights[2 * k + 1].rgb * brdf(s, w) * c * v;
    }
    return result;
}

#include "environment_main.glsl"
