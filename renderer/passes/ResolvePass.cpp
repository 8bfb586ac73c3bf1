#include "renderer/passes/ResolvePass.h"

#include <algorithm>
#include <cmath>

#include "renderer/ProgramVariants.h"

namespace candela {

void ResolvePass::resize(int width, int height) {
    mWidth = width;
    mHeight = height;
    int levels = 1 + int(std::floor(std::log2(double(std::max(width, height)))));
    mLinear = gl::Texture2D(width, height, GL_RGBA32F);
    mLuminance = gl::Texture2D(width, height, GL_R32F, levels);
    glTextureParameteri(mLuminance.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    mFbo = gl::Framebuffer({&mLinear, &mLuminance}, nullptr);
    mSum = gl::Texture2D(width, height, GL_RGBA32F);
    mSumFbo = gl::Framebuffer({&mSum}, nullptr);
}

void ResolvePass::execute(ShaderLibrary& shaders, const std::vector<Term>& terms,
                          const gl::Texture2D& emission) {
    const float zero[4] = {0.f, 0.f, 0.f, 0.f};
    glClearNamedFramebufferfv(mSumFbo.id(), GL_COLOR, 0, zero);
    addScaled(shaders, mSumFbo, mWidth, mHeight, terms);

    GLuint program = shaders.program(programs::resolve());
    glUseProgram(program);
    glProgramUniform1f(program, 0, 1.f);
    glBindTextureUnit(0, mSum.id());
    glBindTextureUnit(1, emission.id());
    glBindFramebuffer(GL_FRAMEBUFFER, mFbo.id());
    glViewport(0, 0, mWidth, mHeight);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glGenerateTextureMipmap(mLuminance.id());
}

void addScaled(ShaderLibrary& shaders, const gl::Framebuffer& target, int width, int height,
               const std::vector<ResolvePass::Term>& terms) {
    GLuint add = shaders.program(programs::accumulate());
    glUseProgram(add);
    glBindFramebuffer(GL_FRAMEBUFFER, target.id());
    glViewport(0, 0, width, height);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    for (const ResolvePass::Term& t : terms) {
        if (!t.accumulation) continue;
        glProgramUniform1f(add, 0, t.scale);
        glBindTextureUnit(0, t.accumulation->id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glDisable(GL_BLEND);
}

}  // namespace candela
