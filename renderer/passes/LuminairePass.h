#pragma once
// A placed luminaire's GPU pass: its record (gpuData, luminaires/Adapter.h) in a buffer of its own,
// its tables (gpuTables) in textures, uploaded again only when the model changes, its shadow maps
// when its technique reads them (rendered from its shadowLights when stale), and the shading of its
// technique's variant (luminaires/Registry.cpp names the shader).

#include <memory>
#include <vector>

#include "renderer/passes/ShadowMapPass.h"
#include "renderer/passes/SourcePass.h"

namespace candela {

/// One table as an immutable 2D array texture (texelFetch only: nearest, no mipmaps); throws
/// RuntimeError where it exceeds the GL's texture limits.
gl::TextureArray uploadGpuTable(const GpuTable& t);

class LuminairePass final : public SourcePass {
  public:
    void setSource(const Luminaire& source, const std::vector<std::byte>& record) override;
    void prepare(const ShadeStep& step, SourceContext& context, int frame, int spp) override;
    void shade(const ShadeStep& step, SourceContext& context,
               const gl::Framebuffer& target) override;

  private:
    std::vector<std::byte> mRecord;  ///< As uploaded.
    gl::Buffer mBuffer;
    std::shared_ptr<const GpuTables> mTables;  ///< As uploaded into mTextures (same order).
    std::vector<gl::TextureArray> mTextures;
    std::unique_ptr<ShadowMaps> mShadowMaps;
};

}  // namespace candela
