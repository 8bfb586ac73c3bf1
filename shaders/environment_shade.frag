// Shades the G-buffer with the environment map (Algorithm 2 of Lu et al. 2013). Variants:
//   TECHNIQUE_BALANCED       Eq. (4)-(5): N_f = mu_f(n) N_s fractional samples per face, mu_f of
//                            Eq. (3), the last one weighted by beta = frac(N_f);
//   INTEGER_FACE_COUNTS      with TECHNIQUE_BALANCED: N_f rounded to whole samples (the
//                            popping baseline of the temporal-stability bench);
//   TECHNIQUE_UNIFORM_FACES  the same with mu_f = 1/6 (Fig. 2's baseline);
//   TECHNIQUE_BALANCED_MIS   Eq. (6): N_s/2 balanced light samples and N_s/2 BRDF samples
//                            (cosine lobe, and the Phong lobe on glossy materials), balance
//                            heuristic;
//   TECHNIQUE_GLOBAL_CDF     one CDF over the lat-long map (built on the CPU when the map
//                            changes, as static-map renderers do), per-pixel samples;
//   TECHNIQUE_HAVRAN         the filtered directional lights of Havran et al. 2005 (CPU);
//   SHADOWS                  a shadow ray per sample through the scene BVH;
//   SHADOW_MAPS              with TECHNIQUE_HAVRAN: one directional shadow map per light;
//   GLOSSY                   the scene has glossy materials: add the Phong lobe.
// The light samples of the face techniques are the pools drawn before shading
// (environment_cdf.comp, PASS_SAMPLES), shared by all pixels; each pixel starts at a random
// place in each pool (the interleaving the paper suggests against its spatial bias), so its
// estimate is unbiased and neighbours' errors are not all alike. Background pixels show the map.
#include "shade_common.glsl"
#include "environment.glsl"
#ifdef SHADOWS
#include "bvh_traverse.glsl"
#endif
#ifdef SHADOW_MAPS
#include "shadow_directional.glsl"
#endif

#if defined(TECHNIQUE_GLOBAL_CDF)
// [0 .. H]: CDF over rows; then per row y, [H + 1 + y (W + 1) ..]: CDF over columns.
layout(std430, binding = 13) readonly buffer EnvExtra { float envGlobal[]; };
#elif defined(TECHNIQUE_HAVRAN)
// Per light: direction (xyz), then power (rgb irradiance at normal incidence, W/m2).
layout(std430, binding = 13) readonly buffer EnvExtra { vec4 envLights[]; };
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

vec3 brdf(Surface s, vec3 wi) {
    vec3 f = s.albedo / kPi;
#ifdef GLOSSY
    if ((s.flags & kMaterialGlossy) != 0) f += glossyBrdf(s, wi);
#endif
    return f;
}

/// radiance x BRDF x cosine x visibility for a direction with a positive cosine, else 0.
vec3 integrand(Surface s, vec3 w, vec3 radiance) {
    float c = dot(s.n, w);
    if (!(c > 0.0)) return vec3(0.0);
    return radiance * brdf(s, w) * c * envVisibility(s, w);
}

#if defined(TECHNIQUE_BALANCED) || defined(TECHNIQUE_UNIFORM_FACES) || defined(TECHNIQUE_BALANCED_MIS)
/// Sample i of face f's pool, starting at `start`.
EnvironmentSampleGpu poolSample(int f, int start, int i) {
    int pool = env.dims.w;
    return envSamples[f * pool + (start + i) % pool];
}
#endif

#ifdef TECHNIQUE_BALANCED_MIS
/// Probability of choosing the diffuse lobe among the BRDF's lobes.
float diffuseShare(Surface s) {
#ifdef GLOSSY
    if ((s.flags & kMaterialGlossy) != 0) {
        float d = luminance(s.albedo), g = luminance(s.specular);
        return d + g > 0.0 ? d / (d + g) : 1.0;
    }
#endif
    return 1.0;
}

/// pdf_B: the cosine lobe (cos / pi) and the Phong lobe about the mirror direction
/// ((e + 1) / (2 pi) cos^e), mixed by diffuseShare.
float brdfPdf(Surface s, vec3 w, float share) {
    float pd = share * max(dot(s.n, w), 0.0) / kPi;
    if (share < 1.0) {
        vec3 r = reflect(-s.wo, s.n);
        pd += (1.0 - share) * (s.exponent + 1.0) / (2.0 * kPi) * pow(max(dot(r, w), 0.0), s.exponent);
    }
    return pd;
}

/// A direction about axis z with cos(theta) = u1^(1/(e+1)): pdf (e + 1) / (2 pi) cos^e(theta)
/// (e = 1 is the cosine lobe, pdf cos / pi).
vec3 lobeSample(vec3 z, float e, float u1, float u2) {
    float cosT = pow(u1, 1.0 / (e + 1.0));
    float sinT = sqrt(max(0.0, 1.0 - cosT * cosT));
    float phi = 2.0 * kPi * u2;
    vec3 t = normalize(abs(z.x) > 0.5 ? cross(z, vec3(0.0, 1.0, 0.0)) : cross(z, vec3(1.0, 0.0, 0.0)));
    vec3 b = cross(z, t);
    return normalize(sinT * cos(phi) * t + sinT * sin(phi) * b + cosT * z);
}
#endif

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    Surface s;
    if (!loadSurface(s)) {
        if (texelFetch(gPosition, px, 0).w == 0.0 && env.params.y > 0.5) {
            // Background: the map along the view ray, exact (the mean of constant frames).
            vec2 ndc = gl_FragCoord.xy * frame.viewport.zw * 2.0 - 1.0;
            vec4 far = frame.invViewProj * vec4(ndc, 1.0, 1.0);
            outRadiance = vec4(envRadiance(far.xyz / far.w - frame.cameraPos.xyz), 1.0);
            return;
        }
        discard;
    }
    int ns = frame.frameInfo.y;
    uint rng = rngSeed(uvec2(px), uint(frame.frameInfo.x * 7919 + 104729) + uint(frame.seeds.x) * 2654435761u);
    vec3 result = vec3(0.0);

#if defined(TECHNIQUE_BALANCED) || defined(TECHNIQUE_UNIFORM_FACES)
    float mu[6];
#ifdef TECHNIQUE_BALANCED
    envBalance(s.n, mu);
#ifdef INTEGER_FACE_COUNTS
    // The baseline the fractional counts replace: whole samples per face (biased, pops).
    for (int f = 0; f < 6; ++f) mu[f] = round(mu[f] * float(ns)) / float(ns);
#endif
#else
    for (int f = 0; f < 6; ++f) mu[f] = 1.0 / 6.0;
#endif
    for (int f = 0; f < 6; ++f) {
        float nf = mu[f] * float(ns);  // N_f(n), fractional (Eq. 4)
        if (!(nf > 0.0)) continue;
        int count = int(ceil(nf));
        int start = int(rand01(rng) * float(env.dims.w));
        for (int i = 0; i < count; ++i) {
            float beta = float(i + 1) <= nf ? 1.0 : nf - floor(nf);  // Eq. (5)
            EnvironmentSampleGpu smp = poolSample(f, start, i);
            float pdf = smp.direction.w;
            if (!(pdf > 0.0)) continue;
            result += beta * integrand(s, smp.direction.xyz, smp.radiance.rgb) / (mu[f] * pdf);
        }
    }
    result /= float(ns);
#elif defined(TECHNIQUE_BALANCED_MIS)
    float mu[6];
    envBalance(s.n, mu);
    float share = diffuseShare(s);
    for (int f = 0; f < 6; ++f) {
        float nf = 0.5 * mu[f] * float(ns);
        if (!(nf > 0.0)) continue;
        int count = int(ceil(nf));
        int start = int(rand01(rng) * float(env.dims.w));
        for (int i = 0; i < count; ++i) {
            float beta = float(i + 1) <= nf ? 1.0 : nf - floor(nf);
            EnvironmentSampleGpu smp = poolSample(f, start, i);
            float pdf = smp.direction.w;
            if (!(pdf > 0.0)) continue;
            vec3 w = smp.direction.xyz;
            float denom = 0.5 * mu[f] * pdf + 0.5 * brdfPdf(s, w, share);
            result += beta * integrand(s, w, smp.radiance.rgb) / denom;
        }
    }
    float nb = 0.5 * float(ns);
    int countB = int(ceil(nb));
    vec3 mirror = reflect(-s.wo, s.n);
    for (int i = 0; i < countB; ++i) {
        float beta = float(i + 1) <= nb ? 1.0 : nb - floor(nb);
        float u0 = rand01(rng), u1 = rand01(rng), u2 = rand01(rng);
        vec3 w = u0 < share ? lobeSample(s.n, 1.0, u1, u2) : lobeSample(mirror, s.exponent, u1, u2);
        float denom = 0.5 * envPdf(mu, w) + 0.5 * brdfPdf(s, w, share);
        if (!(denom > 0.0)) continue;
        result += beta * integrand(s, w, envRadiance(w)) / denom;
    }
    result /= float(ns);
#elif defined(TECHNIQUE_GLOBAL_CDF)
    int W = env.dims.x, H = env.dims.y;
    for (int k = 0; k < ns; ++k) {
        float u1 = rand01(rng), u2 = rand01(rng);
        int lo = 0, hi = H;
        while (hi - lo > 1) {
            int mid = (lo + hi) >> 1;
            if (envGlobal[mid] <= u1) lo = mid; else hi = mid;
        }
        int y = lo;
        float py = envGlobal[y + 1] - envGlobal[y];
        if (!(py > 0.0)) continue;
        float fy = clamp((u1 - envGlobal[y]) / py, 0.0, 1.0);
        int base = H + 1 + y * (W + 1);
        lo = 0;
        hi = W;
        while (hi - lo > 1) {
            int mid = (lo + hi) >> 1;
            if (envGlobal[base + mid] <= u2) lo = mid; else hi = mid;
        }
        int x = lo;
        float px_ = envGlobal[base + x + 1] - envGlobal[base + x];
        if (!(px_ > 0.0)) continue;
        float fx = clamp((u2 - envGlobal[base + x]) / px_, 0.0, 1.0);
        // Uniform in solid angle inside the texel: phi linear, cos(theta) linear.
        float c0 = cos(kPi * float(y) / float(H)), c1 = cos(kPi * float(y + 1) / float(H));
        float cosT = clamp(c0 - fy * (c0 - c1), -1.0, 1.0);
        float sinT = sqrt(max(0.0, 1.0 - cosT * cosT));
        float phi = 2.0 * kPi * (float(x) + fx) / float(W) + env.params.x;
        vec3 w = vec3(sinT * cos(phi), cosT, sinT * sin(phi));
        float t0 = kPi * float(y) / float(H), t1 = kPi * float(y + 1) / float(H);
        float omega = 2.0 * kPi / float(W) * 2.0 * sin(0.5 * (t0 + t1)) * sin(0.5 * (t1 - t0));
        result += integrand(s, w, texelFetch(uEnvMap, ivec2(x, y), 0).rgb) * omega / (py * px_);
    }
    result /= float(ns);
#elif defined(TECHNIQUE_HAVRAN)
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
#endif
    // Hard cases must never poison the accumulation: drop non-finite estimates.
    if (any(isnan(result)) || any(isinf(result))) result = vec3(0.0);
    outRadiance = vec4(result, 1.0);
}
