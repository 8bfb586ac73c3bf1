#pragma once
// Rasterises the scene and the luminaires' emitting surfaces into the G-buffer (layout in
// shaders/shared/GpuTypes.h). In probe mode the G-buffer is filled with given points instead.
// In illuminance mode the materials are replaced by a white Lambertian receiver of albedo pi.

#include <array>
#include <vector>

#include "renderer/FramePlan.h"
#include "renderer/ShaderLibrary.h"
#include "renderer/gl/GlObjects.h"
#include "scene/Scene.h"

namespace candela {

class GBufferPass {
  public:
    void resize(int width, int height);
    void setGeometry(const Scene& scene);
    void setLuminaires(const Scene& scene);
    /// Illuminance: every non-emitter gets albedo pi and no glossy lobe, emitters no emission,
    /// so the shading passes write irradiance (shaders/gbuffer.frag).
    void execute(ShaderLibrary& shaders, Quantity quantity = Quantity::Radiance);
    /// Fills the G-buffer with points (one texel each, rows of `width`, row-major) for the
    /// probe; albedo = pi. Texels past the last point stay empty (no surface).
    void uploadPoints(const std::vector<glm::vec3>& points, const std::vector<glm::vec3>& normals,
                      int width);

    const gl::Texture2D& texture(int attachment) const { return mTextures[size_t(attachment)]; }
    int width() const { return mWidth; }
    int height() const { return mHeight; }

    /// Interleaved vertex for the G-buffer (locations in shaders/gbuffer.vert).
    struct Vertex {
        glm::vec3 position, normal, albedo;
        glm::vec4 specular;  ///< rgb reflectance, a = Phong exponent
        glm::vec3 emission;
        float flags;
    };

  private:
    struct Draw {
        gl::Buffer vbo;
        gl::Buffer ibo;
        gl::VertexArray vao;
        GLsizei indexCount = 0;
    };
    static Draw makeDraw(const std::vector<Vertex>& vertices, const std::vector<uint32_t>& indices);

    int mWidth = 0, mHeight = 0;
    std::array<gl::Texture2D, 5> mTextures;
    gl::Texture2D mDepth;
    gl::Framebuffer mFbo;
    Draw mScene, mLuminaires;
};

}  // namespace candela
