// Compile-time checks that the C++ view of the structs in shaders/shared/GpuTypes.h has the
// std140/std430 layout the shaders expect (vec4-aligned members only, no padding surprises).
#include "renderer/passes/GBufferPass.h"
#include "shaders/shared/GpuTypes.h"

namespace candela::gpu {
static_assert(sizeof(FrameUniforms) == 2 * 64 + 4 * 16);
static_assert(sizeof(LambertianRectGpu) == 5 * 16);
static_assert(sizeof(LightFieldGpu) == 12 * 16);
static_assert(sizeof(PhotometricGpu) == 8 * 16);
static_assert(sizeof(EnvironmentGpu) == 4 * 16);
static_assert(sizeof(EnvironmentFaceGpu) == 16);
static_assert(sizeof(EnvironmentSampleGpu) == 2 * 16);
static_assert(sizeof(ShadowMapsGpu) == 2 * 16);
static_assert(sizeof(ShadowMapGpu) == 16);
static_assert(sizeof(BvhNode) == 32);
static_assert(sizeof(BvhTriangle) == 48);
static_assert(sizeof(GBufferPass::Vertex) == 17 * sizeof(float));
}  // namespace candela::gpu
