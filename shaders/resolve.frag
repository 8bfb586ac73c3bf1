// The linear HDR image: the sum of the luminaires' and the environment's mean estimates
// (Renderer sums its per-luminaire accumulations into uAccum first), or, where the camera sees a
// luminaire, its emission alone (the G-buffer's emission alpha marks those pixels).
// Also writes its luminance for the exposure average (mip-mapped by the renderer).
#include "common.glsl"
layout(binding = 0) uniform sampler2D uAccum;
layout(binding = 1) uniform sampler2D gEmission;
layout(location = 0) uniform float uScale;

layout(location = 0) out vec4 outLinear;
layout(location = 1) out float outLuminance;

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 emission = texelFetch(gEmission, px, 0);
    vec3 c = emission.a > 0.5 ? emission.rgb : texelFetch(uAccum, px, 0).rgb * uScale;
    outLinear = vec4(c, 1.0);
    outLuminance = luminance(c);
}
