// photometric `hybrid`: scattered within half an opening size, 24 Poisson points from one and a
// half on, blended between (Prost Sec. 6.6).
#include "photometric_shading.glsl"

vec3 shadeTechnique(Surface s, vec3 p, vec3 n, int spp, inout uint rng) {
    float E;
    if (!phSettled(p, n, E)) {
        int place, index;
        float distance = length(phClosest(phOpening(p), vec3(0.0), 0.0, place, index));
        float w = hybridWeight(distance, ph.axisX.w);  // shared/Photometric.h
        int flips;
        float nearE = w < 1.0 ? phScattered(p, n, flips) : 0.0;
        float farE = w > 0.0 ? phPoisson(p, n, ph.samples.x, 24) : 0.0;
        E = mix(nearE, farE, w);
    }
    return phShadeIrradiance(s, p, n, spp, rng, E);
}

#include "photometric_main.glsl"
