// One term of the resolve's sum: a luminaire's (or the environment's) accumulated estimates
// times 1 / its passes, added by blending into ResolvePass's sum.
#include "common.glsl"
layout(binding = 0) uniform sampler2D uSource;
layout(location = 0) uniform float uScale;

layout(location = 0) out vec4 outSum;

void main() {
    outSum = vec4(texelFetch(uSource, ivec2(gl_FragCoord.xy), 0).rgb * uScale, 0.0);
}
