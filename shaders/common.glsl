// Shared by every pass: the per-frame uniform block, constants and random numbers.
#include "shared/GpuTypes.h"
#include "shared/Constants.h"

layout(std140, binding = 0) uniform FrameBlock { FrameUniforms frame; };

/// PCG hash (O'Neill): a well-mixed 32-bit value from a 32-bit input.
uint pcgHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

/// Per-pixel, per-sample random stream: state advanced by rand01().
uint rngSeed(uvec2 pixel, uint sampleIndex) {
    return pcgHash(pixel.x + pcgHash(pixel.y + pcgHash(sampleIndex)));
}

float rand01(inout uint state) {
    state = pcgHash(state);
    return float(state >> 8) * (1.0 / 16777216.0);
}

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }
