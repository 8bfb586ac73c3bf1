// Interreflected light as seen: the surface's diffuse albedo / pi times the interpolated
// interreflected irradiance (the albedo is pi in illuminance mode, so the image holds E there).
// Patches reflect on their front side only; a back face shows none.
#include "common.glsl"
layout(binding = 2) uniform sampler2D gAlbedo;

in vec3 vIrradiance;
layout(location = 0) out vec4 outRadiance;

void main() {
    vec3 albedo = texelFetch(gAlbedo, ivec2(gl_FragCoord.xy), 0).rgb;
    vec3 result = gl_FrontFacing ? albedo / kPi * max(vIrradiance, vec3(0.0)) : vec3(0.0);
    if (any(isnan(result)) || any(isinf(result))) result = vec3(0.0);
    outRadiance = vec4(result, 1.0);
}
