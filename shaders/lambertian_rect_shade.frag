// Shades the G-buffer with one Lambertian rectangle. Variants:
//   TECHNIQUE_ANALYTIC  closed-form polygon irradiance (Baum et al. 1989) for the diffuse part;
//                       with SHADOWS it is scaled by a stochastic visibility ratio
//                       sum(cos V) / sum(cos) over solid-angle samples (consistent, not unbiased).
//   TECHNIQUE_REFERENCE Monte Carlo, samples uniform in solid angle (Urena et al. 2013).
//   SHADOWS             trace shadow rays through the scene BVH.
//   GLOSSY              the scene has glossy materials: add the Phong lobe by light sampling.
// Output is this frame's radiance estimate, added into the accumulation buffer.
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

void main() {
    Surface s;
    if (!loadSurface(s)) discard;
    LambertianRectGpu L = lights[uLuminaire];
    int spp = frame.frameInfo.y;
    uint rng = rngSeed(uvec2(gl_FragCoord.xy), uint(frame.frameInfo.x * 7919 + uLuminaire) + uint(frame.seeds.x) * 2654435761u);
    vec3 result = vec3(0.0);

#ifdef TECHNIQUE_ANALYTIC
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
#else  // TECHNIQUE_REFERENCE
    for (int k = 0; k < spp; ++k) {
        vec3 wi;
        float dist, pdf;
        vec2 u = vec2(rand01(rng), rand01(rng));
        if (!lambertRectSample(L, s.p, u, wi, dist, pdf)) continue;
        float c = max(dot(s.n, wi), 0.0);
        if (c <= 0.0) continue;
        vec3 f = s.albedo / kPi;
#ifdef GLOSSY
        if ((s.flags & kMaterialGlossy) != 0) f += glossyBrdf(s, wi);
#endif
        result += L.radiance.rgb * f * c * visibility(s, wi, dist) / pdf;
    }
    result /= float(spp);
#endif
    // Hard cases must never poison the accumulation: drop non-finite estimates.
    if (any(isnan(result)) || any(isinf(result))) result = vec3(0.0);
    outRadiance = vec4(result, 1.0);
}
