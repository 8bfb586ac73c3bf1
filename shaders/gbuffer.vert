#include "common.glsl"
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec3 inAlbedo;
layout(location = 3) in vec4 inSpecular;  // rgb reflectance, a = Phong exponent
layout(location = 4) in vec3 inEmission;
layout(location = 5) in float inFlags;

out vec3 vPosition;
out vec3 vNormal;
out vec3 vAlbedo;
out vec4 vSpecular;
out vec3 vEmission;
flat out float vFlags;

void main() {
    vPosition = inPosition;
    vNormal = inNormal;
    vAlbedo = inAlbedo;
    vSpecular = inSpecular;
    vEmission = inEmission;
    vFlags = inFlags;
    gl_Position = frame.viewProj * vec4(inPosition, 1.0);
}
