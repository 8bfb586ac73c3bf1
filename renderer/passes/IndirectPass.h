#pragma once
// Shows interreflected light (calculation/InterreflectionWorker.h): rasterises the radiosity
// patches with their per-vertex interreflected irradiance into an image of the radiance they
// reflect (shaders/indirect.*), with its own depth buffer, which the resolve adds to the
// luminaires' accumulations. It runs only when the solution or the view changed.

#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "renderer/ShaderLibrary.h"
#include "renderer/gl/GlObjects.h"

namespace candela {

class GBufferPass;
struct RadiosityMesh;

class IndirectPass {
  public:
    void resize(int width, int height);
    /// The patches (uploaded when the mesh object changes) and their vertices' irradiance.
    void set(const std::shared_ptr<const RadiosityMesh>& mesh,
             const std::vector<glm::vec3>& vertexIrradiance);
    void clear();
    bool hasLight() const { return mIndexCount > 0; }
    /// Renders the image of the interreflected light for the current frame uniforms.
    void execute(ShaderLibrary& shaders, const GBufferPass& gbuffer);
    const gl::Texture2D& image() const { return mImage; }

  private:
    std::shared_ptr<const RadiosityMesh> mMesh;
    gl::Buffer mPositions, mIrradiance, mIndices;
    gl::VertexArray mVao;
    GLsizei mIndexCount = 0;
    gl::Texture2D mImage, mDepth;
    gl::Framebuffer mFbo;
    int mWidth = 0, mHeight = 0;
};

}  // namespace candela
