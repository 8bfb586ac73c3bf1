// Runs the production GLSL of shaders/lightfield.glsl on test inputs so that
// tests/lightfield_gltest.cpp can compare it with the C++ implementation and test the GLSL
// sampler with chi-square.
#include "common.glsl"
#include "lightfield.glsl"

layout(local_size_x = 64) in;

struct ParityIn {
    vec4 box;  // xy = box min, zw = box max on S (m)
    vec4 xi;   // xy = sampler input in [0,1)^2
    ivec4 m;   // x = image index
};
struct ParityOut {
    vec4 sampled;  // xy = sample on S (m), z = 1 if a sample was produced, w = C_m there
    vec4 area;     // x = A_m of the box, y = C_m at the box centre
};

layout(std430, binding = 6) readonly buffer Inputs { ParityIn inputs[]; };
layout(std430, binding = 7) writeonly buffer Outputs { ParityOut outputs[]; };
layout(location = 0) uniform int uCount;

void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i >= uCount) return;
    ParityIn p = inputs[i];
    int m = p.m.x;
    vec2 s;
    bool ok = lfSampleBox(m, p.box.xy, p.box.zw, p.xi.xy, s);
    ParityOut o;
    o.sampled = vec4(s, ok ? 1.0 : 0.0, ok ? lfLum(m, s) : 0.0);
    o.area = vec4(lfBoxIntegral(m, p.box.xy, p.box.zw), lfLum(m, 0.5 * (p.box.xy + p.box.zw)), 0.0, 0.0);
    outputs[i] = o;
}
