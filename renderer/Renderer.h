#pragma once
// The progressive renderer: G-buffer, one shading pass per luminaire (its technique's shader
// variant), accumulation in float buffers, resolve to linear HDR, tone mapping. Works in any
// current GL 4.5 context. Nothing runs that the scene does not need, and a converged image with
// no change costs no pass at all.

#include <cstddef>
#include <memory>
#include <cstdint>
#include <string>
#include <vector>

#include "renderer/FramePlan.h"
#include "renderer/FrameStats.h"
#include "renderer/ShaderLibrary.h"
#include "renderer/gl/GlObjects.h"
#include "renderer/passes/ShadowMapPass.h"
#include "renderer/passes/TonemapPass.h"
#include "scene/Scene.h"

#include <map>

namespace candela {

class GBufferPass;
class ShadePass;
class ResolvePass;
class TonemapPass;
class EnvironmentPass;
class IndirectPass;
struct Bvh;
struct RadiosityMesh;

/// Which light the image shows: all of it, the direct light alone, or the interreflected light
/// alone (what a designer's false colour compares).
enum class LightParts { Total = 0, Direct = 1, Interreflected = 2 };

/// FalseColour maps the values (lux in illuminance mode) through `RenderSettings::legend`.
enum class ToneMapOperator { Exponential = 0, Reinhard = 1, FalseColour = 2 };

struct RenderSettings {
    int width = 512;
    int height = 512;
    int samplesPerFrame = 4;        ///< Light samples per pixel per luminaire each frame.
    int maxSamples = 0;             ///< Stop refining at this many samples per pixel; 0 = never.
    /// Empty: each luminaire's own technique. Else names separated by commas; each luminaire
    /// uses the first its kind has (see planFrame).
    std::string techniqueOverride;
    ToneMapOperator toneMap = ToneMapOperator::Exponential;
    float exposure = 1.0f;          ///< k of the operators in shaders/tonemap.frag.
    float fixedAverage = 0.0f;      ///< > 0: tone-map against this luminance, not the frame mean.
    /// Radiance: what the camera sees. Illuminance: every surface but the luminaires is a white
    /// Lambertian receiver of albedo pi (no glossy lobe), so each pixel holds the irradiance E on
    /// the surface, W/m2 (lux for photometric luminaires); luminaires show no value.
    Quantity quantity = Quantity::Radiance;
    FalseColourLegend legend;       ///< Used by ToneMapOperator::FalseColour.
    LightParts parts = LightParts::Total;  ///< Display only: changing it re-renders nothing.
    uint32_t seed = 0;              ///< Seeds the random numbers (independent renders differ).
    /// The environment's technique; empty: techniqueOverride if it names one, else "balanced".
    std::string environmentTechnique;
    int environmentFaceSize = 0;    ///< Cube faces of N^2 texels; 0: EnvironmentPass's default.
    ShadowMapSettings shadowMaps;   ///< For techniques that read shadow maps.
    /// > 0: renderFrame() shades only a band of rows that takes about this long (ms), so an
    /// interactive caller gets control back in time whatever one pass over the image costs; the
    /// image shown is updated when a pass is complete (band by band during the first pass).
    /// 0: every call shades the whole image (headless rendering, benches, tests).
    double bandBudgetMs = 0.0;
    /// A luminaire behind the others (one that moved) takes up to this many passes' samples in
    /// one pass: a pass has a fixed cost per pixel that more samples share (the light field's
    /// restricted-cdf at 960x540 on llvmpipe: 2.5 s for 16 spp, 4.4 s for 48). 1: every pass
    /// takes samplesPerFrame (the live preview, where a frame's time counts).
    int catchUpPasses = 3;
};

/// What changed since the last frame (the editor sets these; all of them restart accumulation).
enum ChangeFlags : unsigned {
    kChangeNone = 0,
    kChangeCamera = 1,
    kChangeLuminaires = 2,
    kChangeGeometry = 4,
    kChangeSettings = 8,
    kChangeEnvironment = 16,  ///< The environment map (a sequence's frame, a moved sun, a file).
    kChangeAll = 31,
};

class Renderer {
public:
    explicit Renderer(ShaderLibrary& shaders);
    ~Renderer();

    /// Takes the scene (by reference: it must outlive the next renderFrame) and what changed.
    void update(const Scene& scene, unsigned changes);
    void setSettings(const RenderSettings& settings);
    const RenderSettings& settings() const { return mSettings; }

    /// One progressive iteration; does nothing once converged.
    void renderFrame();
    bool converged() const { return mStats.converged; }
    const FrameStats& stats() const { return mStats; }
    const FramePlan& plan() const { return mPlan; }
    /// The environment's GPU state (tables, samples), for tests and the editor's sample view.
    const EnvironmentPass& environment() const { return *mEnvironment; }

    /// Tone-mapped sRGB image (RGBA8, row 0 at the bottom) for display.
    const gl::Texture2D& displayTexture() const;
    /// Linear HDR radiance, RGB float, rows top to bottom, W/(m2 sr) (irradiance, W/m2 or lux,
    /// in illuminance mode).
    std::vector<float> readLinear() const;
    /// Tone-mapped 8-bit RGB, rows top to bottom.
    std::vector<unsigned char> readDisplay() const;
    /// Per pixel, rows top to bottom: 1 where the camera sees a luminaire (either side; the
    /// same emitted radiance in every image of the view, whatever the technique), else 0.
    std::vector<unsigned char> readEmitterMask() const;

    /// Irradiance at points for normals through the production shading passes (albedo pi, so
    /// the radiance they write is E). Returns RGB per point, W/m2.
    std::vector<glm::vec3> probe(const Scene& scene, const std::vector<glm::vec3>& points,
                                 const std::vector<glm::vec3>& normals, int spp, int width = 0);
    /// (width > 0: the points form a width x (count / width) image, row-major, so more than the
    /// largest texture width fit; the shading passes' GPU times are in stats() afterwards.)

    /// Interreflected light to add to the image (scene/InterreflectionWorker.h): the patches and
    /// their vertices' interreflected irradiance in the scene's units; a null mesh removes it.
    /// The "indirect" pass draws it again only when this or the view changes.
    void setIndirect(std::shared_ptr<const RadiosityMesh> mesh, std::vector<glm::vec3> vertexIrradiance);
    bool hasIndirect() const;

    glm::mat4 viewProj() const;
    /// Pick: index of the luminaire under the pixel (x right, y down), or -1.
    int pickLuminaire(const Scene& scene, double x, double y) const;

private:
    void resize(int width, int height);
    void rebuildPlan();
    void uploadGeometry();
    void uploadLuminaires();
    /// One luminaire's (or the environment's) estimates, summed over its own passes: moving a
    /// luminaire restarts its accumulation alone, and the others keep theirs.
    struct Accumulation {
        gl::Texture2D texture;         ///< Complete passes, summed.
        gl::Framebuffer fbo;
        gl::Texture2D working;         ///< The pass under way (added to texture when complete,
        gl::Framebuffer workingFbo;    ///< dropped when the pass is abandoned).
        int frames = 0;                ///< Complete passes in texture.
        int samples = 0;               ///< Their samples per pixel (texture holds each pass's
                                       ///< estimate times its samples).
        bool catchingUp = false;       ///< Restarted alone: behind the others, larger passes.
        std::vector<std::byte> key;    ///< What it was shaded for (GPU record, technique, variant).
    };
    /// The plan's steps: -1 for the environment (when it has one), then 0, 1, ... shading.
    std::vector<int> planSteps() const;
    /// The luminaire a step shades (null for the environment, -1).
    const Luminaire* luminaireOf(int step) const;
    bool progressiveStep(int step) const;
    /// The accumulation of a step of the plan (-1: the environment).
    Accumulation& accumulationOf(int step);
    /// Whether the step still refines: a progressive one below maxSamples, a deterministic one
    /// not shaded yet.
    bool refines(int step);
    /// The steps the next pass shades: those that still refine with the fewest samples, so a
    /// luminaire that restarted catches up with the others first; sets mPassSpp.
    std::vector<const Luminaire*> choosePass();
    /// Step index of a pass entry (nullptr: the environment, -1); -2 when it left the plan.
    int stepOf(const Luminaire* lum) const;
    void setFrameUniforms(int frame, int spp);
    /// Shades rows [row0, row0 + rows) of the image (top row 0) for the pass's steps (all steps
    /// into mAccum in probe mode); the environment's per-frame tables and samples are drawn when
    /// row0 is 0.
    void runShading(int spp, int row0, int rows);
    void runEnvironment(int spp, bool newPass, int frame, const gl::Framebuffer& target);
    /// Renders the shadow maps that are missing or stale (timed as "shadow:NAME").
    void updateShadowMaps();
    /// mShadowGeometry for the current geometry.
    const ShadowGeometry& shadowGeometry();

    ShaderLibrary& mShaders;
    const Scene* mScene = nullptr;
    RenderSettings mSettings;
    FramePlan mPlan;
    FrameStats mStats;
    unsigned mPending = kChangeAll;
    int mFrames = 0;             ///< Passes of a probe (probe mode only).
    int mBandRow = 0;            ///< Next row of the pass under way (banded refinement).
    double mPixelsPerMs = 0.0;   ///< Pixels shaded per ms in the last band (0: not measured yet).
    bool mNeedDisplay = false;
    bool mPointMode = false;  ///< The G-buffer holds probe points, not a camera view.

    std::unique_ptr<GBufferPass> mGBuffer;
    std::unique_ptr<ShadePass> mShade;
    std::unique_ptr<ResolvePass> mResolve;
    std::unique_ptr<TonemapPass> mTonemap;
    std::unique_ptr<EnvironmentPass> mEnvironment;
    std::unique_ptr<IndirectPass> mIndirect;
    std::shared_ptr<const RadiosityMesh> mIndirectMesh;  ///< Handed over, not uploaded yet...
    std::vector<glm::vec3> mIndirectIrradiance;          ///< ... while mIndirectUpload is set.
    bool mIndirectUpload = false, mIndirectDirty = false;
    std::unique_ptr<Bvh> mBvh;
    gl::Buffer mFrameUniforms;
    gl::Buffer mBvhNodes, mBvhTris;
    std::vector<gl::Buffer> mLuminaireBuffers;  ///< One record buffer per luminaire.
    ShadowGeometry mShadowGeometry;
    int mGeometryGeneration = 0;        ///< Counts geometry changes.
    int mShadowGeometryGeneration = -1; ///< The generation mShadowGeometry holds.
    /// Each luminaire's maps, by luminaire (entries of luminaires that left are dropped).
    std::map<const Luminaire*, std::unique_ptr<ShadowMaps>> mShadowMaps;
    DirectionalShadowMaps mEnvironmentShadows;  ///< The Havran lights' maps.
    gl::Texture2D mAccum;        ///< Probe mode: every step's estimates.
    gl::Framebuffer mAccumFbo;
    /// Each luminaire's accumulation (deterministic steps hold their one pass: shaded once, not
    /// again on every pass), and the environment's.
    std::map<const Luminaire*, Accumulation> mAccumulations;
    Accumulation mEnvironmentAccumulation;
    std::vector<std::vector<std::byte>> mRecords;  ///< Each luminaire's GPU record, as uploaded.
    std::vector<const Luminaire*> mPass;  ///< Steps of the pass under way (nullptr: environment).
    int mPassSpp = 1;                     ///< Samples per pixel of that pass.
    gl::VertexArray mEmptyVao;
};

}  // namespace candela
