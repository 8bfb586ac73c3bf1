#pragma once
// Which passes and shader variants a scene needs. Derived from the scene alone (no GL), so tests
// can assert it: a luminaire kind that is absent compiles nothing, shadow tracing runs only for
// luminaires that an occluder can block from what the camera sees, the glossy variant only when
// a glossy material exists.

#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "luminaires/Registry.h"
#include "renderer/ShaderLibrary.h"
#include "scene/Scene.h"

namespace candela {

/// What the shading passes compute per pixel (see RenderSettings::quantity).
enum class Quantity { Radiance = 0, Illuminance = 1 };

struct ShadeStep {
    /// What it shades: a luminaire or the environment (an entry of Scene::sources()).
    /// The plan keeps the pointer: read the fields below instead where the scene may be gone.
    const Luminaire* source = nullptr;
    bool atInfinity = false;                   ///< The source is at infinity (the environment).
    const TechniqueInfo* technique = nullptr;  ///< Its kind is the source's.
    ProgramKey program;                        ///< Shader file and variant defines.
    bool shadows = false;                      ///< An occluder may block the source.
    bool shadowMaps = false;                   ///< ... and the technique reads shadow maps for it
                                               ///< (else it traces a shadow ray per sample).
    bool progressive = false;                  ///< Needs more than one frame to converge.
    std::string name;  ///< "shade:Panel:analytic", "shade:environment:balanced"
    /// Multiplies what the step writes: 683 lm/W for a radiometric source in a mixed scene
    /// and its maintenance factor (Scene::lightScale), else 1.
    float unitScale = 1.f;
    /// What its kind's GPU pass runs before shading it in a pass (the environment's "env:cdf",
    /// "env:samples"), as the frame statistics name them (renderer/passes/SourcePass.h).
    std::vector<std::string> prepasses;
};

struct FramePlan {
    std::vector<ShadeStep> shading;  ///< One step per source, in Scene::sources() order.
    bool needsBvh = false;           ///< Some step traces shadow rays: build and upload the BVH.
    bool glossy = false;
    bool progressive() const;
    /// Pass names in execution order for the first frame: the G-buffer, then per step its
    /// prepasses, its shadow maps and its shading, then resolve and tone mapping (shadow maps are
    /// rendered again only when their source or the geometry changes).
    std::vector<std::string> passNames() const;
    /// The step that shades `source`; null when it has none.
    const ShadeStep* stepOf(const Luminaire* source) const;
    /// The first step shading a source of `kind`; null when none.
    const ShadeStep* stepOfKind(LuminaireKind kind) const;
};

/// "shadow:NAME": the pass that renders the shadow maps of a step's luminaire.
std::string shadowPassName(const ShadeStep& step);

/// The first name of a comma-separated techniqueOverride that source kind `kind` has; empty when
/// none. An item "KIND=NAME" applies to that kind only ("environment=NAME" to the environment),
/// so a list can give two kinds different techniques that both have
/// ("lambertian-rect=reference,photometric=hybrid").
std::string overrideFor(const std::string& techniqueOverride, LuminaireKind kind);

/// Checks a techniqueOverride list: every item names a technique of some source kind, and every
/// "KIND=NAME" a kind ("environment" included) that has NAME. Throws InputError naming the item
/// otherwise (a typo would silently leave luminaires their own).
void checkTechniqueList(const std::string& techniqueOverride);

/// World to clip transform of the camera for an image of the given aspect (width / height).
glm::mat4 cameraViewProj(const Camera& camera, double aspect);

/// techniqueOverride: technique names separated by commas ("analytic,precomputed-global,point");
/// each source uses the first its kind has (its own technique when none). In illuminance mode
/// every receiver is white Lambertian: no GLOSSY variant whatever the materials. Throws
/// InputError if a source names a technique its kind does not have or one without a GPU pass.
FramePlan planFrame(const Scene& scene, const glm::mat4& viewProj,
                    const std::string& techniqueOverride = {},
                    Quantity quantity = Quantity::Radiance);

}  // namespace candela
