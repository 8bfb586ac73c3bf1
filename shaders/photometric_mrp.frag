// photometric `mrp`: one sample at Drobot's most representative point (Eq. 4.3).
#include "photometric_shading.glsl"

vec3 shadeTechnique(Surface s, vec3 p, vec3 n, int spp, inout uint rng) {
    float E;
    if (!phSettled(p, n, E)) {
        E = phMrp(p, n);
    }
    return phShadeIrradiance(s, p, n, spp, rng, E);
}

#include "photometric_main.glsl"
