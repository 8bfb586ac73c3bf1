#pragma once
// The scene file's rooms and furniture (docs/scene-files.md, "Rooms and furniture"):
//
//   {"room": {"name": "Classroom", "floor": [[-5,-4],[5,-4],[5,4],[-5,4]], "height": 3,
//             "elevation": 0,
//             "reflectance": {"floor": 0.2, "walls": 0.5, "ceiling": 0.7, "wall 2": 0.8},
//             "openings": [{"type": "window", "wall": 1, "offset": 1, "width": 2,
//                           "sill": 0.9, "height": 1.5, "glazing": 0.7},
//                          {"type": "door", "wall": 3, "offset": 0.5, "width": 1,
//                           "height": 2.1},
//                          {"type": "skylight", "center": [0, 0], "size": [1.2, 1.2]}]}}
//   {"furniture": {"type": "desk", "position": [0, 0, 0], "rotate_y_deg": 90,
//                  "size": [1.6, 0.75, 0.8], "reflectance": 0.5, "name": "Teacher's desk"}}
//
// A room is its floor polygon ([x, z] corners in metres, any simple polygon, either direction)
// raised to `height`: a floor, a ceiling and one wall per edge (wall N runs from corner N to
// corner N + 1), all facing in, one mesh each ("Classroom: wall 2"). Openings are holes: light
// leaves through them. Furniture is built from boxes, standing on `position` (the middle of its
// footprint at floor level), its width along x and depth along z before `rotate_y_deg`.

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene/Scene.h"
#include "util/JsonRead.h"

namespace candela {

/// The most corners a room's floor and the most openings a room may have: a room's tessellation
/// grows with their product, and no building plan needs more.
constexpr size_t kMaxRoomCorners = 1000, kMaxRoomOpenings = 1000;
/// The most a room's corners times (its skylights + 1) may be: the ceiling is cut into up to
/// that many strips, each of which looks at every edge (at the limit, about 0.1 s).
constexpr size_t kMaxCornersTimesSkylights = 100000;

/// EN 12464-1's usual reflectances, taken when a room gives none.
constexpr double kDefaultFloorReflectance = 0.2, kDefaultWallReflectance = 0.5,
                 kDefaultCeilingReflectance = 0.7;

/// One piece of the built-in furniture.
struct FurnitureType {
    const char* name;    ///< "desk", as the scene file writes it.
    const char* label;   ///< "Desk", as the editor shows it.
    glm::dvec3 size;     ///< Width (x), height (y), depth (z) by default, m.
    double reflectance;  ///< By default.
};
const std::vector<FurnitureType>& furnitureTypes();

/// Appends the meshes and materials of a {"room": ...} entry to `scene`; InputError naming the
/// field for anything it cannot build (a crossing outline, an opening off its wall).
void parseRoom(const nlohmann::json& item, const json::Where& where, Scene& scene);
/// Appends the mesh and material of a {"furniture": ...} entry.
void parseFurniture(const nlohmann::json& item, const json::Where& where, size_t index,
                    Scene& scene);

}  // namespace candela
