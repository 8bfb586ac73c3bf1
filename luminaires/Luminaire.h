#pragma once
// A luminaire is a model and its placement (docs/architecture.md, "Models and placements"). The
// model (LuminaireModel) is what every kind implements: emitted radiance, power in closed form, a
// light sampler with its pdf, its outline; built once, immutable, shared. A placement (Luminaire)
// is a model at a pose, with a name, a technique and a maintenance factor. What a kind does besides
// its physics is its adapter (luminaires/Adapter.h).

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
    /// World point p in the frame's coordinates (origin at position), metres.
    glm::dvec3 toLocal(const glm::dvec3& p) const;
    /// A direction in the frame's coordinates to world.
    glm::dvec3 toWorldDir(const glm::dvec3& v) const;
    bool operator==(const Pose&) const = default;
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

/// What a luminaire's body (luminaires/Adapter.h) gives the scene.
struct LuminaireBody {
    /// World-space triangles, three points (metres) each; empty for none.
    std::vector<glm::dvec3> triangles;
    /// Seen by the camera: an L3D housing is; the luminous box of a photometry is not (the camera
    /// sees the opening's light, which the box only stands in for).
    bool drawn = true;
    /// Diffuse reflectance of its surface (black unless the scene entry says otherwise).
    double reflectance = 0.0;
};

/// The kinds of light source. Scene files name them by kindName(); code compares the enum.
enum class LuminaireKind : unsigned char { LambertianRect, LightField, Photometric, Environment };

/// What a luminaire emits, apart from where it is placed: built once from its parameters (a file,
/// sizes, a dimming), immutable afterwards and shared by every placement of it (Luminaire). Its
/// interface is the physics, evaluated at the pose a placement gives; what a kind packs for the
/// GPU, writes to a scene file or shows a user lives in its adapter (luminaires/Adapter.h).
class LuminaireModel {
  public:
    explicit LuminaireModel(LuminaireKind kind) : mKind(kind) {}
    virtual ~LuminaireModel() = default;

    LuminaireKind kind() const { return mKind; }
    /// Radiance leaving emitter point x in unit direction w (away from the luminaire),
    /// W/(m2 sr), RGB, placed at `pose`. Zero off the emitter and on its back side.
    virtual glm::dvec3 radiance(const Pose& pose, const glm::dvec3& x,
                                const glm::dvec3& w) const = 0;
    /// Total emitted power in closed form (or exact quadrature), W per channel (lm for a
    /// photometric source, quantities()).
    virtual glm::dvec3 power() const = 0;
    /// The unit system of its numbers: radiometric (W, W/(m2 sr)) or photometric (lm, cd/m2).
    virtual Quantities quantities() const = 0;
    /// Samples a point on the emitter placed at `pose` as seen from receiver p; u in [0,1)^2.
    virtual LightSample sample(const Pose& pose, const glm::dvec3& p,
                               const glm::dvec2& u) const = 0;
    /// Solid-angle pdf of sample() at p for the unit direction wi.
    virtual double pdf(const Pose& pose, const glm::dvec3& p, const glm::dvec3& wi) const = 0;
    /// World-space outline of the emitting surface placed at `pose` (for drawing, picking and
    /// occlusion analysis); empty for a source without a surface.
    virtual std::vector<glm::dvec3> outline(const Pose& pose) const = 0;
    /// Where its emitting surface is for a placement at `pose`: the pose itself, except for a
    /// model whose geometry places the opening away from its insertion point (a GLDF variant's
    /// L3D light-emitting object).
    virtual Pose emitterPose(const Pose& pose) const { return pose; }

  protected:
    LuminaireModel(const LuminaireModel&) = default;
    LuminaireModel& operator=(const LuminaireModel&) = default;

  private:
    LuminaireKind mKind;
};

/// A luminaire placed in a scene: a shared, immutable model and where it is (pose), what it is
/// called, how it is rendered and its maintenance factor. Copying one shares the model; an edit
/// of the model's parameters builds a new model (setModel). Its methods are the model's physics
/// at its pose.
class Luminaire {
  public:
    explicit Luminaire(std::shared_ptr<const LuminaireModel> model);

    const LuminaireModel& model() const { return *mModel; }
    const std::shared_ptr<const LuminaireModel>& sharedModel() const { return mModel; }
    void setModel(std::shared_ptr<const LuminaireModel> model);
    std::unique_ptr<Luminaire> clone() const { return std::make_unique<Luminaire>(*this); }

    LuminaireKind kind() const { return mModel->kind(); }
    glm::dvec3 radiance(const glm::dvec3& x, const glm::dvec3& w) const {
        return mModel->radiance(pose, x, w);
    }
    glm::dvec3 power() const { return mModel->power(); }
    Quantities quantities() const { return mModel->quantities(); }
    LightSample sample(const glm::dvec3& p, const glm::dvec2& u) const {
        return mModel->sample(pose, p, u);
    }
    double pdf(const glm::dvec3& p, const glm::dvec3& wi) const { return mModel->pdf(pose, p, wi); }
    std::vector<glm::dvec3> outline() const { return mModel->outline(pose); }
    Pose emitterPose() const { return mModel->emitterPose(pose); }
    /// A source at infinity (the environment): light arrives from directions, not from points;
    /// it has no outline, no pose and no finite flux.
    bool atInfinity() const { return kind() == LuminaireKind::Environment; }

    Pose pose;  ///< Where it is placed (the insertion point, for a luminaire with geometry).
    std::string name;
    std::string technique;  ///< A technique registered for kind() (luminaires/Registry.h).
    /// Its own maintenance factor (EN 12464-1: maintained over initial output, in (0, 1]);
    /// unset: the scene's (Scene::maintenanceFactor).
    std::optional<double> maintenanceFactor;

  private:
    std::shared_ptr<const LuminaireModel> mModel;
};

/// The kind's name in scene files ("lambertian-rect").
std::string_view kindName(LuminaireKind kind);
/// The kind a scene file's name means; false if none.
bool kindNamed(std::string_view name, LuminaireKind& kind);

}  // namespace candela
