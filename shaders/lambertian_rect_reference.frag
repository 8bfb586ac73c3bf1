// lambertian-rect `reference`: Monte Carlo, samples uniform in solid angle (Urena et al. 2013).
#include "lambertian_rect_shading.glsl"

vec3 shadeTechnique(Surface s, LambertianRectGpu L, int spp, inout uint rng) {
    vec3 result = vec3(0.0);
    for (int k = 0; k < spp; ++k) {
        vec3 wi;
        float dist, pdf;
        vec2 u = vec2(rand01(rng), rand01(rng));
        if (!lambertRectSample(L, s.p, u, wi, dist, pdf)) continue;
        float c = max(dot(s.n, wi), 0.0);
        if (c <= 0.0) continue;
        result += L.radiance.rgb * brdf(s, wi) * c * visibility(s, wi, dist) / pdf;
    }
    result /= float(spp);
    return result;
}

#include "lambertian_rect_main.glsl"
