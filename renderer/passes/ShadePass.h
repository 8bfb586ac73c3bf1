#pragma once
// The draw every shading pass ends with (renderer/passes/SourcePass.h): the G-buffer bound, one
// full-screen triangle of the current program added into the target.

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
};

}  // namespace candela
