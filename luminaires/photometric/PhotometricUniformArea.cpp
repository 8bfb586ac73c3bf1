#include "luminaires/photometric/PhotometricUniformArea.h"

#include <cmath>
#include <limits>

#include "luminaires/Random.h"
#include "luminaires/photometric/PhotometricLuminaire.h"

namespace candela {

Estimate photometricUniformArea(const Luminaire& luminaire, const glm::dvec3& p,
                                const glm::dvec3& n, const EstimateOptions& options) {
    const auto& light = *photometricModel(luminaire);
    const Pose& pose = luminaire.pose;
    if (!(light.area() > 0.0))
        return photometricReference(luminaire, p, n, options);  // a segment or a point
    glm::dvec3 x, y, z;
    light.photometricFrame(pose, x, y, z);
    glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    for (const glm::dvec2& v : light.polygon()) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
    const double rect = (hi.x - lo.x) * (hi.y - lo.y);
    double len = glm::length(n);
    glm::dvec3 normal = len > 0.0 ? n / len : glm::dvec3(0.0);
    Random rng(options.seed);
    double mean = 0.0, m2 = 0.0;
    int spp = std::max(1, options.spp);
    const glm::dvec3 centre = luminaire.emitterPose().position;
    for (int k = 0; k < spp; ++k) {
        glm::dvec2 u = lo + glm::dvec2(rng.uniform(), rng.uniform()) * (hi - lo);
        double value = 0.0;
        if (light.contains(u)) {
            glm::dvec3 q = centre + u.x * x + u.y * y;
            glm::dvec3 v = q - p;
            double r = glm::length(v), cosP = r > 0.0 ? glm::dot(normal, v) / r : 0.0;
            if (cosP > 0.0 && (!options.visibility || options.visibility->visible(p, q)))
                value = light.intensity(pose, -v) * cosP * rect / (light.area() * r * r);
        }
        if (!std::isfinite(value)) value = 0.0;
        double delta = value - mean;
        mean += delta / double(k + 1);
        m2 += delta * (value - mean);
    }
    double variance = spp > 1 ? std::max(0.0, m2) / double(spp - 1) : 0.0;
    Estimate e;
    e.irradiance = mean * light.colour;
    e.stdError = std::sqrt(variance / double(spp)) * light.colour;
    return e;
}

}  // namespace candela
