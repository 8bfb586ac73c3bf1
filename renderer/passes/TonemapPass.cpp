#include "renderer/passes/TonemapPass.h"

#include "renderer/Renderer.h"

namespace candela {

void TonemapPass::resize(int width, int height) {
    mWidth = width;
    mHeight = height;
    mDisplay = gl::Texture2D(width, height, GL_RGBA8);
    glTextureParameteri(mDisplay.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(mDisplay.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    mFbo = gl::Framebuffer({&mDisplay}, nullptr);
}

void TonemapPass::execute(ShaderLibrary& shaders, const gl::Texture2D& linear,
                          const gl::Texture2D& luminance, const RenderSettings& settings) {
    GLuint program = shaders.program({"fullscreen.vert", "tonemap.frag", "", {}});
    glUseProgram(program);
    glProgramUniform1i(program, 0, int(settings.toneMap));
    glProgramUniform1f(program, 1, settings.exposure);
    glProgramUniform1f(program, 2, settings.fixedAverage);
    glBindTextureUnit(0, linear.id());
    glBindTextureUnit(1, luminance.id());
    glBindFramebuffer(GL_FRAMEBUFFER, mFbo.id());
    glViewport(0, 0, mWidth, mHeight);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace candela
