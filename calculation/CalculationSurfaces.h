#pragma once
// EN 12464-1 calculation surfaces: task areas on work planes, each with its immediate surrounding
// (a band 0.5 m wide around it) and its background (a band 3 m wide beyond that, inside the room
// less its 0.5 m wall band), gridded by the standard's rule; their maintained illuminance (Em,
// U0 = Emin / Em, Emin, Emax) checked against requirements; and planar (horizontal, vertical or
// any) and cylindrical illuminance at points. Evaluated by computeReceivers
// (calculation/CalculationGrid.h), so every luminaire is measured by its own CPU estimator.

#include <functional>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "calculation/CalculationGrid.h"
#include "calculation/Isolines.h"
#include "util/JsonRead.h"

namespace candela {

struct Scene;

/// EN 12464-1's largest grid cell for an area of sides a x b (m): p = 0.2 x 5^log10(d) m, at most
/// 10 m, where d is the longer side, or the shorter one when the longer is twice it or more.
double standardGridCell(double a, double b);
/// Points along a side of `length` m for cells of at most p: the next whole number at or above
/// length / p, at least 1 (points sit at the cells' centres).
int standardPointCount(double length, double p);
/// EN 12464-1 (2011), Table 1: the immediate surrounding's maintained illuminance for a task
/// area's: 500 lx for 750 lx and above, 300 for 500, 200 for 300, 150 for 200, and the task's
/// own below 200. Between rows, the lower row's (the table's values are steps).
double surroundingIlluminance(double taskLux);
/// The standard's uniformity floors for the immediate surrounding and the background, and the
/// background's illuminance as a share of the immediate surrounding's.
constexpr double kSurroundingU0 = 0.40, kBackgroundU0 = 0.10, kBackgroundShare = 1.0 / 3.0;
/// Widths of the immediate surrounding, the background and the wall band, m.
constexpr double kSurroundingBand = 0.5, kBackgroundBand = 3.0, kWallBand = 0.5;
/// The immediate surrounding's grid cell for its rectangle of `size` (m, task area and band): the
/// standard's rule on the whole rectangle, at most a third of the band. The rule alone gives the
/// whole rectangle's cell (0.39 m around a 1.6 x 0.8 m desk), which leaves one ring of points
/// across the 0.5 m band: the surrounding's Emin and U0 would then be one ring's and its picture
/// the interpolation of one ring. With cells of at most a third of the band, the centres in a
/// whole band are sLo + (k + 1/2) p < sLo + 0.5 m for k = 0, 1, 2 on every side: three rings
/// (fewer where the room's walls cut the band). 0 for an empty rectangle.
double surroundingCell(const glm::dvec2& size);
/// Cylindrical illuminance is the mean vertical illuminance over this many horizontal
/// directions: light from any one direction is then weighted within 0.33 % of the exact 1/pi
/// (the ripple of a mean of 32 shifted clamped cosines; less for light from many directions).
constexpr int kCylinderAzimuths = 32;

/// How a surface or a point stands against its requirement. A surface the room leaves no points
/// of (an immediate surrounding or background clipped away by the walls) has nothing to judge:
/// it neither passes nor fails.
enum class Verdict { Pass, Fail, NoRequirement, NoPoints };
/// The words every output uses: "PASS", "FAIL", "no requirement", "no points".
const char* verdictText(Verdict verdict);

/// One surface as evaluated: its grid (the points of `lo`..`hi` outside `hole`), summary and
/// verdict.
struct SurfaceResult {
    std::string name;  ///< "Desk", "Desk: immediate surrounding", "Desk: background".
    std::string role;  ///< "task area", "cylindrical task area", "immediate surrounding" or
                       ///< "background".
    CalcPlane plane;
    glm::dvec2 lo{0.0}, hi{0.0};          ///< The gridded rectangle, m.
    glm::dvec2 holeLo{0.0}, holeHi{0.0};  ///< Points inside are not part of it (empty: none).
    glm::dvec2 spacing{0.0};              ///< Along u and v, m.
    glm::ivec2 cells{0};                  ///< Grid columns and rows before the hole.
    bool cylindrical = false;             ///< E is cylindrical illuminance Ez.
    std::vector<glm::dvec2> points;       ///< In-plane (u, v) of each point, m.
    std::vector<double> E, stdError;      ///< Maintained illuminance per point, lx (or W/m2).
    std::vector<double> initial;          ///< The same before maintenance (GridResult::initial).
    GridSummary summary;
    Requirement required;
    Verdict verdict = Verdict::NoPoints;
    /// Not failing: verdict is not Fail (true when there is no requirement, or no point).
    bool passes = true;
};

struct PointResult {
    CalcPoint point;
    double E = 0.0, stdError = 0.0;
    double initial = 0.0;  ///< E before maintenance.
    Verdict verdict = Verdict::NoRequirement;
    bool passes = true;  ///< Not failing: verdict is not Fail.
};

struct SurfaceReport {
    UnitSystem units;
    std::string maintenance;     ///< Scene::maintenanceNote().
    std::string bodies;          ///< Scene::bodiesNote().
    std::string light;           ///< What light E includes (lightStatement).
    double projectFactor = 1.0;  ///< Scene::maintenanceFactor.
    bool hasIndirect = false;
    std::string indirectNote;  ///< How the interreflected light was found (ReceiverResult).
    size_t patches = 0;        ///< The interreflection's patches (0 without it).
    std::vector<SurfaceResult> surfaces;
    std::vector<PointResult> points;
};

/// The grids of the scene's task areas and, where asked, their surroundings and backgrounds
/// (no illuminance yet). The room is the scene's bounds on each area's plane.
std::vector<SurfaceResult> layoutSurfaces(const Scene& scene);
/// A surface's values on its full grid of cells.x x cells.y points (at the cells' centres), NaN
/// at the points its hole takes, for its isolines (calculation/Isolines.h).
NodeGrid surfaceNodes(const SurfaceResult& surface);
/// Lays out and evaluates every surface and point in one computeReceivers call (`how`: its
/// technique, spp, visibility and interreflection). Throws InputError when the scene has
/// neither, or when a requirement in lux meets a radiometric scene.
SurfaceReport computeSurfaces(const Scene& scene, const GridSpec& how,
                              const std::function<void(const std::string&)>& status = {});

}  // namespace candela
