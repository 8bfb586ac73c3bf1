#include "calculation/Glare.h"

#include <cmath>

#include "luminaires/photometric/PhotometricLuminaire.h"
#include "scene/Scene.h"
#include "shaders/shared/Constants.h"
#include "util/Error.h"

namespace candela {

namespace {

using gpu::kPi;
constexpr double kDeg = 180.0 / kPi;
const glm::dvec3 kUp{0.0, 1.0, 0.0};

}  // namespace

double guthPositionIndex(const glm::dvec3& toSource, const glm::dvec3& view, const glm::dvec3& up) {
    double c = glm::dot(toSource, view);
    if (!(c > 0.0)) return 0.0;
    if (c >= 1.0) return 1.0;
    double s = std::sqrt(1.0 - c * c);
    double sigma = std::acos(c) * kDeg;
    double cosTau = std::min(std::abs(glm::dot(toSource, up)) / s, 1.0);
    double tau = std::acos(cosTau) * kDeg;
    double first = (35.2 - 0.31889 * tau - 1.22 * std::exp(-2.0 * tau / 9.0)) * 1e-3;
    double second = (21.0 + 0.26667 * tau - 0.002963 * tau * tau) * 1e-5;
    return std::exp(sigma * first + sigma * sigma * second);
}

namespace {

/// `units`: the scene's (Scene::units(), which looks at every luminaire: found once, not per
/// luminaire).
GlareSource seenBy(const Scene& scene, const UnitSystem& units, const Luminaire& luminaire,
                   const GlareObserver& o) {
    GlareSource g;
    g.luminaire = luminaire.name;
    const PhotometricLuminaire* p = photometricModel(luminaire);
    if (!p || !p->data) {
        g.excluded = "not a photometric luminaire: UGR needs a luminaire's intensity table";
        return g;
    }
    glm::dvec3 x, y, z;
    p->photometricFrame(luminaire.pose, x, y, z);
    glm::dvec3 centre = luminaire.emitterPose().position;
    glm::dvec3 toEye = o.position - centre;
    g.distance = glm::length(toEye);
    if (!(g.distance > 0.0)) {
        g.excluded = "at the eye";
        return g;
    }
    glm::dvec3 toSource = -toEye / g.distance;
    g.positionIndex = guthPositionIndex(toSource, o.view, kUp);
    if (!(centre.y > o.position.y)) {
        g.excluded = "not above eye height (outside Guth's position index)";
        return g;
    }
    if (!(g.positionIndex > 0.0)) {
        g.excluded = "behind the eye's frontal plane";
        return g;
    }
    g.intensity = p->intensity(luminaire.pose, toEye) * scene.lightScale(luminaire, units);
    g.projectedArea = p->area() * std::abs(glm::dot(z, toEye / g.distance));
    g.solidAngle = g.projectedArea / (g.distance * g.distance);
    double p2 = g.positionIndex * g.positionIndex;
    if (g.projectedArea < kSmallSourceArea) {
        // CIE 147: L^2 omega = I^2 / (A r^2) grows without bound as A shrinks; a small source's
        // glare depends on its intensity alone, as if it were 0.005 m2.
        g.small = true;
        g.luminance = g.projectedArea > 0.0 ? g.intensity / g.projectedArea : 0.0;
        g.term = 200.0 * g.intensity * g.intensity / (g.distance * g.distance * p2);
    } else {
        g.luminance = g.intensity / g.projectedArea;
        g.term = g.luminance * g.luminance * g.solidAngle / p2;
        g.large = g.solidAngle > kLargeSourceSolidAngle;
    }
    return g;
}

}  // namespace

GlareReport computeGlare(const Scene& scene, const GridSpec& how,
                         const std::vector<GlareObserver>& given,
                         const std::function<void(const std::string&)>& status) {
    const std::vector<GlareObserver>& observers = given.empty() ? scene.glareObservers : given;
    if (observers.empty())
        throw InputError(scene.path +
                         ": no glare observers (add \"glare_observers\" to the scene, or place an "
                         "observer)");
    if (!scene.units().photometric)
        throw InputError(scene.path +
                         ": UGR is photometric (cd/m2), and every source of this scene is "
                         "radiometric");
    GlareReport report;
    report.maintenance = scene.maintenanceNote();
    report.bodies = scene.bodiesNote();
    std::vector<Receiver> eyes;
    for (const GlareObserver& o : observers)
        if (o.background <= 0.0) eyes.push_back({o.position, o.view});
    ReceiverResult indirect;
    if (!eyes.empty()) {
        if (!scene.hasSurfaces())
            throw InputError(scene.path + ": observer \"" + observers[0].name +
                             "\" needs the background luminance, from light the room reflects, "
                             "and the scene has no surfaces: give \"background_cd_m2\" (or "
                             "--background)");
        GridSpec withIndirect = how;
        withIndirect.indirect = true;
        indirect = computeReceivers(scene, withIndirect, eyes, status);
    }
    size_t eye = 0;
    for (const GlareObserver& o : observers) {
        GlareResult r;
        r.observer = o;
        if (o.background > 0.0) {
            r.background = o.background;
        } else {
            double e = indirect.indirect[eye];
            r.indirectStdError = indirect.indirectStdError[eye];
            ++eye;
            r.background = e / kPi;
            r.backgroundFromIndirect = true;
            if (!(r.background > 0.0))
                throw InputError(scene.path + ": observer \"" + o.name +
                                 "\": no light reflected to the eye (background luminance 0 "
                                 "cd/m2), so UGR is unbounded; give \"background_cd_m2\"");
        }
        double sum = 0.0;
        UnitSystem units = scene.units();
        for (const auto& l : scene.luminaires) {
            r.sources.push_back(seenBy(scene, units, *l, o));
            if (r.sources.back().excluded.empty()) sum += r.sources.back().term;
        }
        r.ugr = sum > 0.0 ? 8.0 * std::log10(0.25 / r.background * sum) : 0.0;
        r.passes = o.limit <= 0.0 || r.ugr <= o.limit;
        report.observers.push_back(std::move(r));
    }
    return report;
}

}  // namespace candela
