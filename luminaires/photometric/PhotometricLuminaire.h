#pragma once
// A photometric area light: far-field photometry (IES LM-63 / EULUMDAT, formats/Photometry.h)
// emitted from the luminous opening as a flat two-sided polygon (Prost 2019, Ch. 2.3 and 6.1).
//
// Radiance leaving the opening in direction w is I(w) / (A |cos theta_L|), theta_L the angle to the
// opening's normal (the aim), so that far away it is a point source of intensity I(w) and the
// irradiance at p is the average over the opening of I(w) cos(theta_p) / r^2 — which stays finite
// even for receivers in the opening's plane. Openings of zero area (a point, or a segment for a
// zero width) are treated as that point or segment. Units: the file's candela give lux and cd/m2.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "formats/Gldf.h"
#include "formats/Photometry.h"
#include "luminaires/Adapter.h"
#include "luminaires/Estimate.h"
#include "luminaires/Luminaire.h"
#include "util/JsonRead.h"

namespace candela {

class PhotometricLuminaire final : public LuminaireModel {
  public:
    PhotometricLuminaire() : LuminaireModel(LuminaireKind::Photometric) {}

    std::shared_ptr<const PhotometricData> data;
    std::string file;        ///< As written in the scene (relative to it or absolute).
    double scale = 1.0;      ///< Dimming: multiplies every intensity.
    glm::dvec3 colour{1.0};  ///< RGB tint of the luminous quantities (white: lux in all three).
    glm::dvec2 openingOverride{
        0.0};  ///< > 0: a length x width rectangle instead of the file's opening.

    /// Set when it is a GLDF variant (scene type "gldf"): the container's product data (for
    /// describe(), `candela info` and the editor). `file` is then the .gldf container and
    /// `data` its variant's photometry.
    std::shared_ptr<const GldfProduct> gldf;
    std::string gldfVariant;  ///< The variant's id (set with gldf).
    /// Which of the variant's placements this is (from 0), of how many: a variant placing several
    /// emitters (at its L3D geometry's objects) is one luminaire per placement.
    int gldfEmitter = 0, gldfEmitterCount = 1;
    /// Set when the entry derives its maintenance factor from the product's data ("maintenance":
    /// formats/Gldf.h), with the factors found; maintenanceFactor is then their product.
    std::optional<GldfMaintenanceChoice> gldfMaintenance;
    GldfMaintenanceFactors gldfFactors;
    /// The light emitter this luminaire places (null when not a GLDF variant).
    const GldfLightEmitter* gldfLightEmitter() const;
    /// The GLDF variant's L3D geometry (null when it has none) and the light-emitting object its
    /// emitter is placed at: the opening and its frame in the luminaire's L3D frame (+z up,
    /// metres; formats/L3d.h), which replace the photometry file's rough opening and put the
    /// emitter where the product has it relative to the pose (the insertion point).
    std::shared_ptr<const L3dLuminaire> geometry;
    struct Placement {
        std::string object;  ///< The L3D light-emitting object's name.
        glm::dvec3 centre{0.0}, c0{1, 0, 0}, aim{0, 0, -1};
        LuminousOpening opening;
    };
    std::optional<Placement> placement;
    /// The body blocks other light (scene entry "body": false turns it off): the L3D geometry,
    /// drawn (a variant's placements share it: its first placement, gldfEmitter 0, gives it),
    /// or without one the photometry's luminous box, which the camera sees through.
    bool showBody = true;
    /// The body's diffuse reflectance (scene entry "body_reflectance"; neither L3D nor the
    /// photometric formats hold one): black.
    double bodyReflectance = 0.0;

    /// The pose moved to the placement's object (the pose itself without one).
    Pose emitterPose(const Pose& pose) const override;
    glm::dvec3 radiance(const Pose& pose, const glm::dvec3& x, const glm::dvec3& w) const override;
    /// Flux from the table (exact quadrature of the interpolant) times scale, lm per channel.
    glm::dvec3 power() const override;
    Quantities quantities() const override { return Quantities::Photometric; }
    /// Uniform in area on the opening (the reference's density, Eq. 6.3), as a solid-angle pdf;
    /// pdf 0 in the opening's plane.
    LightSample sample(const Pose& pose, const glm::dvec3& p, const glm::dvec2& u) const override;
    double pdf(const Pose& pose, const glm::dvec3& p, const glm::dvec3& wi) const override;
    std::vector<glm::dvec3> outline(const Pose& pose) const override;

    /// The opening in the local z = 0 plane (metres), counter-clockwise about +z; empty for a
    /// point source.
    const std::vector<glm::dvec2>& polygon() const { return mPolygon; }
    double area() const { return mArea; }
    /// Whether local point q (metres, z = 0 plane) lies in the opening polygon; `slack` metres
    /// of tolerance outside its edges.
    bool contains(const glm::dvec2& q, double slack = 0.0) const;
    /// Largest extent of the opening, metres (0 for a point).
    double size() const { return mSize; }
    /// Candela towards world direction w (from the luminaire placed at `pose`), scale applied.
    double intensity(const Pose& pose, const glm::dvec3& w) const;
    /// The photometric frame in world directions: x = C0 (c0 made orthogonal to the aim),
    /// y = C90 = c0 x aim (so C grows counter-clockwise seen from above a downlight, the
    /// photometric convention; Pose::frame's y is aim x c0, the other way), z = the aim
    /// (gamma = 0). The opening, the table and the GPU record all use this frame.
    void photometricFrame(const Pose& pose, glm::dvec3& x, glm::dvec3& y, glm::dvec3& z) const;
    /// The opening used: openingOverride, else the placement's, else the file's.
    LuminousOpening opening() const;
    /// Recomputes the polygon after data or openingOverride changed.
    void updateOpening();

    /// Loads (shared between instances) a photometric file; throws InputError naming it.
    static std::shared_ptr<const PhotometricData> load(const std::string& path);
    /// Sets gldf, gldfVariant and data from a GLDF container's variant ("" for the first),
    /// shared between instances like load(); throws InputError naming the container.
    void loadGldf(const std::string& path, const std::string& variant, int emitter = 0);

  private:
    friend struct PhotometricAdapter;
    bool mAllEmitters = false;  ///< Parsed from an entry without "emitter" (see companions()).
    /// The GPU tables of `data` as last made (rebuilt when `data` is another model).
    mutable std::shared_ptr<const GpuTables> mGpuTables;
    mutable const PhotometricData* mGpuTablesFor = nullptr;
    std::vector<glm::dvec2> mPolygon;
    double mArea = 0.0;
    double mSize = 0.0;
};

/// Its scene entry (type "photometric", or "gldf" for a GLDF variant: {"type": "gldf", "file":
/// "lamp.gldf", "variant": "id", "emitter": k}, variant optional: the first; emitter optional:
/// every placement of the variant, the others as companions), its GPU record and tables, the
/// photometric file and its TILT file (the .gldf container for a variant) as source files, its
/// body, and shadow maps at the opening's centre and near its four corners (the polygon vertex
/// closest to each corner of its bounding rectangle; the two ends of a segment; the centre alone
/// for a point or for count 1): item 0, the whole opening, averages them with equal weights;
/// item 1, the centre, reads the centre's map (the `point` technique).
const LuminaireAdapter& photometricAdapter();
/// A scene's "gldf" entry (luminaires/Registry.h: a format of the photometric kind), with the
/// photometric entry's scale, colour and opening; a "maintenance" object sets the placement's
/// maintenance factor from the product's data.
std::unique_ptr<Luminaire> parseGldfLuminaire(const nlohmann::json& entry,
                                              const json::Where& where);
/// The photometric model of a luminaire; null when it is of another kind.
const PhotometricLuminaire* photometricModel(const Luminaire& luminaire);
/// Whether a and b place emitters of one GLDF variant that places several (the luminaires one
/// scene entry makes, which the editor moves as one).
bool sameGldfVariant(const Luminaire& a, const Luminaire& b);

/// The techniques (luminaires/photometric/PhotometricEstimators.cpp); all take world p and unit
/// normal n and return illuminance in lux (per channel, times the colour).
Estimate photometricReference(const Luminaire&, const glm::dvec3& p, const glm::dvec3& n,
                              const EstimateOptions&);
Estimate photometricPoint(const Luminaire&, const glm::dvec3& p, const glm::dvec3& n,
                          const EstimateOptions&);
Estimate photometricStructured(const Luminaire&, const glm::dvec3& p, const glm::dvec3& n,
                               const EstimateOptions&);
Estimate photometricMrp(const Luminaire&, const glm::dvec3& p, const glm::dvec3& n,
                        const EstimateOptions&);
Estimate photometricScattered(const Luminaire&, const glm::dvec3& p, const glm::dvec3& n,
                              const EstimateOptions&);
Estimate photometricPoisson24(const Luminaire&, const glm::dvec3& p, const glm::dvec3& n,
                              const EstimateOptions&);
Estimate photometricPoisson40(const Luminaire&, const glm::dvec3& p, const glm::dvec3& n,
                              const EstimateOptions&);
Estimate photometricAdaptive(const Luminaire&, const glm::dvec3& p, const glm::dvec3& n,
                             const EstimateOptions&);
Estimate photometricHybrid(const Luminaire&, const glm::dvec3& p, const glm::dvec3& n,
                           const EstimateOptions&);

/// The fixed Poisson-disk set of the mc-poisson-N techniques: N points in [0,1)^2 by dart
/// throwing with a fixed seed and the largest minimum distance that admits them.
const std::vector<glm::dvec2>& poissonSet(int n);

}  // namespace candela
