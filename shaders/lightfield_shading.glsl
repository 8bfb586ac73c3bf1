// What every light-field technique's shader shares (Lu et al. 2015); luminaires/Registry.cpp
// names one shader per technique, shaders/lightfield_<technique>.frag, which defines
//   vec3 shadeTechnique(Surface s, vec3 q, vec3 nl, bool onS, int K, vec2 shift, float offset)
// (q and nl the receiver and its normal in the luminaire's frame, onS true when q is within
// float rounding of S; K samples, the pixel's Halton rotation and systematic-sampling offset)
// between an include of this file and of lightfield_main.glsl. Variants every technique honours:
//   SHADOWS               one shadow ray per sample through the scene BVH (exact visibility:
//                         restricted-cdf-raytraced)
//   SHADOW_MAPS           per-cell shadow maps (Sec. 6.2): each image C_m's samples are scaled
//                         by its visibility v_m(p), averaged over the maps of its 9 cells
//   GLOSSY                the scene has glossy materials: add the Phong lobe
#include "shade_common.glsl"
#include "lightfield.glsl"
#ifdef SHADOWS
#include "bvh_traverse.glsl"
#endif
#ifdef SHADOW_MAPS
#include "shadow_maps.glsl"
#endif

layout(location = 0) uniform int uLuminaire;
layout(location = 0) out vec4 outRadiance;


float visibility(Surface s, vec3 target) {
#ifdef SHADOWS
    return bvhOccluded(shadowOrigin(s), target) ? 0.0 : 1.0;
#else
    return 1.0;
#endif
}

/// v_m(p) of Sec. 6.2 from the shadow maps; 1 without them.
float imageVisibility(Surface s, int m) {
#ifdef SHADOW_MAPS
    return shadowItemVisibility(m, s.p, s.n);
#else
    return 1.0;
#endif
}

vec3 toWorld(vec3 local) {
    return lf.position.xyz + local.x * lf.axisX.xyz + local.y * lf.axisY.xyz + local.z * lf.axisZ.xyz;
}

/// Eq. (9): p on S. u uniform over each support, images chosen in proportion to C_m(p).
vec3 shadeOnS(Surface s, vec3 q, vec3 nl, int K, vec2 shift, float offset) {
    int M = lfImageCount();
    float total = 0.0;
    for (int m = 0; m < M; ++m) total += lfLum(m, q.xy);
    if (!(total > 0.0)) return vec3(0.0);
    vec2 h = lf.geometry.yz;
    float area = 9.0 * h.x * h.y;
    vec3 sum = vec3(0.0);
    float cum = 0.0;
    for (int m = 0; m < M; ++m) {
        float c = lfLum(m, q.xy);
        if (!(c > 0.0)) continue;
        int k0 = int(ceil(cum / total * float(K) - offset));
        cum += c;
        int k1 = int(ceil(cum / total * float(K) - offset));
        float vm = k1 > k0 ? imageVisibility(s, m) : 0.0;
        if (!(vm > 0.0)) continue;
        for (int k = k0; k < k1; ++k) {
            uint index = uint(k - k0 + 1);
            vec2 xi = fract(vec2(lfHalton2(index), lfHalton3(index)) + shift);
            vec2 u = lfNode(m) - 1.5 * h + xi * 3.0 * h;
            vec3 d = vec3(u - q.xy, -q.z);
            float r = length(d);
            vec3 wl = d / r;
            float cosR = dot(nl, wl);
            if (cosR <= 0.0) continue;
            vec3 wi = normalize(wl.x * lf.axisX.xyz + wl.y * lf.axisY.xyz + wl.z * lf.axisZ.xyz);
            float term = total * area * lfPsi(m, u, q.xy) * lfDelta() * cosR / (r * r * r);
            sum += term * vm * lfColour(m, q.xy) * brdf(s, wi) * visibility(s, toWorld(vec3(u, 0.0)));
        }
    }
    return sum / float(K);
}

/// Granier et al. 2003 (seed 001, Eq. 14), as luminaires/lightfield/LightFieldEstimators.cpp.
