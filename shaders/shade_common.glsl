// G-buffer access and the BRDF shared by every luminaire shading pass.
#include "common.glsl"

layout(binding = 0) uniform sampler2D gPosition;
layout(binding = 1) uniform sampler2D gNormal;
layout(binding = 2) uniform sampler2D gAlbedo;
layout(binding = 3) uniform sampler2D gSpecular;

struct Surface {
    vec3 p;         // world position, metres
    vec3 n;         // unit normal facing the camera
    vec3 wo;        // unit direction to the camera
    vec3 albedo;    // diffuse reflectance
    vec3 specular;  // glossy reflectance (0: Lambertian only)
    float exponent; // Phong exponent of the glossy lobe
    int flags;
};

/// Reads the surface under this fragment; false for background and emitter pixels.
bool loadSurface(out Surface s) {
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 pos = texelFetch(gPosition, px, 0);
    vec4 alb = texelFetch(gAlbedo, px, 0);
    s.flags = int(alb.w + 0.5);
    if (pos.w == 0.0 || (s.flags & kMaterialEmitter) != 0) return false;
    vec4 nrm = texelFetch(gNormal, px, 0);
    s.p = pos.xyz;
    s.n = nrm.xyz;
    s.exponent = nrm.w;
    s.albedo = alb.rgb;
    s.specular = texelFetch(gSpecular, px, 0).rgb;
    vec3 toCam = frame.cameraPos.xyz - s.p;
    s.wo = toCam / max(length(toCam), 1e-20);
    return true;
}

/// Normalised modified Phong lobe (Lafortune and Willems 1994): (n+2)/(2 pi) cos^n(alpha).
vec3 glossyBrdf(Surface s, vec3 wi) {
    vec3 r = reflect(-s.wo, s.n);
    float c = max(dot(r, wi), 0.0);
    return s.specular * (s.exponent + 2.0) / (2.0 * kPi) * pow(c, s.exponent);
}

/// The surface's BRDF for light arriving from wi: Lambert, plus the Phong lobe on glossy
/// materials in GLOSSY variants.
vec3 brdf(Surface s, vec3 wi) {
    vec3 f = s.albedo / kPi;
#ifdef GLOSSY
    if ((s.flags & kMaterialGlossy) != 0) f += glossyBrdf(s, wi);
#endif
    return f;
}

/// Offset origin for shadow rays, so a surface does not shadow itself.
vec3 shadowOrigin(Surface s) { return s.p + s.n * 1e-4 * max(1.0, length(s.p)); }
