// Mean of the accumulated estimates, plus the deterministic steps shaded once (Renderer::mStatic),
// plus the emitters seen directly: the linear HDR image.
// Also writes its luminance for the exposure average (mip-mapped by the renderer).
#include "common.glsl"
layout(binding = 0) uniform sampler2D uAccum;
layout(binding = 1) uniform sampler2D gEmission;
layout(binding = 2) uniform sampler2D uOnce;
layout(location = 0) uniform float uInvFrames;

layout(location = 0) out vec4 outLinear;
layout(location = 1) out float outLuminance;

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec3 c = texelFetch(uAccum, px, 0).rgb * uInvFrames + texelFetch(uOnce, px, 0).rgb +
             texelFetch(gEmission, px, 0).rgb;
    outLinear = vec4(c, 1.0);
    outLuminance = luminance(c);
}
