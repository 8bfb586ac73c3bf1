#pragma once
// A layout that reaches its target: given a task area, a luminaire, a mounting height and a
// target maintained illuminance (and uniformity), the count and regular arrangement of luminaires
// that meets it with the fewest. The lumen method gives the first guess
//
//   N = Em A / (Phi MF UF),  UF ~ DLOR k / (k + 1),  k = L W / (h (L + W)),
//
// (A = L x W the arrangement's area, h the luminaires' height above the task's plane, DLOR the
// share of the luminaire's flux emitted downwards; this UF is the direct share a room of index k
// catches, low for a room that reflects light, which is why it is only a guess). Each candidate
// arrangement is then computed as `candela surfaces` computes the task area (direct light with
// shadows, interreflected light), and the count moves up or down a chain of grids of near-square
// spacing until the smallest that meets the target is found; the grids between the largest that
// failed and the smallest that met, with spacings within 1.5 of each other, are tried last.
//
// The luminaires are spread over the room that holds the task area (a scene-file "room" whose
// outline contains the area's middle: its bounding rectangle, less the points outside an L or
// other concave outline), else over the scene's bounds (a room written as planes), else over the
// task area itself: a regular grid with half a spacing to the walls. They replace the scene's
// luminaires above that rectangle; others stay and light too.

#include <functional>
#include <glm/glm.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "calculation/CalculationSurfaces.h"

namespace candela {

struct Scene;
class Luminaire;

struct LayoutRequest {
    std::string name = "Layout";  ///< Its luminaires are named "<name> 1", "<name> 2", ...
    std::string area;             ///< The task area's name; "" for the scene's only task area.
    /// A scene-file luminaire entry (its position is set here; its file relative to the
    /// scene's folder, as the scene's own entries are).
    nlohmann::json luminaire;
    double mountingHeight = 0.0;  ///< The luminaires' openings above the room's floor, m.
    double targetEm = 0.0;        ///< Maintained illuminance to reach, lx; 0: the area's own.
    double targetU0 = 0.0;        ///< Uniformity to reach; 0: the area's own (if any).
    int maxLuminaires = 400;      ///< Stop looking beyond this many.
    int maxTries = 16;            ///< Arrangements computed at most.
};

/// One arrangement tried: columns along x and rows along z, and what the task area got.
struct LayoutCandidate {
    int columns = 0, rows = 0;
    glm::dvec2 spacing{0.0};                ///< Along x and z, m.
    std::vector<glm::dvec3> positions;      ///< The luminaires' openings, m.
    double em = 0.0, u0 = 0.0, eMin = 0.0;  ///< The task area's, lx.
    bool meets = false;
    int count() const { return int(positions.size()); }
};

struct LayoutResult {
    std::string area;             ///< The task area's name.
    glm::dvec2 lo{0.0}, hi{0.0};  ///< The rectangle the luminaires are spread over (x, z), m.
    double floorY = 0.0;          ///< The room's floor, m.
    double roomIndex = 0.0, utilisationGuess = 0.0, downwardShare = 0.0;
    double flux = 0.0;  ///< One luminaire's, lm.
    double maintenanceFactor = 1.0;
    double targetEm = 0.0, targetU0 = 0.0;
    int lumenMethodCount = 0;            ///< The lumen method's N (before rounding to a grid).
    std::vector<LayoutCandidate> tried;  ///< In the order computed.
    int chosen = -1;    ///< Index into tried of the smallest arrangement that meets the target.
    std::string light;  ///< What light the task area's values include.
    const LayoutCandidate* best() const { return chosen < 0 ? nullptr : &tried[size_t(chosen)]; }
    /// Whether a luminaire at `p` (m) stands over the rectangle: the layout replaces it.
    bool covers(const glm::dvec3& p) const {
        return p.x >= lo.x && p.x <= hi.x && p.z >= lo.y && p.z <= hi.y;
    }
};

/// Proposes the layout; InputError naming what is wrong (no such task area, a luminaire that is
/// not a photometry, a mounting height below the task's plane, no target). `status` hears each
/// arrangement as it is computed.
LayoutResult proposeLayout(const Scene& scene, const LayoutRequest& request,
                           const std::function<void(const std::string&)>& status = {});

/// The scene with the layout applied, as a scene-file document (so that the editor can apply it
/// as one undoable step): the luminaires above the layout's rectangle removed (and any layout
/// that placed one of them), and a "layouts" entry (scene/LayoutGrid.h) of the chosen grid added;
/// every other thing as it was.
nlohmann::json applyLayout(const Scene& scene, const LayoutRequest& request,
                           const LayoutResult& result);

}  // namespace candela
