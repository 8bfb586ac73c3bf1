#pragma once
// Side-by-side comparison of techniques on one view (the editor's split viewport and
// `candela render --compare`): up to four panes, each a Renderer with its own technique list
// and sample budget, and a progressive reference rendered beside them with each kind's unbiased
// technique and exact (ray-traced) visibility.
//
// Each pane is measured against the reference at 1, 2, 4, ... times its samples per pass and
// when it stops: GPU time, relative RMSE of luminance (over the pixels that do not see a
// luminaire, whose emission every image shares) with the reference's own noise removed,
// and mean Delta E of the images tone-mapped alike. The reference's noise is estimated from its
// image at half its samples (the difference of the two is an independent copy of that noise),
// and every measurement is taken again whenever the reference's samples double, so the series
// stay measured against the best reference there is.

#include <memory>
#include <string>
#include <vector>

#include "renderer/ImageMetrics.h"
#include "renderer/Renderer.h"

namespace candela {

struct PaneSpec {
    /// RenderSettings::techniqueOverride: names separated by commas, each luminaire (and the
    /// environment) uses the first its kind has; empty: the scene's own techniques.
    std::string technique;
    int samples =
        64;  ///< Sample budget, samples per pixel (a deterministic technique stops after one pass).
    bool operator==(const PaneSpec&) const = default;
};

/// A pane's progress and measurements.
struct PaneResult {
    double gpuMs = 0.0;  ///< GPU time of its shading and shadow passes over the accumulation, ms.
    int spp = 0;         ///< Samples per pixel so far (0 for a deterministic technique).
    bool done = false;   ///< Reached its sample budget (or deterministic and shaded).
    bool measured = false;    ///< `latest` holds a measurement against the reference.
    ErrorPoint latest;        ///< The last measurement.
    double rawRelRmse = 0.0;  ///< latest's relative RMSE before the reference's noise is removed.
    std::vector<ErrorPoint> series;  ///< All measurements, increasing time.
};

/// The techniques a plan uses, each once, in step order ("hybrid + restricted-cdf + balanced").
std::string techniqueSummary(const FramePlan& plan);

class Comparison {
  public:
    /// The reference's techniques (an override list): the light field's sampler with a shadow
    /// ray per sample, Monte Carlo for the others, the environment's MIS estimator.
    static constexpr const char* kReferenceTechniques =
        "lightfield=restricted-cdf-raytraced,lambertian-rect=reference,photometric=reference,"
        "environment=balanced-mis";

    explicit Comparison(ShaderLibrary& shaders);
    ~Comparison();
    Comparison(const Comparison&) = delete;
    Comparison& operator=(const Comparison&) = delete;

    /// Panes (1 to 4), the settings they share (size, samples per pass, tone mapping, quantity,
    /// shadow maps, seed; techniqueOverride and maxSamples are the panes' own) and the
    /// reference's sample budget. Only what changed restarts.
    void configure(const std::vector<PaneSpec>& panes, const RenderSettings& shared,
                   int referenceSamples);
    /// The scene (it must outlive the next step) and what changed: everything restarts.
    void update(const Scene& scene, unsigned changes);
    /// About budgetMs of work: a band of each pane still refining and of the reference, then
    /// the measurements due. budgetMs 0: a whole pass of each (headless).
    void step(double budgetMs);
    bool panesDone() const;
    bool referenceDone() const;
    bool done() const { return panesDone() && referenceDone(); }

    size_t paneCount() const { return mPanes.size(); }
    const PaneSpec& spec(size_t pane) const { return mPanes[pane].spec; }
    const PaneResult& result(size_t pane) const { return mPanes[pane].result; }
    const Renderer& paneRenderer(size_t pane) const { return *mPanes[pane].renderer; }
    const Renderer& referenceRenderer() const { return *mReference.renderer; }
    int referenceSpp() const { return mReference.spp; }
    int referenceSamples() const { return mReferenceSamples; }
    double referenceGpuMs() const { return mReference.gpuMs; }
    /// The reference's own relative RMSE (its noise); NaN until its samples have doubled once.
    double referenceNoise() const;
    /// Mean luminance of the reference that every image is tone-mapped against (0: none yet).
    double toneAverage() const { return mToneAverage; }

    /// Signed error of a pane's last measured image: (luminance - reference's) / the
    /// reference's mean luminance, blue below, orange above, black at 0, saturating at
    /// +-errorScale. RGBA8, row 0 at the bottom (as Renderer::displayTexture).
    const gl::Texture2D& errorMap(size_t pane) const { return mPanes[pane].errorTexture; }
    /// The same as sRGB8 RGB rows top to bottom (empty until measured).
    const std::vector<unsigned char>& errorImage(size_t pane) const {
        return mPanes[pane].errorRgb;
    }
    void setErrorScale(float scale);
    float errorScale() const { return mErrorScale; }

    /// Measures every pane as it is now (a snapshot of each that refined since its last one)
    /// against the reference as it is now, so the images below, their results and the series
    /// agree (what an export shows).
    void measureNow();
    /// Whether measureNow has images to measure: the reference and every pane have a pass.
    bool measurable() const;
    /// A pane's last measured image (RGB float, rows top to bottom; empty until it has one).
    const std::vector<float>& paneImage(size_t pane) const;
    /// The reference image the last measurements used.
    const std::vector<float>& referenceImage() const { return mReference.image.linear(); }
    /// An image of the view as the errors see it: tone-mapped (the operator and exposure of the
    /// shared settings) against the reference's mean luminance, sRGB8 rows top to bottom.
    std::vector<unsigned char> toneMapped(const std::vector<float>& linear) const;

  private:
    /// A linear image and, made on demand, the CIELAB of it tone-mapped as Delta E sees it.
    class Measured {
      public:
        void set(std::vector<float> linear) {
            mLinear = std::move(linear);
            mLab.clear();  // of the image it replaces
        }
        const std::vector<float>& linear() const { return mLinear; }
        bool empty() const { return mLinear.empty(); }
        /// Its CIELAB tone-mapped against `average` (cached per average).
        const std::vector<glm::vec3>& lab(const Comparison& c);

      private:
        std::vector<float> mLinear;
        std::vector<glm::vec3> mLab;
        double mLabAverage = 0.0;  ///< The tone-mapping average mLab was made with.
    };
    struct Snapshot {
        ErrorPoint point;
        Measured image;
    };
    struct Pane {
        PaneSpec spec;
        std::unique_ptr<Renderer> renderer;
        PaneResult result;
        int frames = 0;             ///< Renderer's accumulated frames at the last step.
        int snapshotFrames = 0;     ///< Its frames at the last snapshot.
        double passGpuMs = 0.0;     ///< result.gpuMs when its last pass completed.
        bool displayStale = false;  ///< Tone-mapped with an older average.
        int nextSnapshot = 1;       ///< Snapshot when the frames reach this (doubles).
        std::vector<Snapshot> snapshots;
        gl::Texture2D errorTexture;
        std::vector<unsigned char> errorRgb;
    };
    struct Reference {
        std::unique_ptr<Renderer> renderer;
        int frames = 0;
        int spp = 0;
        double gpuMs = 0.0;
        bool displayStale = false;
        Measured image;           ///< At the last measurement.
        int imageFrames = 0;      ///< frames when image was read.
        std::vector<float> half;  ///< At the last power-of-two pass count.
        int halfFrames = 0;
        double noise2 = -1.0;  ///< Relative MSE of noise at noiseSpp; < 0 unknown.
        int noiseSpp = 0;
        /// Pixels that see a luminaire: left out of the relative RMSE, whose sum of squares
        /// they would dominate with an emitted radiance every image shares exactly.
        std::vector<unsigned char> emitters;
    };

    RenderSettings paneSettings(size_t pane) const;
    RenderSettings referenceSettings() const;
    /// Runs one renderFrame of r, adding its timed passes to gpuMs (restarted with a new
    /// accumulation); returns whether a pass over the image completed.
    static bool advance(Renderer& r, int& frames, double& gpuMs);
    void snapshot(Pane& pane);
    void measure(Pane& pane, Snapshot& shot);
    void referenceAdvanced();
    void remeasureAll();
    void updateErrorMap(Pane& pane, const Snapshot& shot);
    void restartPane(Pane& pane);
    void restartReference();
    void setToneAverage(double average);

    ShaderLibrary& mShaders;
    const Scene* mScene = nullptr;
    RenderSettings mShared;
    int mReferenceSamples = 1024;
    std::vector<Pane> mPanes;
    Reference mReference;
    double mToneAverage = 0.0;
    float mErrorScale = 0.25f;
};

}  // namespace candela
