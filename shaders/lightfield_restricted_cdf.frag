// lightfield `restricted-cdf` (and `restricted-cdf-raytraced`, its SHADOWS variant): position-
// dependent restricted CDFs with balancing (Lu et al. 2015, Eq. 8, 12, 14): each image sampled
// in proportion to C_m within its box restricted to what the receiver can see.
#include "lightfield_shading.glsl"

bool lfBox(int m, vec3 q, out vec2 a, out vec2 b) { return lfRestrictedBox(m, q, a, b); }
float lfBoxWeight(int m, vec2 a, vec2 b) { return lfBoxIntegral(m, a, b); }
bool lfDraw(int m, vec2 a, vec2 b, vec2 xi, float Am, out vec2 sp, out float scale) {
    scale = 1.0;
    return lfSampleBoxOf(m, a, b, Am, xi, sp);  // Am is lfBoxIntegral(m, a, b)
}

#include "lightfield_balanced.glsl"
#include "lightfield_main.glsl"
