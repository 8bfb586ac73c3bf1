#pragma once
// Importance sampling of environment maps on the CPU (the reference for the GPU passes):
// the cube-map CDFs and per-receiver balancing of Lu, Pacanowski, Granier (2013), a global
// lat-long CDF, the directional-light decomposition of Havran et al. (2005), and the exact
// irradiance of a piecewise-constant map. All densities are per steradian, in double precision.
//
// Cube faces follow the OpenEXR envmap=cube layout (ImfEnvmap.h): faces +X, -X, +Y, -Y, +Z, -Z,
// stacked top to bottom in one N x 6N image. Texel (col, row) of face f (row 0 at the top of
// the face) has face coordinates a = 2 (col + 0.5) / N - 1, b = 2 (row + 0.5) / N - 1 and looks
// along centre_f + a right_f + b down_f, the OpenEXR orientation (seen from inside the cube); the
// frames are the table in shaders/shared/CubeFaces.h, which the GLSL side uses too.
//
// (OpenEXR's own resampler puts the outermost texel centres on the cube's edges; here texel
// edges are on the cube's edges, the GPU cube-map convention, so every direction has one texel.)

#include <algorithm>
#include <array>
#include <deque>
#include <glm/glm.hpp>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "luminaires/Estimate.h"
#include "luminaires/environment/Environment.h"

namespace candela {

struct CubeFaceFrame {
    glm::dvec3 centre, right, down;
};
/// The frame of face f in 0..5 (shaders/shared/CubeFaces.h).
const CubeFaceFrame& cubeFaceFrame(int face);
/// Face of a direction (largest |component|, ties in the order x, y, z) and its face
/// coordinates (a, b) in [-1, 1]^2; -1 for a zero or non-finite direction.
int cubeFaceOf(const glm::dvec3& w, glm::dvec2& ab);

/// A tabulated piecewise-constant 1D distribution: cdf[0] = 0, cdf[n] = 1.
struct Cdf1D {
    std::vector<double> cdf;
    double total = 0.0;  ///< Sum of the weights.
    void build(const double* weights, int n);
    /// Index i with cdf[i] <= u < cdf[i+1] and the fraction of u inside it.
    int sample(double u, double& fraction) const;
    double probability(int i) const { return cdf[size_t(i) + 1] - cdf[size_t(i)]; }
};

/// Sample of a distribution of directions.
struct DirectionSample {
    glm::dvec3 w{0.0};  ///< Unit direction.
    double pdf = 0.0;   ///< Solid-angle density, 1/sr; 0: no sample.
};

/// The cube-map importance (Algorithm 1, lines 5-10, on the CPU): the lat-long map resampled
/// into 6 faces of N^2 texels, per-face luminance, and per face the marginal CDF over columns
/// CDF(u) and the conditional CDFs over rows CDF(v | u) (the paper's two prefix sums).
/// A texel's weight is its exact solid angle times: its mean luminance (k x k supersampled from
/// the lat-long map), plus 1/10 of the largest luminance of the lat-long texels it touches (a
/// conservative (u, v) box), plus a floor of 1e-3 of the face's mean luminance. The max term
/// bounds L / pdf on every texel (a one-texel sun between the subsamples cannot make rare,
/// huge samples: the heavy tail that looks like bias at any practical spp); the floor keeps
/// pdf_L(w|f) > 0 on the whole of a lit face, so every estimator stays unbiased. Within a texel
/// samples are uniform in the face plane: pdf_L(w|f) = P_texel / (2/N)^2 * (1 + a^2 + b^2)^(3/2).
class CubeMapDistribution {
  public:
    CubeMapDistribution(const EnvironmentMap& map, int faceSize);

    int faceSize() const { return mN; }
    /// Resampled mean luminance of a texel (cd/m2 or W/(m2 sr) x luminance weights).
    double texelLuminance(int face, int col, int row) const;
    /// Sampling weight of a texel (luminance x solid angle, plus the floor).
    double texelWeight(int face, int col, int row) const;
    /// I_f of Eq. (3): the face's total weight (0: the face is black, it gets no samples).
    double faceImportance(int face) const { return mFaces[size_t(face)].columns.total; }
    /// Exact solid angle of texel (col, row) of any face, sr.
    double texelSolidAngle(int col, int row) const;

    /// pdf_L(w | f): samples of face f only (Eq. 2).
    DirectionSample sampleFace(int face, const glm::dvec2& u) const;
    double pdfFace(int face, const glm::dvec3& w) const;
    /// Inverse of sampleFace: the (u1, u2) that gives w (w on face f).
    glm::dvec2 invertFace(int face, const glm::dvec3& w) const;

    /// mu_f(n) of Eq. (3): F_f(n) I_f / sum, F_f(n) = sum over the face's 4 unit corner
    /// directions of max(0, n . c_j). All zero when no lit face is in front of n.
    std::array<double, 6> balance(const glm::dvec3& n) const;
    /// The face proportions as one density: face f chosen with probability mu[f], then
    /// pdf_L(w | f). pdf = mu_f pdf_L(w | f) (the denominator of Eq. 2, one term non-zero).
    DirectionSample sample(const std::array<double, 6>& mu, const glm::dvec3& u) const;
    double pdf(const std::array<double, 6>& mu, const glm::dvec3& w) const;
    /// (u0, u1, u2) giving w under `mu` (u0 at the middle of the face's interval).
    glm::dvec3 invert(const std::array<double, 6>& mu, const glm::dvec3& w) const;

  private:
    struct Face {
        std::vector<double> luminance;  ///< N x N, row-major (row 0 at the top).
        std::vector<double> weight;     ///< N x N.
        Cdf1D columns;                  ///< CDF(u): marginal over columns.
        std::vector<Cdf1D> rows;        ///< CDF(v | u): per column, over rows.
    };
    int mN = 0;
    std::vector<double> mSolidAngle;  ///< N x N, the same for every face.
    std::array<Face, 6> mFaces;
    std::array<std::array<glm::dvec3, 4>, 6> mCorners;  ///< Unit corner directions.
};

/// One CDF over the whole lat-long map: texel probability proportional to luminance x solid
/// angle (the sin(theta) Jacobian, exactly integrated over the row), marginal over rows and
/// conditional over columns; within a texel uniform in solid angle (phi linear, cos(theta)
/// linear), so pdf(w) = P_texel / Omega_texel exactly.
class LatLongDistribution {
  public:
    explicit LatLongDistribution(const EnvironmentMap& map);
    DirectionSample sample(const glm::dvec2& u) const;
    double pdf(const glm::dvec3& w) const;
    glm::dvec2 invert(const glm::dvec3& w) const;
    bool empty() const { return !(mRows.total > 0.0); }
    /// The tables (the GPU's global-cdf technique uploads them).
    const Cdf1D& rows() const { return mRows; }
    const Cdf1D& columns(int row) const { return mColumns[size_t(row)]; }

  private:
    const EnvironmentMap* mMap;
    Cdf1D mRows;
    std::vector<Cdf1D> mColumns;
};

/// K Halton (2, 3) points in the unit square after Lloyd relaxation (Havran et al. 2005): each
/// iteration moves every point to the centroid of its Voronoi cell, computed on a 256^2 grid of
/// cell centres (the square is not wrapped, matching the inverse-transform domain).
std::vector<glm::dvec2> relaxedHalton(int count, int iterations = 16);

/// The directional-light decomposition of Havran et al. (2005): the same K relaxed Halton points
/// every frame, mapped to directions by the inverse transform of the frame's global CDF; each
/// light's power is the map's RGB irradiance at normal incidence from its spherical Voronoi cell
/// (the texels nearer to it than to any other light), so the lights carry all the map's energy.
/// Temporal filtering: a causal 4-tap FIR low-pass h = (0.4, 0.3, 0.2, 0.1) (newest first) over
/// each light's direction (weighted sum of unit vectors, renormalised) and power, renormalised
/// over the frames seen so far (the abstract names a perception-inspired FIR filter without its
/// taps; this triangular one halves a one-frame flicker while following a steady change within
/// 4 frames).
class HavranLights {
  public:
    struct Light {
        glm::dvec3 direction{0.0, 1.0, 0.0};  ///< Unit direction towards the light.
        glm::dvec3 power{0.0};                ///< Irradiance at normal incidence, W/m2, RGB.
    };
    explicit HavranLights(int count = 256);
    /// Adds a frame: recomputes the lights from `map` and filters them with the last frames.
    void update(const EnvironmentMap& map);
    /// Forgets the history (a cut in the sequence).
    void reset() { mHistory.clear(); }
    const std::vector<Light>& lights() const { return mLights; }
    /// Unfiltered lights of the newest frame.
    const std::vector<Light>& rawLights() const;
    /// A light chosen with probability proportional to its luminance power; -1 if all are 0.
    int sample(double u) const;
    double probability(int light) const;
    static constexpr double kTaps[4] = {0.4, 0.3, 0.2, 0.1};

  private:
    std::vector<glm::dvec2> mPoints;
    std::deque<std::vector<Light>> mHistory;  ///< Newest first, at most 4.
    std::vector<Light> mLights;
    Cdf1D mChoice;
};

/// Everything the environment estimators share for one map (one frame): built once per frame,
/// used by every receiver.
class EnvironmentLighting {
  public:
    /// faceSize 0: max(8, width / 2): cube texels no larger than the lat-long texels at the
    /// equator, so a one-texel sun stays one or two cube texels (the paper used 256^2 faces).
    explicit EnvironmentLighting(std::shared_ptr<const EnvironmentMap> map, int faceSize = 0,
                                 int havranLights = 256);
    /// The face size that faceSize 0 picks.
    static int defaultFaceSize(const EnvironmentMap& map) { return std::max(8, map.width() / 2); }
    const EnvironmentMap& map() const { return *mMap; }
    const std::shared_ptr<const EnvironmentMap>& sharedMap() const { return mMap; }
    const CubeMapDistribution& cube() const { return mCube; }
    const LatLongDistribution& global() const { return mGlobal; }
    const HavranLights& havran() const { return mHavran; }

  private:
    std::shared_ptr<const EnvironmentMap> mMap;
    CubeMapDistribution mCube;
    LatLongDistribution mGlobal;
    HavranLights mHavran;
};

/// Diagnostics of one estimate: the samples drawn and those with a positive cosine.
struct SampleCounts {
    int drawn = 0;
    int effective = 0;
};

/// CPU irradiance at p for unit normal n from the environment (W/m2, lux for the sky). With
/// options.visibility, stochastic estimators trace a shadow ray from p along w to infinity.
using EnvironmentIrradianceFn = Estimate (*)(const EnvironmentLighting& lighting,
                                             const glm::dvec3& p, const glm::dvec3& n,
                                             const EstimateOptions& options);

/// Exact: sum over texels of L_texel times the integral of max(0, n . w) over the texel.
Estimate environmentReference(const EnvironmentLighting& lighting, const glm::dvec3& p,
                              const glm::dvec3& n, const EstimateOptions& options);
/// Eq. (4)-(5) with mu_f(n) of Eq. (3) (environmentFaceEstimate also reports sample counts).
Estimate environmentBalanced(const EnvironmentLighting& lighting, const glm::dvec3& p,
                             const glm::dvec3& n, const EstimateOptions& options);
Estimate environmentUniformFaces(const EnvironmentLighting& lighting, const glm::dvec3& p,
                                 const glm::dvec3& n, const EstimateOptions& options);
Estimate environmentGlobalCdf(const EnvironmentLighting& lighting, const glm::dvec3& p,
                              const glm::dvec3& n, const EstimateOptions& options);
Estimate environmentHavran(const EnvironmentLighting& lighting, const glm::dvec3& p,
                           const glm::dvec3& n, const EstimateOptions& options);
/// balanced with N_f rounded to whole samples (biased; the temporal-stability bench's baseline).
Estimate environmentBalancedInteger(const EnvironmentLighting& lighting, const glm::dvec3& p,
                                    const glm::dvec3& n, const EstimateOptions& options);
/// Eq. (6): half the samples balanced light samples, half cosine samples, balance heuristic.
Estimate environmentBalancedMis(const EnvironmentLighting& lighting, const glm::dvec3& p,
                                const glm::dvec3& n, const EstimateOptions& options);

/// The face-balanced estimator with explicit face proportions (balanced: Eq. 3; uniform: 1/6).
Estimate environmentFaceEstimate(const EnvironmentLighting& lighting, const glm::dvec3& p,
                                 const glm::dvec3& n, const EstimateOptions& options,
                                 const std::array<double, 6>& mu, SampleCounts* counts);

/// Fig. 1-2 of Lu et al. (2013) for one receiver: the light samples its normal selects from each
/// face (N_f = mu_f N_s, the last one fractional, as the estimators draw them) and which are
/// effective (n . w > 0), drawn on the unfolded cube. The chart is a horizontal cross seen from
/// inside, faces facePixels wide:
///          [+Y]
///     [-X] [-Z] [+X] [+Z]
///          [-Y]
/// The map is tone-mapped and dimmed (more so on faces with mu_f = 0); effective samples are
/// green, wasted ones red, the normal a white cross.
struct SampleChart {
    int width = 0, height = 0;  ///< 4 x 3 faces of facePixels
    int facePixels = 0;
    std::vector<unsigned char> rgb;  ///< RGB8, row 0 at the top
    std::array<double, 6> mu{};      ///< the faces' shares of the samples
    std::array<int, 6> drawn{}, effective{};
    /// Where face f sits in the cross, in faces (column, row).
    static glm::ivec2 faceCell(int face);
};
SampleChart sampleChart(const EnvironmentMap& map, const CubeMapDistribution& cube,
                        const glm::dvec3& normal, int spp, bool balanced, uint64_t seed,
                        int facePixels = 64);

}  // namespace candela
