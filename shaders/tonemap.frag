// Tone mapping of the linear image to display sRGB.
//   Exponential (Lu et al. 2015, Sec. 5, after Reinhard's survey): Ld = 1 - exp(-k L / Lavg),
//   with Lavg the frame's mean luminance and k the exposure.
//   Reinhard (2002, global): Lm = 0.18 k L / Lavg, Ld = Lm / (1 + Lm).
//   False colour: the pixel's luminance (illuminance E in lux when the renderer runs in
//   illuminance mode) through the legend (linear or log over [min, max]) to the scale of
//   shared/FalseColour.h, with isolux contour lines at the given levels. Pixels with no surface
//   are dark grey, luminaires light grey: neither carries a measurement.
#include "common.glsl"
#include "shared/FalseColour.h"
layout(binding = 0) uniform sampler2D uLinear;
layout(binding = 1) uniform sampler2D uLuminance;  // full mip chain; top level = mean
layout(binding = 2) uniform sampler2D gPosition;   // w = 1 where a surface was hit
layout(binding = 3) uniform sampler2D gEmission;   // a = 1 where a luminaire is seen
layout(location = 0) uniform int uOperator;         // 0 exponential, 1 Reinhard, 2 false colour
layout(location = 1) uniform float uExposure;
layout(location = 2) uniform float uFixedAverage;  // > 0: use instead of the frame mean
layout(location = 3) uniform float uLegendMin;     // value at the bottom of the scale (lux)
layout(location = 4) uniform float uLegendMax;     // value at the top of the scale (lux)
layout(location = 5) uniform int uLogScale;        // 1: log scale (then uLegendMin > 0)
layout(location = 6) uniform int uLevelCount;      // contour levels used, <= kMaxContourLevels
layout(location = 7) uniform float uLevels[kMaxContourLevels];  // contour levels (lux), ascending

layout(location = 0) out vec4 outColor;

vec3 linearToSrgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

/// The value contours are drawn in: legend position (linear or log), so lines are equally
/// well resolved wherever they fall on the scale.
float contourValue(ivec2 px) {
    ivec2 size = textureSize(uLinear, 0);
    px = clamp(px, ivec2(0), size - 1);
    return legendPosition(luminance(texelFetch(uLinear, px, 0).rgb), uLegendMin, uLegendMax,
                          uLogScale);
}

/// Coverage (0..1) of the pixel by the isolux lines, each 1 px wide and box-filtered: a line
/// crossing the pixel at signed distance d pixels from its centre covers max(0, 1 - |d|) of it.
/// The screen-space gradient is the smaller one-sided difference per axis (central differences
/// would smear a depth edge's jump into the gradient and draw spurious lines along silhouettes;
/// dFdx of llvmpipe is per 2x2 quad, which makes lines step). Where the value changes by more than
/// half the spacing of adjacent levels within one pixel, lines would merge into a blot: none there.
float contourCoverage(float v, ivec2 px) {
    float gx = min(abs(contourValue(px + ivec2(1, 0)) - v), abs(v - contourValue(px - ivec2(1, 0))));
    float gy = min(abs(contourValue(px + ivec2(0, 1)) - v), abs(v - contourValue(px - ivec2(0, 1))));
    float g = max(length(vec2(gx, gy)), 1e-12);
    float coverage = 0.0;
    float prev = -1e30;
    for (int k = 0; k < min(uLevelCount, kMaxContourLevels); ++k) {
        float level = legendPosition(uLevels[k], uLegendMin, uLegendMax, uLogScale);
        float next = k + 1 < uLevelCount ? legendPosition(uLevels[k + 1], uLegendMin, uLegendMax, uLogScale) : 1e30;
        float spacing = min(level - prev, next - level);
        prev = level;
        if (g > 0.5 * spacing) continue;
        float d = (v - level) / g;
        coverage = max(coverage, clamp(1.0 - abs(d), 0.0, 1.0));
    }
    return coverage;
}

vec3 falseColourPixel(vec3 c) {
    ivec2 px = ivec2(gl_FragCoord.xy);
    if (texelFetch(gEmission, px, 0).a > 0.5) return vec3(0.75);
    if (texelFetch(gPosition, px, 0).w == 0.0) return vec3(0.12);
    float v = legendPosition(luminance(c), uLegendMin, uLegendMax, uLogScale);
    vec3 colour = falseColour(v);
    // Dark lines on the light half of the scale, light lines on the dark half.
    vec3 ink = v > 0.45 ? vec3(0.0) : vec3(1.0);
    return mix(colour, ink, contourCoverage(v, px));
}

void main() {
    vec3 c = texelFetch(uLinear, ivec2(gl_FragCoord.xy), 0).rgb;
    if (uOperator == 2) {
        outColor = vec4(falseColourPixel(c), 1.0);  // the scale is already sRGB-encoded
        return;
    }
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
