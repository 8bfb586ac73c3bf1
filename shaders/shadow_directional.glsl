// Visibility along a directional light from its orthographic shadow map
// (renderer/passes/ShadowMapPass.h, DirectionalShadowMaps). Bias and filtering as
// shadow_maps.glsl, with a texel of fixed size (the scene's bounding sphere over the map):
// the receiver moves params.z texels along its normal and params.w texels towards the light;
// four hardware-compared bilinear lookups at +-1/2 texel make a 3 x 3 texel tent. A receiver
// outside the map (it cannot be: the map covers the scene) is lit.
#pragma once
#include "common.glsl"

layout(binding = 7) uniform sampler2DArrayShadow uDirectionalMaps;  // kUnitDirectionalShadowMaps
layout(std430, binding = 16) readonly buffer DirectionalShadowBlock {  // kBindingDirectionalShadowMaps
    ShadowMapsGpu dsHeader;
    mat4 dsViewProj[];
};

/// Visibility of p (unit normal n) towards the unit direction w of map k.
float directionalVisibility(int k, vec3 p, vec3 n, vec3 w) {
    float texel = dsHeader.params.x;
    vec3 nl = dot(n, w) < 0.0 ? -n : n;
    vec3 q = p + (nl * dsHeader.params.z + w * dsHeader.params.w) * texel;
    vec4 clip = dsViewProj[k] * vec4(q, 1.0);
    vec3 ndc = clip.xyz / clip.w;
    if (any(greaterThan(abs(ndc.xy), vec2(1.0)))) return 1.0;
    vec2 uv = 0.5 * ndc.xy + 0.5;
    float ref = 0.5 * ndc.z + 0.5;
    float h = 0.5 / float(dsHeader.dims.y);
    float v = 0.0;
    v += texture(uDirectionalMaps, vec4(uv + vec2(-h, -h), float(k), ref));
    v += texture(uDirectionalMaps, vec4(uv + vec2(h, -h), float(k), ref));
    v += texture(uDirectionalMaps, vec4(uv + vec2(-h, h), float(k), ref));
    v += texture(uDirectionalMaps, vec4(uv + vec2(h, h), float(k), ref));
    return 0.25 * v;
}
