// Writes position, normal, material and emission. Luminaires are drawn after the scene into the
// emission attachment only (GBufferPass), so the other attachments describe the surface behind
// them and no luminaire's shading depends on where another one is. Normals face the camera (two-sided surfaces);
// emitters show their radiance only from their emitting side. In illuminance mode every other
// surface becomes a white Lambertian receiver of albedo pi (no glossy lobe), so the unchanged
// shading passes write (albedo / pi) E = E, the irradiance; emitters show nothing (their
// luminance is not an illuminance).
#include "common.glsl"
in vec3 vPosition;
in vec3 vNormal;
in vec3 vAlbedo;
in vec4 vSpecular;
in vec3 vEmission;
flat in float vFlags;
layout(location = 0) uniform int uIlluminance;  // 1: illuminance mode

layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outAlbedo;
layout(location = 3) out vec4 outSpecular;
layout(location = 4) out vec4 outEmission;

void main() {
    vec3 n = normalize(vNormal);
    vec3 toCamera = frame.cameraPos.xyz - vPosition;
    bool front = dot(n, toCamera) > 0.0;
    int flags = int(vFlags + 0.5);
    bool emitter = (flags & kMaterialEmitter) != 0;
    if (!front && !emitter) n = -n;
    outPosition = vec4(vPosition, 1.0);
    outNormal = vec4(n, vSpecular.a);
    vec3 albedo = vAlbedo, specular = vSpecular.rgb, emission = emitter && front ? vEmission : vec3(0.0);
    if (uIlluminance != 0) {
        emission = vec3(0.0);
        if (!emitter) {
            albedo = vec3(kPi);
            specular = vec3(0.0);
            flags &= ~kMaterialGlossy;
        }
    }
    outAlbedo = vec4(albedo, float(flags));
    outSpecular = vec4(specular, 0.0);
    // Alpha marks a luminaire's pixel (either side): the resolve shows its emission there.
    outEmission = vec4(emission, emitter ? 1.0 : 0.0);
}
