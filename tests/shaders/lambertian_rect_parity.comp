// Runs the production GLSL of shaders/lambertian_rect.glsl on test inputs so that
// tests/lambertian_rect_gltest.cpp can compare it with the C++ implementation.
#include "common.glsl"
#include "lambertian_rect.glsl"

layout(local_size_x = 64) in;

struct ParityIn {
    vec4 p;  // receiver position, metres
    vec4 n;  // receiver unit normal
    vec4 u;  // xy: sampler input in [0,1)^2
};
struct ParityOut {
    vec4 irradiance;  // rgb closed-form irradiance, a = solid angle (sr)
    vec4 sampleDir;   // xyz sampled direction, w = distance (m)
    vec4 sampleInfo;  // x = pdf (1/sr), y = 1 if a sample was produced
};

layout(std430, binding = 1) readonly buffer Luminaires { LambertianRectGpu lights[]; };
layout(std430, binding = 6) readonly buffer Inputs { ParityIn inputs[]; };
layout(std430, binding = 7) writeonly buffer Outputs { ParityOut outputs[]; };
layout(location = 0) uniform int uCount;

void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i >= uCount) return;
    LambertianRectGpu L = lights[0];
    vec3 p = inputs[i].p.xyz, n = inputs[i].n.xyz;
    ParityOut o;
    o.irradiance = vec4(lambertRectIrradiance(L, p, n), lambertRectSolidAngle(L, p));
    vec3 wi;
    float dist, pdf;
    bool ok = lambertRectSample(L, p, inputs[i].u.xy, wi, dist, pdf);
    o.sampleDir = vec4(wi, dist);
    o.sampleInfo = vec4(ok ? pdf : 0.0, ok ? 1.0 : 0.0, 0.0, 0.0);
    outputs[i] = o;
}
