#include "luminaires/Registry.h"

#include "luminaires/environment/EnvironmentLight.h"
#include "luminaires/lambertian/LambertianRect.h"
#include "luminaires/lightfield/LightField.h"
#include "luminaires/photometric/PhotometricLuminaire.h"
#include "luminaires/photometric/PhotometricUniformArea.h"

namespace candela {

// The one table of luminaire kinds and techniques. A new technique is one line here plus its own
// files; a new kind is one line in kKinds plus its model in luminaires/ and shaders.
static const LuminaireKindInfo kKinds[] = {
    {LuminaireKind::LambertianRect, "lambertian-rect", "uniformly emitting (Lambertian) rectangle",
     &lambertianRectAdapter, "analytic", "analytic"},
    {LuminaireKind::LightField, "lightfield",
     "measured near-field luminaire (light field on two planes, Lu et al. 2015)",
     &lightFieldAdapter, "restricted-cdf", "precomputed-global"},
    {LuminaireKind::Photometric, "photometric",
     "far-field photometry (IES LM-63, EULUMDAT) on its luminous opening (Prost 2019)",
     &photometricAdapter, "adaptive", "scattered"},
    // Not placed: a scene's "environment" field makes it (Scene::environmentLight).
    {LuminaireKind::Environment, "environment",
     "environment map at infinity (lat-long image, sky, sequence; Lu et al. 2013)",
     &environmentAdapter, "balanced", "balanced"},
};
// Scene types that are file formats: a GLDF variant is its emitter's photometry.
static const LuminaireFormatInfo kFormats[] = {
    {"gldf", LuminaireKind::Photometric, &parseGldfLuminaire},
};

/// The kinds a scene places: all of kKinds but the last.
constexpr size_t kPlacedKinds = std::size(kKinds) - 1;

using Limits = StatedLimits;

static const TechniqueInfo kTechniques[] = {
    {LuminaireKind::LambertianRect,
     "analytic",
     "closed-form polygon irradiance (Baum et al. 1989); stochastic visibility ratio if occluded",
     false,
     &lambertianRectAnalytic,
     "lambertian_rect_analytic.frag",
     false,
     {},
     {Limits::Exact, 1e-6, -1, 0, true, "Lambert's formula: exact to double rounding"}},
    {LuminaireKind::LambertianRect,
     "reference",
     "Monte Carlo, samples uniform in solid angle (Urena et al. 2013)",
     true,
     &lambertianRectReference,
     "lambertian_rect_reference.frag",
     false,
     {},
     {Limits::Unbiased, 2e-3, -1, 0, true, "unbiased; its standard error covers its error"}},
    // The light-field GPU techniques read per-cell shadow maps (Sec. 6.2) when an occluder may
    // block the luminaire; restricted-cdf-raytraced is the same sampler with a shadow ray per
    // sample (the exact visibility the maps approximate, Fig. 7). On the CPU both trace rays.
    {LuminaireKind::LightField,
     "restricted-cdf",
     "position-dependent restricted CDFs with balancing (Lu et al. 2015, Eq. 8, 12, 13); per-cell "
     "shadow maps",
     true,
     &lightFieldRestrictedCdf,
     "lightfield_restricted_cdf.frag",
     true,
     {},
     {Limits::Unbiased, 1e-3, -1, 0, true, "unbiased; its standard error covers its error"}},
    {LuminaireKind::LightField,
     "restricted-cdf-raytraced",
     "restricted-cdf with a shadow ray per sample (exact visibility; BVH on the GPU, Embree on the "
     "CPU)",
     true,
     &lightFieldRestrictedCdf,
     "lightfield_restricted_cdf.frag",
     false,
     {},
     {Limits::Unbiased, 1e-3, -1, 0, true, "unbiased; its standard error covers its error"}},
    {LuminaireKind::LightField,
     "uniform-restricted",
     "uniform samples in the same restricted boxes (Fig. 12)",
     true,
     &lightFieldUniformRestricted,
     "lightfield_uniform_restricted.frag",
     true,
     {},
     {Limits::Unbiased, 1e-3, -1, 0, true, "unbiased; its standard error covers its error"}},
    {LuminaireKind::LightField,
     "precomputed-global",
     "one global CDF over all images, the same for every receiver (Fig. 11)",
     true,
     &lightFieldPrecomputedGlobal,
     "lightfield_precomputed_global.frag",
     true,
     {},
     {Limits::Unbiased, 1e-3, -1, 0, true,
      "unbiased; its standard error covers its error (near S it adds the distance to a "
      "restricted-cdf pilot)"}},
    // The CPU estimator is precomputed-global's: at one receiver the shared set is distributed as
    // a set of the receiver's own.
    {LuminaireKind::LightField,
     "precomputed-shared",
     "one set of global-CDF samples shared by every receiver (the paper's Fig. 11 baseline)",
     true,
     &lightFieldPrecomputedGlobal,
     "lightfield_precomputed_shared.frag",
     true,
     {},
     {Limits::Unbiased, 1e-3, -1, 0, true,
      "unbiased; its standard error covers its error (near S it adds the distance to a "
      "restricted-cdf pilot); one set of samples for all receivers, so its error is structured"}},
    {LuminaireKind::LightField,
     "granier2003",
     "one textured spot light per basis function (Granier et al. 2003, Eq. 14); approximate",
     false,
     &lightFieldGranier2003,
     "lightfield_granier2003.frag",
     true,
     {},
     // One bright pixel 1 cm away: 9 %; 1e5 m away it conserves the light field's far field.
     {Limits::Approximate, 0.1, 1e-2, 0, true,
      "an approximation within 10 % near the luminaire; within 1 % far away (its far field "
      "conserved)"}},
    {LuminaireKind::LightField,
     "reference",
     "Gauss-Legendre quadrature of the exact model over U, split at knots and pixel edges",
     false,
     &lightFieldReference,
     "",
     false,
     {},
     {Limits::Exact, 2e-3, -1, 0, true, "quadrature over U: exact to 0.2 %"}},
    {LuminaireKind::Photometric,
     "scattered",
     "corners + closest point, spherical Delaunay cubature normalised by the form factor (Prost "
     "Eq. 5.6, 5.11)",
     false,
     &photometricScattered,
     "photometric_scattered.frag",
     true,
     {},
     // Measured: the hard cases' up-and-down box 28 % (beside it, 0.1 m); the flux audit 3.6x
     // (spot.ies in a box 0.1 m round its opening).
     {Limits::Exact, 1e-3, -1, 0, false,
      "exact for a Lambertian opening, a segment or a point; on measured tables five directions "
      "near the opening: 28 % off on a smooth batwing 0.1 m away, any factor on a peaked one (the "
      "flux 0.1 m round spot.ies 3.6x)",
      0.3, 3.7}},
    {LuminaireKind::Photometric,
     "structured",
     "corners and barycentre as uniform solid-angle samples (Lagarde 2014)",
     false,
     &photometricStructured,
     "photometric_structured.frag",
     true,
     {},
     // Measured: the up-and-down box 49 %; the flux audit 3.3x (side.ies).
     {Limits::Exact, 1e-3, -1, 0, false,
      "exact for a Lambertian opening, a segment or a point; on measured tables near the "
      "opening: 49 % off on a smooth batwing, any factor on a peaked one (flux 3.3x)",
      0.5, 2.4}},
    {LuminaireKind::Photometric,
     "mrp",
     "one sample at the most representative point (Drobot 2014)",
     false,
     &photometricMrp,
     "photometric_mrp.frag",
     true,
     {},
     // Measured: the up-and-down box 67 %; the flux audit 12.5x (display.ies).
     {Limits::Exact, 1e-3, -1, 0, false,
      "exact for a Lambertian opening, a segment or a point; one direction for a measured table: "
      "67 % off on a smooth batwing near the opening, any factor on a peaked one (flux 12.5x)",
      0.7, 11.6}},
    {LuminaireKind::Photometric,
     "mc-poisson-24",
     "a fixed set of 24 Poisson-disk points on the opening (MCI-24)",
     false,
     &photometricPoisson24,
     "photometric_poisson24.frag",
     true,
     {},
     {Limits::Exact, 1e-2, -1, 5, false,
      "within 1 % from 5 opening diagonals on for a Lambertian or smooth table (and the flux); "
      "its 24 points are no symmetric rule, so a peaked table is off by up to 30 % there and "
      "3.5 % 28 diagonals away (vee.ies)",
      1e-2, 1e-2}},
    {LuminaireKind::Photometric,
     "mc-poisson-40",
     "a fixed set of 40 Poisson-disk points on the opening (MCI-40)",
     false,
     &photometricPoisson40,
     "photometric_poisson40.frag",
     true,
     {},
     {Limits::Exact, 1e-2, -1, 5, false,
      "within 1 % from 5 opening diagonals on for a Lambertian or smooth table (and the flux); "
      "a peaked table is off by up to 24 % there (Type C - 02.ies)",
      1e-2, 1e-2}},
    // 1e-4: the test reads the cosine it tabulates at 1 degree steps (linear interpolation: at
    // most (pi / 180)^2 / 8 = 4e-5 relative).
    {LuminaireKind::Photometric,
     "point",
     "one photometric point light at the centre (DIALux-style preview)",
     false,
     &photometricPoint,
     "photometric_point.frag",
     true,
     {},
     {Limits::PointLaw, 1e-4, -1, 0, true, "the point law at the opening's centre, at any distance",
      1e-3, 0.0}},
    {LuminaireKind::Photometric,
     "adaptive",
     "scattered sampling refined where it matters: the worst spherical triangle split in four "
     "until the estimate's error is 0.1 % of it",
     false,
     &photometricAdaptive,
     "photometric_adaptive.frag",
     true,
     {},
     // CPU: 0.2 % on the up-and-down box; on the 71 files' near points 2 % (cplanes.ies, 0.1 m),
     // 0.9 % from 2 diagonals on; the flux audit 1 %.
     {Limits::Exact, 3e-2, -1, 0, false,
      "within 3 % at every distance, contact included, and 1 % from 2 opening diagonals on (on "
      "the CPU; the GPU's fewer splits: within 3 % from 0.3 m); a peak narrower than its first "
      "triangles can be missed",
      1e-2, 1e-2}},
    {LuminaireKind::Photometric,
     "hybrid",
     "scattered within half an opening size, 24 Poisson points from 1.5 on, blended between (Prost "
     "Sec. 6.6)",
     false,
     &photometricHybrid,
     "photometric_hybrid.frag",
     true,
     {},
     // Measured: as scattered near the opening (the box 28 %, the flux audit 3.6x), as
     // mc-poisson-24 beyond (a peaked table 30 % off at 5 diagonals).
     {Limits::Exact, 3e-2, -1, 0, false,
      "within 3 % at every distance on a Lambertian opening; on measured tables scattered's "
      "errors near the opening (28 % on a smooth batwing, any factor on a peaked one) and "
      "mc-poisson-24's beyond (30 % on a peaked one at 5 diagonals)",
      0.3, 3.7}},
    {LuminaireKind::Photometric,
     "reference",
     "Monte Carlo: opening points (Prost Eq. 6.3), cosine and intensity-proportional directions, "
     "balance heuristic",
     true,
     &photometricReference,
     "photometric_reference.frag",
     false,
     {},
     {Limits::Unbiased, 2e-3, -1, 0, true,
      "unbiased; its standard error covers its error (4 standard errors)", 1e-3, 0.0}},
    {LuminaireKind::Photometric,
     "uniform-area",
     "Monte Carlo: points uniform on the opening only (Prost Eq. 6.3 on its own)",
     true,
     &photometricUniformArea,
     "photometric_uniform_area.frag",
     false,
     {},
     {Limits::Unbiased, 2e-3, -1, 1, false,
      "unbiased, error bar covers, from 1 opening diagonal on; nearer, its points almost never "
      "land at the "
      "receiver's foot, where the light comes from, and a peak narrower than the angle its points "
      "span is missed",
      1e-3, 0.0}},
    // The environment. Its pass (renderer/passes/EnvironmentPass) builds the tables each names:
    // the cube-map CDFs and a pool of light samples per pass, the lat-long CDF, or Havran's
    // lights.
    {LuminaireKind::Environment,
     "reference",
     "exact: every texel's radiance times its clipped-cosine integral",
     false,
     &onEnvironmentLight<&environmentReference>,
     "",
     false,
     {},
     {Limits::Exact, 1e-3, -1, 0, true, "exact: every texel's clipped-cosine integral"}},
    {LuminaireKind::Environment,
     "balanced",
     "cube-map CDFs, samples per face balanced per normal (Lu et al. 2013, Eq. 3-5)",
     true,
     &onEnvironmentLight<&environmentBalanced>,
     "environment_balanced.frag",
     false,
     "cube",
     {Limits::Unbiased, 1e-3, -1, 0, true, "unbiased; its standard error covers its error"}},
    {LuminaireKind::Environment,
     "uniform-faces",
     "cube-map CDFs, 1/6 of the samples per face (Lu et al. 2013, Fig. 2)",
     true,
     &onEnvironmentLight<&environmentUniformFaces>,
     "environment_uniform_faces.frag",
     false,
     "cube",
     {Limits::Unbiased, 1e-3, -1, 0, true, "unbiased; its standard error covers its error"}},
    {LuminaireKind::Environment,
     "global-cdf",
     "one CDF over the lat-long map with the sin(theta) Jacobian",
     true,
     &onEnvironmentLight<&environmentGlobalCdf>,
     "environment_global_cdf.frag",
     false,
     "latlong",
     {Limits::Unbiased, 1e-3, -1, 0, true, "unbiased; its standard error covers its error"}},
    {LuminaireKind::Environment,
     "havran2005",
     "256 filtered directional lights from relaxed Halton points (Havran et al. 2005); a shadow "
     "map each",
     false,
     &onEnvironmentLight<&environmentHavran>,
     "environment_havran2005.frag",
     true,
     "lights",
     {Limits::Approximate, 3e-2, -1, 0, true,
      "256 directional lights: within 3 % of a smooth sky"}},
    {LuminaireKind::Environment,
     "havran2005-raytraced",
     "havran2005 with a shadow ray per light instead of its shadow map (exact visibility)",
     false,
     &onEnvironmentLight<&environmentHavran>,
     "environment_havran2005.frag",
     false,
     "lights",
     {Limits::Approximate, 3e-2, -1, 0, true,
      "256 directional lights: within 3 % of a smooth sky"}},
    {LuminaireKind::Environment,
     "balanced-mis",
     "balanced light samples and cosine samples, balance heuristic (Eq. 6)",
     true,
     &onEnvironmentLight<&environmentBalancedMis>,
     "environment_balanced_mis.frag",
     false,
     "cube",
     {Limits::Unbiased, 1e-3, -1, 0, true, "unbiased; its standard error covers its error"}},
    {LuminaireKind::Environment,
     "balanced-integer",
     "balanced with N_f rounded to whole samples (biased, pops; the baseline of the "
     "temporal-stability bench)",
     true,
     &onEnvironmentLight<&environmentBalancedInteger>,
     "environment_balanced_integer.frag",
     false,
     "cube",
     {Limits::Approximate, 5e-2, -1, 0, true,
      "biased by rounding N_f: a baseline, not an estimator to trust"}},
};

std::span<const LuminaireKindInfo> luminaireKinds() {
    return std::span<const LuminaireKindInfo>(kKinds, kPlacedKinds);
}
std::span<const LuminaireKindInfo> sourceKinds() {
    return kKinds;
}
std::span<const TechniqueInfo> techniques() {
    return kTechniques;
}

std::vector<TechniqueInfo> techniquesOf(LuminaireKind kind) {
    std::vector<TechniqueInfo> out;
    for (const auto& t : kTechniques)
        if (t.kind == kind) out.push_back(t);
    return out;
}

const LuminaireKindInfo& findKind(LuminaireKind kind) {
    for (const auto& k : kKinds)
        if (k.kind == kind) return k;
    return kKinds[0];  // unreachable: every kind has a line
}

const LuminaireKindInfo* findKind(std::string_view name) {
    for (const auto& k : kKinds)
        if (k.name == name) return &k;
    return nullptr;
}

std::span<const LuminaireFormatInfo> luminaireFormats() {
    return kFormats;
}

const LuminaireFormatInfo* findFormat(std::string_view type) {
    for (const auto& f : kFormats)
        if (f.type == type) return &f;
    return nullptr;
}

const TechniqueInfo* findTechnique(LuminaireKind kind, std::string_view name) {
    for (const auto& t : kTechniques)
        if (t.kind == kind && t.name == name) return &t;
    return nullptr;
}

std::string techniqueNames(LuminaireKind kind) {
    std::string out;
    for (const auto& t : kTechniques)
        if (t.kind == kind) out += (out.empty() ? "" : ", ") + std::string(t.name);
    return out;
}

// The adapters' dispatch (luminaires/Adapter.h).

const LuminaireAdapter& adapterOf(LuminaireKind kind) {
    return findKind(kind).adapter();
}

void writeJson(const Luminaire& luminaire, nlohmann::json& out) {
    if (auto f = adapterOf(luminaire.kind()).writeJson) f(luminaire.model(), out);
}

std::vector<std::byte> gpuData(const Luminaire& luminaire) {
    auto f = adapterOf(luminaire.kind()).gpuData;
    return f ? f(luminaire) : std::vector<std::byte>();
}

std::shared_ptr<const GpuTables> gpuTables(const Luminaire& luminaire) {
    auto f = adapterOf(luminaire.kind()).gpuTables;
    return f ? f(luminaire.model()) : nullptr;
}

std::string describe(const Luminaire& luminaire) {
    auto f = adapterOf(luminaire.kind()).describe;
    return f ? f(luminaire.model()) : std::string(kindName(luminaire.kind()));
}

std::vector<std::string> sourceFiles(const Luminaire& luminaire) {
    auto f = adapterOf(luminaire.kind()).sourceFiles;
    return f ? f(luminaire.model()) : std::vector<std::string>();
}

ShadowLights shadowLights(const Luminaire& luminaire, int count) {
    auto f = adapterOf(luminaire.kind()).shadowLights;
    return f ? f(luminaire, count) : ShadowLights();
}

LuminaireBody body(const Luminaire& luminaire) {
    auto f = adapterOf(luminaire.kind()).body;
    return f ? f(luminaire) : LuminaireBody();
}

std::vector<std::unique_ptr<Luminaire>> companions(const Luminaire& luminaire) {
    auto f = adapterOf(luminaire.kind()).companions;
    return f ? f(luminaire) : std::vector<std::unique_ptr<Luminaire>>();
}

glm::dvec3 displayRadiance(const Luminaire& luminaire) {
    if (auto f = adapterOf(luminaire.kind()).displayRadiance) return f(luminaire);
    glm::dvec3 x, y, z;
    Pose emitter = luminaire.emitterPose();
    emitter.frame(x, y, z);
    return luminaire.radiance(emitter.position, z);
}

}  // namespace candela
