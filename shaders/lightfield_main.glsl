// The main of every light-field technique's shader that gives each pixel its own samples: one
// pass of lightfield_pass.glsl seeded by the fragment's pixel.
#include "lightfield_pass.glsl"

void main() { lfShadePass(uvec2(gl_FragCoord.xy)); }
