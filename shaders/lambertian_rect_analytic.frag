// lambertian-rect `analytic`: closed-form polygon irradiance (Baum et al. 1989) for the diffuse
// part; with SHADOWS it is scaled by a stochastic visibility ratio sum(cos V) / sum(cos) over
// solid-angle samples (consistent, not unbiased).
#include "lambertian_rect_shading.glsl"

vec3 shadeTechnique(Surface s, LambertianRectGpu L, int spp, inout uint rng) {
    vec3 result = vec3(0.0);
    vec3 E = lambertRectIrradiance(L, s.p, s.n);
    float ratio = 1.0;
#ifdef SHADOWS
    float sumCos = 0.0, sumCosV = 0.0;
    for (int k = 0; k < spp; ++k) {
        vec3 wi;
        float dist, pdf;
        vec2 u = vec2(rand01(rng), rand01(rng));
        if (!lambertRectSample(L, s.p, u, wi, dist, pdf)) continue;
        float c = max(dot(s.n, wi), 0.0);
        if (c <= 0.0) continue;
        sumCos += c;
        sumCosV += c * visibility(s, wi, dist);
    }
    ratio = sumCos > 0.0 ? sumCosV / sumCos : 1.0;
#endif
    result = s.albedo / kPi * E * ratio;
#ifdef GLOSSY
    if ((s.flags & kMaterialGlossy) != 0) {
        vec3 g = vec3(0.0);
        for (int k = 0; k < spp; ++k) {
            vec3 wi;
            float dist, pdf;
            vec2 u = vec2(rand01(rng), rand01(rng));
            if (!lambertRectSample(L, s.p, u, wi, dist, pdf)) continue;
            float c = max(dot(s.n, wi), 0.0);
            if (c <= 0.0) continue;
            g += L.radiance.rgb * glossyBrdf(s, wi) * c * visibility(s, wi, dist) / pdf;
        }
        result += g / float(spp);
    }
#endif
    return result;
}

#include "lambertian_rect_main.glsl"
