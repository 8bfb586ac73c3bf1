#pragma once
// Linear HDR to display sRGB with the exponential or Reinhard operator (shaders/tonemap.frag).

#include "renderer/ShaderLibrary.h"
#include "renderer/gl/GlObjects.h"

namespace candela {

struct RenderSettings;

class TonemapPass {
public:
    void resize(int width, int height);
    void execute(ShaderLibrary& shaders, const gl::Texture2D& linear,
                 const gl::Texture2D& luminance, const RenderSettings& settings);
    const gl::Texture2D& display() const { return mDisplay; }

private:
    gl::Texture2D mDisplay;
    gl::Framebuffer mFbo;
    int mWidth = 0, mHeight = 0;
};

}  // namespace candela
