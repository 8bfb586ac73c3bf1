// The main of every photometric technique's shader: the receiver in the opening's frame, the
// technique's shadeTechnique(), the table's colour; this pass's estimate, added into the
// accumulation buffer. Hard cases must never poison the accumulation: non-finite estimates are
// dropped.
void main() {
    Surface s;
    if (!loadSurface(s)) discard;
    vec3 p = phToLocal(s.p - ph.position.xyz);
    vec3 n = normalize(phToLocal(s.n));
    int spp = frame.frameInfo.y;
    uint rng = rngSeed(uvec2(gl_FragCoord.xy), uint(frame.frameInfo.x * 7919 + uLuminaire) + uint(frame.seeds.x) * 2654435761u);
    vec3 result = shadeTechnique(s, p, n, spp, rng) * ph.colour.rgb;
    if (any(isnan(result)) || any(isinf(result))) result = vec3(0.0);
    outRadiance = vec4(result, 1.0);
}
