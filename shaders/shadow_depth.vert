// Depth of the scene's triangles as one cube face of a shadow map sees them
// (renderer/passes/ShadowMapPass.cpp).
layout(location = 0) in vec3 inPosition;
layout(location = 0) uniform mat4 uViewProj;

void main() { gl_Position = uViewProj * vec4(inPosition, 1.0); }
