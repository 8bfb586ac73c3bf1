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
#include <optional>
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

/// A window, door or skylight of a room, as written (m).
struct RoomOpening {
    std::string type;  ///< "window", "door" or "skylight".
    std::string name;  ///< May be empty.
    size_t wall = 0;   ///< Window or door: its wall, from 0 (the file's wall N is N - 1).
    double offset = 0.0, width = 0.0;   ///< Along the wall from its first corner, m.
    double sill = 0.0, height = 0.0;    ///< Above the floor, m.
    glm::dvec2 center{0.0}, size{0.0};  ///< Skylight: its middle and size (x, z), m.
};

/// A {"room": ...} entry as read: the meshes are built from it, and the report's room data and
/// plan read it back from the geometry entry the scene keeps as written (roomSpec).
struct RoomSpec {
    std::string name;
    std::vector<glm::dvec2> floor;  ///< Corners (x, z), m, as written.
    double height = 0.0;            ///< Floor to ceiling, m.
    double elevation = 0.0;         ///< The floor's y, m.
    glm::dvec3 floorReflectance{kDefaultFloorReflectance};
    glm::dvec3 ceilingReflectance{kDefaultCeilingReflectance};
    std::vector<glm::dvec3> wallReflectances;  ///< One per wall (wall N from corner N).
    std::vector<RoomOpening> openings;
    /// The floor's area by the shoelace formula, m2.
    double area() const;
    /// Wall `i`'s length, m.
    double wallLength(size_t i) const;
};

/// A {"furniture": ...} entry as read.
struct FurnitureSpec {
    std::string type, name;
    glm::dvec3 position{0.0};  ///< The middle of its footprint at floor level, m.
    double rotateYDeg = 0.0;
    glm::dvec3 size{0.0};  ///< Width (x), height (y), depth (z) before the turn, m.
    glm::dvec3 reflectance{0.5};
    /// The footprint's corners (x, z), m, turned as placed.
    std::vector<glm::dvec2> footprint() const;
};

/// Reads a {"room": ...} entry; InputError naming the field for anything it cannot build (a
/// crossing outline, an opening off its wall).
RoomSpec readRoom(const nlohmann::json& item, const json::Where& where);
/// Reads a {"furniture": ...} entry (`index`: its place in the geometry list, for its default
/// name).
FurnitureSpec readFurniture(const nlohmann::json& item, const json::Where& where, size_t index);

/// The room a scene's geometry entry holds (read back from the entry as written); empty for
/// another kind of entry. `index`: its place in scene.geometry.
std::optional<RoomSpec> roomSpec(const Scene& scene, size_t index);
/// The furniture a scene's geometry entry holds, likewise.
std::optional<FurnitureSpec> furnitureSpec(const Scene& scene, size_t index);

/// Appends the meshes and materials of a {"room": ...} entry to `scene` (readRoom's checks).
void parseRoom(const nlohmann::json& item, const json::Where& where, Scene& scene);
/// Appends the mesh and material of a {"furniture": ...} entry.
void parseFurniture(const nlohmann::json& item, const json::Where& where, size_t index,
                    Scene& scene);

}  // namespace candela
