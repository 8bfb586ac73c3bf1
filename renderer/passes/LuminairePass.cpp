#include "renderer/passes/LuminairePass.h"

#include "renderer/PassTimer.h"
#include "renderer/passes/GBufferPass.h"
#include "renderer/passes/ShadePass.h"
#include "shaders/shared/GpuTypes.h"

namespace candela {

void LuminairePass::setSource(const Luminaire&, const std::vector<std::byte>& record) {
    if (record == mRecord && mBuffer.id()) return;
    mRecord = record;
    // GL refuses an empty buffer's storage: a kind with no record gets one zero word.
    std::vector<std::byte> data = mRecord.empty() ? std::vector<std::byte>(4) : mRecord;
    mBuffer = gl::Buffer(GLsizeiptr(data.size()), data.data());
}

void LuminairePass::prepare(const ShadeStep& step, SourceContext& context, int, int) {
    if (!step.shadowMaps) return;
    if (!mShadowMaps) mShadowMaps = std::make_unique<ShadowMaps>();
    ShadowLights lights = step.source->shadowLights(context.settings.shadowMaps.count);
    if (!mShadowMaps->stale(lights, context.settings.shadowMaps, context.geometryGeneration))
        return;
    const ShadowGeometry& geometry = context.geometry();
    context.timer.timed(context.stats, shadowPassName(step), [&] {
        mShadowMaps->render(context.shaders, geometry, lights, context.settings.shadowMaps,
                            context.geometryGeneration);
    });
}

void LuminairePass::shade(const ShadeStep& step, SourceContext& context,
                          const gl::Framebuffer& target) {
    if (step.shadowMaps && mShadowMaps) mShadowMaps->bind();
    GLuint program = context.shaders.program(step.program);
    glUseProgram(program);
    // Each luminaire has its own record buffer; the shader reads element 0.
    glProgramUniform1i(program, 0, 0);
    mBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, gpu::kBindingLuminaire);
    ShadePass::drawAdditive(context.gbuffer, target, context.gbuffer.width(),
                            context.gbuffer.height(), step.unitScale);
}

}  // namespace candela
