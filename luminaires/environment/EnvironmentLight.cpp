#include "luminaires/environment/EnvironmentLight.h"

#include <limits>

namespace candela {

EnvironmentLight::EnvironmentLight(std::shared_ptr<const EnvironmentMap> map, Quantities quantities,
                                   std::string technique)
    : mMap(std::move(map)), mQuantities(quantities), mShared(std::make_shared<Shared>()) {
    name = std::string(kKind);
    this->technique = std::move(technique);
}

EnvironmentLight::EnvironmentLight(std::shared_ptr<const EnvironmentLighting> lighting,
                                   Quantities quantities)
    : mMap(lighting->sharedMap()), mQuantities(quantities), mShared(std::make_shared<Shared>()) {
    name = std::string(kKind);
    technique = "balanced";
    mShared->lighting = std::move(lighting);
    std::call_once(mShared->once, [] {});  // built already
}

std::unique_ptr<Luminaire> EnvironmentLight::clone() const {
    return std::make_unique<EnvironmentLight>(*this);
}

glm::dvec3 EnvironmentLight::radiance(const glm::dvec3&, const glm::dvec3& w) const {
    return mMap->radiance(-w);
}

const EnvironmentLighting& EnvironmentLight::lighting() const {
    std::call_once(mShared->once,
                   [&] { mShared->lighting = std::make_shared<const EnvironmentLighting>(mMap); });
    return *mShared->lighting;
}

LightSample EnvironmentLight::sample(const glm::dvec3& p, const glm::dvec2& u) const {
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

double EnvironmentLight::pdf(const glm::dvec3&, const glm::dvec3& wi) const {
    return lighting().global().pdf(wi);
}

std::string EnvironmentLight::describe() const {
    return "environment map " + mMap->source() + " (" + std::to_string(mMap->width()) + " x " +
           std::to_string(mMap->height()) + ", " + radianceUnit(mQuantities) + ")";
}

}  // namespace candela
