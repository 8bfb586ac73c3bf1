#pragma once
// Shades the G-buffer with one luminaire through its technique's shader variant and adds the
// frame's estimate into the accumulation buffer. Generic over kinds and techniques: the
// technique table (luminaires/Registry.cpp) names the shader and the variant define.

#include "renderer/FramePlan.h"
#include "renderer/ShaderLibrary.h"
#include "renderer/gl/GlObjects.h"

namespace candela {

class GBufferPass;

class ShadePass {
public:
    /// Binds the G-buffer to units 0-3 and adds one full-screen triangle of the current program
    /// into `target` times `scale` (every shading pass, the environment's too; the scale is the
    /// step's unit conversion, ShadeStep::unitScale).
    static void drawAdditive(const GBufferPass& gbuffer, const gl::Framebuffer& target, int width,
                             int height, float scale = 1.f);
    void execute(ShaderLibrary& shaders, const ShadeStep& step, const gl::Buffer& luminaire,
                 const GBufferPass& gbuffer, const gl::Framebuffer& target, int width, int height);
};

}  // namespace candela
