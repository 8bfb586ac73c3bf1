#pragma once
// Projection of a ray set (a measured TM-25 file or a simulated luminaire) onto a light field
// (luminaires/lightfield/LightField.h, canned model): L(u->s) = sum_m C_m(s) Phi_m(u), U at local z
// = 0, S at z = delta, light towards +z.
//
// Each ray is a line; it crosses U at u and S at s. The flux of the rays estimates the flux
// density of the light field over U x S, dPhi = L cos^4(theta) / delta^2 du ds. The estimator of
// C_m on pixel P (the quasi-interpolant of L with the weights Phi_m / (hx hy)) is
//
//   flux-conserving (default):  C_m(P) = sum_{k in P} flux_k Phi_m(u_k) / G_m(P),
//                               G_m(P) = int_P int_U Phi_m(u) cos^4(theta) / delta^2 du ds,
//   per-ray:                    C_m(P) = sum_{k in P} flux_k Phi_m(u_k) delta^2 / cos^4(theta_k)
//                                        / (|P| hx hy).
//
// Both are unbiased for a radiance that is constant over a basis function's support, and they
// agree when cos^4(theta) hardly varies over the support (hx, hy << delta). Where L varies across
// a support (a source's edges) they weight its rays differently: the per-ray form by Phi_m alone,
// the flux-conserving one by Phi_m cos^4(theta), which is what the model's flux integral uses.
// Dividing by the model's own geometric factor makes the light field's power (LightFieldData::
// power(), the same integral) equal the kept ray flux whatever hx / delta is, with no 1 / cos^4
// weight on single grazing rays. Measured on the OSRAM LED at 5x5 x 64x64: power() is 99.98 % of
// the kept flux (flux-conserving) against 99.2 % (per-ray). Units: flux in lm gives C in cd/m2
// (flux in W gives W/(m2 sr)): lm / (m2 sr), G_m being an etendue in m2 sr.

#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "formats/Tm25RayFile.h"
#include "luminaires/lightfield/LightField.h"

namespace candela {

/// One ray of a source.
struct EmittedRay {
    glm::dvec3 position{0.0};             ///< A point of the ray (its start), metres.
    glm::dvec3 direction{0.0, 0.0, 1.0};  ///< Unit direction of travel.
    double flux = 0.0;                    ///< lm (photometric) or W (radiometric).
};

/// Rigid map from the source's frame to the light field's local frame:
/// local = rotation * source - (0, 0, uPlaneZ).
struct RayFrame {
    glm::dmat3 rotation{1.0};  ///< Source to local; takes the chosen main axis to +z.
    double uPlaneZ = 0.0;      ///< z of U in the rotated source frame, metres.
    glm::dvec3 point(const glm::dvec3& p) const {
        glm::dvec3 q = rotation * p;
        q.z -= uPlaneZ;
        return q;
    }
    glm::dvec3 direction(const glm::dvec3& d) const { return rotation * d; }
};

/// Everything the light field's geometry needs (the LightFieldData fields of the same names).
struct LightFieldLayout {
    double delta = 0.01;                         ///< U to S, metres.
    glm::ivec2 count{5, 5};                      ///< Basis functions (W, H).
    glm::dvec2 spacing{0.001, 0.001};            ///< Node spacing (hx, hy), metres.
    glm::dvec2 origin{-0.002, -0.002};           ///< Node (0, 0) on U, metres.
    glm::dvec2 imageMin{-0.01}, imageMax{0.01};  ///< Image extent on S, metres.
    glm::ivec2 resolution{64, 64};               ///< Pixels of every image.
};

/// How the source's frame becomes the luminaire's.
enum class SourceAxis {
    AsGiven,   ///< The rays' +z is the emission axis.
    MainAxis,  ///< Rotate the flux-weighted mean direction onto +z.
    Custom,    ///< Rotate LayoutOptions::customAxis onto +z.
};

struct LayoutOptions {
    glm::ivec2 count{5, 5};         ///< Basis functions (W, H), each at least 3.
    glm::ivec2 resolution{64, 64};  ///< Pixels per image.
    double delta = 0.0;             ///< U to S, metres; 0 picks the U box's larger half-width.
    /// Share of the forward flux that the U box (complete partition of unity) and the S box each
    /// keep, split evenly over the box's sides (no unit).
    double coverage = 0.995;
    SourceAxis axis = SourceAxis::AsGiven;
    glm::dvec3 customAxis{0.0, 0.0, 1.0};  ///< Main emission axis in the source frame (Custom).
    glm::dvec2 uHalfWidth{0.0};  ///< Half-size of the U box, metres; 0 chooses it from the rays.
    /// z of U in the rotated source frame, metres; NaN puts U at the forward-most ray origin,
    /// so no ray starts beyond S.
    double uPlaneZ = std::numeric_limits<double>::quiet_NaN();
    std::string what = "rays";  ///< Names the input in error messages (a file).
};

struct LayoutChoice {
    RayFrame frame;
    LightFieldLayout layout;
    /// Flux-weighted mean direction in the source frame; its length is 1 for a collimated source
    /// and about 0 for one without a preferred direction.
    glm::dvec3 meanDirection{0.0};
    bool axisFallback = false;   ///< MainAxis asked for, but no preferred direction: +z kept.
    glm::dvec2 uHalfWidth{0.0};  ///< Box on U where the basis sums to one, metres.
};

/// Frame and layout from the rays (source frame): U centred on the source's axis, the node grid
/// centred on the local origin, delta and the S extent covering `coverage` of the forward flux.
/// Throws InputError when no ray goes forward.
LayoutChoice chooseLayout(const std::vector<EmittedRay>& rays, const LayoutOptions& options);

enum class Estimator { FluxConserving, PerRay };

/// Where the flux went; totalFlux = kept + backward + outsideImage + outsideBasis.
struct ProjectionReport {
    uint64_t rays = 0;
    uint64_t backwardRays = 0;  ///< No forward component (local z <= 0).
    uint64_t outsideImageRays =
        0;  ///< Forward, reaching the basis, but crossing S outside the image.
    uint64_t outsideBasisRays = 0;  ///< Crossing U where no basis function reaches.
    double totalFlux = 0.0;         ///< All rays, lm or W.
    double keptFlux = 0.0;          ///< Sum of flux * sum_m Phi_m(u) over rays inside the image.
    double backwardFlux = 0.0;
    double outsideImageFlux = 0.0;
    /// flux * (1 - sum_m Phi_m(u)): rays crossing U where the basis is not a partition of unity.
    double outsideBasisFlux = 0.0;
    /// sum_m sum_P C_m(P) G_m(P) of the built images (the model's flux): keptFlux for the
    /// flux-conserving estimator.
    double modelFlux = 0.0;
    double seconds = 0.0;  ///< Wall time of the projection, s.
};

/// Accumulates rays given in the local frame, then builds the images.
class LightFieldAccumulator {
  public:
    explicit LightFieldAccumulator(const LightFieldLayout& layout,
                                   Estimator estimator = Estimator::FluxConserving);
    void add(const EmittedRay& local);
    /// Source-frame rays through `frame`; progress(fraction done) now and then.
    void add(const std::vector<EmittedRay>& rays, const RayFrame& frame,
             const std::function<void(double)>& progress = {});
    /// The light field (canned model, luminance only, precomputed), unit "cd/m2" or "W/(m2 sr)".
    std::shared_ptr<LightFieldData> build(const std::string& unit);
    const ProjectionReport& report() const { return mReport; }

  private:
    LightFieldLayout mLayout;
    Estimator mEstimator;
    glm::dvec2 mPixel{0.0};     ///< Pixel size on S, metres.
    size_t mPixels = 0;         ///< Pixels per image.
    std::vector<double> mSums;  ///< Per image and pixel: sum of flux * Phi_m (* per-ray weight).
    ProjectionReport mReport;
};

/// chooseLayout's frame and layout applied to all rays, then built.
std::shared_ptr<LightFieldData> projectRays(const std::vector<EmittedRay>& rays,
                                            const LayoutChoice& choice, const std::string& unit,
                                            ProjectionReport& report,
                                            Estimator estimator = Estimator::FluxConserving,
                                            const std::function<void(double)>& progress = {});

/// Which flux of a TM-25 file the rays carry.
struct Tm25FluxInfo {
    bool photometric = true;   ///< Luminous flux (lm, C in cd/m2), else radiant (W).
    double headerTotal = 0.0;  ///< The header's total for that quantity (NaN when not given).
    double raySum = 0.0;       ///< Sum over the rays as stored.
    double scale = 1.0;        ///< Factor applied to every ray (header total / ray sum, or 1).
    std::string unit;          ///< "cd/m2" or "W/(m2 sr)".
};

/// The rays of a TM-25 file, carrying luminous flux when the file has it (else radiant). With
/// scaleToHeader, per-ray values are relative weights scaled to the header's total when that is
/// finite and positive (TM25.md Sec. 7's recommendation).
std::vector<EmittedRay> raysFromTm25(const Tm25RayFile& file, bool scaleToHeader,
                                     Tm25FluxInfo& info);

}  // namespace candela
