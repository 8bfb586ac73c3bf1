#pragma once
// Light-field luminaires (Lu, Pacanowski, Granier 2015, "Position-Dependent Importance Sampling
// of Light Field Luminaires", seed 000): a measured near-field source stored as images C_m on a
// plane S (local z = delta) weighted by basis functions Phi_m on a parallel plane U (local z = 0).
// Radiance along the ray from u on U through s on S: L(u->s) = sum_m C_m(s) Psi_m(u->s) (Eq. 1).
//
// LightFieldData is the immutable model (file contents plus precomputed tables), shared between
// luminaire instances. The file format is `NAME.lf.json` plus one float image per basis function
// (docs/luminaire-files.md, "Light-field files"). No GL here.

#include <filesystem>
#include <glm/glm.hpp>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "luminaires/Adapter.h"
#include "luminaires/Estimate.h"
#include "luminaires/Luminaire.h"
#include "util/JsonRead.h"

namespace candela {

/// Uniform quadratic B-spline, support [-1.5, 1.5] (in units of the node spacing), centred on 0;
/// its integer shifts sum to one.
double bspline2(double x);

/// One basis image C_m, piecewise constant per pixel. Row 0 is the smallest s_y, column 0 the
/// smallest s_x.
struct LightFieldImage {
    std::vector<float>
        luminance;  ///< width*height, C_m (RGB images: 0.2126 R + 0.7152 G + 0.0722 B).
    std::vector<glm::vec3>
        colour;  ///< RGB / luminance per pixel (Sec. 5); empty for 1-channel data.
};

/// Per-image tables computed once after loading (Sec. 3.1, Eq. 6 and 10).
struct LightFieldTables {
    /// Summed-area table, (width+1) x (height+1), entry (i, j) = integral of C_m over
    /// [s0.x, s0.x + i dx] x [s0.y, s0.y + j dy], in C's unit times m2. A_m of any axis-aligned
    /// box, the restricted marginal in s and the conditional in t all come from it.
    std::vector<double> sat;
    /// Marginal CDF over columns, width+1 entries from 0 to 1 (Eq. 6, cdf_m(s)).
    std::vector<double> marginalCdf;
    /// Conditional CDF of t in column i at row boundary j (Eq. 6, cdf_m(t|s)), read from the SAT
    /// (a column's running sum over its total) rather than stored: a stored copy would double the
    /// tables' memory (50 MB for 11x9 images of 256^2) for nothing the sampler needs, since the
    /// restricted CDFs of Eq. 8 come from the SAT too. An all-zero column gives a uniform CDF.
    double conditionalCdf(size_t i, size_t j, size_t width, size_t height) const {
        double column = sat[height * (width + 1) + i + 1] - sat[height * (width + 1) + i];
        double below = sat[j * (width + 1) + i + 1] - sat[j * (width + 1) + i];
        return column > 0.0 ? below / column : double(j) / double(height);
    }
    double total = 0.0;      ///< Integral of C_m over S (C's unit times m2).
    glm::dvec2 median{0.0};  ///< s_m with cdf_m(s) = cdf_m(t|s) = 0.5 (Sec. 6.2), metres.
};

/// granier2003's far-field correction. Far away, Granier et al.'s spot light of image m gives
/// U_m(c) = (1/9) int over the basis support of C_m (the support centred on c = node + shift, the
/// shift set by the direction) where the light field gives W_m(c) = int C_m(s) Phi_m(s - c +
/// node) ds, the image weighted by the B-spline. The table holds W_m on a grid of centres over S
/// widened by the support; granier2003 scales each spot light by W_m(c) / U_m(c) (U_m from the
/// summed-area table, exact), so that its far field is the light field's own to W's bilinear
/// interpolation.
struct GranierTable {
    int size = 0;                   ///< Centres per axis.
    glm::dvec2 min{0.0}, max{0.0};  ///< The grid's first and last centres on S, metres.
    std::vector<float> weighted;    ///< W_m at [(m * size + j) * size + i], C's unit times m2.
    /// W_m for a support centred on `centre` (bilinear; 0 off the grid).
    double at(int m, glm::dvec2 centre) const;
};
constexpr int kGranierTableSize = 128;

class LightFieldData {
  public:
    enum class Model { Canned, Goesele };

    // --- File contents ---------------------------------------------------------------------
    Model model = Model::Canned;
    double delta = 0.05;             ///< Distance between U (z = 0) and S (z = delta), metres.
    glm::ivec2 count{1, 1};          ///< Basis functions along x and y (W, H).
    glm::dvec2 spacing{0.01, 0.01};  ///< Node spacing (hx, hy), metres.
    glm::dvec2 origin{0.0,
                      0.0};  ///< Node (0, 0) on U, metres; node (i, j) = origin + (i hx, j hy).
    glm::dvec2 imageMin{-0.05}, imageMax{0.05};  ///< Extent of every C_m on S, metres.
    int width = 0, height = 0;                   ///< Pixels of every image.
    bool rgb = false;                            ///< Images carry colour (else luminance only).
    std::string unit = "W/(m2 sr)";       ///< Or "cd/m2" (then irradiance is illuminance in lux).
    std::vector<LightFieldImage> images;  ///< count.x * count.y, index j * W + i.
    std::filesystem::path path;  ///< Where it was loaded from (empty when built in memory).
    std::vector<std::filesystem::path> imageFiles;  ///< The image files load() read, in order.

    // --- Precomputed -----------------------------------------------------------------------
    std::vector<LightFieldTables> tables;  ///< One per image, after precompute().
    double precomputeMs = 0.0;             ///< Wall time of the last precompute(), ms.

    /// Reads NAME.lf.json and its images (OpenImageIO); validates everything (image count and
    /// sizes, NaN or negative pixels, zero spacing, ...) and precomputes. Throws InputError
    /// naming the file and the problem.
    static std::shared_ptr<LightFieldData> load(const std::filesystem::path& file);
    /// Writes NAME.lf.json and one EXR per image beside it (NAME_i_j.exr): all to temporary files,
    /// then renamed (util/FileOutput.h), so a failed write replaces none. Throws InputError.
    void save(const std::filesystem::path& file) const;
    /// Checks the fields of an in-memory model (as load() does); throws InputError with `what`.
    void validate(const std::string& what) const;
    /// Builds the tables. Call after changing images.
    void precompute();

    // --- Geometry (local frame: U at z = 0, S at z = delta, emission towards +z) -------------
    int imageCount() const { return count.x * count.y; }
    glm::dvec2 node(int m) const;
    /// Support of Phi_m on U: node +- 1.5 spacing.
    void support(int m, glm::dvec2& uMin, glm::dvec2& uMax) const;
    /// Phi_m(u): product of two quadratic B-splines.
    double basis(int m, const glm::dvec2& u) const;
    /// Psi_m(u->s) (Eq. 1): Phi_m(u) for "canned"; times delta^2 cos^4(theta) for "goesele".
    double psi(int m, const glm::dvec2& u, const glm::dvec2& s) const;
    glm::dvec2 pixelSize() const;
    /// C_m(s) luminance, 0 outside the image extent.
    double lum(int m, const glm::dvec2& s) const;
    /// RGB colour ratio c_m(s) (1,1,1 for luminance data).
    glm::dvec3 colour(int m, const glm::dvec2& s) const;
    /// Radiance along the ray u -> s, RGB (Eq. 1).
    glm::dvec3 radiance(const glm::dvec2& u, const glm::dvec2& s) const;

    /// Restricted sampling box of image m on S seen from q (local, q.z > delta): the projection
    /// of Phi_m's support through q onto S (Eq. 7, corrected: s = u + (q - u) delta / q.z),
    /// clipped to the image extent. False when empty.
    bool restrictedBox(int m, const glm::dvec3& q, glm::dvec2& sMin, glm::dvec2& sMax) const;
    /// Integral of C_m over an axis-aligned box on S, exact for the piecewise constant image
    /// (fractional pixels included), through the summed-area table (Eq. 10, A_m).
    double boxIntegral(int m, glm::dvec2 sMin, glm::dvec2 sMax) const;
    /// Draws s in [sMin, sMax] with density C_m(s) / boxIntegral (the restricted CDFs of Eq. 8,
    /// inverted exactly with a secant-guided search over the piecewise linear pieces). False when
    /// the box holds no energy.
    bool sampleBox(int m, const glm::dvec2& sMin, const glm::dvec2& sMax, glm::dvec2 xi,
                   glm::dvec2& s) const;

    /// Total emitted flux (W, or lm for photometric data), RGB, by quadrature of
    /// L cos(theta_u) cos(theta_s) / r^2 over U x S.
    glm::dvec3 power() const;
    /// power(), computed once and kept (thread-safe).
    glm::dvec3 cachedPower() const;
    /// granier2003's far-field correction (computed once, thread-safe; GranierTable).
    const GranierTable& granierTable() const;
    /// The GPU's tables (made once, thread-safe): per image, the summed-area table as float-float
    /// pairs ((width + 1) x (height + 1), kUnitLightFieldSat), the luminance (kUnitLightFieldLum)
    /// and, for RGB data, the colour ratios in half floats (kUnitLightFieldColour).
    std::shared_ptr<const GpuTables> gpuTables() const;

  private:
    mutable std::once_flag mPowerOnce, mGranierOnce, mGpuTablesOnce;
    mutable std::shared_ptr<const GpuTables> mGpuTables;
    mutable glm::dvec3 mPower{0.0};
    mutable GranierTable mGranier;
};

/// A light-field luminaire placed in a scene: local +z is aim, +x is c0, position the local
/// origin (U's node grid is centred there by the converters).
class LightFieldLuminaire final : public LuminaireModel {
  public:
    LightFieldLuminaire() : LuminaireModel(LuminaireKind::LightField) {}

    /// K_max of the paper's Fig. 9: at most this many samples per image per frame on the GPU
    /// (the samples taken are reweighted, so the cap keeps the estimator unbiased).
    static constexpr int kMaxSamplesPerImage = 64;

    std::shared_ptr<const LightFieldData> data;
    std::string file;  ///< As written in the scene file (relative to it or absolute).

    /// x on S (world), w the direction of travel: L of the ray through x from U.
    glm::dvec3 radiance(const Pose& pose, const glm::dvec3& x, const glm::dvec3& w) const override;
    glm::dvec3 power() const override;
    /// Photometric when the file's unit is cd/m2 (lm, lx), else radiometric.
    Quantities quantities() const override {
        return data && data->unit == "cd/m2" ? Quantities::Photometric : Quantities::Radiometric;
    }
    /// A point on S by the balanced restricted sampler (image chosen with probability A_m / A
    /// from u.x, then s in its box); pdf is the marginal solid-angle density over all images.
    LightSample sample(const Pose& pose, const glm::dvec3& p, const glm::dvec2& u) const override;
    double pdf(const Pose& pose, const glm::dvec3& p, const glm::dvec3& wi) const override;
    std::vector<glm::dvec3> outline(const Pose& pose) const override;
};

/// Its scene entry ("file"), GPU record and tables, per-cell shadow maps (Sec. 6.2,
/// luminaires/lightfield/ShadowCells.h: items are the images), the manifest and its images as
/// source files, and as display radiance the mean over S of the rays parallel to the axis.
const LuminaireAdapter& lightFieldAdapter();
/// The light-field model of a luminaire; null when it is of another kind.
const LightFieldLuminaire* lightFieldModel(const Luminaire& luminaire);

/// CPU estimators (luminaires/lightfield/LightFieldEstimators.cpp); all take world p and unit
/// normal n. Exact model by Gauss-Legendre quadrature over U, split at knots and pixel edges
/// (double).
Estimate lightFieldReference(const Luminaire& l, const glm::dvec3& p, const glm::dvec3& n,
                             const EstimateOptions& options);
/// Restricted CDFs with balancing (Eq. 8, 12, 13), p on S by Eq. (9).
Estimate lightFieldRestrictedCdf(const Luminaire& l, const glm::dvec3& p, const glm::dvec3& n,
                                 const EstimateOptions& options);
/// Uniform sampling of the same restricted boxes (the paper's Fig. 12 baseline).
Estimate lightFieldUniformRestricted(const Luminaire& l, const glm::dvec3& p, const glm::dvec3& n,
                                     const EstimateOptions& options);
/// Granier et al. 2003 (seed 001, Eq. 14): one textured spot light per basis function at its node,
/// the image averaged over the support's footprint on S; deterministic and approximate.
Estimate lightFieldGranier2003(const Luminaire& l, const glm::dvec3& p, const glm::dvec3& n,
                               const EstimateOptions& options);
/// One global CDF over all images and pixels, independent of p (the paper's Fig. 11 baseline).
Estimate lightFieldPrecomputedGlobal(const Luminaire& l, const glm::dvec3& p, const glm::dvec3& n,
                                     const EstimateOptions& options);

}  // namespace candela
