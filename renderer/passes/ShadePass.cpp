#include "renderer/passes/ShadePass.h"

#include "renderer/passes/GBufferPass.h"
#include "shaders/shared/GpuTypes.h"

namespace candela {

void ShadePass::drawAdditive(const GBufferPass& gbuffer, const gl::Framebuffer& target, int width,
                             int height, float scale) {
    for (int i = 0; i < 4; ++i) glBindTextureUnit(GLuint(i), gbuffer.texture(i).id());
    glBindFramebuffer(GL_FRAMEBUFFER, target.id());
    glViewport(0, 0, width, height);
    glEnable(GL_BLEND);
    // target += scale * colour (the unit conversion of a mixed scene; alpha keeps its weight 1).
    glBlendColor(scale, scale, scale, 1.f);
    glBlendFunc(GL_CONSTANT_COLOR, GL_ONE);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_BLEND);
}

}  // namespace candela
