#pragma once
// The table of luminaire kinds and of the techniques that render them. Adding a technique means
// writing its files (a CPU estimator for `candela probe` and tests, a GLSL variant for the
// renderer) and adding one line to the table in Registry.cpp; nothing in the core changes.

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "luminaires/Luminaire.h"
#include "util/JsonRead.h"

namespace candela {

/// Answers whether the segment between two points is free of occluders.
class Visibility {
public:
    virtual ~Visibility() = default;
    virtual bool visible(const glm::dvec3& from, const glm::dvec3& to) const = 0;
    /// Is the ray from `from` along the unit `dir` free of occluders out to infinity (a distant
    /// light)? Implementations bias only its start.
    virtual bool visibleToward(const glm::dvec3& from, const glm::dvec3& dir) const = 0;
};

struct EstimateOptions {
    int spp = 4096;                          ///< Samples per point for stochastic techniques.
    uint64_t seed = 1;                       ///< Fixed seed: results are reproducible.
    const Visibility* visibility = nullptr;  ///< null: no shadowing.
};

struct Estimate {
    glm::dvec3 irradiance{0.0};  ///< W/m2 per channel (lux for photometric data).
    glm::dvec3 stdError{0.0};    ///< Standard error of the estimate; 0 for exact techniques.
};

/// CPU double-precision irradiance at p for the unit normal n.
using IrradianceFn = Estimate (*)(const Luminaire& luminaire, const glm::dvec3& p,
                                  const glm::dvec3& n, const EstimateOptions& options);

struct TechniqueInfo {
    std::string_view kind;         ///< Luminaire kind it renders.
    std::string_view name;         ///< As in scene files and --technique.
    std::string_view description;  ///< One line for the editor and `candela info`.
    bool progressive;              ///< Stochastic: refines over frames. Else exact in one frame.
    IrradianceFn irradiance;       ///< CPU estimator (probe, tests, parity).
    std::string_view shader;       ///< Fragment shader in shaders/ that shades with it.
    std::string_view define;       ///< Variant #define selecting this technique in that shader.
    /// Where an occluder can block the luminaire: true reads shadow maps (SHADOW_MAPS, rendered
    /// from Luminaire::shadowLights()), false traces a ray per sample through the BVH (SHADOWS).
    bool shadowMaps = false;
};

/// Builds a luminaire from its scene-file entry (kind-specific fields; pose is read by the caller).
using LuminaireParser = std::unique_ptr<Luminaire> (*)(const nlohmann::json& entry,
                                                       const json::Where& where);
/// A luminaire of this kind with default parameters (the editor's "Add").
using LuminaireFactory = std::unique_ptr<Luminaire> (*)();

struct LuminaireKindInfo {
    std::string_view kind;
    std::string_view description;
    LuminaireParser parse;
    LuminaireFactory create;
    std::string_view defaultTechnique;
    /// The editor's fallback while the user drags (renderer/LivePreview.h): cheap per sample and
    /// close at one sample per pixel.
    std::string_view previewTechnique;
};

std::span<const LuminaireKindInfo> luminaireKinds();
std::span<const TechniqueInfo> techniques();
const LuminaireKindInfo* findKind(std::string_view kind);
const TechniqueInfo* findTechnique(std::string_view kind, std::string_view name);
/// Comma-separated technique names of a kind, for error messages and help.
std::string techniqueNames(std::string_view kind);

}  // namespace candela
