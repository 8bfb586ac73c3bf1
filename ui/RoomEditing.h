#pragma once
// Rooms, openings and furniture in the editor: File > New's room dialog and the Add menu fill a
// RoomDraft, which becomes the scene file's entries (scene/RoomIo.h) and is built by the same
// parser as a scene file, so that a room made in the editor and one written by hand are the same
// room. Geometry entries are edited as their scene-file JSON (the inspector) and every change
// rebuilds the scene's geometry from its entries, as one undo step.

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "scene/RoomIo.h"
#include "scene/Scene.h"

namespace candela::ui {

struct EditorState;

enum class RoomShape { Rectangle, LShape, Polygon };

/// A window or door on a wall (by offset along it from its first corner, width, sill and height,
/// m), or a skylight in the ceiling (centre [x, z] and size, m).
struct OpeningDraft {
    std::string type = "window";  ///< "window", "door" or "skylight".
    int wall = 1;                 ///< Wall N runs from corner N to corner N + 1 (1-based).
    double offset = 1.0, width = 1.5, sill = 0.9, height = 1.5;
    double glazing = 0.7;  ///< Windows: the glass's transmittance (kept for daylight).
    glm::dvec2 center{0.0}, size{1.2, 1.2};
};

/// A piece of the built-in furniture (furnitureTypes()) standing at [x, z] on the floor.
struct FurnitureDraft {
    std::string type = "desk";
    glm::dvec2 position{0.0};
    double rotateYDeg = 0.0;
};

/// What the room dialog edits. The rectangle and the L are centred on the origin: width along x,
/// depth along z; the L loses the corner at +x, +z (notchWidth x notchDepth).
struct RoomDraft {
    std::string name = "Room";
    RoomShape shape = RoomShape::Rectangle;
    double width = 10.0, depth = 8.0;
    double notchWidth = 4.0, notchDepth = 3.0;
    /// RoomShape::Polygon: "x z, x z, ..." in metres (commas or semicolons between corners).
    std::string polygon = "0 0, 6 0, 6 4, 3 7, 0 4";
    double height = 3.0;
    double floorReflectance = kDefaultFloorReflectance;
    double wallReflectance = kDefaultWallReflectance;
    double ceilingReflectance = kDefaultCeilingReflectance;
    std::vector<OpeningDraft> openings;
    std::vector<FurnitureDraft> furniture;
    /// A task area on the work plane over the floor (the rectangle, the L's full-width part;
    /// none for a drawn polygon), less a band along the walls, with its requirement.
    bool taskArea = true;
    double workPlane = 0.75, wallBand = 0.0, requiredEm = 500.0, requiredU0 = 0.6;
    double maintenanceFactor = 0.8;  ///< New scenes only.
    ProjectInfo project;             ///< New scenes only.
};

/// The floor's corners ([x, z], m) the draft describes. InputError saying what is wrong with a
/// typed polygon ("corner 3: two numbers, x and z") or a size that is not positive.
std::vector<glm::dvec2> floorOutline(const RoomDraft& draft);
/// The {"room": ...} geometry entry.
nlohmann::json roomEntry(const RoomDraft& draft);
/// One {"furniture": ...} entry per piece.
std::vector<nlohmann::json> furnitureEntries(const RoomDraft& draft);
/// The draft's task area as a scene-file entry; null when it has none.
nlohmann::json taskAreaEntry(const RoomDraft& draft);
/// A whole scene file of the room: the project block, the room and its furniture, the task area,
/// the maintenance factor, and a camera in a corner at eye height looking across the room.
nlohmann::json newSceneDocument(const RoomDraft& draft);
/// The room in a line ("80.0 m² floor, 4 walls, 3.00 m high, 240 m³; 3 openings"), or what is
/// wrong with it (the scene parser's message), for the dialog to show as the user types.
std::string roomDraftSummary(const RoomDraft& draft, bool& valid);

/// File > New: the draft becomes the editor's scene (untitled until saved). Unsaved edits of the
/// scene it replaces go to the autosave first, as when opening a file. False, with the error
/// reported, when the draft cannot be built.
bool newSceneFromRoom(EditorState& state, const RoomDraft& draft);
/// Adds the draft's room, its furniture and its task area to the scene as one undo step.
bool addRoom(EditorState& state, const RoomDraft& draft);
/// Adds a piece of furniture (a furnitureTypes() name) standing at `at` ([x, z], m, on the floor
/// at `floorY`), as one undo step; selects it. Returns its geometry index or -1.
int addFurniture(EditorState& state, const std::string& type, glm::dvec2 at, double floorY);
/// Adds an opening to the room entry `geometryIndex`, as one undo step.
bool addOpening(EditorState& state, int geometryIndex, const OpeningDraft& opening);
/// Replaces geometry entry `index` by `entry` (its edited scene-file JSON) as one undo step named
/// `label`, rebuilding the scene's geometry from its entries. A value the parser refuses changes
/// nothing and is reported in state.inspectorError. Returns whether it changed the scene.
bool replaceGeometryEntry(EditorState& state, int index, const nlohmann::json& entry,
                          const std::string& label);
/// Removes geometry entry `index` as one undo step.
bool removeGeometryEntry(EditorState& state, int index);

/// The floor under a point: the elevation of the scene-file room whose outline holds [x, z]
/// (nothing when no room does).
std::optional<double> roomFloorAt(const Scene& scene, glm::dvec2 xz);

/// The floor under a point of the scene: the room's (roomFloorAt) where a room holds it, else the
/// first surface straight below (luminaire bodies left out); nothing when there is none.
std::optional<double> floorBelow(EditorState& state, const glm::dvec3& point);
/// The distance from `point` along the unit `dir` to the first surface of the scene (walls,
/// partitions; luminaire bodies left out), m; nothing when the ray leaves the scene.
std::optional<double> clearDistance(EditorState& state, const glm::dvec3& point,
                                    const glm::dvec3& dir);

}  // namespace candela::ui
