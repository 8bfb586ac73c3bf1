// The radiosity patches with their interreflected irradiance per vertex (calculation/Radiosity.h),
// rasterised like the G-buffer so each pixel gets the value at the surface it sees.
#include "common.glsl"
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inIrradiance;  // interreflected irradiance, W/m2 or lx, RGB

out vec3 vIrradiance;

void main() {
    vIrradiance = inIrradiance;
    gl_Position = frame.viewProj * vec4(inPosition, 1.0);
}
