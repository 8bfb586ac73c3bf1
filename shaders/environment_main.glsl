// The main of every environment technique's shader: background pixels show the map; surfaces
// get shadeTechnique(), this pass's radiance estimate, added into the accumulation buffer. Hard
// cases must never poison the accumulation: non-finite estimates are dropped.
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
    vec3 result = shadeTechnique(s, ns, rng);
    if (any(isnan(result)) || any(isinf(result))) result = vec3(0.0);
    outRadiance = vec4(result, 1.0);
}
