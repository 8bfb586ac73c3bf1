// One light-field shading pass for the fragment: the receiver in the luminaire's frame, the
// pass's random numbers, and shadeTechnique() where the receiver can see the luminaire (beyond
// S, or on it within float rounding); this pass's radiance estimate, added into the accumulation
// buffer. Hard cases must never poison the accumulation: non-finite estimates are dropped. The
// random numbers (the systematic offset over images, the rotation of the Halton points) are seeded
// by `seedPixel`: the fragment's own pixel gives every pixel its own samples
// (lightfield_main.glsl); one pixel for all shares one set of samples between them
// (lightfield_precomputed_shared.frag).
void lfShadePass(uvec2 seedPixel) {
    Surface s;
    if (!loadSurface(s)) discard;
    int K = frame.frameInfo.y;
    uint rng = rngSeed(seedPixel, uint(frame.frameInfo.x * 7919 + uLuminaire) + uint(frame.seeds.x) * 2654435761u);
    float offset = rand01(rng);  // systematic sampling over the images
    // A new random rotation of the shared Halton points per pixel and pass. (A rotation kept
    // across passes with the index running on would confine each image's points: image m holds
    // the same slots of every pass's block of K indices, so their base-2 digits below K repeat
    // and its samples never leave one dyadic strip. Each pixel would then converge to a wrong
    // value, right only on average over pixels.)
    vec2 shift = vec2(rand01(rng), rand01(rng));

    vec3 d = s.p - lf.position.xyz;
    vec3 q = vec3(dot(d, lf.axisX.xyz), dot(d, lf.axisY.xyz), dot(d, lf.axisZ.xyz));
    vec3 nl = vec3(dot(s.n, lf.axisX.xyz), dot(s.n, lf.axisY.xyz), dot(s.n, lf.axisZ.xyz));
    float dz = q.z - lfDelta();
    // Closer to S than float coordinates resolve the restricted boxes, on either side (a receiver
    // on S has a rounded position): p on S (Eq. 9), the limit the irradiance tends to. The C++
    // twin (LightFieldEstimators.cpp) does the same within its 64-bit rounding.
    bool onS = abs(dz) < 1e-5 * max(q.z, 1e-3);
    // Behind S or between U and S: no light.
    vec3 result = dz < 0.0 && !onS ? vec3(0.0) : shadeTechnique(s, q, nl, onS, K, shift, offset);
    if (any(isnan(result)) || any(isinf(result))) result = vec3(0.0);
    outRadiance = vec4(result, 1.0);
}
