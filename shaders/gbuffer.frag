// Writes position, normal, material and emission. Normals face the camera (two-sided surfaces);
// emitters show their radiance only from their emitting side.
#include "common.glsl"
in vec3 vPosition;
in vec3 vNormal;
in vec3 vAlbedo;
in vec4 vSpecular;
in vec3 vEmission;
flat in float vFlags;

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
    outAlbedo = vec4(vAlbedo, float(flags));
    outSpecular = vec4(vSpecular.rgb, 0.0);
    outEmission = vec4(emitter && front ? vEmission : vec3(0.0), 1.0);
}
