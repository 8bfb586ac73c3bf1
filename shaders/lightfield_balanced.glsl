// The balanced sampler of Sec. 6.1 shared by the light-field techniques that sample images in
// boxes (restricted-cdf, uniform-restricted, precomputed-global, precomputed-shared). The technique's shader defines,
// before including this file:
//   bool lfBox(int m, vec3 q, out vec2 a, out vec2 b)   image m's box seen from q (false: empty)
//   float lfBoxWeight(int m, vec2 a, vec2 b)           its weight A_m for the balancing (Eq. 12)
//   bool lfDraw(int m, vec2 a, vec2 b, vec2 xi, float Am, out vec2 sp, out float scale)
//        a point of the box for the Halton point xi, and f / pdf without Psi c cos Delta / r^3,
//        over A (false: no sample).
// K samples per pixel per pass are spread over the images in proportion to A_m(p) (Eq. 12) by
// systematic sampling with one random offset per pixel and pass, which makes the counts the
// nearest integers of K A_m / A and keeps the estimator unbiased; at most K_max samples are
// taken per image (Fig. 9), reweighted. Sample positions come from one Halton sequence shared
// by all pixels (Sec. 6.3): each image uses its first points, rotated by a random offset per
// pixel and pass (the jitter that trades structure for noise and keeps every pass's estimate
// independent and unbiased).

vec3 lfBalanced(Surface s, vec3 q, vec3 nl, int K, vec2 shift, float offset) {
    float dz = q.z - lfDelta();
    vec3 result = vec3(0.0);
    int M = lfImageCount();
    // Step 1 of Sec. 6.1: A_m(p) for every image and their sum A(p); kept for step 2 (up to
    // kCached images; beyond that step 2 recomputes them). Step 2 adds the same floats in the
    // same order, so its running sum ends at exactly A and every slot goes to one image.
    const int kCached = 128;
    float cached[kCached];
    float A = 0.0;
    for (int m = 0; m < M; ++m) {
        vec2 a, b;
        float w = lfBox(m, q, a, b) ? lfBoxWeight(m, a, b) : 0.0;
        if (m < kCached) cached[m] = w;
        A += w;
    }
    if (A > 0.0) {
        float cum = 0.0;
        for (int m = 0; m < M; ++m) {
            vec2 a, b;
            float Am;
            if (m < kCached) {
                Am = cached[m];
                if (!(Am > 0.0)) continue;
                lfBox(m, q, a, b);
            } else {
                Am = lfBox(m, q, a, b) ? lfBoxWeight(m, a, b) : 0.0;
                if (!(Am > 0.0)) continue;
            }
            // Slots k with (k + offset) / K * A in [cum, cum + A_m) go to image m.
            int k0 = int(ceil(cum / A * float(K) - offset));
            cum += Am;
            int k1 = int(ceil(cum / A * float(K) - offset));
            int Km = k1 - k0;
            if (Km <= 0) continue;
            int n = lf.options.x > 0 ? min(Km, lf.options.x) : Km;
            float vm = imageVisibility(s, m);
            if (!(vm > 0.0)) continue;
            // Each slot is worth A / K; n samples stand for Km slots.
            float weight = vm * A / float(K) * float(Km) / float(n);
            for (int k = k0; k < k0 + n; ++k) {
                uint index = uint(k - k0 + 1);  // the image's own points, 1..n, this frame
                vec2 xi = fract(vec2(lfHalton2(index), lfHalton3(index)) + shift);
                vec2 sp;
                float scale;  // (f / pdf) without Psi c cos Delta / r^3, over A
                if (!lfDraw(m, a, b, xi, Am, sp, scale)) continue;
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
    return result;
}

/// On S the restricted boxes vanish: Eq. (9). Beyond it, the balanced sampler.
vec3 shadeTechnique(Surface s, vec3 q, vec3 nl, bool onS, int K, vec2 shift, float offset) {
    return onS ? shadeOnS(s, q, nl, K, shift, offset) : lfBalanced(s, q, nl, K, shift, offset);
}
