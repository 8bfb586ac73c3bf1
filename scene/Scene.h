#pragma once
// The scene as Candela edits and renders it: world-space meshes with materials, luminaire
// instances, the camera. World is Y-up, lengths in metres.

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "luminaires/Luminaire.h"
#include "scene/Measurements.h"
#include "shaders/shared/Constants.h"

namespace candela {
class EnvironmentMap;
class EnvironmentSequence;
}  // namespace candela

namespace candela {

/// Surface material: a Lambertian base with an optional glossy (normalised modified Phong) lobe.
struct Material {
    std::string name;
    glm::vec3 albedo{0.5f};   ///< Diffuse reflectance, linear RGB in [0, 1].
    glm::vec3 specular{0.f};  ///< Glossy reflectance at normal incidence, linear RGB; 0 = no lobe.
    float roughness = 1.f;    ///< Perceptual roughness in [0, 1] (glTF convention).

    bool isGlossy() const { return specular.x + specular.y + specular.z > 0.f; }
    /// Phong exponent equivalent to the roughness (alpha = roughness^2, n = 2/alpha^2 - 2).
    float phongExponent() const;
};

/// How a mesh is shaped, which bounds what it can occlude (see scene/Occlusion.h).
enum class MeshShape {
    Plane,    ///< A single flat polygon: cannot shadow itself.
    Convex,   ///< A closed convex solid (procedural box): cannot shadow itself.
    General,  ///< Anything else (glTF meshes): may shadow itself.
};

/// Triangles in world space, one material.
struct Mesh {
    std::string name;
    std::vector<glm::vec3> positions;  ///< World space, metres.
    std::vector<glm::vec3> normals;    ///< World space, unit length, one per position.
    std::vector<uint32_t> indices;     ///< Three per triangle, counter-clockwise seen from outside.
    uint32_t material = 0;             ///< Index into Scene::materials.
    MeshShape shape = MeshShape::General;
    glm::vec3 boundsMin{0.f}, boundsMax{0.f};  ///< Axis-aligned bounds, metres.
    /// A luminaire's body (Scene::updateBodies): not part of any geometry entry, not saved, and
    /// no shadow on light leaving a point within kBodyMargin of its bounds.
    bool luminaireBody = false;
    /// Not drawn for the camera (a photometry's luminous box: it blocks other light and the
    /// interreflected light, but the camera sees the luminaire's opening through it).
    bool hidden = false;

    size_t triangleCount() const { return indices.size() / 3; }
    void computeBounds();
};

/// How far outside a body's bounds a light's emission point may be and still be the body's own
/// (metres): an opening lies on its body's surface, and shadow-map centres and rounding move it
/// by less than this. Shared with the shaders (shaders/shared/Constants.h).
constexpr double kBodyMargin = gpu::kBodyMargin;
/// Whether `point` (metres) is within kBodyMargin of a body's bounds: light leaving it is the
/// body's own and the body does not shadow it. The one rule every visibility path applies.
inline bool insideBody(const glm::dvec3& point, const glm::dvec3& lo, const glm::dvec3& hi) {
    return point.x >= lo.x - kBodyMargin && point.y >= lo.y - kBodyMargin &&
           point.z >= lo.z - kBodyMargin && point.x <= hi.x + kBodyMargin &&
           point.y <= hi.y + kBodyMargin && point.z <= hi.z + kBodyMargin;
}

/// One entry of the scene file's "geometry" list, kept as written so saving loses nothing.
struct GeometryItem {
    nlohmann::json source;         ///< The entry as read (paths as the user wrote them).
    std::vector<uint32_t> meshes;  ///< The meshes it produced, indices into Scene::meshes.
    /// The files it was read from: a glTF file and the buffers and images it names (empty for
    /// planes, discs and boxes).
    std::vector<std::string> files;
};

/// One entry of the scene file's "layouts" list: a regular grid of one luminaire over a task
/// area's room (scene/LayoutGrid.h), kept as written. Its luminaires are in Scene::luminaires;
/// saving writes the entry back while they are still as it placed them, and writes them one by
/// one once any of them has been moved, changed or removed.
struct LayoutItem {
    nlohmann::json source;               ///< The entry as read.
    std::vector<nlohmann::json> placed;  ///< Its luminaires' scene-file entries as placed.
};

/// The project a report is made for (the scene file's "project" block): plain text for the
/// report's cover and the editor's Project window; empty fields are left out.
struct ProjectInfo {
    std::string name, client, designer, date, description;
    bool empty() const {
        return name.empty() && client.empty() && designer.empty() && date.empty() &&
               description.empty();
    }
};

struct Camera {
    glm::dvec3 position{0.0, 1.5, 4.0};  ///< Metres.
    glm::dvec3 target{0.0, 1.0, 0.0};    ///< Metres.
    double fovDeg = 45.0;                ///< Vertical field of view, degrees.
    /// The tone mapper's k (shaders/tonemap.frag) the scene is best seen with; 0: not given (the
    /// renderer's default). `render --exposure` and the editor's slider override it.
    double exposure = 0.0;
};

struct Scene {
    std::string path;  ///< Scene file this came from; relative paths resolve against its folder.
    std::vector<GeometryItem> geometry;
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<std::unique_ptr<Luminaire>> luminaires;
    std::vector<LayoutItem> layouts;
    nlohmann::json environment;  ///< null: no environment map. Kept as written, for saving.
    /// The environment's radiance now (luminaires/environment/Environment.h); null when
    /// `environment` is.
    std::shared_ptr<const EnvironmentMap> environmentMap;
    /// Set only for {"sequence": ...}: the frames; environmentMap is its frame at t = 0.
    std::shared_ptr<EnvironmentSequence> environmentSequence;
    Camera camera;
    ProjectInfo project;
    /// The project's maintenance factor (EN 12464-1: maintained over initial output, in (0, 1]):
    /// that of every luminaire that sets none. Daylight (the environment) takes none.
    double maintenanceFactor = 1.0;
    /// EN 12464-1 calculation surfaces and points (calculation/CalculationSurfaces.h), evaluated by
    /// `candela surfaces`.
    std::vector<TaskArea> taskAreas;
    std::vector<CalcPoint> calcPoints;
    /// Where UGR is rated (calculation/Glare.h), by `candela glare`.
    std::vector<GlareObserver> glareObservers;

    Scene() = default;
    Scene(Scene&&) = default;
    Scene& operator=(Scene&&) = default;
    /// Deep copy (luminaires are cloned); used by undo and by the editor's render snapshot.
    Scene clone() const;
    /// Every file the scene was read from: the scene file, each geometry item's files, each
    /// luminaire's sourceFiles() and the environment's map or sequence frames. Commands protect
    /// them (util/FileOutput.h) so no output is written onto one.
    std::vector<std::string> inputFiles() const;

    /// Replaces the luminaires' body meshes (body, luminaires/Adapter.h: flat-shaded, a "luminaire
    /// housing" material of the body's reflectance, after every geometry entry's meshes; hidden
    /// when the camera sees through it) with their current shape and pose. Returns whether that
    /// changed the meshes (false when every body is as it was: an edit of another luminaire moves
    /// no geometry). `maxTriangles`: the most triangles the scene's meshes may make with the bodies
    /// (SceneLimits::triangles at load); beyond, InputError naming the scene and the luminaire
    /// that passed it, before its body is kept.
    bool updateBodies(size_t maxTriangles = SIZE_MAX);
    size_t bodyCount() const;
    /// Whether the scene has surfaces of its own (meshes other than luminaire bodies): a room
    /// to reflect light.
    bool hasSurfaces() const;

    glm::vec3 boundsMin() const;
    glm::vec3 boundsMax() const;
    bool hasGlossy() const;

    /// The unit system results are reported in: photometric (lx) when any source is, with a
    /// mixed scene's radiometric sources converted at 683 lm/W (luminaires/Units.h).
    UnitSystem units() const;
    /// Factor on a luminaire's (or the environment's) contribution in those units: 683 lm/W for
    /// a radiometric source in a mixed scene, else 1.
    double unitScale(const Luminaire& luminaire) const;
    /// The same in `units` (this scene's units(), taken once by a loop over many luminaires:
    /// units() itself looks at every luminaire).
    double unitScale(const Luminaire& luminaire, const UnitSystem& units) const;
    double environmentUnitScale() const;
    /// A source's maintenance factor: its own, else the scene's; 1 for a source at infinity.
    double maintenanceFactorOf(const Luminaire& source) const;
    /// Whether any luminaire's maintenance factor is below 1: results are maintained values.
    bool maintained() const;
    /// One line for every output that reports illuminance: "maintenance factor 1 (initial
    /// values)", or the project's factor and each luminaire's own ("maintained values: ...").
    std::string maintenanceNote() const;
    /// One line for every output that reports light: the luminaire bodies that block it ("6
    /// luminaire bodies (luminous boxes), opaque and black, block other luminaires' light and
    /// the reflected light"), or that there are none.
    std::string bodiesNote() const;
    /// Factor on everything a source contributes: unitScale x maintenanceFactorOf. Every
    /// estimator, pass and report scales a luminaire's light by it.
    double lightScale(const Luminaire& source) const;
    double lightScale(const Luminaire& source, const UnitSystem& units) const;

    /// The environment as a light source (luminaires/environment/EnvironmentLight.h), made from
    /// environmentMap and kept while the map stays the same (a new map is a new source); null
    /// without one. Not thread-safe: each thread renders its own copy of a scene.
    const Luminaire* environmentLight() const;
    /// Every light source the renderer and the estimators iterate over: the environment (when
    /// there is one), then the luminaires.
    std::vector<const Luminaire*> sources() const;

  private:
    mutable std::shared_ptr<const Luminaire> mEnvironmentLight;  ///< Made for the map it holds.
};

}  // namespace candela
