// lightfield `uniform-restricted`: uniform samples in the same restricted boxes (Fig. 12).
#include "lightfield_shading.glsl"

bool lfBox(int m, vec3 q, out vec2 a, out vec2 b) { return lfRestrictedBox(m, q, a, b); }
float lfBoxWeight(int m, vec2 a, vec2 b) { return lfBoxIntegral(m, a, b); }
bool lfDraw(int m, vec2 a, vec2 b, vec2 xi, float Am, out vec2 sp, out float scale) {
    sp = a + xi * (b - a);
    float c = lfLum(m, sp);
    scale = c * (b.x - a.x) * (b.y - a.y) / Am;
    return c > 0.0;
}

#include "lightfield_balanced.glsl"
#include "lightfield_main.glsl"
