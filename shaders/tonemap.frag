// Tone mapping of the linear image to display sRGB.
//   Exponential (Lu et al. 2015, Sec. 5, after Reinhard's survey): Ld = 1 - exp(-k L / Lavg),
//   with Lavg the frame's mean luminance and k the exposure.
//   Reinhard (2002, global): Lm = 0.18 k L / Lavg, Ld = Lm / (1 + Lm).
#include "common.glsl"
layout(binding = 0) uniform sampler2D uLinear;
layout(binding = 1) uniform sampler2D uLuminance;  // full mip chain; top level = mean
layout(location = 0) uniform int uOperator;         // 0 exponential, 1 Reinhard
layout(location = 1) uniform float uExposure;
layout(location = 2) uniform float uFixedAverage;  // > 0: use instead of the frame mean

layout(location = 0) out vec4 outColor;

vec3 linearToSrgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

void main() {
    vec3 c = texelFetch(uLinear, ivec2(gl_FragCoord.xy), 0).rgb;
    float top = float(textureQueryLevels(uLuminance) - 1);
    float avg = uFixedAverage > 0.0 ? uFixedAverage : textureLod(uLuminance, vec2(0.5), top).r;
    avg = max(avg, 1e-8);
    vec3 mapped;
    if (uOperator == 0) {
        mapped = 1.0 - exp(-uExposure * c / avg);
    } else {
        vec3 m = 0.18 * uExposure * c / avg;
        mapped = m / (1.0 + m);
    }
    outColor = vec4(linearToSrgb(mapped), 1.0);
}
