#include "luminaires/Luminaire.h"

#include <algorithm>
#include <cmath>

namespace candela {

namespace {

/// v divided by its largest absolute component, so that its length can be taken without overflow
/// or underflow; zero when v is zero or not finite.
glm::dvec3 rescaled(const glm::dvec3& v) {
    double m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    if (!(m > 0.0) || !std::isfinite(m)) return glm::dvec3(0.0);
    return v / m;
}

}  // namespace

void Pose::frame(glm::dvec3& x, glm::dvec3& y, glm::dvec3& z) const {
    glm::dvec3 a = rescaled(aim);
    double la = glm::length(a);
    // A zero or non-finite aim cannot come from a checked scene file; fall back to straight down.
    z = la > 0.0 ? a / la : glm::dvec3(0.0, -1.0, 0.0);

    // Gram-Schmidt of c0 against z, on the rescaled c0 (whose largest component is 1): a residual
    // below 1e-9 means c0 is parallel to aim to within ~1e-9 rad and carries no usable direction.
    glm::dvec3 c = rescaled(c0);
    c -= glm::dot(c, z) * z;
    double lc = glm::length(c);
    if (!(lc > 1e-9)) {
        // Use the world axis along z's smallest component: it makes an angle of at least
        // acos(1/sqrt(3)) with z, so the projection below has length >= sqrt(2/3).
        glm::dvec3 m = glm::abs(z);
        glm::dvec3 axis = m.x <= m.y && m.x <= m.z ? glm::dvec3(1.0, 0.0, 0.0)
                          : m.y <= m.z             ? glm::dvec3(0.0, 1.0, 0.0)
                                                   : glm::dvec3(0.0, 0.0, 1.0);
        c = axis - glm::dot(axis, z) * z;
        lc = glm::length(c);
    }
    x = c / lc;
    // Re-orthogonalise once more: removes the rounding left by a nearly parallel c0.
    x = glm::normalize(x - glm::dot(x, z) * z);
    y = glm::cross(z, x);
}

glm::dvec3 Pose::toLocal(const glm::dvec3& p) const {
    glm::dvec3 x, y, z;
    frame(x, y, z);
    glm::dvec3 d = p - position;
    return {glm::dot(d, x), glm::dot(d, y), glm::dot(d, z)};
}

glm::dvec3 Pose::toWorldDir(const glm::dvec3& v) const {
    glm::dvec3 x, y, z;
    frame(x, y, z);
    return v.x * x + v.y * y + v.z * z;
}

}  // namespace candela

namespace candela {

Luminaire::Luminaire(std::shared_ptr<const LuminaireModel> model) : mModel(std::move(model)) {}

void Luminaire::setModel(std::shared_ptr<const LuminaireModel> model) {
    mModel = std::move(model);
}

namespace {

struct KindName {
    LuminaireKind kind;
    std::string_view name;
};
constexpr KindName kKindNames[] = {
    {LuminaireKind::LambertianRect, "lambertian-rect"},
    {LuminaireKind::LightField, "lightfield"},
    {LuminaireKind::Photometric, "photometric"},
    {LuminaireKind::Environment, "environment"},
};

}  // namespace

std::string_view kindName(LuminaireKind kind) {
    for (const KindName& k : kKindNames)
        if (k.kind == kind) return k.name;
    return "unknown";
}

bool kindNamed(std::string_view name, LuminaireKind& kind) {
    for (const KindName& k : kKindNames)
        if (k.name == name) {
            kind = k.kind;
            return true;
        }
    return false;
}

}  // namespace candela
