#pragma once
// The photometric technique `uniform-area`: points uniform on the opening, the textbook Monte
// Carlo of the area form (Prost Eq. 6.3 on its own). Its own files (this, its .cpp and
// shaders/photometric_uniform_area.frag) and one registry line are all there is to it.

#include <glm/glm.hpp>

#include "luminaires/Estimate.h"
#include "luminaires/Luminaire.h"

namespace candela {

/// Irradiance at p for the unit normal n: (1/N) sum of I(-w) cos_p S_rect / (A r^2) over N points
/// uniform on the opening's bounding rectangle (0 outside the opening or in shadow), times the
/// light's colour; a segment or a point opening takes the reference's closed forms.
Estimate photometricUniformArea(const Luminaire& luminaire, const glm::dvec3& p,
                                const glm::dvec3& n, const EstimateOptions& options);

}  // namespace candela
