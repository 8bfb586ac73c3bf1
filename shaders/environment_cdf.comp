// Algorithm 1 of Lu et al. 2013 (lines 5-10) in compute shaders, one variant per step:
//   PASS_CUBE     per cube texel: mean luminance of k x k subsamples of the lat-long map (the
//                 cube-map conversion) and its sampling weight before the face floor;
//   PASS_ENERGY   per face: the sum of luminance x solid angle (a reduction), for the floor;
//   PASS_ROWS     per face and column: the final weights, an inclusive prefix sum over rows
//                 giving CDF(v | u), and the column's total;
//   PASS_COLUMNS  per face: the prefix sum over column totals giving CDF(u), and I_f;
//   PASS_SAMPLES  per face: a pool of light samples drawn by binary search (line 10).
// The weights are exactly those of CubeMapDistribution (luminaires/environment/EnvironmentSampling.cpp):
// (mean luminance + kEnvMaxShare x the largest lat-long luminance the texel touches + a floor of
// kEnvFaceFloor x the face's mean luminance) x the texel's solid angle. Prefix sums run in
// float-float (ff.glsl) and the tables are stored as float-float pairs (see envRand48 in
// environment.glsl).
#if defined(PASS_ROWS) || defined(PASS_COLUMNS)
#define ENV_WRITES_TABLES
#endif
#include "environment.glsl"

#if defined(PASS_CUBE)
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
#elif defined(PASS_SAMPLES)
layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;
#else
layout(local_size_x = 256, local_size_y = 1, local_size_z = 1) in;
#endif

#ifdef PASS_CUBE
float latLongLuminance(int x, int y) { return luminance(texelFetch(uEnvMap, ivec2(x, y), 0).rgb); }

/// The largest lat-long luminance texel (c, r) of face f may touch: over the (u, v) box of 17
/// points per edge, all columns across a pole or a box wider than a quarter turn
/// (touchedMaximum in EnvironmentSampling.cpp).
float touchedMaximum(int f, int c, int r, int n) {
    const int kEdge = kEnvTouchedSteps;
    int w = env.dims.x, h = env.dims.y;
    float a0 = -1.0 + 2.0 * float(c) / float(n), a1 = -1.0 + 2.0 * float(c + 1) / float(n);
    float b0 = -1.0 + 2.0 * float(r) / float(n), b1 = -1.0 + 2.0 * float(r + 1) / float(n);
    float uc = envUv(envFaceDirection(f, 0.5 * (a0 + a1), 0.5 * (b0 + b1))).x;
    float duMin = 0.0, duMax = 0.0, vMin = 1.0, vMax = 0.0;
    for (int e = 0; e < 4; ++e)
        for (int i = 0; i <= kEdge; ++i) {
            float t = float(i) / float(kEdge);
            float a = e < 2 ? a0 + t * (a1 - a0) : (e == 2 ? a0 : a1);
            float b = e < 2 ? (e == 0 ? b0 : b1) : b0 + t * (b1 - b0);
            vec2 uv = envUv(envFaceDirection(f, a, b));
            float du = uv.x - uc;
            du -= round(du);
            duMin = min(duMin, du);
            duMax = max(duMax, du);
            vMin = min(vMin, uv.y);
            vMax = max(vMax, uv.y);
        }
    bool pole = (f == 2 || f == 3) && a0 <= 0.0 && a1 >= 0.0 && b0 <= 0.0 && b1 >= 0.0;
    if (pole) {
        if (f == 2) vMin = 0.0; else vMax = 1.0;
    }
    int y0 = max(0, int(floor(vMin * float(h)))), y1 = min(h - 1, int(floor(vMax * float(h))));
    bool allColumns = pole || duMax - duMin > 0.25;
    int x0 = int(floor((uc + duMin) * float(w))), x1 = int(floor((uc + duMax) * float(w)));
    if (allColumns) {
        x0 = 0;
        x1 = w - 1;
    }
    float best = 0.0;
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) best = max(best, latLongLuminance(((x % w) + w) % w, y));
    return best;
}

void main() {
    int n = env.dims.z, k = env.frame.y;
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (id.x >= n || id.y >= n) return;
    int c = id.x, r = id.y, f = id.z;
    float sum = 0.0;
    for (int j = 0; j < k; ++j)
        for (int i = 0; i < k; ++i) {
            float a = -1.0 + 2.0 * (float(c) + (float(i) + 0.5) / float(k)) / float(n);
            float b = -1.0 + 2.0 * (float(r) + (float(j) + 0.5) / float(k)) / float(n);
            sum += luminance(envRadiance(envFaceDirection(f, a, b)));
        }
    float lum = sum / float(k * k);
    float omega = envTexelSolidAngle(c, r, n);
    envCube[(f * n + r) * n + c] = vec2(lum, (lum + kEnvMaxShare * touchedMaximum(f, c, r, n)) * omega);
}
#endif

#if defined(PASS_ENERGY) || defined(PASS_ROWS) || defined(PASS_COLUMNS)
shared vec2 partial[256];

/// Inclusive prefix sum of partial[] over the workgroup (Hillis and Steele).
void scanPartials(uint t) {
    for (uint offset = 1u; offset < 256u; offset <<= 1u) {
        barrier();
        vec2 add = t >= offset ? partial[t - offset] : vec2(0.0);
        barrier();
        partial[t] = ffAdd(partial[t], add);
    }
    barrier();
}
#endif

#ifdef PASS_ENERGY
void main() {
    int n = env.dims.z, f = int(gl_WorkGroupID.x);
    uint t = gl_LocalInvocationID.x;
    vec2 sum = vec2(0.0);
    for (int i = int(t); i < n * n; i += 256)
        sum = ffAdd(sum, ffMulF(vec2(envCube[f * n * n + i].x, 0.0), envTexelSolidAngle(i % n, i / n, n)));
    partial[t] = sum;
    scanPartials(t);
    if (t == 0u) envFaces[f].totals.y = ffToFloat(partial[255]);
}
#endif

#ifdef PASS_ROWS
void main() {
    int n = env.dims.z, c = int(gl_WorkGroupID.x), f = int(gl_WorkGroupID.y);
    uint t = gl_LocalInvocationID.x;
    int per = (n + 255) / 256, first = int(t) * per, last = min(first + per, n);
    float floorLum = kEnvFaceFloor * envFaces[f].totals.y / (4.0 * kPi / 6.0);
    vec2 sum = vec2(0.0);
    for (int r = first; r < last; ++r) {
        int idx = (f * n + r) * n + c;
        float weight = envCube[idx].y + floorLum * envTexelSolidAngle(c, r, n);
        envCube[idx].y = weight;
        sum = ffAddF(sum, weight);
    }
    partial[t] = sum;
    scanPartials(t);
    vec2 total = partial[255];
    vec2 running = t > 0u ? partial[t - 1u] : vec2(0.0);
    for (int r = first; r < last; ++r) {
        running = ffAddF(running, envCube[(f * n + r) * n + c].y);
        // The last entry is exactly 1 (or 0 for an empty column), as in Cdf1D::build.
        vec2 cdf = total.x > 0.0 ? (r == n - 1 ? vec2(1.0, 0.0) : ffDiv(running, total)) : vec2(0.0);
        imageStore(envRowCdfImage, ivec3(r + 1, c, f), vec4(cdf, 0.0, 0.0));
    }
    if (t == 0u) {
        imageStore(envRowCdfImage, ivec3(0, c, f), vec4(0.0));
        imageStore(envColumnCdfImage, ivec2(c, 6 + f), vec4(total, 0.0, 0.0));
    }
}
#endif

#ifdef PASS_COLUMNS
void main() {
    int n = env.dims.z, f = int(gl_WorkGroupID.x);
    uint t = gl_LocalInvocationID.x;
    int per = (n + 255) / 256, first = int(t) * per, last = min(first + per, n);
    vec2 sum = vec2(0.0);
    for (int c = first; c < last; ++c) sum = ffAdd(sum, envColumnCdfAt(6 + f, c));
    partial[t] = sum;
    scanPartials(t);
    vec2 total = partial[255];
    vec2 running = t > 0u ? partial[t - 1u] : vec2(0.0);
    for (int c = first; c < last; ++c) {
        running = ffAdd(running, envColumnCdfAt(6 + f, c));
        vec2 cdf = total.x > 0.0 ? (c == n - 1 ? vec2(1.0, 0.0) : ffDiv(running, total)) : vec2(0.0);
        imageStore(envColumnCdfImage, ivec2(c + 1, f), vec4(cdf, 0.0, 0.0));
    }
    if (t == 0u) {
        imageStore(envColumnCdfImage, ivec2(0, f), vec4(0.0));
        envFaces[f].totals.x = ffToFloat(total);
    }
}
#endif

#ifdef PASS_SAMPLES
// Sample i of face f: (u1, u2) from the frame's seed, CDF(u) then CDF(v | u) inverted by binary
// search, uniform inside the texel on the face plane.
void main() {
    int n = env.dims.z, pool = env.dims.w;
    int i = int(gl_GlobalInvocationID.x);
    int f = int(gl_GlobalInvocationID.z);
    if (i >= pool) return;
    EnvironmentSampleGpu s;
    s.direction = vec4(0.0, 1.0, 0.0, 0.0);
    s.radiance = vec4(0.0);
    if (envFaceImportance(f) > 0.0) {
        uint rng = pcgHash(uint(env.frame.x) ^ pcgHash(uint(f * pool + i) + 0x9e3779b9u));
        vec2 u1 = envRand48(rng), u2 = envRand48(rng);
        float fx, fy;
        int c = envSearch(f, -1, n, u1, fx);
        int r = envSearch(f, c, n, u2, fy);
        float a = -1.0 + 2.0 * (float(c) + fx) / float(n), b = -1.0 + 2.0 * (float(r) + fy) / float(n);
        vec3 w = envFaceDirection(f, a, b);
        s.direction = vec4(w, envTexelPdf(f, c, r, vec2(a, b)));
        s.radiance = vec4(envRadiance(w), 0.0);
    }
    envSamples[f * pool + i] = s;
}
#endif
