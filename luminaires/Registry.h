#pragma once
// The table of light-source kinds and of the techniques that render them. Adding a technique
// means writing its files (a CPU estimator for `candela probe` and tests, its shader
// shaders/KIND_TECHNIQUE.frag) and adding one line to the table in Registry.cpp, with what it
// promises at the extremes; nothing in the core or the tests changes.

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "luminaires/Adapter.h"
#include "luminaires/Estimate.h"
#include "luminaires/Luminaire.h"
#include "util/JsonRead.h"

namespace candela {

/// CPU double-precision irradiance at p for the unit normal n.
using IrradianceFn = Estimate (*)(const Luminaire& luminaire, const glm::dvec3& p,
                                  const glm::dvec3& n, const EstimateOptions& options);

/// What a technique promises at the extremes: tests/hardcases holds every technique to it on the
/// hard-case grid (on the GPU with float's own allowances), and docs/hard-cases.md's table states
/// it.
struct StatedLimits {
    enum Accuracy {
        Exact,        ///< Within `tolerance` of the truth.
        Unbiased,     ///< Its standard error covers its error (4 of them), plus `tolerance`.
        PointLaw,     ///< Exactly the point law at the opening's centre, within `tolerance`.
        Approximate,  ///< Within `tolerance` near the source, `farTolerance` far from it.
    };
    Accuracy accuracy = Exact;
    double tolerance = 1e-3;     ///< Relative.
    double farTolerance = -1.0;  ///< Approximate: 1e5 m away; < 0: `tolerance`.
    /// The promise holds from this distance on, in opening diagonals (photometric openings);
    /// nearer the estimate is only finite and non-negative.
    double fromOpeningSizes = 0.0;
    /// False: a peak of the table narrower than its few sample directions is anywhere between 0
    /// and what the opening gives at its brightest radiance everywhere (pi F L_max).
    bool resolvesPeaks = true;
    /// The wording of docs/hard-cases.md; empty: no statement, and the suites hold the technique to
    /// the strictest promise (exact if deterministic, unbiased if progressive).
    std::string_view statement = {};
    /// Photometric techniques on a smooth, non-Lambertian table within a few opening sizes (an
    /// up-and-down luminaire's batwings): within this, relative; < 0: any factor off.
    double tableTolerance = 1e-3;
    /// Photometric techniques: the flux a closed box absorbs whose walls lie 0.1 m from the
    /// opening (or fromOpeningSizes, if farther) is the file's within this fraction, for every
    /// file the flux audit reads (tests/flux_audit_test.cpp).
    double fluxTolerance = 1.0;
};

struct TechniqueInfo {
    LuminaireKind kind;            ///< Luminaire kind it renders.
    std::string_view name;         ///< As in scene files and --technique.
    std::string_view description;  ///< One line for the editor and `candela info`.
    bool progressive;              ///< Stochastic: refines over frames. Else exact in one frame.
    IrradianceFn irradiance;       ///< CPU estimator (probe, tests, parity).
    /// Its fragment shader in shaders/ (kind_technique.frag: the technique's own function and its
    /// kind's shared shading); empty: CPU only (probe, tests, benches).
    std::string_view shader;
    /// Where an occluder can block the luminaire: true reads shadow maps (SHADOW_MAPS, rendered
    /// from the luminaire's shadowLights, luminaires/Adapter.h), false traces a ray per sample
    /// through the BVH (SHADOWS).
    bool shadowMaps = false;
    /// What its kind's GPU pass prepares for it besides the source's record (space-separated
    /// names that pass knows; the environment's: "cube", "latlong", "lights"); empty: nothing.
    std::string_view resources = {};
    StatedLimits limits = {};
};

/// Builds a placed luminaire from its scene-file entry (luminaires/Adapter.h).
using LuminaireParser = std::unique_ptr<Luminaire> (*)(const nlohmann::json& entry,
                                                       const json::Where& where);

struct LuminaireKindInfo {
    LuminaireKind kind;
    std::string_view name;  ///< As in scene files (kindName()).
    std::string_view description;
    const LuminaireAdapter& (*adapter)();
    std::string_view defaultTechnique;
    /// The editor's fallback while the user drags (renderer/LivePreview.h): cheap per sample and
    /// close at one sample per pixel.
    std::string_view previewTechnique;
    /// Placed by a scene's "luminaires" list (the environment is not: its own field makes it).
    bool placed() const { return adapter().parse != nullptr; }
};

/// A scene-file luminaire type that is a file format rather than a kind of its own: its entries
/// build a luminaire of an existing kind, rendered by that kind's techniques (a GLDF variant is a
/// photometric luminaire).
struct LuminaireFormatInfo {
    std::string_view type;  ///< The entry's "type".
    LuminaireKind kind;     ///< The kind of luminaire it builds.
    LuminaireParser parse;
};

/// The kinds of luminaires a scene places (its "luminaires" list; the editor's Add).
std::span<const LuminaireKindInfo> luminaireKinds();
/// Every kind of light source: the luminaire kinds, then the environment.
std::span<const LuminaireKindInfo> sourceKinds();
std::span<const TechniqueInfo> techniques();
/// The techniques of one kind, in the table's order.
std::vector<TechniqueInfo> techniquesOf(LuminaireKind kind);
const LuminaireKindInfo& findKind(LuminaireKind kind);
/// The kind a scene file names; null if none.
const LuminaireKindInfo* findKind(std::string_view name);
/// The formats a scene's luminaire entries may name besides the kinds ("gldf").
std::span<const LuminaireFormatInfo> luminaireFormats();
const LuminaireFormatInfo* findFormat(std::string_view type);
const TechniqueInfo* findTechnique(LuminaireKind kind, std::string_view name);
/// Comma-separated technique names of a kind, for error messages and help.
std::string techniqueNames(LuminaireKind kind);

}  // namespace candela
