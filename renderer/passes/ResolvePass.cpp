#include "renderer/passes/ResolvePass.h"

#include <algorithm>
#include <cmath>

namespace candela {

void ResolvePass::resize(int width, int height) {
    mWidth = width;
    mHeight = height;
    int levels = 1 + int(std::floor(std::log2(double(std::max(width, height)))));
    mLinear = gl::Texture2D(width, height, GL_RGBA32F);
    mLuminance = gl::Texture2D(width, height, GL_R32F, levels);
    glTextureParameteri(mLuminance.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    mFbo = gl::Framebuffer({&mLinear, &mLuminance}, nullptr);
}

void ResolvePass::execute(ShaderLibrary& shaders, const gl::Texture2D& accum, const gl::Texture2D& once,
                          const gl::Texture2D& emission, int frames) {
    GLuint program = shaders.program({"fullscreen.vert", "resolve.frag", "", {}});
    glUseProgram(program);
    glProgramUniform1f(program, 0, frames > 0 ? 1.f / float(frames) : 0.f);
    glBindTextureUnit(0, accum.id());
    glBindTextureUnit(1, emission.id());
    glBindTextureUnit(2, once.id());
    glBindFramebuffer(GL_FRAMEBUFFER, mFbo.id());
    glViewport(0, 0, mWidth, mHeight);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glGenerateTextureMipmap(mLuminance.id());
}

}  // namespace candela
