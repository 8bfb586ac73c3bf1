#pragma once
// Where a regular layout of luminaires goes (calculation/Layout.h chooses the grid; the scene
// file's "layouts" entries name one): over the room that holds a task area, a grid of columns
// along x and rows along z with half a spacing to the walls, less the points outside the room's
// outline.

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <vector>

#include "scene/Scene.h"
#include "util/JsonRead.h"

namespace candela {

/// The rectangle a layout spreads over and the room's floor.
struct LayoutFrame {
    glm::dvec2 lo{0.0}, hi{0.0};      ///< x and z, m.
    double floorY = 0.0;              ///< m.
    std::vector<glm::dvec2> outline;  ///< The room's outline (x, z); empty: the rectangle.
};

/// The frame of task area `area`: the scene-file room whose outline holds the area's middle, else
/// the scene's bounds when it has surfaces (a room written as planes), else the area itself.
LayoutFrame layoutFrame(const Scene& scene, const TaskArea& area);

/// The luminaires' positions (m, each rounded to a millimetre as a designer would place them) of
/// a grid of `columns` x `rows` at `mountingHeight` above the frame's floor.
std::vector<glm::dvec3> layoutPositions(const LayoutFrame& frame, int columns, int rows,
                                        double mountingHeight);

/// The luminaire entries a scene file's layout places (its "luminaire" with a position and the
/// name "<name> N" each), checked like every field:
///
///   {"name": "Pendants", "area": "Classroom", "grid": [5, 3], "height": 2.4,
///    "luminaire": {"type": "photometric", "file": "../luminaires/lamp.ldt"}}
///
/// `area` names one of `scene`'s task areas (it may be left out when there is one), `grid` is
/// columns along x and rows along z, `height` the mounting height above the room's floor (m).
/// At most `maxLuminaires` grid points.
std::vector<nlohmann::json> parseLayout(const nlohmann::json& item, const json::Where& where,
                                        const Scene& scene, size_t maxLuminaires);

}  // namespace candela
