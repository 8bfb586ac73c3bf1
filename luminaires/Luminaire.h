#pragma once
// The interface every luminaire kind implements (pbrt's "specified object" idea): emitted
// radiance, power in closed form, a light sampler with its pdf, and the data its GPU passes read.
// No GL here: renderer/ uploads what gpuData() packs.

#include <cstddef>
#include <glm/glm.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "luminaires/GpuTable.h"
#include "luminaires/Units.h"

namespace candela {

/// Placement of a luminaire: local +z is `aim`, local +x is `c0` made orthogonal to aim,
/// local +y is aim x c0. Position in metres, world Y-up.
struct Pose {
    glm::dvec3 position{0.0, 2.0, 0.0};
    glm::dvec3 aim{0.0, -1.0, 0.0};  ///< Main emission axis; need not be normalised.
    glm::dvec3 c0{1.0, 0.0, 0.0};    ///< Reference horizontal axis; need not be orthogonal to aim.

    /// Orthonormal frame (x = c0', y = aim x c0', z = aim'). Falls back to a stable perpendicular
    /// when c0 is parallel to aim, so it never produces NaN.
    void frame(glm::dvec3& x, glm::dvec3& y, glm::dvec3& z) const;
};

/// One light sample as seen from a receiver point p.
struct LightSample {
    glm::dvec3 position{0.0};  ///< Point on the emitter, metres.
    glm::dvec3 wi{0.0};        ///< Unit direction from p to the point.
    double distance = 0.0;     ///< From p to the point, metres.
    glm::dvec3 radiance{0.0};  ///< Radiance leaving the emitter towards p, W/(m2 sr) (RGB).
    double pdf = 0.0;          ///< Solid-angle density at p, 1/sr; 0 means "no sample".
};

/// Where a luminaire's shadow maps are rendered from and how its shading combines them
/// (renderer/passes/ShadowMapPass.h). Shading splits the luminaire into items (a light field's
/// images; the whole opening of a photometric light) and gives item i the visibility
/// sum_j weight_j * V(map_j), over its sharesPerItem shares (weights summing to one).
struct ShadowLights {
    std::vector<glm::dvec3> lights;  ///< World position of each map's light, metres.
    std::vector<char> lit;           ///< Per map: 0 when no item uses it (not rendered).
    int sharesPerItem = 0;
    struct Share {
        int map = 0;
        float weight = 0.f;  ///< 0 for padding.
        bool operator==(const Share&) const = default;
    };
    std::vector<Share> shares;  ///< items x sharesPerItem.
    bool operator==(const ShadowLights&) const = default;
};

/// What Luminaire::body() gives the scene.
struct LuminaireBody {
    /// World-space triangles, three points (metres) each; empty for none.
    std::vector<glm::dvec3> triangles;
    /// Seen by the camera: an L3D housing is; the luminous box of a photometry is not (the camera
    /// sees the opening's light, which the box only stands in for).
    bool drawn = true;
    /// Diffuse reflectance of its surface (black unless the scene entry says otherwise).
    double reflectance = 0.0;
};

class Luminaire {
  public:
    virtual ~Luminaire() = default;

    /// Kind name as in scene files ("lambertian-rect").
    virtual std::string_view kind() const = 0;
    virtual std::unique_ptr<Luminaire> clone() const = 0;

    /// Radiance leaving emitter point x in unit direction w (away from the luminaire),
    /// W/(m2 sr), RGB. Zero off the emitter and on its back side.
    virtual glm::dvec3 radiance(const glm::dvec3& x, const glm::dvec3& w) const = 0;
    /// Total emitted power in closed form (or exact quadrature), W per channel (lm for a
    /// photometric source, quantities()).
    virtual glm::dvec3 power() const = 0;
    /// The unit system of its numbers: radiometric (W, W/(m2 sr)) or photometric (lm, cd/m2).
    virtual Quantities quantities() const = 0;
    /// Samples a point on the emitter as seen from receiver p; u in [0,1)^2.
    virtual LightSample sample(const glm::dvec3& p, const glm::dvec2& u) const = 0;
    /// Solid-angle pdf of sample() at p for the unit direction wi.
    virtual double pdf(const glm::dvec3& p, const glm::dvec3& wi) const = 0;

    /// World-space outline of the emitting surface (for drawing, picking and occlusion analysis).
    virtual std::vector<glm::dvec3> outline() const = 0;
    /// Kind-specific fields written into the scene file entry (pose, name, technique are common).
    virtual void writeJson(nlohmann::json& out) const = 0;
    /// Packed std430 record for this kind's GPU passes (layout in shaders/shared/).
    virtual std::vector<std::byte> gpuData() const = 0;
    /// The tables its shaders read from textures (luminaires/GpuTable.h), made once per model and
    /// shared: the same object comes back until the model changes. Null: none.
    virtual std::shared_ptr<const GpuTables> gpuTables() const { return nullptr; }
    /// Radiance the viewport shows on the emitting surface, W/(m2 sr): by default what leaves its
    /// centre along the aim (exact for Lambertian emitters).
    virtual glm::dvec3 displayRadiance() const {
        glm::dvec3 x, y, z;
        pose.frame(x, y, z);
        return radiance(pose.position, z);
    }
    /// One line for `candela info` and the editor.
    virtual std::string describe() const = 0;
    /// The files its data was read from (a photometric file and its TILT file, a light field's
    /// manifest and images), so commands never write onto them; empty for kinds made of numbers.
    virtual std::vector<std::string> sourceFiles() const { return {}; }
    /// The shadow maps this luminaire's shading reads for about `count` maps (0: the kind's
    /// natural count); empty (no lights) for a kind that traces shadow rays instead.
    virtual ShadowLights shadowLights(int count) const {
        (void)count;
        return {};
    }
    /// A source at infinity (the environment): light arrives from directions, not from points;
    /// it has no outline, no pose and no finite flux.
    virtual bool atInfinity() const { return false; }
    /// Where its emitting surface is: the pose, except for a luminaire whose geometry places the
    /// opening away from its insertion point (a GLDF variant's L3D light-emitting object).
    virtual Pose emitterPose() const { return pose; }
    /// The luminaire's body: its housing from L3D geometry, or the photometry's luminous box.
    /// Scene::updateBodies makes it a mesh that blocks every other light and the interreflected
    /// light, except light leaving a point inside its own bounds (the photometry already holds
    /// what the housing does to its own light).
    virtual LuminaireBody body() const { return {}; }
    /// The other luminaires its scene entry makes (a GLDF variant placing several emitters: one
    /// luminaire per emitter, this one the first); the loader gives them this one's name, pose,
    /// technique and maintenance factor.
    virtual std::vector<std::unique_ptr<Luminaire>> companions() const { return {}; }

    Pose pose;  ///< Where it is placed (the insertion point, for a luminaire with geometry).
    std::string name;
    std::string technique;  ///< A technique registered for kind() (luminaires/Registry.h).
    /// Its own maintenance factor (EN 12464-1: maintained over initial output, in (0, 1]);
    /// unset: the scene's (Scene::maintenanceFactor).
    std::optional<double> maintenanceFactor;
};

}  // namespace candela
