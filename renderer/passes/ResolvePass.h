#pragma once
// The linear HDR image and its luminance mips: the sum of the accumulated means of every
// luminaire (and of the environment), each its accumulation over its own number of passes,
// with directly seen luminaires' emission in their pixels.

#include <vector>

#include "renderer/ShaderLibrary.h"
#include "renderer/gl/GlObjects.h"

namespace candela {

class ResolvePass {
  public:
    /// A term of the sum: accumulated estimates and 1 / the passes they hold.
    struct Term {
        const gl::Texture2D* accumulation = nullptr;
        float scale = 1.f;
    };

    void resize(int width, int height);
    /// linear = sum of the terms (shaders/accumulate.frag), or the emission where the
    /// G-buffer's emission alpha marks a luminaire (shaders/resolve.frag).
    void execute(ShaderLibrary& shaders, const std::vector<Term>& terms,
                 const gl::Texture2D& emission);
    const gl::Texture2D& linear() const { return mLinear; }
    const gl::Texture2D& luminance() const { return mLuminance; }

  private:
    gl::Texture2D mLinear, mLuminance, mSum;
    gl::Framebuffer mFbo, mSumFbo;
    int mWidth = 0, mHeight = 0;
};

/// Adds each term's accumulation times its scale into target's first attachment (width x height),
/// by blending (shaders/accumulate.frag): the resolve's sum, and a pass joining an accumulation.
void addScaled(ShaderLibrary& shaders, const gl::Framebuffer& target, int width, int height,
               const std::vector<ResolvePass::Term>& terms);

}  // namespace candela
