#pragma once
// What a CPU estimator takes and returns (luminaires/Registry.h: TechniqueInfo::irradiance): the
// options of an estimate, its result with its standard error, and the visibility it may query.
// Beside the luminaire interface so that a kind's header needs no more than this.

#include <cstdint>
#include <glm/glm.hpp>

namespace candela {

/// Answers whether the segment between two points is free of occluders.
class Visibility {
  public:
    virtual ~Visibility() = default;
    /// From a receiver `from` to a point `to` on a light: a luminaire's body casts no shadow on
    /// the light of its own openings (scene/Scene.h: insideBody).
    virtual bool visible(const glm::dvec3& from, const glm::dvec3& to) const = 0;
    /// Between two surface points (interreflection): every surface occludes, bodies included.
    virtual bool visibleBetweenSurfaces(const glm::dvec3& from, const glm::dvec3& to) const {
        return visible(from, to);
    }
    /// Is the ray from `from` along the unit `dir` free of occluders out to infinity (a distant
    /// light)? Implementations bias only its start.
    virtual bool visibleToward(const glm::dvec3& from, const glm::dvec3& dir) const = 0;
};

struct Estimate;

struct EstimateOptions {
    int spp = 4096;                          ///< Samples per point for stochastic techniques.
    uint64_t seed = 1;                       ///< Fixed seed: results are reproducible.
    const Visibility* visibility = nullptr;  ///< null: no shadowing.
    /// The same technique's estimate at the same point without visibility, when the caller has
    /// it already (a design calculation measures every luminaire unshadowed first, to share its
    /// shadow rays): an exact technique may take it instead of computing it again. null: none.
    const Estimate* unshadowed = nullptr;
};

struct Estimate {
    glm::dvec3 irradiance{0.0};  ///< W/m2 per channel (lux for photometric data).
    glm::dvec3 stdError{0.0};    ///< Standard error of the estimate; 0 for exact techniques.
};

}  // namespace candela
