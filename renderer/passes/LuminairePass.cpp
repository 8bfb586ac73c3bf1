#include "renderer/passes/LuminairePass.h"

#include "renderer/PassTimer.h"
#include "renderer/passes/GBufferPass.h"
#include "renderer/passes/ShadePass.h"
#include "shaders/shared/GpuTypes.h"
#include "util/Error.h"

namespace candela {

gl::TextureArray uploadGpuTable(const GpuTable& t) {
    GLint maxSize = 0, maxLayers = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
    if (t.width < 1 || t.height < 1 || t.layers < 1 || t.width > maxSize || t.height > maxSize ||
        t.layers > maxLayers)
        throw RuntimeError("a luminaire table of " + std::to_string(t.width) + " x " +
                           std::to_string(t.height) + " texels x " + std::to_string(t.layers) +
                           " layers exceeds this GL's textures (" + std::to_string(maxSize) +
                           " texels a side, " + std::to_string(maxLayers) + " layers)");
    static const GLenum kFloat[] = {0, GL_R32F, GL_RG32F, 0, GL_RGBA32F};
    static const GLenum kHalf[] = {0, GL_R16F, GL_RG16F, 0, GL_RGBA16F};
    static const GLenum kFormat[] = {0, GL_RED, GL_RG, 0, GL_RGBA};
    gl::TextureArray texture(GL_TEXTURE_2D_ARRAY, t.width, t.height, t.layers,
                             t.half ? kHalf[t.channels] : kFloat[t.channels]);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage3D(texture.id(), 0, 0, 0, 0, t.width, t.height, t.layers, kFormat[t.channels],
                        GL_FLOAT, t.texels.data());
    return texture;
}

void LuminairePass::setSource(const Luminaire& source, const std::vector<std::byte>& record) {
    std::shared_ptr<const GpuTables> tables = gpuTables(source);
    if (tables != mTables) {
        mTextures.clear();
        try {
            if (tables)
                for (const GpuTable& t : *tables) mTextures.push_back(uploadGpuTable(t));
        } catch (const RuntimeError& e) {
            // Name the luminaire and its file: the table is the file's data.
            std::vector<std::string> files = sourceFiles(source);
            throw RuntimeError("luminaire \"" + source.name + "\"" +
                               (files.empty() ? std::string() : " (" + files.front() + ")") + ": " +
                               e.what());
        }
        mTables = tables;
    }
    if (record == mRecord && mBuffer.id()) return;
    mRecord = record;
    // GL refuses an empty buffer's storage: a kind with no record gets one zero word.
    std::vector<std::byte> data = mRecord.empty() ? std::vector<std::byte>(4) : mRecord;
    mBuffer = gl::Buffer(GLsizeiptr(data.size()), data.data());
}

void LuminairePass::prepare(const ShadeStep& step, SourceContext& context, int, int) {
    if (!step.shadowMaps) return;
    if (!mShadowMaps) mShadowMaps = std::make_unique<ShadowMaps>();
    ShadowLights lights = shadowLights(*step.source, context.settings.shadowMaps.count);
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
    for (size_t i = 0; i < mTextures.size(); ++i)
        glBindTextureUnit(GLuint((*mTables)[i].unit), mTextures[i].id());
    ShadePass::drawAdditive(context.gbuffer, target, context.gbuffer.width(),
                            context.gbuffer.height(), step.unitScale);
}

}  // namespace candela
