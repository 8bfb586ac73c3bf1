// The calculation grid: illuminance at the points of a grid on an axis-aligned plane from each
// luminaire's CPU estimator in the registry, so every luminaire kind present and future is
// measured by its own technique, and its summary (Emin, Eavg, Emax, U0 = Emin / Eavg).
#include "calculation/CalculationGrid.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <thread>

#include "calculation/Interreflection.h"
#include "calculation/SettingError.h"
#include "luminaires/Registry.h"
#include "luminaires/environment/EnvironmentSampling.h"
#include "scene/EmbreeVisibility.h"
#include "scene/Scene.h"
#include "util/Activity.h"
#include "util/Error.h"
#include "util/Threads.h"

namespace candela {

namespace {

constexpr double kMaxGridPoints = 1e6;  ///< Refuse grids larger than this (a typo in --spacing).

}  // namespace

bool sceneCastsShadows(const Scene& scene) {
    return scene.hasSurfaces() || scene.bodyCount() > 0;
}

bool sceneReflects(const Scene& scene) {
    // One flat floor alone reflects nothing onto itself, but onto every receiver that faces it
    // (a wall's or a face's vertical illuminance, a point under a canopy): any surface counts.
    for (const Mesh& m : scene.meshes)
        if (!m.luminaireBody && m.triangleCount() > 0 && m.material < scene.materials.size() &&
            glm::any(glm::greaterThan(scene.materials[m.material].albedo, glm::vec3(0.f))))
            return true;
    return false;
}

void applyLightChoice(const Scene& scene, const LightChoice& choice, GridSpec& spec) {
    spec.visibility = choice.shadows && sceneCastsShadows(scene);
    spec.indirect = choice.interreflection && (choice.insist || sceneReflects(scene));
}

std::string lightStatement(const Scene& scene, const GridSpec& spec) {
    std::string s = "direct light";
    if (spec.visibility)
        s += " with shadows";
    else if (sceneCastsShadows(scene))
        s += " without shadows (switched off)";
    else
        s += " (nothing in the scene casts a shadow)";
    if (spec.indirect)
        s += ", and interreflected light";
    else if (sceneReflects(scene))
        s += "; no interreflected light (switched off)";
    else
        s += "; no interreflected light (no surface reflects)";
    return s;
}

std::vector<double> gridCoordinates(double lo, double hi, double spacing) {
    double n = std::max(1.0, std::floor((hi - lo) / spacing + 1e-9));
    double first = 0.5 * (lo + hi) - 0.5 * (n - 1.0) * spacing;
    std::vector<double> out;
    for (int i = 0; i < int(n); ++i) out.push_back(first + i * spacing);
    return out;
}

namespace {

/// A long step's progress for `status`: "STEP, 30 %" at every tenth, once the step has run for a
/// second (a quick one says nothing). Called from one thread.
std::function<void(double)> tenths(const std::function<void(const std::string&)>& status,
                                   const std::string& step) {
    if (!status) return nullptr;
    return [status, step, start = std::chrono::steady_clock::now(), shown = 0](double f) mutable {
        int tenth = int(std::floor(10.0 * std::clamp(f, 0.0, 1.0)));
        if (tenth <= shown || tenth >= 10 ||
            std::chrono::steady_clock::now() - start < std::chrono::seconds(1))
            return;
        shown = tenth;
        status(step + ", " + std::to_string(10 * tenth) + " %");
    };
}

/// The interreflected part of every receiver: the radiosity solution, then a final gather of spp
/// rays per receiver (over the hardware's threads), added to E with its standard error.
void addIndirect(const Scene& scene, const GridSpec& spec, const std::vector<Receiver>& receivers,
                 ReceiverResult& r, const std::function<void(const std::string&)>& status) {
    if (!scene.hasSurfaces())
        throw InputError(
            (scene.path.empty() ? std::string("the scene") : scene.path) +
            ": geometry: no surfaces, so no light is interreflected (--indirect needs a room)");
    InterreflectionOptions o;
    o.mesh.targetPatches = spec.patches;
    o.technique = spec.technique;
    Interreflection ir(scene, o);
    auto say = [&](const std::string& s) {
        if (status) status(s);
    };
    say("interreflection: " + std::to_string(ir.mesh().patches.size()) + " patches, form factors");
    if (std::string warning = ir.orientationWarning(scene); !warning.empty())
        say("warning: " + warning);
    auto stepProgress = [&](const std::string& step) {
        Progress p;
        p.report = tenths(status, "interreflection: " + step);
        return p;
    };
    {
        ScopedActivity activity("computing the interreflected light of " +
                                (scene.path.empty() ? std::string("the scene") : scene.path));
        if (!ir.buildTransfer(stepProgress("form factors")) ||
            !ir.sync(scene, 0,
                     stepProgress(
                         "direct light on the patches from " +
                         std::to_string(scene.luminaires.size() + (scene.environmentMap ? 1 : 0)) +
                         " sources")))
            throw InputError("interreflection: cancelled");
    }
    say("interreflection: solved in " + std::to_string(ir.lastIterations()) +
        " iterations; final gather at " + std::to_string(receivers.size()) + " points");
    size_t count = receivers.size();
    r.indirect.assign(count, 0.0);
    r.indirectStdError.assign(count, 0.0);
    std::atomic<size_t> next{0}, gathered{0};
    auto work = [&] {
        for (size_t index; (index = next.fetch_add(1)) < count;) {
            EstimateOptions g;
            g.spp = std::max(1, spec.spp);
            g.seed = 7777ull * index + 13;
            glm::dvec3 p = receivers[index].position, n = receivers[index].normal;
            Estimate e;
            if (spec.indirectMethod == GridSpec::Indirect::Patches) {
                e.irradiance = ir.fromPatches(p, n);
            } else if (spec.indirectMethod == GridSpec::Indirect::Adaptive) {
                glm::dvec3 error;
                e.irradiance = ir.fromPatches(p, n, error);
                double total = r.direct[index] + luminanceOf(e.irradiance);
                if (luminanceOf(error) > GridSpec::kGatherAbove * total) {
                    e = ir.gather(p, n, g);
                    ++gathered;
                }
            } else {
                e = ir.gather(p, n, g);
            }
            r.indirect[index] = luminanceOf(e.irradiance);
            r.indirectStdError[index] = luminanceOf(e.stdError);
        }
    };
    runInParallel(workerThreads(0), work);
    r.hasIndirect = true;
    r.patches = ir.mesh().patches.size();
    std::string rays = std::to_string(std::max(1, spec.spp)) + " rays";
    switch (spec.indirectMethod) {
        case GridSpec::Indirect::Gather:
            r.indirectNote = "interreflected light: a final gather of " + rays + " at every point";
            break;
        case GridSpec::Indirect::Patches:
            r.indirectNote = "interreflected light: the patches' solution at every point";
            break;
        case GridSpec::Indirect::Adaptive: {
            char above[16];
            std::snprintf(above, sizeof above, "%g", 100.0 * GridSpec::kGatherAbove);
            r.indirectNote =
                "interreflected light: the patches' solution, refined near surfaces; a "
                "final gather of " +
                rays + " at " + std::to_string(gathered.load()) + " of " + std::to_string(count) +
                " points, where the patches' error estimate exceeded " + above + " % of the light";
            break;
        }
    }
    for (size_t k = 0; k < count; ++k) {
        r.E[k] = r.direct[k] + r.indirect[k];
        r.stdError[k] = std::sqrt(r.directStdError[k] * r.directStdError[k] +
                                  r.indirectStdError[k] * r.indirectStdError[k]);
    }
}

/// Adds the interreflected light to r.E and to r.initial (which holds the direct light before
/// maintenance). The reflected light is linear in the sources: where every source has one
/// factor, it is the maintained light over that factor; where they differ, a second solution
/// with every factor at 1 gives it.
void addIndirectBeforeMaintenance(const Scene& scene, const GridSpec& spec,
                                  const std::vector<Receiver>& receivers, ReceiverResult& r,
                                  const std::function<void(const std::string&)>& status) {
    addIndirect(scene, spec, receivers, r, status);
    std::vector<double> factors;
    if (scene.environmentMap) factors.push_back(1.0);
    for (const auto& l : scene.luminaires) factors.push_back(scene.maintenanceFactorOf(*l));
    bool common =
        std::all_of(factors.begin(), factors.end(), [&](double f) { return f == factors.front(); });
    if (common) {
        double f = factors.empty() ? 1.0 : factors.front();
        for (size_t k = 0; k < r.initial.size(); ++k) r.initial[k] += r.indirect[k] / f;
        return;
    }
    Scene initial = scene.clone();
    initial.maintenanceFactor = 1.0;
    for (auto& l : initial.luminaires) l->maintenanceFactor.reset();
    ReceiverResult again = r;  // addIndirect fills its E and indirect; only `indirect` is read
    auto say = [&](const std::string& s) {
        if (status) status("before maintenance (luminaires with their own factors): " + s);
    };
    addIndirect(initial, spec, receivers, again, say);
    for (size_t k = 0; k < r.initial.size(); ++k) r.initial[k] += again.indirect[k];
}

}  // namespace

GridSummary summariseGrid(const std::vector<double>& E) {
    GridSummary s;
    s.count = E.size();
    if (E.empty()) return s;
    s.eMin = *std::min_element(E.begin(), E.end());
    s.eMax = *std::max_element(E.begin(), E.end());
    double sum = 0.0;
    for (double e : E) sum += e;
    s.eAvg = sum / double(E.size());
    s.u0 = s.eAvg > 0.0 ? s.eMin / s.eAvg : 0.0;
    s.minOverMax = s.eMax > 0.0 ? s.eMin / s.eMax : 0.0;
    return s;
}

void defaultGridExtent(const Scene& scene, GridSpec& spec) {
    glm::dvec2 lo = spec.plane.inPlane(glm::dvec3(scene.boundsMin()));
    glm::dvec2 hi = spec.plane.inPlane(glm::dvec3(scene.boundsMax()));
    if (scene.meshes.empty() || !(hi.x > lo.x) || !(hi.y > lo.y))
        throw SettingError("extent",
                           "the scene's geometry does not span the plane: give the grid's "
                           "rectangle (u0, v0, u1, v1 in metres)");
    spec.lo = lo;
    spec.hi = hi;
}

GridResult computeGrid(const Scene& scene, const GridSpec& spec,
                       const std::function<void(const std::string& status)>& status) {
    if (!(spec.spacing > 0.0) || !std::isfinite(spec.spacing))
        throw SettingError("spacing", "expected a positive number of metres");
    for (double x : {spec.lo.x, spec.lo.y, spec.hi.x, spec.hi.y})
        if (!std::isfinite(x)) throw SettingError("extent", "expected finite coordinates");
    if (!(spec.hi.x > spec.lo.x) || !(spec.hi.y > spec.lo.y))
        throw SettingError("extent", "expected u1 > u0 and v1 > v0 (an area, not a line)");
    double nu = std::floor((spec.hi.x - spec.lo.x) / spec.spacing) + 1.0;
    double nv = std::floor((spec.hi.y - spec.lo.y) / spec.spacing) + 1.0;
    if (nu * nv > kMaxGridPoints) {
        // Neither flag may have been given (the scene's extent at the default spacing).
        char text[240];
        std::snprintf(text, sizeof text,
                      "the grid at a spacing of %g m over %.4g x %.4g m gives %.4g x %.4g points, "
                      "more than the %.0f allowed: a larger spacing or a smaller extent",
                      spec.spacing, spec.hi.x - spec.lo.x, spec.hi.y - spec.lo.y, nu, nv,
                      double(kMaxGridPoints));
        throw SettingError("spacing", text);
    }
    GridResult r;
    r.spec = spec;
    r.u = gridCoordinates(spec.lo.x, spec.hi.x, spec.spacing);
    r.v = gridCoordinates(spec.lo.y, spec.hi.y, spec.spacing);
    std::vector<Receiver> receivers;
    for (double v : r.v)
        for (double u : r.u) receivers.push_back({spec.plane.point(u, v), spec.plane.normal()});
    ReceiverResult e = computeReceivers(scene, spec, receivers, status);
    r.units = e.units;
    r.maintenance = std::move(e.maintenance);
    r.bodies = std::move(e.bodies);
    r.light = std::move(e.light);
    r.projectFactor = e.projectFactor;
    r.E = std::move(e.E);
    r.stdError = std::move(e.stdError);
    r.hasIndirect = e.hasIndirect;
    r.direct = std::move(e.direct);
    r.directStdError = std::move(e.directStdError);
    r.indirect = std::move(e.indirect);
    r.indirectStdError = std::move(e.indirectStdError);
    r.indirectNote = std::move(e.indirectNote);
    r.patches = e.patches;
    r.initial = std::move(e.initial);
    return r;
}

double effectiveMaintenanceFactor(double E, double initial, double fallback) {
    return initial > 0.0 ? E / initial : fallback;
}

int shadowRays(int spp, double unshadowed, double brightest) {
    if (!(unshadowed > 0.0) || !(brightest > 0.0)) return kMinShadowRays;
    double share = std::min(1.0, unshadowed / brightest);
    return std::clamp(int(std::ceil(double(spp) * share)), std::min(spp, kMinShadowRays), spp);
}

ReceiverResult computeReceivers(const Scene& scene, const GridSpec& spec,
                                const std::vector<Receiver>& receivers,
                                const std::function<void(const std::string& status)>& status) {
    if (double(receivers.size()) > kMaxGridPoints)
        throw InputError("over 1e6 calculation points (" + std::to_string(receivers.size()) + ")");
    for (const Receiver& q : receivers)
        if (!std::isfinite(q.position.x + q.position.y + q.position.z) ||
            !(std::abs(glm::length(q.normal) - 1.0) < 1e-9))
            throw InputError("a calculation point needs a finite position and a unit normal");
    // The environment's technique, as `candela probe` chooses it.
    const TechniqueInfo* envChosen = nullptr;
    if (scene.environmentMap) {
        std::string name = spec.environmentTechnique;
        if (name.empty())
            name = findTechnique(LuminaireKind::Environment, spec.technique) ? spec.technique
                                                                             : "reference";
        envChosen = findTechnique(LuminaireKind::Environment, name);
        if (!envChosen)
            throw SettingError("environment technique",
                               "\"" + name + "\" is not an environment technique (available: " +
                                   techniqueNames(LuminaireKind::Environment) + ")");
    }
    std::vector<const TechniqueInfo*> chosen;
    for (const auto& l : scene.luminaires) {
        std::string name = spec.technique.empty() ? l->technique : spec.technique;
        if (!spec.technique.empty() && !findTechnique(l->kind(), name) &&
            findTechnique(LuminaireKind::Environment, name))
            name = l->technique;  // a name only the environment has leaves luminaires on their own
        const TechniqueInfo* t = findTechnique(l->kind(), name);
        if (!t || !t->irradiance)
            throw SettingError(
                "technique",
                "\"" + name + "\" is not a technique of " + std::string(kindName(l->kind())) +
                    " with a CPU estimator (available: " + techniqueNames(l->kind()) + ")");
        chosen.push_back(t);
    }
    // Shadows through Embree, the ray-traced reference (docs/visibility.md).
    std::unique_ptr<EmbreeVisibility> vis;
    EstimateOptions options;
    options.spp = std::max(1, spec.spp);
    if (spec.visibility) {
        vis = std::make_unique<EmbreeVisibility>(scene);
        options.visibility = vis.get();
    }

    ReceiverResult r;
    r.units = scene.units();
    r.maintenance = scene.maintenanceNote();
    r.bodies = scene.bodiesNote();
    r.light = lightStatement(scene, spec);
    r.projectFactor = scene.maintenanceFactor;
    std::vector<double> scales;      // 683 lm/W for a radiometric luminaire in a mixed scene
    std::vector<double> unitScales;  // the same without maintenance
    for (const auto& l : scene.luminaires) {
        scales.push_back(scene.lightScale(*l, r.units));
        unitScales.push_back(scene.unitScale(*l, r.units));
    }
    const Luminaire* environment = envChosen ? scene.environmentLight() : nullptr;
    double envScale = scene.environmentUnitScale();
    // Every receiver on its own (seeded by its index), over the hardware's threads.
    size_t count = receivers.size();
    r.direct.assign(count, 0.0);
    r.initial.assign(count, 0.0);
    r.directStdError.assign(count, 0.0);
    std::atomic<size_t> next{0}, done{0};
    std::thread::id caller = std::this_thread::get_id();
    auto report = tenths(status, "direct light at " + std::to_string(count) + " points");
    auto work = [&] {
        std::vector<double> unshadowed;  // per luminaire at this receiver; -1: not measured
        std::vector<Estimate> free;      // the same, as the technique gave it (no visibility)
        for (size_t index; (index = next.fetch_add(1)) < count;) {
            glm::dvec3 p = receivers[index].position, n = receivers[index].normal;
            glm::dvec3 e(0.0), var(0.0), before(0.0);  // before: without maintenance
            if (environment) {
                EstimateOptions o = options;
                o.seed = 1000003ull * index + 999983ull;
                Estimate est = envChosen->irradiance(*environment, p, n, o);
                e += envScale * est.irradiance;
                before += envScale * est.irradiance;  // daylight takes no maintenance factor
                var += envScale * envScale * est.stdError * est.stdError;
            }
            // Shadow rays where the light is: an exact technique's rays go to each luminaire in
            // proportion to its unshadowed light here (shadowRays), so a far luminaire of
            // thousands costs a few rays, not spp of them.
            unshadowed.assign(scene.luminaires.size(), -1.0);
            free.resize(scene.luminaires.size());
            double brightest = 0.0;
            if (options.visibility)
                for (size_t k = 0; k < scene.luminaires.size(); ++k) {
                    if (chosen[k]->progressive) continue;
                    EstimateOptions o = options;
                    o.visibility = nullptr;
                    free[k] = chosen[k]->irradiance(*scene.luminaires[k], p, n, o);
                    unshadowed[k] = luminanceOf(scales[k] * free[k].irradiance);
                    brightest = std::max(brightest, unshadowed[k]);
                }
            for (size_t k = 0; k < scene.luminaires.size(); ++k) {
                EstimateOptions o = options;
                o.seed = 1000003ull * index + k + 1;
                if (unshadowed[k] >= 0.0) {
                    o.spp = shadowRays(options.spp, unshadowed[k], brightest);
                    o.unshadowed = &free[k];
                }
                Estimate est = chosen[k]->irradiance(*scene.luminaires[k], p, n, o);
                e += scales[k] * est.irradiance;
                before += unitScales[k] * est.irradiance;
                var += scales[k] * scales[k] * est.stdError * est.stdError;
            }
            r.direct[index] = luminanceOf(e);
            r.initial[index] = luminanceOf(before);
            r.directStdError[index] = luminanceOf(glm::sqrt(var));
            size_t finished = done.fetch_add(1) + 1;
            if (report && std::this_thread::get_id() == caller)
                report(double(finished) / double(count));
        }
    };
    runInParallel(workerThreads(0), work);
    r.E = r.direct;
    r.stdError = r.directStdError;
    if (spec.indirect) addIndirectBeforeMaintenance(scene, spec, receivers, r, status);
    // No infinity or NaN is ever printed as a result: the first such point stops the calculation.
    for (size_t i = 0; i < r.E.size(); ++i)
        if (!std::isfinite(r.E[i]) || !std::isfinite(r.stdError[i])) {
            const glm::dvec3& p = receivers[i].position;
            char at[96];
            std::snprintf(at, sizeof at, "(%.3f, %.3f, %.3f) m", p.x, p.y, p.z);
            throw InputError(
                (scene.path.empty() ? std::string("the scene") : scene.path) + ": the light at " +
                at + " is not a finite number (" +
                (std::isfinite(r.direct[i]) ? "its interreflected part" : "its direct part") +
                "); a luminaire's data or a scene value is out of range");
        }
    return r;
}

}  // namespace candela
