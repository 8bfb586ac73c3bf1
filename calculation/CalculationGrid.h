#pragma once
// The calculation grid of `candela grid` and of the editor's Measure panel: illuminance at the
// points of a grid on an axis-aligned plane from each luminaire's CPU estimator in the registry,
// and its summary (EN 12464-1 style: Emin, Eavg, Emax, U0).

#include <cstddef>
#include <functional>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "luminaires/Units.h"
#include "scene/Measurements.h"

namespace candela {

struct Scene;

struct GridSpec {
    CalcPlane plane;
    glm::dvec2 lo{0.0}, hi{0.0};  ///< Extent in (u, v), metres.
    double spacing = 0.25;        ///< Distance between adjacent points, metres.
    int spp = 1024;               ///< Samples per point and luminaire for stochastic techniques.
    bool visibility = false;      ///< Shadow rays through the scene's BVH.
    std::string technique;        ///< Empty: each luminaire's own technique.
    /// The environment's technique (luminaires/environment/EnvironmentSampling.h); empty:
    /// `technique` if it names an environment technique, else the exact `reference`.
    std::string environmentTechnique;
    /// Adds interreflected light (calculation/Interreflection.h: radiosity refined near each point,
    /// with a final gather of `spp` rays where it is not accurate enough). Its own rays see the
    /// geometry whatever `visibility` says, which is the direct light's shadows alone.
    bool indirect = false;
    /// About this many radiosity patches for the interreflection. The patches' solution is
    /// refined near each point (Interreflection::fromPatches), so the patches need only carry
    /// the light across the room: on the office 1500 (1824 with the bodies) are within 0.13 % of
    /// 8000 at every grid point, at a fifth of the time of 4000 (docs/computation.md,
    /// "Interreflected light").
    int patches = 1500;
    /// How each point gets its interreflected light: the final gather (a reference, `spp`
    /// rays, with a standard error), the patches' solution alone (deterministic, about ten
    /// times faster: the editor's grid), or the patches' solution refined near p with the final
    /// gather only where its error estimate exceeds kGatherAbove of the point's light.
    enum class Indirect { Gather, Patches, Adaptive } indirectMethod = Indirect::Adaptive;
    /// Adaptive: the part of a point's light (direct plus interreflected) the patches' error
    /// estimate may reach before the point gets the final gather. A quarter of the 1 % the
    /// calculation promises: the estimate is what refining the near patches changed, which
    /// understates what a second refinement would change.
    static constexpr double kGatherAbove = 0.0025;
};

/// The light a designer asks for. By default everything the scene calls for: shadows wherever
/// something can block a luminaire's light, interreflected light wherever a surface reflects,
/// so that a result is what a light meter in the scene would read. Switching a part off is an
/// explicit choice (`--light direct`, `--no-shadows`; the Measure panel's checkboxes) that every
/// output then states (lightStatement).
struct LightChoice {
    bool interreflection = true;
    bool shadows = true;
    /// Interreflected light asked for by name (`--indirect`): computed even where the scene
    /// seems to call for none, so that a scene without surfaces gets its error.
    bool insist = false;
};
/// Something in `scene` can block a luminaire's light: a surface or a luminaire body.
bool sceneCastsShadows(const Scene& scene);
/// A surface of `scene` reflects light: an albedo above 0 on any surface that is not a luminaire's
/// body (a lone floor reflects onto every receiver that faces it).
bool sceneReflects(const Scene& scene);
/// Sets spec.visibility and spec.indirect to what `scene` calls for, less what `choice` turns
/// off.
void applyLightChoice(const Scene& scene, const LightChoice& choice, GridSpec& spec);
/// What light a calculation with `spec` on `scene` includes, in plain words for a designer, and
/// why a part is missing: "direct light with shadows, and interreflected light", "direct light
/// without shadows (switched off); no interreflected light (no surface reflects)".
std::string lightStatement(const Scene& scene, const GridSpec& spec);

/// Point coordinates along one axis: floor(len / spacing) points (at least 1) spacing apart,
/// centred in [lo, hi], so a 4 m side at 0.25 m gets 16 points at cell centres 0.125 .. 3.875.
std::vector<double> gridCoordinates(double lo, double hi, double spacing);

struct GridResult {
    GridSpec spec;
    std::vector<double> u, v;      ///< Point coordinates along u (columns) and v (rows), metres.
    UnitSystem units;              ///< What E is in: lx, or W/m2 for a radiometric scene.
    std::string maintenance;       ///< Its maintenance factors (Scene::maintenanceNote).
    std::string bodies;            ///< The bodies that block light (Scene::bodiesNote).
    std::string light;             ///< What light E includes (lightStatement).
    double projectFactor = 1.0;    ///< Scene::maintenanceFactor.
    std::vector<double> E;         ///< Illuminance at point (i, j) in E[j * u.size() + i], in
                                   ///< units.irradiance(), luminance-weighted: direct plus
                                   ///< interreflected when hasIndirect.
    std::vector<double> stdError;  ///< Standard error of each value (0 for exact techniques).
    bool hasIndirect = false;      ///< Interreflected light was computed (GridSpec::indirect).
    std::string indirectNote;      ///< How (ReceiverResult::indirectNote).
    size_t patches = 0;            ///< The interreflection's patches (0 without it).
    std::vector<double> direct, directStdError;      ///< The direct part alone (always filled).
    std::vector<double> indirect, indirectStdError;  ///< The interreflected part (hasIndirect).
    /// E before maintenance (every maintenance factor 1): E / initial is the factor in effect at
    /// the point, which varies where luminaires with their own factors mix.
    std::vector<double> initial;
};

struct GridSummary {
    size_t count = 0;
    double eMin = 0.0, eAvg = 0.0, eMax = 0.0;  ///< In the grid's unit (GridResult::units).
    double u0 = 0.0;                            ///< Uniformity Emin / Eavg (0 when Eavg is 0).
    double minOverMax = 0.0;                    ///< Emin / Emax (0 when Emax is 0).
};

GridSummary summariseGrid(const std::vector<double>& E);
/// The scene's bounds projected on the plane, or throws InputError when it has no geometry.
void defaultGridExtent(const Scene& scene, GridSpec& spec);
/// Checks the spec (finite extent with hi > lo, spacing > 0, at most 1e6 points) and evaluates
/// every point; throws InputError on bad values or a luminaire without a CPU estimator.
/// `status` (optional) hears what it is doing, for progress on long grids.
GridResult computeGrid(const Scene& scene, const GridSpec& spec,
                       const std::function<void(const std::string& status)>& status = {});

/// A receiving surface element: a point (m) and its unit normal.
struct Receiver {
    glm::dvec3 position{0.0}, normal{0.0, 1.0, 0.0};
};

/// Illuminance at arbitrary receivers, as computeGrid evaluates its points.
struct ReceiverResult {
    UnitSystem units;
    std::string maintenance;
    std::string bodies;               ///< Scene::bodiesNote().
    std::string light;                ///< What light E includes (lightStatement).
    double projectFactor = 1.0;       ///< Scene::maintenanceFactor.
    std::vector<double> E, stdError;  ///< In units.irradiance(), per receiver: direct (+ indirect).
    bool hasIndirect = false;
    std::vector<double> direct, directStdError, indirect, indirectStdError;
    /// How the interreflected light was found ("" without it): the method, and for the adaptive
    /// one at how many points the final gather was needed.
    std::string indirectNote;
    size_t patches = 0;           ///< The interreflection's patches (0 without it).
    std::vector<double> initial;  ///< E before maintenance (GridResult::initial).
};

/// The maintenance factor in effect where maintained illuminance `E` was `initial` before
/// maintenance: E / initial, or `fallback` (the project's factor) where no light arrives.
double effectiveMaintenanceFactor(double E, double initial, double fallback);

/// The fewest shadow rays an exact technique traces to one luminaire from one receiver: enough
/// for the visible fraction's standard error to mean something.
constexpr int kMinShadowRays = 8;

/// Shadow rays for one luminaire at a receiver where an exact technique finds `unshadowed` of its
/// light and the brightest luminaire `brightest` (same units): spp for the brightest, the share
/// spp * unshadowed / brightest for the others, never fewer than kMinShadowRays (nor more than
/// spp). With n_k in proportion to E_k, the variance of the sum, sum E_k^2 v_k / n_k, is at most
/// (E_total / E_max) times the brightest's at spp rays: the relative error of the total is no
/// worse than one luminaire's at spp rays. Equal luminaires all get spp.
int shadowRays(int spp, double unshadowed, double brightest);

/// Evaluates the receivers with the estimators, visibility and interreflection that `how`
/// asks for (its technique, environmentTechnique, spp, visibility, indirect, patches and
/// indirectMethod; its plane, extent and spacing are not read). One interreflection solution
/// serves every receiver.
ReceiverResult computeReceivers(const Scene& scene, const GridSpec& how,
                                const std::vector<Receiver>& receivers,
                                const std::function<void(const std::string& status)>& status = {});

}  // namespace candela
