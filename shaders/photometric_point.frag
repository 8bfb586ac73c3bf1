// photometric `point`: one photometric point light at the centre, whatever the opening's shape
// (as its C++ twin); its shadows and highlights come from the centre too.
#include "photometric_shading.glsl"

vec3 shadeTechnique(Surface s, vec3 p, vec3 n, int spp, inout uint rng) {
    float E = phPointIrradiance(p, n, vec3(0.0));
    float visibleFraction = visibleTo(s, vec3(0.0));
#ifdef SHADOW_MAPS
    visibleFraction = shadowItemVisibility(1, s.p, s.n);
#endif
    vec3 glossy = vec3(0.0);
#ifdef GLOSSY
    if ((s.flags & kMaterialGlossy) != 0) glossy = E * visibleFraction * glossyBrdf(s, normalize(phFromLocal(-p)));
#endif
    return s.albedo / kPi * E * visibleFraction + glossy;
}

#include "photometric_main.glsl"
