#pragma once
// A uniformly emitting (Lambertian) rectangle: the simplest luminaire with exact answers.
// It is centred on pose.position, spans the pose's local x (width) and y (height) axes and emits
// only into the half-space its aim (local +z) points to.

#include "luminaires/Adapter.h"
#include "luminaires/Estimate.h"
#include "luminaires/Luminaire.h"
#include "util/JsonRead.h"

namespace candela {

class LambertianRect final : public LuminaireModel {
  public:
    LambertianRect() : LuminaireModel(LuminaireKind::LambertianRect) {}

    glm::dvec2 size{1.0, 0.5};  ///< Width along local x (c0), height along local y, metres.
    glm::dvec3 emitted{10.0};   ///< Radiance to the +aim side, W/(m2 sr), RGB (cd/m2 if luminous).
    /// Given as a luminance ("luminance" in cd/m2) rather than a radiance ("radiance", W/(m2 sr)).
    bool luminous = false;

    glm::dvec3 radiance(const Pose& pose, const glm::dvec3& x, const glm::dvec3& w) const override;
    glm::dvec3 power() const override;
    Quantities quantities() const override {
        return luminous ? Quantities::Photometric : Quantities::Radiometric;
    }
    /// Uniform in the solid angle of the rectangle seen from p (Urena, Fajardo, King 2013);
    /// pdf = 1 / solidAngle(p), or no sample (pdf 0) when p is not in front of the emitting side.
    LightSample sample(const Pose& pose, const glm::dvec3& p, const glm::dvec2& u) const override;
    double pdf(const Pose& pose, const glm::dvec3& p, const glm::dvec3& wi) const override;
    /// Corners counter-clockwise seen from the emitting side, starting at -x/2, -y/2.
    std::vector<glm::dvec3> outline(const Pose& pose) const override;

    /// Solid angle subtended at p (steradians); 0 behind the emitting side or in its plane.
    double solidAngle(const Pose& pose, const glm::dvec3& p) const;
};

/// Its scene entry ("size", "radiance" or "luminance"), its GPU record (one
/// gpu::LambertianRectGpu, shaders/shared/GpuTypes.h) and its description.
const LuminaireAdapter& lambertianRectAdapter();
/// The rectangle model of a luminaire; null when it is of another kind.
const LambertianRect* lambertianRectModel(const Luminaire& luminaire);

/// Closed-form irradiance (polygon formula after horizon clipping); with a visibility query it
/// is scaled by the stochastic ratio sum(cos V) / sum(cos) over solid-angle samples.
Estimate lambertianRectAnalytic(const Luminaire& luminaire, const glm::dvec3& p,
                                const glm::dvec3& n, const EstimateOptions& options);
/// Monte Carlo with samples uniform in solid angle; reports the standard error.
Estimate lambertianRectReference(const Luminaire& luminaire, const glm::dvec3& p,
                                 const glm::dvec3& n, const EstimateOptions& options);

}  // namespace candela
