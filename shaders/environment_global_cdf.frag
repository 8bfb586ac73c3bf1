// environment `global-cdf`: one CDF over the lat-long map (built on the CPU when the map changes,
// as static-map renderers do), per-pixel samples.
#include "environment_shading.glsl"

// Row 0: the CDF over rows; row 1 + y: the CDF over row y's columns; per texel i, .r is entry
// i + 1 (entry 0 is 0) and .g entry i of the line's search guide (cdfSearchGuide in
// renderer/passes/EnvironmentPass.h; kUnitEnvGlobalCdf in shared/GpuTypes.h).
layout(binding = 13) uniform sampler2D uEnvGlobalCdf;

float globalCdf(int line, int i) { return i == 0 ? 0.0 : texelFetch(uEnvGlobalCdf, ivec2(i - 1, line), 0).r; }

// The last entry of line's n-entry CDF not above u (its bin): the guide brackets it, a binary
// search inside the bracket finds it (the same index as a search of the whole line).
int globalCdfBin(int line, int n, float u) {
    int j = min(int(u * float(n)), n - 1);
    int lo = int(texelFetch(uEnvGlobalCdf, ivec2(j, line), 0).g);
    int hi = j + 1 < n ? int(texelFetch(uEnvGlobalCdf, ivec2(j + 1, line), 0).g) + 1 : n;
    while (hi - lo > 1) {
        int mid = (lo + hi) >> 1;
        if (globalCdf(line, mid) <= u) lo = mid; else hi = mid;
    }
    return lo;
}

vec3 shadeTechnique(Surface s, int ns, inout uint rng) {
    vec3 result = vec3(0.0);
    int W = env.dims.x, H = env.dims.y;
    for (int k = 0; k < ns; ++k) {
        float u1 = rand01(rng), u2 = rand01(rng);
        int y = globalCdfBin(0, H, u1);
        float py = globalCdf(0, y + 1) - globalCdf(0, y);
        if (!(py > 0.0)) continue;
        float fy = clamp((u1 - globalCdf(0, y)) / py, 0.0, 1.0);
        int x = globalCdfBin(1 + y, W, u2);
        float px_ = globalCdf(1 + y, x + 1) - globalCdf(1 + y, x);
        if (!(px_ > 0.0)) continue;
        float fx = clamp((u2 - globalCdf(1 + y, x)) / px_, 0.0, 1.0);
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
    return result;
}

#include "environment_main.glsl"
