#pragma once
// The far field of a light-field luminaire: its luminous intensity per direction,
// I(w) = integral over S of L(u(s, w) -> s) cos(theta) ds, with u = s - delta (w.x, w.y) / w.z the
// point of U the ray through s in direction w comes from. Seen from farther than a few opening
// sizes the light field is this photometric point source on S's image rectangle, which Prost's
// techniques render in a fraction of the restricted sampler's time: the editor's fallback while
// the user drags (renderer/LivePreview.h). Not used for the final image.

#include <memory>
#include <vector>

#include "luminaires/lightfield/LightField.h"
#include "luminaires/photometric/PhotometricLuminaire.h"

namespace candela {

/// The intensity table (type C, gamma 0-180 by stepDeg, C 0-360 by 2 stepDeg; 0 beyond 90
/// degrees) of the light field, in its unit times m2 (cd for cd/m2 data), summed over pixel
/// centres of S (every k-th pixel when an image is wider than `points`); the opening is S's
/// image rectangle.
std::shared_ptr<const PhotometricData> farFieldPhotometry(const LightFieldData& data,
                                                          double stepDeg = 2.5, int points = 64);

/// A photometric luminaire standing in for a light-field luminaire `light`: the same name, aim
/// and c0, centred on S's image rectangle, technique "scattered", with farFieldPhotometry of its
/// data (computed once per light-field data and kept while that data lives). Null for a
/// luminaire of another kind.
std::unique_ptr<Luminaire> farFieldTwin(const Luminaire& light);
/// A thumbnail of what a far field casts: the illuminance on a floor `height` metres below it
/// (aimed straight down, C0 along +x), over a square of half-side 2.5 height, size x size RGB8
/// pixels, rows from +y down. Logarithmic over three decades below its brightest pixel, in a
/// warm ramp; the opening's footprint is ignored (a point source).
std::vector<unsigned char> footprintImage(const PhotometricData& data, int size,
                                          double height = 1.0);

/// Moves a twin to where the light-field luminaire `light` now is (its pose, name and nothing
/// else); nothing for a luminaire of another kind.
void placeFarFieldTwin(Luminaire& twin, const Luminaire& light);

}  // namespace candela
