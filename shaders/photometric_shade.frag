// Shades the G-buffer with one photometric area light (Prost 2019). Variants, one per technique:
//   TECHNIQUE_SCATTERED, TECHNIQUE_STRUCTURED, TECHNIQUE_MRP, TECHNIQUE_POISSON24,
//   TECHNIQUE_POISSON40, TECHNIQUE_POINT, TECHNIQUE_HYBRID: deterministic, converged in one frame;
//   TECHNIQUE_REFERENCE: Monte Carlo, progressive: opening points (Eq. 6.3), cosine directions and
//            directions in proportion to the table's intensity, balance heuristic.
//   SHADOWS: the deterministic techniques are scaled by the irradiance-weighted visible fraction
//            of a few random points on the opening per frame (refined progressively, consistent);
//            the reference traces a shadow ray per sample.
//   SHADOW_MAPS: the deterministic techniques are scaled by the visibility of the opening from
//            the shadow maps at its centre and corners (their mean; the centre's alone for
//            `point`), deterministic and converged in one frame.
//   GLOSSY:  the Phong lobe through the area form: the reference's samples, or the same random
//            points for the deterministic techniques.
// Output: this frame's radiance estimate, added into the accumulation buffer.
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

#ifdef TECHNIQUE_REFERENCE
/// One sample of the reference (PhotometricEstimators.cpp): the BRDF times f / (c.x pdf_area +
/// c.y pdf_cosine + c.z pdf_table) for the direction d toward opening point q at distance r,
/// multiplied through by cos_L so that it stays finite in the opening's plane; 0 outside the
/// opening or in shadow.
vec3 phMisTerm(Surface s, vec3 n, vec3 q, vec3 d, float r, float rect, vec3 c) {
    if (!phInside(q.xy)) return vec3(0.0);
    float cosP = dot(n, d), cosL = abs(d.z);
    if (!(cosP > 0.0) || !(ph.position.w > 0.0)) return vec3(0.0);
    float pdfTable = c.z > 0.0 ? phTablePdf(-d) : 0.0;
    float w = phIntensity(-d) * cosP / ph.position.w /
              (c.x * r * r / rect + c.y * cosL * cosP / kPi + c.z * cosL * pdfTable);
    if (!(w > 0.0) || isinf(w)) return vec3(0.0);
    vec3 brdf = s.albedo / kPi;
#ifdef GLOSSY
    if ((s.flags & kMaterialGlossy) != 0) brdf += glossyBrdf(s, normalize(phFromLocal(d)));
#endif
    return brdf * w * visibleTo(s, q);
}
#endif

void main() {
    Surface s;
    if (!loadSurface(s)) discard;
    vec3 p = phToLocal(s.p - ph.position.xyz);
    vec3 n = normalize(phToLocal(s.n));
    vec3 colour = ph.colour.rgb;
    vec3 result = vec3(0.0);
    int spp = frame.frameInfo.y;
    uint rng = rngSeed(uvec2(gl_FragCoord.xy), uint(frame.frameInfo.x * 7919 + uLuminaire) + uint(frame.seeds.x) * 2654435761u);

#ifdef TECHNIQUE_REFERENCE
    float degenerateE;
    if (phDegenerate(p, n, degenerateE)) {
        result = s.albedo / kPi * degenerateE;
    } else {
        // One of three strategies per sample, balance heuristic (PhotometricEstimators.cpp): a
        // point uniform on the bounding rectangle; a direction cosine-distributed about the normal
        // (probability the form factor, clamped to [0.05, 0.5], of three quarters); a direction in
        // proportion to the table's intensity (a quarter, where the table has any).
        vec2 lo, hi;
        phBounds(lo, hi);
        float rect = (hi.x - lo.x) * (hi.y - lo.y);
        PhPolygon seen = phClip(phOpening(p), n);
        float cTable = ph.samples.z != 0 ? 0.25 : 0.0;
        float cCosine = (1.0 - cTable) * clamp(seen.count >= 3 ? phProjectedSolidAngle(seen, n) / kPi : 0.0, 0.05, 0.5);
        vec3 c = vec3(1.0 - cTable - cCosine, cCosine, cTable);
        float sgn = n.z >= 0.0 ? 1.0 : -1.0, fa = -1.0 / (sgn + n.z), fb = n.x * n.y * fa;
        vec3 t = vec3(1.0 + sgn * n.x * n.x * fa, sgn * fb, -sgn * n.x), bt = vec3(fb, sgn + n.y * n.y * fa, -n.y);
        for (int k = 0; k < spp; ++k) {
            // Stratified over the pass's samples, as the C++ twin.
            float pick = min((float(k) + rand01(rng)) / float(spp), 0.99999994), u1 = rand01(rng), u2 = rand01(rng);
            if (pick < c.x) {
                vec3 q = vec3(lo + vec2(u1, u2) * (hi - lo), 0.0);
                vec3 v = q - p;
                float r = length(v);
                if (r > 0.0) result += phMisTerm(s, n, q, v / r, r, rect, c);
            } else {
                vec3 d;
                if (pick < c.x + c.y) {
                    float rad = sqrt(u1), phi = 2.0 * kPi * u2;
                    d = rad * cos(phi) * t + rad * sin(phi) * bt + sqrt(max(0.0, 1.0 - u1)) * n;
                } else {
                    // The table's direction leaves the opening toward the receiver: look back.
                    d = -phTableSample(min((pick - c.x - c.y) / c.z, 0.99999994), vec2(u1, u2));
                }
                if (abs(d.z) > 0.0) {
                    float along = -p.z / d.z;
                    vec3 hit = p + along * d;
                    if (along > 0.0 && all(greaterThanEqual(hit.xy, lo)) && all(lessThanEqual(hit.xy, hi)))
                        result += phMisTerm(s, n, vec3(hit.xy, 0.0), d, along, rect, c);
                }
            }
        }
        result /= float(spp);
    }
#else
    float E;
#if defined(TECHNIQUE_POINT)
    // A point light at the centre, whatever the opening's shape (as its C++ twin).
    E = phPointIrradiance(p, n, vec3(0.0));
#else
    if (ph.axisX.w < 0.01 * length(p)) {
        // An opening under a hundredth of its distance: the point law, within (size / r)^2 ~ 1e-4
        // of the truth, where the spherical polygons of 1e-4 rad and less cancel in float (a 1e-6
        // m opening 2 m away gave 3800x its light; the C++ twins, in double, stay exact).
        E = phPointIrradiance(p, n, vec3(0.0));
    } else if (!phDegenerate(p, n, E)) {
#if defined(TECHNIQUE_SCATTERED)
        int flips;
        E = phScattered(p, n, flips);
#elif defined(TECHNIQUE_STRUCTURED)
        E = phStructured(p, n);
#elif defined(TECHNIQUE_MRP)
        E = phMrp(p, n);
#elif defined(TECHNIQUE_POISSON24)
        E = phPoisson(p, n, ph.samples.x, 24);
#elif defined(TECHNIQUE_POISSON40)
        E = phPoisson(p, n, ph.samples.y, 40);
#elif defined(TECHNIQUE_HYBRID)
        int place, index;
        float distance = length(phClosest(phOpening(p), vec3(0.0), 0.0, place, index));
        float w = phHybridWeight(distance);
        int flips;
        float nearE = w < 1.0 ? phScattered(p, n, flips) : 0.0;
        float farE = w > 0.0 ? phPoisson(p, n, ph.samples.x, 24) : 0.0;
        E = mix(nearE, farE, w);
#endif
    }
#endif
#ifdef TECHNIQUE_POINT
    // The point technique is a point light: its shadows and highlights come from the centre.
    float visibleFraction = visibleTo(s, vec3(0.0));
#ifdef SHADOW_MAPS
    visibleFraction = shadowItemVisibility(1, s.p, s.n);
#endif
    vec3 glossy = vec3(0.0);
#ifdef GLOSSY
    if ((s.flags & kMaterialGlossy) != 0) glossy = E * visibleFraction * glossyBrdf(s, normalize(phFromLocal(-p)));
#endif
#else
    float visibleFraction;
    vec3 glossy;
    stochasticExtras(s, p, n, spp, rng, visibleFraction, glossy);
#endif
    result = s.albedo / kPi * E * visibleFraction + glossy;
#endif
    result *= colour;
    // Hard cases must never poison the accumulation: drop non-finite estimates.
    if (any(isnan(result)) || any(isinf(result))) result = vec3(0.0);
    outRadiance = vec4(result, 1.0);
}
