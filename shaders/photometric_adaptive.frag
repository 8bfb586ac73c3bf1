// photometric `adaptive`: scattered sampling on the opening clipped at the true horizon, its worst
// spherical triangle split in four until the cubature's estimated error is 0.1 % of its value
// (or its split budget is spent); times the closed-form projected solid angle.
#include "photometric_shading.glsl"

vec3 shadeTechnique(Surface s, vec3 p, vec3 n, int spp, inout uint rng) {
    float E;
    if (!phSettled(p, n, E)) E = phAdaptive(p, n);
    return phShadeIrradiance(s, p, n, spp, rng, E);
}

#include "photometric_main.glsl"
