// The environment map on the GPU: the lat-long map, the cube-face frames and the per-face
// tables built each time the map changes (environment_cdf.comp, Algorithm 1 of Lu et al. 2013).
// Mirrors luminaires/environment/EnvironmentSampling.cpp (the CPU reference): same face layout (OpenEXR
// envmap=cube), same texel weights, same piecewise-constant CDFs, so pdfs agree.
#include "common.glsl"
#include "shared/CubeFaces.h"
#include "ff.glsl"

layout(std140, binding = 4) uniform EnvironmentBlock { EnvironmentGpu env; };
layout(binding = 5) uniform sampler2D uEnvMap;  // kUnitEnvironmentMap: RGB32F, row 0 = v = 0

layout(std430, binding = 8) buffer EnvCube { vec2 envCube[]; };            // [f][row][col]
layout(std430, binding = 11) buffer EnvFaces { EnvironmentFaceGpu envFaces[6]; };

// The CDFs are textures of float-float pairs (ff.glsl, see envRand48; layout in
// shared/GpuTypes.h, kUnitEnvRowCdf): the passes that build them (ENV_WRITES_TABLES) reach them
// through image units, everything else reads them with texelFetch.
#ifdef ENV_WRITES_TABLES
layout(rg32f, binding = 0) uniform image2DArray envRowCdfImage;  // kImageEnvRowCdf
layout(rg32f, binding = 1) uniform image2D envColumnCdfImage;    // kImageEnvColumnCdf
vec2 envRowCdfAt(int f, int c, int i) { return imageLoad(envRowCdfImage, ivec3(i, c, f)).xy; }
vec2 envColumnCdfAt(int row, int i) { return imageLoad(envColumnCdfImage, ivec2(i, row)).xy; }
#else
layout(binding = 11) uniform sampler2DArray uEnvRowCdf;  // kUnitEnvRowCdf
layout(binding = 12) uniform sampler2D uEnvColumnCdf;    // kUnitEnvColumnCdf
vec2 envRowCdfAt(int f, int c, int i) { return texelFetch(uEnvRowCdf, ivec3(i, c, f), 0).xy; }
vec2 envColumnCdfAt(int row, int i) { return texelFetch(uEnvColumnCdf, ivec2(i, row), 0).xy; }
#endif
layout(std430, binding = 12) buffer EnvSamples { EnvironmentSampleGpu envSamples[]; };

// Face frames (centre, right = +col, down = +row): shared/CubeFaces.h.
vec3 envFaceDirection(int f, float a, float b) {
    return normalize(kCubeFaceCentre[f] + a * kCubeFaceRight[f] + b * kCubeFaceDown[f]);
}

/// Face of a direction (largest |component|, ties in the order x, y, z) and its face
/// coordinates in [-1, 1]^2; -1 for a zero direction.
int envFaceOf(vec3 w, out vec2 ab) {
    vec3 aw = abs(w);
    int f;
    float major;
    if (aw.x >= aw.y && aw.x >= aw.z) {
        f = w.x > 0.0 ? 0 : 1;
        major = aw.x;
    } else if (aw.y >= aw.z) {
        f = w.y > 0.0 ? 2 : 3;
        major = aw.y;
    } else {
        f = w.z > 0.0 ? 4 : 5;
        major = aw.z;
    }
    ab = vec2(0.0);
    if (!(major > 0.0)) return -1;
    vec3 d = w / major;
    ab = clamp(vec2(dot(d, kCubeFaceRight[f]), dot(d, kCubeFaceDown[f])), -1.0, 1.0);
    return f;
}

/// (u, v) of a direction under the scene-file convention (EnvironmentMap::uvOf).
vec2 envUv(vec3 w) {
    vec3 d = normalize(w);
    // atan of sine and cosine, never acos: NVIDIA's acos is a cubic fit off by up to 7e-5 rad
    // (seen on an H200: face sums 0.3 % high, texels in their neighbours' columns).
    float theta = atan(length(d.xz), d.y);
    float phi = atan(d.z, d.x);
    float u = (phi - env.params.x) / (2.0 * kPi);
    return vec2(u - floor(u), theta / kPi);
}

ivec2 envTexelOf(vec3 w) {
    vec2 uv = envUv(w);
    return clamp(ivec2(uv * vec2(env.dims.xy)), ivec2(0), env.dims.xy - 1);
}

/// Radiance of the map towards w: exactly the texel's value (no filtering).
vec3 envRadiance(vec3 w) { return texelFetch(uEnvMap, envTexelOf(w), 0).rgb; }

/// Exact solid angle of texel (col, row) of a face of N^2 texels, as two spherical triangles
/// (Van Oosterom and Strackee 1983): the triple product of the corner vectors is da db exactly
/// (the face plane is at distance 1), so nothing cancels in float, unlike a difference of
/// corner atans.
float envTexelSolidAngle(int col, int row, int n) {
    float a0 = -1.0 + 2.0 * float(col) / float(n), a1 = -1.0 + 2.0 * float(col + 1) / float(n);
    float b0 = -1.0 + 2.0 * float(row) / float(n), b1 = -1.0 + 2.0 * float(row + 1) / float(n);
    vec3 p00 = vec3(a0, b0, 1.0), p10 = vec3(a1, b0, 1.0), p11 = vec3(a1, b1, 1.0), p01 = vec3(a0, b1, 1.0);
    float l00 = length(p00), l10 = length(p10), l11 = length(p11), l01 = length(p01);
    float det = (a1 - a0) * (b1 - b0);
    float d1 = l00 * l10 * l11 + dot(p00, p10) * l11 + dot(p10, p11) * l00 + dot(p11, p00) * l10;
    float d2 = l00 * l11 * l01 + dot(p00, p11) * l01 + dot(p11, p01) * l00 + dot(p01, p00) * l11;
    return 2.0 * atan(det, d1) + 2.0 * atan(det, d2);
}

/// The CDFs hold about 48 bits (float-float pairs) and are drawn with 48-bit uniforms: in float, a
/// texel 1e8 times dimmer than a sun on the same face has a probability below the CDF's
/// resolution near 1 (6e-8), so it would be sampled at the wrong rate (a measured +12 % bias
/// facing away from such a sun).
vec2 envRand48(inout uint state) {
    float hi = rand01(state), lo = rand01(state);
    return ffFastTwoSum(hi, lo * (1.0 / 16777216.0));
}

/// Entry i of face f's CDF(u) (column < 0) or of CDF(v | u) of a column.
vec2 envCdfAt(int f, int column, int i) {
    return column < 0 ? envColumnCdfAt(f, i) : envRowCdfAt(f, column, i);
}

/// Index of the CDF piece holding u: cdf[i] <= u < cdf[i + 1] over the n + 1 entries of face
/// f's CDF(u) (column < 0) or CDF(v | u) (non-empty pieces only), and u's fraction inside it.
int envSearch(int f, int column, int n, vec2 u, out float fraction) {
    int lo = 0, hi = n;  // invariant: cdf[lo] <= u < cdf[hi] (cdf[n] = 1 > u)
    while (hi - lo > 1) {
        int mid = (lo + hi) >> 1;
        if (ffLessEqual(envCdfAt(f, column, mid), u)) lo = mid; else hi = mid;
    }
    vec2 left = envCdfAt(f, column, lo);
    float w = ffToFloat(ffSub(envCdfAt(f, column, lo + 1), left));
    fraction = w > 0.0 ? clamp(ffToFloat(ffSub(u, left)) / w, 0.0, 1.0) : 0.5;
    return lo;
}

/// Probability of piece i of a CDF (its difference, rounded once).
float envPieceProbability(int f, int column, int i) {
    return ffToFloat(ffSub(envCdfAt(f, column, i + 1), envCdfAt(f, column, i)));
}

/// I_f of Eq. (3).
float envFaceImportance(int f) { return envFaces[f].totals.x; }

/// pdf_L(w | f) of a point (a, b) of texel (c, r) of face f, 1/sr: the texel's probability (CDF
/// differences, what the sampler draws) over its area on the face plane, times the
/// plane-to-sphere Jacobian (1 + a^2 + b^2)^(3/2).
float envTexelPdf(int f, int c, int r, vec2 ab) {
    int n = env.dims.z;
    float p = envPieceProbability(f, -1, c) * envPieceProbability(f, c, r);
    float q = 1.0 + dot(ab, ab);
    return p * float(n) * float(n) * 0.25 * q * sqrt(q);
}

/// pdf_L(w | f) of a direction (0 off the face or on a black face).
float envPdfFace(int f, vec3 w) {
    vec2 ab;
    if (envFaceOf(w, ab) != f || !(envFaceImportance(f) > 0.0)) return 0.0;
    int n = env.dims.z;
    int c = clamp(int((ab.x + 1.0) * 0.5 * float(n)), 0, n - 1);
    int r = clamp(int((ab.y + 1.0) * 0.5 * float(n)), 0, n - 1);
    return envTexelPdf(f, c, r, ab);
}

/// mu_f(n) of Eq. (3): F_f(n) I_f normalised, F_f(n) the sum over the face's four unit corner
/// directions of max(0, n . c). All zero when no lit face is in front of n.
void envBalance(vec3 n, out float mu[6]) {
    float sum = 0.0;
    for (int f = 0; f < 6; ++f) {
        float form = 0.0;
        for (int j = 0; j < 4; ++j) {
            vec3 c = envFaceDirection(f, (j & 1) != 0 ? 1.0 : -1.0, (j & 2) != 0 ? 1.0 : -1.0);
            form += max(0.0, dot(n, c));
        }
        mu[f] = form * envFaceImportance(f);
        sum += mu[f];
    }
    for (int f = 0; f < 6; ++f) mu[f] = sum > 0.0 ? mu[f] / sum : 0.0;
}

/// pdf of the face mixture mu: mu_f pdf_L(w | f) for w's face (the denominator of Eq. 2).
float envPdf(float mu[6], vec3 w) {
    vec2 ab;
    int f = envFaceOf(w, ab);
    return f < 0 || !(mu[f] > 0.0) ? 0.0 : mu[f] * envPdfFace(f, w);
}
