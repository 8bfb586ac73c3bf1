// photometric `structured`: corners and barycentre of the horizon-clipped opening as uniform
// solid-angle samples (Eq. 4.3).
#include "photometric_shading.glsl"

vec3 shadeTechnique(Surface s, vec3 p, vec3 n, int spp, inout uint rng) {
    float E;
    if (!phSettled(p, n, E)) {
        E = phStructured(p, n);
    }
    return phShadeIrradiance(s, p, n, spp, rng, E);
}

#include "photometric_main.glsl"
