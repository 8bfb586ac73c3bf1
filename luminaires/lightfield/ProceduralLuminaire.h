#pragma once
// Procedural light-field luminaires: a small deterministic virtual goniophotometer. A few LED dies
// (small Lambertian squares) sit at the focus of a paraboloidal reflector with a rectangular
// aperture; a shield blocks their direct light; a patterned cover in the aperture (a lens with
// stripes of cylindrical lenslets, or a grid of prisms with frosted and opaque cells) attenuates
// and deflects what the reflector sends forward. A fixed-seed Monte Carlo traces rays through it,
// and the rays leaving the cover are projected onto a light field
// (luminaires/lightfield/LightFieldRays.h) whose U plane is the cover, with the node grid centred
// on the cover's centre.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "luminaires/lightfield/LightField.h"
#include "luminaires/lightfield/LightFieldRays.h"

namespace candela {

struct ProceduralOptions {
    uint64_t rays = 0;  ///< Rays emitted by the dies; 0 takes the preset's default.
    uint64_t seed = 1;
    int threads = 0;  ///< Tracing threads; 0 uses the hardware's (at most 8). Same result for any.
    std::function<void(double)> progress;  ///< Fraction of the rays traced, now and then.
};

struct ProceduralResult {
    std::shared_ptr<LightFieldData> data;
    LightFieldLayout layout;
    ProjectionReport report;  ///< Of the rays leaving the cover.
    uint64_t emittedRays = 0;
    uint64_t exitRays = 0;      ///< Rays leaving through the cover.
    double emittedFlux = 0.0;   ///< Flux of the dies, lm.
    double exitFlux = 0.0;      ///< Flux leaving through the cover, lm (the rest is absorbed).
    double traceSeconds = 0.0;  ///< Wall time of tracing and accumulating the rays, s.
    double totalSeconds = 0.0;  ///< Wall time of the whole build, s.
};

/// "bike-headlight" (9x7 images of 300x300) and "car-headlight" (11x9 images of 256x256).
const std::vector<std::string>& proceduralPresets();
/// One line describing a preset's geometry; empty for an unknown name.
std::string proceduralDescription(const std::string& preset);
/// Traces and projects a preset. Throws InputError for an unknown preset.
ProceduralResult buildProceduralLuminaire(const std::string& preset,
                                          const ProceduralOptions& options);

}  // namespace candela
