// Shades the G-buffer with one light-field luminaire (Lu et al. 2015). Variants:
//   TECHNIQUE_RESTRICTED  position-dependent restricted CDFs with balancing (Eq. 8, 12, 14)
//   TECHNIQUE_UNIFORM     uniform samples in the same restricted boxes (Fig. 12 baseline)
//   TECHNIQUE_GLOBAL      one CDF per image over the whole image, the same for every pixel
//                         (Fig. 11 baseline, "precomputed global light importance sampling")
//   TECHNIQUE_GRANIER     Granier et al. 2003, Eq. 14: one textured spot light per basis function
//                         at its node, C_m averaged over the support's footprint (deterministic)
//   SHADOWS               one shadow ray per sample through the scene BVH (exact visibility:
//                         restricted-cdf-raytraced)
//   SHADOW_MAPS           per-cell shadow maps (Sec. 6.2): each image C_m's samples are scaled
//                         by its visibility v_m(p), averaged over the maps of its 9 cells
//   GLOSSY                the scene has glossy materials: add the Phong lobe
// K samples per pixel per frame are spread over the images in proportion to A_m(p) (Eq. 12) by
// systematic sampling with one random offset per pixel and frame, which makes the counts the
// nearest integers of K A_m / A and keeps the estimator unbiased; at most K_max samples are
// taken per image (Fig. 9), reweighted. Sample positions come from one Halton sequence shared
// by all pixels (Sec. 6.3): each image uses its first points, rotated by a random offset per
// pixel and frame (the jitter that trades structure for noise and keeps every frame's estimate
// independent and unbiased). Output: this frame's radiance estimate, added to the accumulation
// buffer.
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

vec3 brdf(Surface s, vec3 wi) {
    vec3 f = s.albedo / kPi;
#ifdef GLOSSY
    if ((s.flags & kMaterialGlossy) != 0) f += glossyBrdf(s, wi);
#endif
    return f;
}

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

/// Image weight for the balancing: A_m(p) in its restricted box, or the image's whole energy.
double imageWeight(int m, vec3 q, out vec2 a, out vec2 b) {
#ifdef TECHNIQUE_GLOBAL
    a = lfImageMin();
    b = lfImageMax();
    return lfSatEntry(m, lf.dims.z, lf.dims.w);
#else
    if (!lfRestrictedBox(m, q, a, b)) return 0.0;
    return lfBoxIntegral(m, a, b);
#endif
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

/// Granier et al. 2003 (seed 001, Eq. 14), as luminaires/LightFieldEstimators.cpp.
/// On S (onS) the footprints shrink to the receiver's point, and each mean to the pixel there:
/// the limit from beyond S, as the C++ twin.
vec3 shadeGranier(Surface s, vec3 q, vec3 nl, bool onS) {
    vec3 sum = vec3(0.0);
    float phiIntegral = lf.geometry.y * lf.geometry.z;
    if (onS) q.z = lfDelta();
    for (int m = 0; m < lfImageCount(); ++m) {
        vec2 a, b;
        float scale = (q.z - lfDelta()) / q.z, mean;
        if (onS) {
            a = b = q.xy;
            mean = lfLum(m, q.xy);
        } else {
            if (!lfRestrictedBox(m, q, a, b)) continue;
            // Mean over the support's whole footprint on S (C_m is 0 where it leaves the image).
            float footprint = 9.0 * lf.geometry.y * lf.geometry.z * scale * scale;
            mean = float(lfBoxIntegral(m, a, b)) / footprint;
        }
        if (!(mean > 0.0)) continue;
        vec2 node = lfNode(m);
        vec3 d = vec3(node - q.xy, -q.z);
        float dist = length(d);
        vec3 wl = d / dist;
        float cosR = dot(nl, wl), cosL = q.z / dist;
        if (cosR <= 0.0) continue;
        vec2 centre = 0.5 * (a + b);
        float model = lfPsi(m, node, centre) / 0.5625;  // Phi_m at its node is 0.75^2
        vec3 wi = normalize(wl.x * lf.axisX.xyz + wl.y * lf.axisY.xyz + wl.z * lf.axisZ.xyz);
        // The far-field correction W_m / U_m, blended in with the footprint's area (the C++ twin,
        // LightFieldEstimators.cpp, says why).
        vec2 farCentre = node + (q.xy - node) * (lfDelta() / q.z), half_ = 1.5 * lf.geometry.yz;
        float uniform_ = float(lfBoxIntegral(m, farCentre - half_, farCentre + half_)) / 9.0;
        float weighted = lfGranierWeighted(m, farCentre), blend = scale * scale;
        float conserve = uniform_ > 0.0 && weighted >= 0.0 ? (1.0 - blend) + blend * weighted / uniform_ : 1.0;
        sum += conserve * phiIntegral * mean * model * cosR * cosL / (dist * dist) * lfColour(m, centre) * brdf(s, wi) *
               visibility(s, toWorld(vec3(node, 0.0))) * imageVisibility(s, m);
    }
    return sum;
}

void main() {
    Surface s;
    if (!loadSurface(s)) discard;
    int K = frame.frameInfo.y;
    uvec2 pixel = uvec2(gl_FragCoord.xy);
    uint rng = rngSeed(pixel, uint(frame.frameInfo.x * 7919 + uLuminaire) + uint(frame.seeds.x) * 2654435761u);
    float offset = rand01(rng);  // systematic sampling over the images
    // A new random rotation of the shared Halton points per pixel and frame. (A rotation kept
    // across frames with the index running on would confine each image's points: image m holds
    // the same slots of every frame's block of K indices, so their base-2 digits below K repeat
    // and its samples never leave one dyadic strip. Each pixel would then converge to a wrong
    // value, right only on average over pixels.)
    vec2 shift = vec2(rand01(rng), rand01(rng));

    vec3 d = s.p - lf.position.xyz;
    vec3 q = vec3(dot(d, lf.axisX.xyz), dot(d, lf.axisY.xyz), dot(d, lf.axisZ.xyz));
    vec3 nl = vec3(dot(s.n, lf.axisX.xyz), dot(s.n, lf.axisY.xyz), dot(s.n, lf.axisZ.xyz));
    float dz = q.z - lfDelta();
    // Closer to S than float coordinates resolve the restricted boxes, on either side (a receiver
    // on S has a rounded position): p on S (Eq. 9), the limit the irradiance tends to. The C++
    // twin (LightFieldEstimators.cpp) does the same within its double rounding.
    bool onS = abs(dz) < 1e-5 * max(q.z, 1e-3);
    vec3 result = vec3(0.0);
    if (dz < 0.0 && !onS) {
        // Behind S or between U and S: no light.
#ifdef TECHNIQUE_GRANIER
    } else if (true) {
        result = shadeGranier(s, q, nl, onS);
#endif
    } else if (onS) {
        result = shadeOnS(s, q, nl, K, shift, offset);
    } else {
        int M = lfImageCount();
        // Step 1 of Sec. 6.1: A_m(p) for every image and their sum A(p); kept for step 2 (up to
        // kCached images; beyond that step 2 recomputes them).
        const int kCached = 128;
        float cached[kCached];
        double A = 0.0;
        for (int m = 0; m < M; ++m) {
            vec2 a, b;
            double w = imageWeight(m, q, a, b);
            if (m < kCached) {
                cached[m] = float(w);
                w = double(cached[m]);  // step 2 reads the float: sum the same values
            }
            A += w;
        }
        if (A > 0.0) {
            double cum = 0.0;
            for (int m = 0; m < M; ++m) {
                vec2 a, b;
                double Am;
                if (m < kCached) {
                    Am = double(cached[m]);
                    if (!(Am > 0.0)) continue;
#ifdef TECHNIQUE_GLOBAL
                    a = lfImageMin();
                    b = lfImageMax();
#else
                    lfRestrictedBox(m, q, a, b);
#endif
                } else {
                    Am = imageWeight(m, q, a, b);
                    if (!(Am > 0.0)) continue;
                }
                // Slots k with (k + offset) / K * A in [cum, cum + A_m) go to image m.
                int k0 = int(ceil(float(cum / A) * float(K) - offset));
                cum += Am;
                int k1 = int(ceil(float(cum / A) * float(K) - offset));
                int Km = k1 - k0;
                if (Km <= 0) continue;
                int n = lf.options.x > 0 ? min(Km, lf.options.x) : Km;
                float vm = imageVisibility(s, m);
                if (!(vm > 0.0)) continue;
                // Each slot is worth A / K; n samples stand for Km slots.
                float weight = vm * float(A) / float(K) * float(Km) / float(n);
#ifdef TECHNIQUE_UNIFORM
                float boxArea = (b.x - a.x) * (b.y - a.y);
#endif
                for (int k = k0; k < k0 + n; ++k) {
                    uint index = uint(k - k0 + 1);  // the image's own points, 1..n, this frame
                    vec2 xi = fract(vec2(lfHalton2(index), lfHalton3(index)) + shift);
                    vec2 sp;
                    float scale;  // (f / pdf) without Psi c cos Delta / r^3, over A
#ifdef TECHNIQUE_UNIFORM
                    sp = a + xi * (b - a);
                    float c = lfLum(m, sp);
                    if (!(c > 0.0)) continue;
                    scale = c * boxArea / float(Am);
#else
                    if (!lfSampleBox(m, a, b, xi, sp)) continue;
                    scale = 1.0;
#endif
                    vec3 dl = vec3(sp - q.xy, -dz);
                    float r = length(dl);
                    vec3 wl = dl / r;
                    float cosR = dot(nl, wl);
                    if (cosR <= 0.0) continue;
                    vec2 u = q.xy + (sp - q.xy) * (q.z / dz);
                    float psi = lfPsi(m, u, sp);
                    if (psi <= 0.0) continue;
                    vec3 wi = normalize(wl.x * lf.axisX.xyz + wl.y * lf.axisY.xyz + wl.z * lf.axisZ.xyz);
                    // Eq. (14): rho_k v_k c_m(s_k) Psi_m / r^3, times Delta and the weight.
                    float term = weight * scale * psi * cosR * dz / (r * r * r);
                    result += term * lfColour(m, sp) * brdf(s, wi) *
                              visibility(s, toWorld(vec3(sp, lfDelta())));
                }
            }
        }
    }
    if (any(isnan(result)) || any(isinf(result))) result = vec3(0.0);
    outRadiance = vec4(result, 1.0);
}
