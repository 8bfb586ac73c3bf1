#include "luminaires/Registry.h"

#include "luminaires/LambertianRect.h"
#include "luminaires/LightField.h"
#include "luminaires/PhotometricLuminaire.h"

namespace candela {

// The one table of luminaire kinds and techniques. A new technique is one line here plus its own
// files; a new kind is one line in kKinds plus its model in luminaires/ and shaders.
static const LuminaireKindInfo kKinds[] = {
    {"lambertian-rect", "uniformly emitting (Lambertian) rectangle", &LambertianRect::parse,
     &LambertianRect::create, "analytic", "analytic"},
    {"lightfield", "measured near-field luminaire (light field on two planes, Lu et al. 2015)",
     &LightFieldLuminaire::parse, &LightFieldLuminaire::create, "restricted-cdf", "precomputed-global"},
    {"photometric", "far-field photometry (IES LM-63, EULUMDAT) on its luminous opening (Prost 2019)",
     &PhotometricLuminaire::parse, &PhotometricLuminaire::create, "hybrid", "scattered"},
};

static const TechniqueInfo kTechniques[] = {
    {"lambertian-rect", "analytic",
     "closed-form polygon irradiance (Baum et al. 1989); stochastic visibility ratio if occluded",
     false, &lambertianRectAnalytic, "lambertian_rect_shade.frag", "TECHNIQUE_ANALYTIC"},
    {"lambertian-rect", "reference",
     "Monte Carlo, samples uniform in solid angle (Urena et al. 2013)", true,
     &lambertianRectReference, "lambertian_rect_shade.frag", "TECHNIQUE_REFERENCE"},
    // The light-field GPU techniques read per-cell shadow maps (Sec. 6.2) when an occluder may
    // block the luminaire; restricted-cdf-raytraced is the same sampler with a shadow ray per
    // sample (the exact visibility the maps approximate, Fig. 7). On the CPU both trace rays.
    {"lightfield", "restricted-cdf",
     "position-dependent restricted CDFs with balancing (Lu et al. 2015, Eq. 8, 12, 13); per-cell shadow maps",
     true, &lightFieldRestrictedCdf, "lightfield_shade.frag", "TECHNIQUE_RESTRICTED", true},
    {"lightfield", "restricted-cdf-raytraced",
     "restricted-cdf with a shadow ray per sample (exact visibility; BVH on the GPU, Embree on the CPU)",
     true, &lightFieldRestrictedCdf, "lightfield_shade.frag", "TECHNIQUE_RESTRICTED"},
    {"lightfield", "uniform-restricted", "uniform samples in the same restricted boxes (Fig. 12)",
     true, &lightFieldUniformRestricted, "lightfield_shade.frag", "TECHNIQUE_UNIFORM", true},
    {"lightfield", "precomputed-global",
     "one global CDF over all images, the same for every receiver (Fig. 11)", true,
     &lightFieldPrecomputedGlobal, "lightfield_shade.frag", "TECHNIQUE_GLOBAL", true},
    {"lightfield", "granier2003",
     "one textured spot light per basis function (Granier et al. 2003, Eq. 14); approximate", false,
     &lightFieldGranier2003, "lightfield_shade.frag", "TECHNIQUE_GRANIER", true},
    // CPU only (probe, tests, benches): no GPU pass.
    {"lightfield", "reference",
     "Gauss-Legendre quadrature of the exact model over U, split at knots and pixel edges", false,
     &lightFieldReference, "", ""},
    {"photometric", "scattered",
     "corners + closest point, spherical Delaunay cubature normalised by the form factor (Prost Eq. 5.6, 5.11)",
     false, &photometricScattered, "photometric_shade.frag", "TECHNIQUE_SCATTERED", true},
    {"photometric", "structured", "corners and barycentre as uniform solid-angle samples (Lagarde 2014)",
     false, &photometricStructured, "photometric_shade.frag", "TECHNIQUE_STRUCTURED", true},
    {"photometric", "mrp", "one sample at the most representative point (Drobot 2014)", false,
     &photometricMrp, "photometric_shade.frag", "TECHNIQUE_MRP", true},
    {"photometric", "mc-poisson-24", "a fixed set of 24 Poisson-disk points on the opening (MCI-24)",
     false, &photometricPoisson24, "photometric_shade.frag", "TECHNIQUE_POISSON24", true},
    {"photometric", "mc-poisson-40", "a fixed set of 40 Poisson-disk points on the opening (MCI-40)",
     false, &photometricPoisson40, "photometric_shade.frag", "TECHNIQUE_POISSON40", true},
    {"photometric", "point", "one photometric point light at the centre (DIALux-style preview)", false,
     &photometricPoint, "photometric_shade.frag", "TECHNIQUE_POINT", true},
    {"photometric", "hybrid",
     "scattered within half an opening size, 24 Poisson points from 1.5 on, blended between (Prost Sec. 6.6)",
     false, &photometricHybrid, "photometric_shade.frag", "TECHNIQUE_HYBRID", true},
    {"photometric", "reference",
     "Monte Carlo: opening points (Prost Eq. 6.3), cosine and intensity-proportional directions, balance heuristic", true,
     &photometricReference, "photometric_shade.frag", "TECHNIQUE_REFERENCE"},
};

std::span<const LuminaireKindInfo> luminaireKinds() { return kKinds; }
std::span<const TechniqueInfo> techniques() { return kTechniques; }

const LuminaireKindInfo* findKind(std::string_view kind) {
    for (const auto& k : kKinds)
        if (k.kind == kind) return &k;
    return nullptr;
}

const TechniqueInfo* findTechnique(std::string_view kind, std::string_view name) {
    for (const auto& t : kTechniques)
        if (t.kind == kind && t.name == name) return &t;
    return nullptr;
}

std::string techniqueNames(std::string_view kind) {
    std::string out;
    for (const auto& t : kTechniques)
        if (t.kind == kind) out += (out.empty() ? "" : ", ") + std::string(t.name);
    return out;
}

}  // namespace candela
