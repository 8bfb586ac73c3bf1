#pragma once
// Reading and writing Candela scene files (JSON). The format:
//
//   { "geometry":   [ {"gltf": "room.gltf",
//                      "transform": {"translate": [0,0,0], "rotate_y_deg": 0, "scale": 1}},
//                     {"plane": {"center": [0,0,0], "normal": [0,1,0], "size": [10,10]},
//                      "albedo": [0.5,0.5,0.5]},
//                     {"box": {"center": [0,0.4,0], "size": [1.2,0.8,0.6], "rotate_y_deg": 0},
//                      "albedo": [0.6,0.5,0.4], "specular": [0,0,0], "roughness": 1} ],
//     "luminaires": [ {"type": "lambertian-rect", "name": "Panel", "position": [0,2,0],
//                      "aim": [0,-1,0], "c0": [1,0,0], "technique": "analytic", ...} ],
//     "environment": null,
//     "camera": {"position": [0,1.5,4], "target": [0,1,0], "fov_deg": 45,
//                "exposure": 0.6} }   (exposure optional: the tone mapper's k)
//
// World is Y-up, lengths in metres, angles in degrees. Relative glTF paths resolve against the
// scene file's folder. Unknown keys, non-finite or out-of-range values are errors (InputError)
// that name the file and the field.
//
// Planes and boxes may carry "name" (mesh and material name) and the material fields "albedo"
// and "specular" (linear RGB, each in [0, 1]) and "roughness" (in [0, 1]).
//
// Plane tangent convention: size[0] runs along u = normalize(Y x normal) (horizontal for walls),
// or along +X when the normal is within about 0.06 degrees of vertical; size[1] runs along
// v = normal x u (upwards for walls). A plane is one quad (two triangles) whose stored normal is
// the given one; the rasteriser draws it from both sides.

#include <glm/glm.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "luminaires/Luminaire.h"
#include "scene/Scene.h"
#include "util/JsonRead.h"

namespace candela {

/// The most entries each of a scene file's lists may hold, and the most triangles its geometry
/// and luminaire bodies may make together: counted before the entries are read (the triangles as
/// each entry is), so that a small file cannot ask for unbounded memory or time. docs/limits.md
/// gives the reason for each; tests pass smaller ones.
struct SceneLimits {
    size_t geometryEntries = 100000;
    size_t luminaires = 100000;  ///< After a GLDF's emitters are counted.
    size_t taskAreas = 10000;
    size_t calculationPoints = 1000000;
    size_t glareObservers = 10000;
    size_t triangles = 20000000;
};

/// Reads a scene file (.json). Throws InputError naming the file (and line and column for
/// invalid JSON, the field for invalid values).
Scene loadScene(const std::string& path);
/// Builds a scene from a parsed document; `path` names it in errors and anchors relative paths.
Scene parseScene(const nlohmann::json& doc, const std::string& path,
                 const SceneLimits& limits = {});
/// The scene file document: geometry entries as written, luminaires, environment, camera.
nlohmann::json sceneToJson(const Scene& scene);
/// Writes the scene atomically: a temporary file in the target folder, flushed and fsync'ed, then
/// renamed over `path`. On failure throws InputError and leaves any existing file untouched.
/// Relative glTF paths are rewritten so they still point at the same files from the new folder.
void saveScene(const Scene& scene, const std::string& path);

/// Builds a luminaire from a scene-file entry: the common fields (type, name, position, aim, c0,
/// technique) here, the kind-specific ones by the registry's parser. `index` makes the default
/// name "<type> <index>".
std::unique_ptr<Luminaire> parseLuminaire(const nlohmann::json& entry, const json::Where& where,
                                          size_t index = 0);
/// The scene-file entry of a luminaire (common fields plus its kind's, writeJson in
/// luminaires/Adapter.h).
nlohmann::json luminaireToJson(const Luminaire& luminaire);

/// Adds a plane (see the tangent convention above) as a new geometry entry with its source JSON.
/// Size in metres along u and v. Returns the index of the new GeometryItem. Throws InputError
/// for invalid values (non-positive size, zero normal, material out of range).
size_t addPlane(Scene& scene, const glm::dvec3& center, const glm::dvec3& normal,
                const glm::dvec2& size, const Material& material);
/// Adds a box centred on `center` with edge lengths `size` (metres), turned by rotateYDeg degrees
/// about +Y, as a new geometry entry. Returns the index of the new GeometryItem.
size_t addBox(Scene& scene, const glm::dvec3& center, const glm::dvec3& size, double rotateYDeg,
              const Material& material);

}  // namespace candela
