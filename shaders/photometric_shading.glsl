// What every photometric technique's shader shares (Prost 2019; luminaires/Registry.cpp names
// one shader per technique, shaders/photometric_<technique>.frag, which defines
//   vec3 shadeTechnique(Surface s, vec3 p, vec3 n, int spp, inout uint rng)
// (the receiver p and its normal n in the opening's frame; the radiance towards the camera,
// before the table's colour) between an include of this file and of photometric_main.glsl).
// Variants every technique honours:
//   SHADOWS: the deterministic techniques are scaled by the irradiance-weighted visible fraction
//            of a few random points on the opening per frame (refined progressively, consistent);
//            the reference traces a shadow ray per sample.
//   SHADOW_MAPS: the deterministic techniques are scaled by the visibility of the opening from
//            the shadow maps at its centre and corners (their mean; the centre's alone for
//            `point`), deterministic and converged in one frame.
//   GLOSSY:  the Phong lobe through the area form: the reference's samples, or the same random
//            points for the deterministic techniques.
#include "shade_common.glsl"
#include "photometric.glsl"
#ifdef SHADOWS
#include "bvh_traverse.glsl"
#endif
#ifdef SHADOW_MAPS
#include "shadow_maps.glsl"
#endif

layout(location = 0) uniform int uLuminaire;
layout(location = 0) out vec4 outRadiance;

float visibleTo(Surface s, vec3 qLocal) {
#ifdef SHADOWS
    vec3 q = ph.position.xyz + phFromLocal(qLocal);
    return bvhOccluded(shadowOrigin(s), q) ? 0.0 : 1.0;
#else
    return 1.0;
#endif
}

/// Irradiance-weighted visibility and the glossy term from `count` random points on the opening
/// (area form) this frame: visibleFraction = sum(E_i V_i) / sum(E_i), which the progressive
/// accumulation refines (consistent, as the Lambertian rectangle's analytic technique), and an
/// unbiased estimate of the glossy lobe. Costs `count` shadow rays per pixel and frame.
void stochasticExtras(Surface s, vec3 p, vec3 n, int count, inout uint rng, out float visibleFraction,
                      out vec3 glossy) {
    visibleFraction = 1.0;
    glossy = vec3(0.0);
#if defined(SHADOWS) || defined(GLOSSY)
    int corners = ph.dims.z;
    float sumE = 0.0, sumEV = 0.0;
    vec2 lo, hi;
    phBounds(lo, hi);
    float ratio = corners >= 3 ? (hi.x - lo.x) * (hi.y - lo.y) / ph.position.w : 1.0;  // S_rect / A
    for (int i = 0; i < count; ++i) {
        vec2 u = vec2(rand01(rng), rand01(rng));
        vec3 q = corners >= 3 ? vec3(lo + u * (hi - lo), 0.0)
                              : (corners == 2 ? vec3(mix(phCorner(0), phCorner(1), u.x), 0.0) : vec3(0.0));
        if (corners >= 3 && !phInside(q.xy)) continue;
        float e = phPointIrradiance(p, n, q);
        if (!(e > 0.0)) continue;
        float v = visibleTo(s, q);
        sumE += e;
        sumEV += e * v;
#ifdef GLOSSY
        if ((s.flags & kMaterialGlossy) != 0)
            glossy += ratio * e * v * glossyBrdf(s, normalize(phFromLocal(q - p)));
#endif
    }
    if (sumE > 0.0) visibleFraction = sumEV / sumE;
    glossy /= float(max(count, 1));
#endif
#ifdef SHADOW_MAPS
    visibleFraction = shadowItemVisibility(0, s.p, s.n);
    glossy *= visibleFraction;
#endif
}

/// True when the irradiance at p is settled without the technique, in E: an opening under a
/// hundredth of its distance takes the point law, within (size / r)^2 ~ 1e-4 of the truth, where
/// the spherical polygons of 1e-4 rad and less cancel in float (a 1e-6 m opening 2 m away gave
/// 3800x its light; the C++ twins, in 64-bit floats, stay exact); a receiver where the opening
/// degenerates (phDegenerate) takes its limit.
bool phSettled(vec3 p, vec3 n, out float E) {
    if (ph.axisX.w < 0.01 * length(p)) {
        E = phPointIrradiance(p, n, vec3(0.0));
        return true;
    }
    return phDegenerate(p, n, E);
}

/// A deterministic technique's irradiance E at p made radiance: the diffuse part times the
/// visible fraction, plus the glossy lobe (stochasticExtras).
vec3 phShadeIrradiance(Surface s, vec3 p, vec3 n, int spp, inout uint rng, float E) {
    float visibleFraction;
    vec3 glossy;
    stochasticExtras(s, p, n, spp, rng, visibleFraction, glossy);
    return s.albedo / kPi * E * visibleFraction + glossy;
}
