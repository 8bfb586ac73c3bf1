// lightfield `precomputed-global`: one CDF per image over the whole image, the same for every
// pixel (Fig. 11 baseline, "precomputed global light importance sampling"), with samples drawn
// independently for each pixel.
#include "lightfield_shading.glsl"
#include "lightfield_global_cdf.glsl"
#include "lightfield_balanced.glsl"
#include "lightfield_main.glsl"
