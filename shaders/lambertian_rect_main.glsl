// The main of every Lambertian rectangle technique's shader: this pass's estimate, added into the
// accumulation buffer. Hard cases must never poison the accumulation: non-finite estimates are
// dropped.
void main() {
    Surface s;
    if (!loadSurface(s)) discard;
    LambertianRectGpu L = lights[uLuminaire];
    int spp = frame.frameInfo.y;
    uint rng = rngSeed(uvec2(gl_FragCoord.xy), uint(frame.frameInfo.x * 7919 + uLuminaire) + uint(frame.seeds.x) * 2654435761u);
    vec3 result = shadeTechnique(s, L, spp, rng);
    if (any(isnan(result)) || any(isinf(result))) result = vec3(0.0);
    outRadiance = vec4(result, 1.0);
}
