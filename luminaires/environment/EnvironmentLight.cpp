#include "luminaires/environment/EnvironmentLight.h"

#include <limits>

namespace candela {

EnvironmentLight::EnvironmentLight(std::shared_ptr<const EnvironmentMap> map, Quantities quantities)
    : LuminaireModel(LuminaireKind::Environment),
      mMap(std::move(map)),
      mQuantities(quantities),
      mShared(std::make_shared<Shared>()) {}

EnvironmentLight::EnvironmentLight(std::shared_ptr<const EnvironmentLighting> lighting,
                                   Quantities quantities)
    : LuminaireModel(LuminaireKind::Environment),
      mMap(lighting->sharedMap()),
      mQuantities(quantities),
      mShared(std::make_shared<Shared>()) {
    mShared->lighting = std::move(lighting);
    std::call_once(mShared->once, [] {});  // built already
}

glm::dvec3 EnvironmentLight::radiance(const Pose&, const glm::dvec3&, const glm::dvec3& w) const {
    return mMap->radiance(-w);
}

const EnvironmentLighting& EnvironmentLight::lighting() const {
    std::call_once(mShared->once,
                   [&] { mShared->lighting = std::make_shared<const EnvironmentLighting>(mMap); });
    return *mShared->lighting;
}

LightSample EnvironmentLight::sample(const Pose&, const glm::dvec3& p, const glm::dvec2& u) const {
    LightSample s;
    DirectionSample d = lighting().global().sample(u);
    if (!(d.pdf > 0.0)) return s;
    s.wi = d.w;
    s.distance = std::numeric_limits<double>::infinity();
    s.position = p + 1e30 * d.w;  // at infinity, for callers that want a point
    s.radiance = mMap->radiance(d.w);
    s.pdf = d.pdf;
    return s;
}

double EnvironmentLight::pdf(const Pose&, const glm::dvec3&, const glm::dvec3& wi) const {
    return lighting().global().pdf(wi);
}

namespace {

const EnvironmentLight& environmentOf(const LuminaireModel& model) {
    return static_cast<const EnvironmentLight&>(model);
}

std::string environmentDescribe(const LuminaireModel& model) {
    const EnvironmentMap& map = environmentOf(model).map();
    return "environment map " + map.source() + " (" + std::to_string(map.width()) + " x " +
           std::to_string(map.height()) + ", " + radianceUnit(model.quantities()) + ")";
}

/// The viewport draws no emitter for it.
glm::dvec3 environmentDisplayRadiance(const Luminaire&) {
    return glm::dvec3(0.0);
}

}  // namespace

const LuminaireAdapter& environmentAdapter() {
    // Not placed (no parse, no create); the scene saves its "environment" field as written, and
    // its GPU state is renderer/passes/EnvironmentPass's (the map and its tables): no record.
    static const LuminaireAdapter adapter{nullptr,
                                          nullptr,
                                          nullptr,
                                          nullptr,
                                          nullptr,
                                          &environmentDescribe,
                                          nullptr,
                                          nullptr,
                                          nullptr,
                                          nullptr,
                                          &environmentDisplayRadiance};
    return adapter;
}

const EnvironmentLight* environmentModel(const Luminaire& luminaire) {
    return luminaire.kind() == LuminaireKind::Environment ? &environmentOf(luminaire.model())
                                                          : nullptr;
}

std::unique_ptr<Luminaire> placedEnvironment(std::shared_ptr<const EnvironmentLight> model,
                                             std::string technique) {
    auto light = std::make_unique<Luminaire>(std::move(model));
    light->name = std::string(kindName(LuminaireKind::Environment));
    light->technique = std::move(technique);
    return light;
}

}  // namespace candela
