#pragma once
// Shadow maps of one luminaire (Lu et al. 2015, Sec. 6.2, for light fields; the same module for
// any kind whose shadowLights (luminaires/Adapter.h) names lights). Each map is a depth cube map
// around one light point, so every direction is covered and no receiver falls outside a frustum;
// the maps of a luminaire share one cube-map array texture (6 layers per map). Shading reads them
// through shaders/shadow_maps.glsl, which documents the bias and the filtering.
//
// Work happens only when something the maps depend on changed: the lights (the luminaire moved,
// turned or was swapped, or the map count changed), the resolution, or the scene's geometry.

#include <vector>

#include "luminaires/Luminaire.h"
#include "renderer/ShaderLibrary.h"
#include "renderer/gl/GlObjects.h"
#include "scene/Scene.h"

namespace candela {

/// The user's shadow-map parameters (RenderSettings::shadowMaps).
struct ShadowMapSettings {
    int count = 49;  ///< Maps per luminaire, about (0: the kind's natural count, one per cell).
    int resolution = 192;             ///< Texels along a cube face's edge.
    int directionalResolution = 256;  ///< Texels along a directional map's edge.
    float normalOffset = 1.0f;  ///< Receiver offset along its normal, texels (shadow_maps.glsl).
    float depthOffset = 1.0f;   ///< Then towards the light, texels.
    bool operator==(const ShadowMapSettings&) const = default;
};

/// The scene's triangles as positions only, for depth rendering.
class ShadowGeometry {
  public:
    void set(const Scene& scene);
    /// Draws every triangle; with a light position, leaves out the luminaire bodies whose bounds
    /// hold it (they cast no shadow on their own light: scene/Scene.h, insideBody).
    void draw(const glm::dvec3* light = nullptr) const;
    /// Smallest and largest corner of the triangles' bounds (metres).
    glm::dvec3 lo{0.0}, hi{0.0};

  private:
    gl::Buffer mVertices, mIndices;
    gl::VertexArray mVao;
    GLsizei mIndexCount = 0;
    /// The indices hold every other mesh first (mSceneCount of them), then each body's.
    GLsizei mSceneCount = 0;
    struct Body {
        GLsizei first = 0, count = 0;
        glm::dvec3 lo{0.0}, hi{0.0};
    };
    std::vector<Body> mBodies;
};

class ShadowMaps {
  public:
    /// Near plane of every face, metres: geometry closer to a map's light casts no shadow.
    static constexpr double kNear = 0.005;

    /// Whether render() would produce something different from what the maps hold.
    bool stale(const ShadowLights& lights, const ShadowMapSettings& settings,
               int geometryGeneration) const;
    /// Renders the lit maps' six faces (unlit maps are skipped and read as lit).
    void render(ShaderLibrary& shaders, const ShadowGeometry& geometry, const ShadowLights& lights,
                const ShadowMapSettings& settings, int geometryGeneration);
    /// Binds the maps' texture and buffers for a shading pass.
    void bind() const;
    int mapCount() const { return int(mLights.lights.size()); }

  private:
    ShadowLights mLights;
    ShadowMapSettings mSettings;
    int mGeneration = -1;
    gl::TextureArray mDepth;
    gl::Framebuffer mFbo;
    gl::Buffer mHeader, mShares;
};

/// Directional shadow maps (the environment's Havran lights, one map per light): orthographic
/// depth maps over the scene's bounding sphere, in one 2D array texture. Shading reads them
/// through shaders/shadow_directional.glsl.
class DirectionalShadowMaps {
  public:
    bool stale(const std::vector<glm::dvec3>& directions, const ShadowMapSettings& settings,
               int geometryGeneration) const;
    /// directions: unit vectors towards each light.
    void render(ShaderLibrary& shaders, const ShadowGeometry& geometry,
                const std::vector<glm::dvec3>& directions, const ShadowMapSettings& settings,
                int geometryGeneration);
    void bind() const;

  private:
    std::vector<glm::dvec3> mDirections;
    ShadowMapSettings mSettings;
    int mGeneration = -1;
    gl::TextureArray mDepth;
    gl::Framebuffer mFbo;
    gl::Buffer mData;
};

}  // namespace candela
