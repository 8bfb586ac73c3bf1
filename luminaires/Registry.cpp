#include "luminaires/Registry.h"

#include "luminaires/LambertianRect.h"

namespace candela {

// The one table of luminaire kinds and techniques. A new technique is one line here plus its own
// files; a new kind is one line in kKinds plus its model in luminaires/ and shaders.
static const LuminaireKindInfo kKinds[] = {
    {"lambertian-rect", "uniformly emitting (Lambertian) rectangle", &LambertianRect::parse,
     &LambertianRect::create, "analytic"},
};

static const TechniqueInfo kTechniques[] = {
    {"lambertian-rect", "analytic",
     "closed-form polygon irradiance (Baum et al. 1989); stochastic visibility ratio if occluded",
     false, &lambertianRectAnalytic, "lambertian_rect_shade.frag", "TECHNIQUE_ANALYTIC"},
    {"lambertian-rect", "reference",
     "Monte Carlo, samples uniform in solid angle (Urena et al. 2013)", true,
     &lambertianRectReference, "lambertian_rect_shade.frag", "TECHNIQUE_REFERENCE"},
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
