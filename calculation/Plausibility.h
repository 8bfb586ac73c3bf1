// Where a luminaire's own figures disagree with each other: a rated flux far from what its
// intensity table integrates to, a light output ratio above 100 %, an efficacy no white light
// source reaches, a UGR reference no real luminaire gives. Each is one plain-language line naming
// the file, both numbers and the one Candela uses (always the intensity table: it is what the
// light is computed from). `candela info`, the editor's inspector and the report print the same
// lines.
#pragma once

#include <string>
#include <vector>

namespace candela {

struct PhotometricData;
struct GldfLightEmitter;
class PhotometricLuminaire;

/// How far a rated or stated flux may sit from the table's integral before it is called out.
/// Catalogue fluxes are rounded to two or three figures and measured on other samples; 5 % is
/// beyond both, and below the differences that matter (a wrong lamp count, a wrong unit).
constexpr double kRatedFluxTolerance = 0.05;
/// How far a declared light output ratio may sit from the table's: EULUMDAT states LORL in whole
/// or tenth percent, and the table's own rounding (four or five digits per intensity) moves its
/// flux by far less than 1 %. Also the margin above 100 % before a ratio is impossible.
constexpr double kLorTolerance = 0.01;
/// Luminous efficacy above which the figures are wrong, lm/W: the best white LED luminaires
/// reach about 220 lm/W, and white light of good colour rendering cannot exceed about
/// 250-300 lm/W (683 lm/W is monochromatic 555 nm light).
constexpr double kMaxPlausibleEfficacy = 250.0;
/// UGR references (CIE 190 table, 4H x 8H room) of real luminaires lie in this range; one
/// outside it points at intensities in the wrong unit or scale.
constexpr double kMinPlausibleUgr = 5.0, kMaxPlausibleUgr = 40.0;

/// The lines for photometry `d` shown as `name` ("lamp.ldt", "product.gldf:ldc/lamp.ldt"), with
/// the GLDF light emitter's ratings when it has them (`rated` may be null): the file's own
/// figures, before any dimming in a scene. Empty when the figures agree.
/// `withUgr` adds the UGR reference check (a CIE 190 table, a few milliseconds).
std::vector<std::string> plausibilityNotes(const std::string& name, const PhotometricData& d,
                                           const GldfLightEmitter* rated, bool withUgr = true);

/// The same for a placed luminaire, named by its file's name without folders.
std::vector<std::string> plausibilityNotes(const PhotometricLuminaire& light, bool withUgr = true);

}  // namespace candela
