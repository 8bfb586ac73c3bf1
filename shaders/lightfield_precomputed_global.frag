// lightfield `precomputed-global`: one CDF per image over the whole image, the same for every
// pixel (Fig. 11 baseline, "precomputed global light importance sampling").
#include "lightfield_shading.glsl"

bool lfBox(int m, vec3 q, out vec2 a, out vec2 b) {
    a = lfImageMin();
    b = lfImageMax();
    return true;
}
double lfBoxWeight(int m, vec2 a, vec2 b) { return lfSatEntry(m, lf.dims.z, lf.dims.w); }
bool lfDraw(int m, vec2 a, vec2 b, vec2 xi, double Am, out vec2 sp, out float scale) {
    scale = 1.0;
    return lfSampleBox(m, a, b, xi, sp);
}

#include "lightfield_balanced.glsl"
#include "lightfield_main.glsl"
