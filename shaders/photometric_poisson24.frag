// photometric `mc-poisson-24`: a fixed set of 24 Poisson-disk points on the opening (MCI-24).
#include "photometric_shading.glsl"

vec3 shadeTechnique(Surface s, vec3 p, vec3 n, int spp, inout uint rng) {
    float E;
    if (!phSettled(p, n, E)) {
        E = phPoisson(p, n, ph.samples.x, 24);
    }
    return phShadeIrradiance(s, p, n, spp, rng, E);
}

#include "photometric_main.glsl"
