#pragma once
// The environment as a light source: an environment map at infinity behind the same technique
// interface as every luminaire kind (luminaires/Registry.h: its techniques are registry lines of
// the kind "environment", each a CPU estimator and a shader shaders/environment_TECHNIQUE.frag).
// It is not placed: a scene has at most one, made from its "environment" field
// (Scene::environmentLight), and it takes no part in what lists, draws or moves luminaires.

#include <memory>
#include <mutex>

#include "luminaires/Adapter.h"
#include "luminaires/Luminaire.h"
#include "luminaires/environment/Environment.h"
#include "luminaires/environment/EnvironmentSampling.h"

namespace candela {

class EnvironmentLight final : public LuminaireModel {
  public:
    EnvironmentLight(std::shared_ptr<const EnvironmentMap> map, Quantities quantities);
    /// With tables already built (another face size or number of Havran lights; tests).
    EnvironmentLight(std::shared_ptr<const EnvironmentLighting> lighting, Quantities quantities);

    /// Radiance travelling along w: what the map holds in the direction -w it comes from,
    /// W/(m2 sr) (cd/m2 for a photometric map), RGB. It has no pose: the one given is ignored.
    glm::dvec3 radiance(const Pose&, const glm::dvec3& x, const glm::dvec3& w) const override;
    /// A source at infinity has no finite flux: 0 (flux totals count luminaires only).
    glm::dvec3 power() const override { return glm::dvec3(0.0); }
    Quantities quantities() const override { return mQuantities; }
    /// A direction from the lat-long CDF (LatLongDistribution); the point is at infinity.
    LightSample sample(const Pose&, const glm::dvec3& p, const glm::dvec2& u) const override;
    double pdf(const Pose&, const glm::dvec3& p, const glm::dvec3& wi) const override;
    /// No surface: nothing to draw or pick.
    std::vector<glm::dvec3> outline(const Pose&) const override { return {}; }

    const EnvironmentMap& map() const { return *mMap; }
    const std::shared_ptr<const EnvironmentMap>& sharedMap() const { return mMap; }
    /// The CPU estimators' tables (cube-map and lat-long CDFs, Havran's lights), built on first
    /// use and shared by clones; safe to call from several threads.
    const EnvironmentLighting& lighting() const;

  private:
    struct Shared {
        std::once_flag once;
        std::shared_ptr<const EnvironmentLighting> lighting;
    };
    std::shared_ptr<const EnvironmentMap> mMap;
    Quantities mQuantities;
    std::shared_ptr<Shared> mShared;
};

/// Its description; nothing else (it is not placed, written or packed: luminaires/Adapter.h).
const LuminaireAdapter& environmentAdapter();
/// The environment model of a source; null when it is a luminaire.
const EnvironmentLight* environmentModel(const Luminaire& luminaire);
/// The environment as a source: named "environment", rendered by `technique`, one of the kind's
/// techniques (the scene's choice; renders may override it).
std::unique_ptr<Luminaire> placedEnvironment(std::shared_ptr<const EnvironmentLight> model,
                                             std::string technique = "balanced");

/// A registry estimator from an estimator over EnvironmentLighting (EnvironmentSampling.h).
template <EnvironmentIrradianceFn F>
Estimate onEnvironmentLight(const Luminaire& light, const glm::dvec3& p, const glm::dvec3& n,
                            const EstimateOptions& options) {
    return F(environmentModel(light)->lighting(), p, n, options);
}

}  // namespace candela
