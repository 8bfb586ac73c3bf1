#pragma once
// The progressive renderer: G-buffer, one shading step per light source (a luminaire or the
// environment, each through its technique's shader variant and its kind's SourcePass),
// accumulation in float buffers per source, resolve to linear HDR, tone mapping. Works in any
// current GL 4.5 context. Nothing runs that the scene does not need, and a converged image with
// no change costs no pass at all. A frame runs its phases in order: apply what changed (plan,
// G-buffer, restarted accumulations), interreflected light, one band of the pass under way,
// resolve and tone mapping when the image changed, statistics.

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "renderer/FramePlan.h"
#include "renderer/FrameStats.h"
#include "renderer/PassTimer.h"
#include "renderer/RenderSettings.h"
#include "renderer/ShaderLibrary.h"
#include "renderer/gl/GlObjects.h"
#include "renderer/passes/ShadowMapPass.h"
#include "scene/Scene.h"

namespace candela {

class GBufferPass;
class ResolvePass;
class TonemapPass;
class IndirectPass;
class SourcePass;
struct Bvh;
struct RadiosityMesh;

/// What changed since the last frame (the editor sets these; all of them restart accumulation).
enum ChangeFlags : unsigned {
    kChangeNone = 0,
    kChangeCamera = 1,
    kChangeLuminaires = 2,
    kChangeGeometry = 4,
    kChangeSettings = 8,
    kChangeEnvironment = 16,  ///< The environment map (a sequence's frame, a moved sun, a file).
    kChangeAll = 31,
    /// Found by the renderer itself: a source appeared or left (a new environment map is a new
    /// source): the new ones are uploaded and start their accumulation.
    kChangeSources = 32,
};

class Renderer {
  public:
    explicit Renderer(ShaderLibrary& shaders);
    ~Renderer();

    /// Takes the scene (by reference: it must outlive the next renderFrame) and what changed.
    void update(const Scene& scene, unsigned changes);
    void setSettings(const RenderSettings& settings);
    const RenderSettings& settings() const { return mSettings; }

    /// Makes the images of the settings' size now rather than at the first frame, so that a size
    /// this GL cannot hold fails (GlError naming it) before any long work that precedes it.
    void allocateImages();
    /// One progressive iteration; does nothing once converged.
    void renderFrame();
    bool converged() const { return mStats.converged; }
    const FrameStats& stats() const { return mStats; }
    /// Exact times: each frame's passes carry their own GPU times (a stall per pass on a GPU);
    /// else, on a GPU, the pooled queries' times of an earlier frame (renderer/PassTimer.h).
    /// Benches and the comparison ask for exact times; llvmpipe always measures wall time.
    void setExactTimes(bool exact) { mTimer.setMode(PassTimer::defaultMode(exact)); }
    const FramePlan& plan() const { return mPlan; }
    /// The GPU pass of a source of the current plan (its tables, for tests); null when none.
    const SourcePass* sourcePass(const Luminaire* source) const;

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

    /// Interreflected light to add to the image (calculation/InterreflectionWorker.h): the patches
    /// and their vertices' interreflected irradiance in the scene's units; a null mesh removes it.
    /// The "indirect" pass draws it again only when this or the view changes.
    void setIndirect(std::shared_ptr<const RadiosityMesh> mesh,
                     std::vector<glm::vec3> vertexIrradiance);
    bool hasIndirect() const;

    glm::mat4 viewProj() const;
    /// Pick: index of the luminaire under the pixel (x right, y down), or -1.
    int pickLuminaire(const Scene& scene, double x, double y) const;

  private:
    /// One source's estimates, summed over its own passes: moving a luminaire restarts its
    /// accumulation alone, and the others keep theirs.
    struct Accumulation {
        gl::Texture2D texture;  ///< Complete passes, summed.
        gl::Framebuffer fbo;
        gl::Texture2D working;       ///< The pass under way (added to texture when complete,
        gl::Framebuffer workingFbo;  ///< dropped when the pass is abandoned).
        int frames = 0;              ///< Complete passes in texture.
        int samples = 0;             ///< Their samples per pixel (texture holds each pass's
                                     ///< estimate times its samples).
        bool catchingUp = false;     ///< Restarted alone: behind the others, larger passes.
        std::vector<std::byte> key;  ///< What it was shaded for (record, technique, variant).
    };

    // The phases of a frame, in order.
    /// The G-buffer, the plan, the sources' passes and the accumulations after a change.
    void applyChanges();
    /// Restarts each accumulation whose source changed (all of them when `everything`).
    void restartAccumulations(bool everything);
    /// Draws the interreflected light's image when its solution or the view changed.
    void updateIndirect();
    /// Shades the next band of the pass under way (choosing the pass at its start) and adds the
    /// pass to the accumulations when it completes.
    void shadeBand();
    /// Sums the accumulations (and the interreflected light) and tone-maps the sum.
    void resolve();
    /// The statistics of the least refined progressive step.
    void updateStatistics();

    void resize(int width, int height);
    /// Whether Scene::sources() differs from the sources of the plan.
    bool sourcesChanged() const;
    /// Records of the sources (all of them, or only those without one) and their passes.
    void syncSources(bool allRecords);
    /// The plan's steps are indices 0, 1, ... into mPlan.shading.
    std::vector<int> planSteps() const;
    const Luminaire* sourceOf(int step) const { return mPlan.shading[size_t(step)].source; }
    bool progressiveStep(int step) const { return mPlan.shading[size_t(step)].progressive; }
    Accumulation& accumulationOf(int step);
    /// Whether the step still refines: a progressive one below maxSamples, a deterministic one
    /// not shaded yet.
    bool refines(int step);
    /// The steps the next pass shades: those that still refine with the fewest samples, so a
    /// source that restarted catches up with the others first; sets mPassSpp.
    std::vector<const Luminaire*> choosePass();
    /// Step index of a source; -1 when it left the plan.
    int stepOf(const Luminaire* source) const;
    void setFrameUniforms(int frame, int spp);
    /// Shades rows [row0, row0 + rows) of the image (top row 0) for the pass's steps (all steps
    /// into mAccum in probe mode); each step's pass prepares what its technique reads when row0
    /// is 0.
    void runShading(int spp, int row0, int rows);
    /// mShadowGeometry for the current geometry.
    const ShadowGeometry& shadowGeometry();

    ShaderLibrary& mShaders;
    const Scene* mScene = nullptr;
    RenderSettings mSettings;
    FramePlan mPlan;
    FrameStats mStats;
    PassTimer mTimer{PassTimer::defaultMode(false)};  ///< Times every pass (renderer/PassTimer.h).
    unsigned mPending = kChangeAll;
    int mFrames = 0;   ///< Passes of a probe (probe mode only).
    int mBandRow = 0;  ///< Next row of the pass under way (banded refinement).
    /// Band sizing: a band's time is modelled as a fixed cost per band (llvmpipe spends tens of
    /// ms on any band, however few rows it covers) plus a cost per pixel, both fitted by least
    /// squares to the last kBandHistory bands (bandRows()), which alternate between two sizes so
    /// that the fit can tell the costs apart.
    struct BandTime {
        double pixels = 0.0, ms = 0.0;
    };
    static constexpr size_t kBandHistory = 16;
    std::vector<BandTime> mBands;  ///< The last bands timed (not a pass's first, which prepares).
    uint64_t mBandCount = 0;
    double mMsPerPixel = 0.0;      ///< Marginal cost (0: not measured yet).
    double mBandOverheadMs = 0.0;  ///< Fixed cost of a band.
    double mDisplayMs = 0.0;       ///< Wall time of the last resolve (bands only).
    int bandRows(int width, int left);
    void timeBand(double pixels, double ms);
    bool mNeedDisplay = false;
    bool mPointMode = false;  ///< The G-buffer holds probe points, not a camera view.

    std::unique_ptr<GBufferPass> mGBuffer;
    std::unique_ptr<ResolvePass> mResolve;
    std::unique_ptr<TonemapPass> mTonemap;
    std::unique_ptr<IndirectPass> mIndirect;
    std::shared_ptr<const RadiosityMesh> mIndirectMesh;  ///< Handed over, not uploaded yet...
    std::vector<glm::vec3> mIndirectIrradiance;          ///< ... while mIndirectUpload is set.
    bool mIndirectUpload = false, mIndirectDirty = false;
    std::unique_ptr<Bvh> mBvh;
    gl::Buffer mFrameUniforms;
    gl::Buffer mBvhNodes, mBvhTris;
    ShadowGeometry mShadowGeometry;
    int mGeometryGeneration = 0;         ///< Counts geometry changes.
    int mShadowGeometryGeneration = -1;  ///< The generation mShadowGeometry holds.
    gl::Texture2D mAccum;                ///< Probe mode: every step's estimates.
    gl::Framebuffer mAccumFbo;
    /// Per source of the plan: its GPU pass, its record as uploaded, its accumulation
    /// (deterministic steps hold their one pass: shaded once, not again on every pass).
    struct KindPass {
        LuminaireKind kind;  ///< Its source's kind (kept: a source that left may be gone).
        std::unique_ptr<SourcePass> pass;
    };
    std::map<const Luminaire*, KindPass> mSourcePasses;
    std::map<const Luminaire*, std::vector<std::byte>> mRecords;
    std::map<const Luminaire*, Accumulation> mAccumulations;
    std::vector<const Luminaire*> mPass;  ///< Steps of the pass under way.
    int mPassSpp = 1;                     ///< Samples per pixel of that pass.
    gl::VertexArray mEmptyVao;
};

}  // namespace candela
