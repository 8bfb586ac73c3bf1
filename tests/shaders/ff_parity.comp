// Runs shaders/ff.glsl on test inputs so that tests/ff_gltest.cpp can compare its float-float
// arithmetic with 64-bit arithmetic on the CPU, under the compiler that runs the shaders.
#include "ff.glsl"

layout(local_size_x = 64) in;

struct FfIn {
    vec4 ab;  // xy = a, zw = b (float-float pairs)
    vec4 c;   // x = a float factor
};
struct FfOut {
    vec4 sumDifference;  // xy = a + b, zw = a - b
    vec4 productQuotient;  // xy = a x c, zw = a / b
    vec4 twoProduct;     // xy = a.hi x c exactly (TwoProduct), zw = TwoSum(a.hi, b.hi)
};

layout(std430, binding = 6) readonly buffer Inputs { FfIn inputs[]; };
layout(std430, binding = 7) writeonly buffer Outputs { FfOut outputs[]; };
layout(location = 0) uniform int uCount;

void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i >= uCount) return;
    vec2 a = inputs[i].ab.xy, b = inputs[i].ab.zw;
    float c = inputs[i].c.x;
    FfOut o;
    o.sumDifference = vec4(ffAdd(a, b), ffSub(a, b));
    o.productQuotient = vec4(ffMulF(a, c), ffDiv(a, b));
    o.twoProduct = vec4(ffTwoProduct(a.x, c), ffTwoSum(a.x, b.x));
    outputs[i] = o;
}
