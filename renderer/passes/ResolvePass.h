#pragma once
// Accumulated mean plus directly seen emission: the linear HDR image and its luminance mips.

#include "renderer/ShaderLibrary.h"
#include "renderer/gl/GlObjects.h"

namespace candela {

class ResolvePass {
public:
    void resize(int width, int height);
    /// linear = accum / frames + once + emission (once: deterministic steps shaded a single time).
    void execute(ShaderLibrary& shaders, const gl::Texture2D& accum, const gl::Texture2D& once,
                 const gl::Texture2D& emission, int frames);
    const gl::Texture2D& linear() const { return mLinear; }
    const gl::Texture2D& luminance() const { return mLuminance; }

private:
    gl::Texture2D mLinear, mLuminance;
    gl::Framebuffer mFbo;
    int mWidth = 0, mHeight = 0;
};

}  // namespace candela
