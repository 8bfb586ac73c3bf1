#pragma once
// Discomfort glare: the Unified Glare Rating of CIE 117 (1995) at observers the user places, as
// EN 12464-1 limits it (UGR_L),
//   UGR = 8 log10( 0.25 / Lb x sum over luminaires of L^2 omega / p^2 ),
// with L the luminance of a luminaire's luminous opening towards the eye (its intensity towards
// the eye over the opening's area projected on that direction, cd/m2), omega the solid angle the
// opening subtends at the eye (projected area over distance squared, sr), p Guth's position index
// and Lb the background luminance, Eind / pi, from the indirect illuminance Eind at the eye on
// the plane facing the line of sight (the interreflected light: calculation/Interreflection.h), or
// as the observer gives it.
//
// The position index is Levin's fit (J. IES, 1975) of Guth's table, which CIE 117 tabulates:
//   ln p = (35.2 - 0.31889 tau - 1.22 exp(-2 tau / 9)) 1e-3 sigma
//          + (21 + 0.26667 tau - 0.002963 tau^2) 1e-5 sigma^2,
// sigma the angle (degrees) between the line of sight and the direction to the luminaire, tau the
// angle (degrees) between the vertical and the plane holding both. Luminaires behind the eye's
// frontal plane (sigma >= 90 degrees) or not above eye height are left out, as the table covers
// neither.
//
// Small sources (a projected area below 0.005 m2, point sources included) take CIE 147's form,
// 200 I^2 / r^2 in place of L^2 omega = I^2 / (A r^2): the same at 0.005 m2 (1 / 0.005 = 200), and
// bounded as A shrinks. Luminaires subtending more than 0.1 sr are marked outside CIE 117's range.
// Intensities are the scene's luminaire output as the illuminance uses it (maintenance factor and
// dimming applied). Only photometric luminaires (IES, EULUMDAT, TM-33, GLDF) have the intensity the
// formula needs; other kinds are listed as not evaluated.

#include <functional>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "calculation/CalculationGrid.h"
#include "util/JsonRead.h"

namespace candela {

struct Scene;

/// Guth's position index by Levin's fit (above). `toSource` and `view` unit, `up` the unit
/// vertical; 0 when the source is at or behind the eye's frontal plane (outside the index).
double guthPositionIndex(const glm::dvec3& toSource, const glm::dvec3& view, const glm::dvec3& up);
/// The largest projected area of a small source (CIE 147), m2, and the largest solid angle of a
/// source within CIE 117's range, sr.
constexpr double kSmallSourceArea = 0.005, kLargeSourceSolidAngle = 0.1;

/// One luminaire as an observer sees it.
struct GlareSource {
    std::string luminaire;
    double intensity = 0.0;      ///< Towards the eye, cd.
    double distance = 0.0;       ///< Eye to the opening's centre, m.
    double projectedArea = 0.0;  ///< The opening seen from the eye, m2 (0: a point source).
    double luminance = 0.0;      ///< intensity / projectedArea, cd/m2 (0 for a point source).
    double solidAngle = 0.0;     ///< projectedArea / distance^2, sr.
    double positionIndex = 0.0;  ///< Guth's p.
    double term = 0.0;           ///< L^2 omega / p^2 (or CIE 147's 200 I^2 / (r^2 p^2)).
    bool small = false;          ///< CIE 147's small-source form was used.
    bool large = false;          ///< Subtends more than kLargeSourceSolidAngle.
    std::string excluded;        ///< Why it does not count ("" when it does).
};

struct GlareResult {
    GlareObserver observer;
    double background = 0.0;  ///< Lb used, cd/m2.
    bool backgroundFromIndirect = false;
    double indirectStdError = 0.0;  ///< Of Eind when computed, lx.
    double ugr = 0.0;               ///< 0 when no luminaire counts (no glare to rate).
    bool passes = true;             ///< ugr <= limit (true without a limit).
    std::vector<GlareSource> sources;
};

struct GlareReport {
    std::string maintenance;  ///< Scene::maintenanceNote().
    std::string bodies;       ///< Scene::bodiesNote().
    std::vector<GlareResult> observers;
};

/// UGR at each of `observers` (the scene's own when empty). Lb comes from one interreflection
/// solution (computeReceivers with `how`'s spp and patches, indirect on) for the observers that
/// give none. Throws InputError naming the observer when a background is needed and the scene
/// has no surfaces to reflect light, or when the scene is radiometric (UGR is photometric).
GlareReport computeGlare(const Scene& scene, const GridSpec& how,
                         const std::vector<GlareObserver>& observers = {},
                         const std::function<void(const std::string&)>& status = {});

}  // namespace candela
