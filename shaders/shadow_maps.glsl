// Visibility from a luminaire's shadow maps (renderer/passes/ShadowMapPass.h): each map is a
// depth cube map around one light point, and each item of the luminaire (a light field's image)
// averages the maps its shares name. Bias and filtering, in texels of the face at the receiver's
// depth (texel = 2 z / R for the major-axis distance z and R texels per face edge):
//  - normal offset: the receiver moves params.z texels along its normal, turned to the light;
//  - depth offset: then params.w texels towards the light;
//  - filtering: four hardware-compared bilinear lookups at +-1/2 texel, a 3 x 3 texel tent.
// A receiver closer to the light than the near plane is lit (nothing fits in between).
#pragma once
#include "common.glsl"

layout(binding = 6) uniform samplerCubeArrayShadow uShadowMaps;  // kUnitShadowMaps
layout(std430, binding = 14) readonly buffer ShadowMapBlock {    // kBindingShadowMaps
    ShadowMapsGpu smHeader;
    ShadowMapGpu smMaps[];
};
layout(std430, binding = 15) readonly buffer ShadowShareBlock {  // kBindingShadowShares
    vec2 smShares[];  // (map, weight), items x smHeader.dims.z
};

/// Fraction of the 3 x 3 texel neighbourhood of p that map k sees lit; n: p's unit normal.
float shadowMapVisibility(int k, vec3 p, vec3 n) {
    vec4 light = smMaps[k].light;
    if (light.w == 0.0) return 1.0;
    float near = smHeader.params.x, far = smHeader.params.y;
    float res = float(smHeader.dims.y);
    vec3 d = p - light.xyz;
    float z = max(abs(d.x), max(abs(d.y), abs(d.z)));
    if (!(z > near)) return 1.0;
    float texel = 2.0 * z / res;
    vec3 toLight = -normalize(d);
    vec3 nl = dot(n, toLight) < 0.0 ? -n : n;
    vec3 dq = d + (nl * smHeader.params.z + toLight * smHeader.params.w) * texel;
    vec3 a = abs(dq);
    float zq = max(a.x, max(a.y, a.z));
    if (!(zq > near)) return 1.0;
    // Window depth of a point at major-axis distance zq under the faces' perspective projection.
    float ndc = (far + near) / (far - near) - 2.0 * far * near / ((far - near) * zq);
    float ref = 0.5 * ndc + 0.5;
    vec3 dir = dq / zq;  // on the unit cube: the face spans [-1, 1], a texel is 2 / res
    vec3 t1, t2;
    if (a.x >= a.y && a.x >= a.z) {
        t1 = vec3(0.0, 1.0, 0.0);
        t2 = vec3(0.0, 0.0, 1.0);
    } else if (a.y >= a.z) {
        t1 = vec3(1.0, 0.0, 0.0);
        t2 = vec3(0.0, 0.0, 1.0);
    } else {
        t1 = vec3(1.0, 0.0, 0.0);
        t2 = vec3(0.0, 1.0, 0.0);
    }
    float h = 1.0 / res;  // half a texel
    float v = 0.0;
    v += texture(uShadowMaps, vec4(dir - h * t1 - h * t2, float(k)), ref);
    v += texture(uShadowMaps, vec4(dir + h * t1 - h * t2, float(k)), ref);
    v += texture(uShadowMaps, vec4(dir - h * t1 + h * t2, float(k)), ref);
    v += texture(uShadowMaps, vec4(dir + h * t1 + h * t2, float(k)), ref);
    return 0.25 * v;
}

/// The item's averaged visibility: sum over its shares of weight x visibility of the map.
float shadowItemVisibility(int item, vec3 p, vec3 n) {
    int count = smHeader.dims.z;
    float v = 0.0;
    for (int j = 0; j < count; ++j) {
        vec2 share = smShares[item * count + j];
        if (share.y > 0.0) v += share.y * shadowMapVisibility(int(share.x), p, n);
    }
    return v;
}
