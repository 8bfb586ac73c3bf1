// photometric `scattered`: Prost's scattered sampling: corners and closest point, spherical Delaunay
// cubature normalised by the closed-form form factor (Eq. 5.6, 5.11).
#include "photometric_shading.glsl"

vec3 shadeTechnique(Surface s, vec3 p, vec3 n, int spp, inout uint rng) {
    float E;
    if (!phSettled(p, n, E)) {
        int flips;
        E = phScattered(p, n, flips);
    }
    return phShadeIrradiance(s, p, n, spp, rng, E);
}

#include "photometric_main.glsl"
