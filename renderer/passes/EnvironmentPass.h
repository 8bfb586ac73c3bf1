#pragma once
// The environment's pass (renderer/passes/SourcePass.h) on the GPU (Lu et al. 2013, Algorithm
// 1): uploads the lat-long map, builds the cube-face luminance, weights and CDFs in compute
// shaders whenever the map changes, draws each pass's pools of light samples per face, builds the
// lat-long CDF or Havran's lights and their shadow maps for the techniques that read them, and
// shades the G-buffer with the technique (shaders/environment_TECHNIQUE.frag). The CPU twin
// is luminaires/EnvironmentSampling. One pass outlives the maps it is given (a sequence's frames,
// a moving sun), so Havran's temporal filter sees them all.

#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "luminaires/environment/EnvironmentSampling.h"
#include "renderer/FramePlan.h"
#include "renderer/ProgramVariants.h"
#include "renderer/ShaderLibrary.h"
#include "renderer/gl/GlObjects.h"
#include "renderer/passes/ShadowMapPass.h"
#include "renderer/passes/SourcePass.h"
#include "shaders/shared/GpuTypes.h"

namespace candela {

class GBufferPass;

/// A guide for searching one CDF the way environment_global_cdf.frag does: `cdf` holds entries
/// 1..n of a CDF whose entry 0 is 0, as floats; the result's entry j is the last entry i in
/// [0, n) that does not exceed the smallest u the shader puts in bucket j = min(int(u n), n - 1)
/// in float arithmetic. Every u of bucket j then lies in [entry g[j], entry g[j + 1] + 1) (n for
/// the last bucket), so the shader's search starts there: the same index as a search of the
/// whole CDF, in one or two steps instead of log2 n dependent fetches.
std::vector<float> cdfSearchGuide(const float* cdf, int n);

class EnvironmentPass final : public SourcePass {
  public:
    EnvironmentPass();  ///< Needs a current GL context.

    /// The source's map (an EnvironmentLight); the tables follow at the next prepare().
    void setSource(const Luminaire& source, const std::vector<std::byte>& record) override;
    /// The technique's resources: "cube" builds the cube-map tables when the map changed
    /// ("env:cdf") and draws this pass's pools of samples ("env:samples"); "latlong" the CPU's
    /// global CDF; "lights" Havran's lights and, with shadow maps, one map per light.
    void prepare(const ShadeStep& step, SourceContext& context, int frame, int spp) override;
    void shade(const ShadeStep& step, SourceContext& context,
               const gl::Framebuffer& target) override;
    /// The timed prepasses prepare() runs for a technique (FramePlan::passNames).
    static std::vector<std::string> prepassNames(const TechniqueInfo& technique);

    /// Face size used for a map when none is asked for: the CPU default (texels no larger than
    /// the lat-long map's at the equator) capped at 256, the paper's size.
    static int defaultFaceSize(const EnvironmentMap& map);

    /// Makes `map` current. Returns true when it differs from the map the tables were built for
    /// (then the next buildTables() does the work). faceSize 0: defaultFaceSize.
    bool setMap(std::shared_ptr<const EnvironmentMap> map, int faceSize = 0);
    /// Algorithm 1, lines 6-9 (cube conversion, face energies, prefix sums, CDFs) on the GPU.
    void buildTables(ShaderLibrary& shaders);
    /// Line 10: `pool` light samples per face from the frame's seed.
    void drawSamples(ShaderLibrary& shaders, uint32_t seed, int pool);
    /// What the global-cdf and havran2005 techniques read, built on the CPU for the current map.
    void prepareGlobalCdf();
    void prepareHavran();
    /// Unit directions towards the Havran lights prepareHavran() uploaded (empty before).
    std::vector<glm::dvec3> havranDirections() const;
    /// Shades the G-buffer into `target` (additive). background: show the map behind the scene.
    void shade(ShaderLibrary& shaders, const ShadeStep& step, const GBufferPass& gbuffer,
               const gl::Framebuffer& target, int width, int height, bool background);

    const EnvironmentMap* map() const { return mMap.get(); }
    int faceSize() const { return mN; }
    bool tablesBuilt() const { return mBuilt; }

    /// Read-backs for tests: per texel (luminance, weight), [face][row][col]; the CDFs; the face
    /// totals (I_f, energy); the last pools of samples [face][pool]. The CDFs are float-float pairs
    /// on the GPU, returned as their 64-bit values.
    std::vector<glm::vec2> readCube() const;
    std::vector<double> readRowCdf() const;
    std::vector<double> readColumnCdf() const;
    std::vector<gpu::EnvironmentFaceGpu> readFaces() const;
    std::vector<gpu::EnvironmentSampleGpu> readSamples() const;

  private:
    void bindAll() const;
    void dispatch(ShaderLibrary& shaders, programs::EnvironmentTables pass, GLuint x, GLuint y,
                  GLuint z);

    std::shared_ptr<const EnvironmentMap> mMap;
    bool mBuilt = false;
    int mN = 0, mPool = 0;
    gpu::EnvironmentGpu mUniforms{};
    gl::Texture2D mTexture;
    gl::Buffer mUniformBuffer, mCube, mFaces, mSamples, mExtra;
    gl::TextureArray mRowCdf;  ///< CDF(v | u) per face and column (kUnitEnvRowCdf).
    gl::Texture2D mColumnCdf;  ///< CDF(u) per face, then the columns' totals.
    gl::Texture2D mGlobalCdf;  ///< The global-cdf technique's lat-long CDF and its search guide.
    std::weak_ptr<const EnvironmentMap> mExtraFor;      ///< Map whose Havran lights mExtra holds.
    std::weak_ptr<const EnvironmentMap> mGlobalCdfFor;  ///< Map mGlobalCdf was built for.
    std::unique_ptr<HavranLights> mHavran;
    std::weak_ptr<const EnvironmentMap> mHavranFor;    ///< Newest map the filter has seen.
    std::shared_ptr<const EnvironmentMap> mSourceMap;  ///< The source's, made current in prepare().
    DirectionalShadowMaps mShadows;                    ///< One map per Havran light.
};

}  // namespace candela
