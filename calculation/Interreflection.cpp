#include "calculation/Interreflection.h"

#include <cmath>

#include "calculation/SettingError.h"
#include "luminaires/Random.h"
#include "luminaires/environment/EnvironmentSampling.h"
#include "scene/EmbreeVisibility.h"
#include "scene/Scene.h"
#include "shaders/shared/Constants.h"
#include "util/Activity.h"
#include "util/Error.h"

namespace candela {

namespace {
using gpu::kPi;
}  // namespace

/// What a source's direct light depends on: its model (shared and immutable, so the same object
/// is the same emission), where it is placed, the technique and the unit scale; for the
/// environment, also the scene's description of it.
struct SourceIdentity {
    std::shared_ptr<const LuminaireModel> model;
    Pose pose;
    const TechniqueInfo* technique = nullptr;
    double scale = 1.0;
    std::string environment;
    bool operator==(const SourceIdentity&) const = default;
};

struct Interreflection::Source {
    SourceIdentity key;                          ///< What its direct light depends on.
    std::shared_ptr<const Luminaire> luminaire;  ///< Its own copy (a luminaire or the environment).
    const Luminaire* origin = nullptr;           ///< The scene's, while sync() runs.
    IrradianceFn irradiance = nullptr;
    double scale = 1.0;              ///< The scene's unit conversion.
    int spp = 0;                     ///< Samples of `direct`.
    std::vector<glm::dvec3> direct;  ///< Per patch.

    Estimate estimate(const glm::dvec3& p, const glm::dvec3& n, const EstimateOptions& o) const {
        Estimate e = irradiance(*luminaire, p, n, o);
        e.irradiance *= scale;
        e.stdError *= scale;
        return e;
    }
};

namespace {

/// A seed that is the same on every run for the same placement and technique (the model's
/// address is not: it does not take part).
uint64_t seedOf(const SourceIdentity& key, int spp) {
    uint64_t seed = 0x5eed0000ull + uint64_t(spp);
    auto mix = [&](const void* data, size_t bytes) {
        const auto* b = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < bytes; ++i) seed = seed * 131ull + b[i];
    };
    LuminaireKind kind = key.model->kind();
    mix(&kind, sizeof kind);
    mix(key.technique->name.data(), key.technique->name.size());
    for (const glm::dvec3* v : {&key.pose.position, &key.pose.aim, &key.pose.c0}) mix(v, sizeof *v);
    mix(&key.scale, sizeof key.scale);
    mix(key.environment.data(), key.environment.size());
    return seed;
}

}  // namespace

Interreflection::Interreflection(const Scene& scene, const InterreflectionOptions& options)
    : mGeometry(scene), mOptions(options), mVisibility(std::make_unique<EmbreeVisibility>(scene)) {
    ScopedActivity activity("building the interreflection's patches of " +
                            (scene.path.empty() ? std::string("the scene") : scene.path));
    mMesh = RadiosityMesh::build(scene, options.mesh);
    mDirectTotal.assign(mMesh.patches.size(), glm::dvec3(0.0));
    mIndirect.assign(mMesh.patches.size(), glm::dvec3(0.0));
    mIndirectVertices.assign(mMesh.vertices.size(), glm::dvec3(0.0));
    mTotalVertices.assign(mMesh.vertices.size(), glm::dvec3(0.0));
}

Interreflection::~Interreflection() = default;

size_t Interreflection::sourceCount() const {
    return mSources.size();
}

int Interreflection::samples() const {
    int fewest = 0;
    for (size_t i = 0; i < mSources.size(); ++i)
        fewest = i == 0 ? mSources[i].spp : std::min(fewest, mSources[i].spp);
    return fewest;
}

bool Interreflection::hasInterreflection() const {
    if (!mMesh.reflects()) return false;
    for (float v : mTransfer.t)
        if (v > 0.f) return true;
    return !mTransferBuilt;  // unknown until the form factors exist
}

bool Interreflection::buildTransfer(const Progress& progress) {
    mTransferBuilt = mTransfer.build(mMesh, *mVisibility, mOptions.threads, progress);
    return mTransferBuilt;
}

bool Interreflection::computeDirect(Source& s, int spp, std::vector<glm::dvec3>& out,
                                    const Progress& progress) const {
    EstimateOptions o;
    o.spp = spp;
    o.seed = seedOf(s.key, spp);
    o.visibility = mVisibility.get();
    // Its own body receives none of its light: the photometry already holds what the housing
    // does to it (points on the body lie on the opening, or behind it).
    std::vector<bool> ownBody(mMesh.bodyBounds.size(), false);
    if (!s.luminaire->atInfinity()) {
        glm::dvec3 centre = s.luminaire->emitterPose().position;
        for (size_t b = 0; b < ownBody.size(); ++b)
            ownBody[b] = insideBody(centre, mMesh.bodyBounds[b].first, mMesh.bodyBounds[b].second);
    }
    auto estimate = [&](const glm::dvec3& p, const glm::dvec3& n, const EstimateOptions& opt) {
        return s.estimate(p, n, opt);
    };
    auto dark = [&](size_t i) {
        int b = mMesh.patches[i].body;
        return b >= 0 && ownBody[size_t(b)];
    };
    return directOnPatches(mMesh, estimate, o, mOptions.threads, out, progress, dark);
}

bool Interreflection::solveChange(const std::vector<glm::dvec3>& change, const Progress& progress) {
    // E_ind is linear in E_dir: solve for the change and add it.
    std::vector<glm::dvec3> delta;
    int iterations = solveRadiosity(mTransfer, mMesh, change, delta, mOptions.tolerance,
                                    mOptions.threads, progress);
    if (iterations < 0) return false;
    mLastIterations = iterations;
    for (size_t i = 0; i < change.size(); ++i) {
        mDirectTotal[i] += change[i];
        mIndirect[i] =
            glm::max(mIndirect[i] + delta[i], glm::dvec3(0.0));  // rounding of differences
        mDirectTotal[i] = glm::max(mDirectTotal[i], glm::dvec3(0.0));
    }
    mIndirectVertices = vertexValues(mMesh, mIndirect);
    std::vector<glm::dvec3> total(mIndirect.size());
    for (size_t i = 0; i < total.size(); ++i) total[i] = mDirectTotal[i] + mIndirect[i];
    mTotalVertices = vertexValues(mMesh, total);
    return true;
}

std::vector<Interreflection::Source> Interreflection::currentSources(const Scene& scene) const {
    std::vector<Source> fresh;
    UnitSystem units = scene.units();
    for (const auto& l : scene.luminaires) {
        // As `candela probe --technique`: the named technique where the kind has it, else the
        // luminaire's own.
        std::string name =
            findTechnique(l->kind(), mOptions.technique) ? mOptions.technique : l->technique;
        const TechniqueInfo* t = findTechnique(l->kind(), name);
        if (!t || !t->irradiance)
            throw SettingError(
                "technique",
                "\"" + name + "\" is not a technique of " + std::string(kindName(l->kind())) +
                    " with a CPU estimator (available: " + techniqueNames(l->kind()) + ")");
        Source s;
        s.origin = l.get();
        s.irradiance = t->irradiance;
        s.scale = scene.lightScale(*l, units);
        s.key = {l->sharedModel(), l->pose, t, s.scale, {}};
        fresh.push_back(std::move(s));
    }
    if (scene.environmentMap) {
        std::string name =
            mOptions.environmentTechnique.empty() ? "balanced-mis" : mOptions.environmentTechnique;
        Source s;
        const TechniqueInfo* t = findTechnique(LuminaireKind::Environment, name);
        if (!t)
            throw SettingError("environment technique",
                               "\"" + name + "\" is not an environment technique (available: " +
                                   techniqueNames(LuminaireKind::Environment) + ")");
        s.origin = scene.environmentLight();
        s.irradiance = t->irradiance;
        s.scale = scene.environmentUnitScale();
        // The light is made for the map the scene holds (Scene::environmentLight): the same map,
        // the same model.
        s.key = {s.origin->sharedModel(), Pose{}, t, s.scale, scene.environment.dump()};
        fresh.push_back(std::move(s));
    }
    return fresh;
}

bool Interreflection::sync(const Scene& scene, int spp, const Progress& progress) {
    if (!mTransferBuilt && !buildTransfer(progress)) return false;
    spp = spp > 0 ? spp : mOptions.directSpp;
    std::vector<Source> fresh = currentSources(scene);
    if (double(fresh.size()) * double(mMesh.patches.size()) > mOptions.maxKeptDirectValues)
        return syncWhole(std::move(fresh), spp, progress);
    // Unchanged sources keep their light; the others get theirs now.
    std::vector<bool> taken(mSources.size(), false);
    // Progress over every source to compute, not each source's patches alone.
    size_t todo = fresh.size(), done = 0;
    Progress each = progress;
    if (progress.report)
        each.report = [&](double f) { progress.report((double(done) + f) / double(todo)); };
    for (Source& s : fresh) {
        for (size_t i = 0; i < mSources.size(); ++i)
            if (!taken[i] && mSources[i].key == s.key) {
                taken[i] = true;
                s.luminaire = mSources[i].luminaire;
                s.direct = std::move(mSources[i].direct);
                s.spp = mSources[i].spp;
                break;
            }
        if (s.spp > 0) continue;
        s.luminaire = s.origin->clone();  // the environment's clone shares its CPU tables
        if (!computeDirect(s, spp, s.direct, each)) {
            // Cancelled: keep the old sources (their light is still in the solution).
            for (size_t i = 0; i < mSources.size(); ++i)
                for (Source& f : fresh)
                    if (taken[i] && f.key == mSources[i].key && !f.direct.empty())
                        mSources[i].direct = std::move(f.direct);
            return false;
        }
        s.spp = spp;
        ++done;
        if (progress.report) progress.report(double(done) / double(todo));
    }
    std::vector<glm::dvec3> change(mMesh.patches.size(), glm::dvec3(0.0));
    for (const Source& s : fresh)
        for (size_t i = 0; i < change.size(); ++i) change[i] += s.direct[i];
    for (size_t i = 0; i < change.size(); ++i) change[i] -= mDirectTotal[i];
    mSources = std::move(fresh);
    if (!solveChange(change, progress)) {
        // The solution lags the sources: solve for the whole direct light next time.
        mDirectTotal.assign(mMesh.patches.size(), glm::dvec3(0.0));
        mIndirect.assign(mMesh.patches.size(), glm::dvec3(0.0));
        for (Source& s : mSources) s.spp = 0;
        return false;
    }
    return true;
}

bool Interreflection::syncWhole(std::vector<Source> fresh, int spp, const Progress& progress) {
    bool same = fresh.size() == mSources.size();
    for (size_t i = 0; same && i < fresh.size(); ++i)
        same = fresh[i].key == mSources[i].key && mSources[i].spp >= spp;
    if (same) return true;
    std::vector<glm::dvec3> change(mMesh.patches.size(), glm::dvec3(0.0)), one;
    size_t done = 0;
    Progress each = progress;
    if (progress.report)
        each.report = [&](double f) { progress.report((double(done) + f) / double(fresh.size())); };
    for (Source& s : fresh) {
        s.luminaire = s.origin ? s.origin->clone() : s.luminaire;
        if (!computeDirect(s, spp, one, each)) return false;  // cancelled: the old light stays
        for (size_t i = 0; i < change.size(); ++i) change[i] += one[i];
        s.spp = spp;
        ++done;
        if (progress.report) progress.report(double(done) / double(fresh.size()));
    }
    for (size_t i = 0; i < change.size(); ++i) change[i] -= mDirectTotal[i];
    mSources = std::move(fresh);
    if (!solveChange(change, progress)) {
        mDirectTotal.assign(mMesh.patches.size(), glm::dvec3(0.0));
        mIndirect.assign(mMesh.patches.size(), glm::dvec3(0.0));
        for (Source& s : mSources) s.spp = 0;
        return false;
    }
    return true;
}

bool Interreflection::refine(int spp, const Progress& progress) {
    if (double(mSources.size()) * double(mMesh.patches.size()) > mOptions.maxKeptDirectValues) {
        std::vector<Source> again;
        for (const Source& s : mSources) {
            Source copy;
            copy.key = s.key;
            copy.luminaire = s.luminaire;
            copy.irradiance = s.irradiance;
            copy.scale = s.scale;
            copy.spp = s.spp;
            again.push_back(std::move(copy));
        }
        return syncWhole(std::move(again), spp, progress);
    }
    std::vector<glm::dvec3> change(mMesh.patches.size(), glm::dvec3(0.0));
    bool any = false;
    for (Source& s : mSources) {
        if (s.spp >= spp) continue;
        std::vector<glm::dvec3> better;
        if (!computeDirect(s, spp, better, progress)) return false;
        for (size_t i = 0; i < change.size(); ++i) change[i] += better[i] - s.direct[i];
        s.direct = std::move(better);
        s.spp = spp;
        any = true;
    }
    if (!any) return true;
    if (!solveChange(change, progress)) {
        for (Source& s : mSources) s.spp = 0;  // out of step: the next sync recomputes
        mDirectTotal.assign(mMesh.patches.size(), glm::dvec3(0.0));
        mIndirect.assign(mMesh.patches.size(), glm::dvec3(0.0));
        return false;
    }
    return true;
}

bool Interreflection::compute(const Progress& progress) {
    ScopedActivity activity("computing the interreflected light of " +
                            (mGeometry.path.empty() ? std::string("the scene") : mGeometry.path));
    return buildTransfer(progress) && sync(mGeometry, mOptions.directSpp, progress);
}

glm::dvec3 Interreflection::directAt(const glm::dvec3& x, const glm::dvec3& n,
                                     const EstimateOptions& o, int body) const {
    glm::dvec3 sum(0.0);
    for (size_t s = 0; s < mSources.size(); ++s) {
        const Luminaire& l = *mSources[s].luminaire;
        if (body >= 0 && !l.atInfinity() &&
            insideBody(l.emitterPose().position, mMesh.bodyBounds[size_t(body)].first,
                       mMesh.bodyBounds[size_t(body)].second))
            continue;  // its own body: none of its light (computeDirect)
        EstimateOptions so = o;
        so.seed = o.seed * 31ull + s;
        Estimate e = mSources[s].estimate(x, n, so);
        if (std::isfinite(e.irradiance.x + e.irradiance.y + e.irradiance.z)) sum += e.irradiance;
    }
    return sum;
}

std::string Interreflection::orientationWarning(const Scene& scene) const {
    const int kRays = 1024;
    for (const auto& l : scene.luminaires) {
        glm::dvec3 x, y, z;
        Pose emitter = l->emitterPose();
        emitter.frame(x, y, z);
        int hits = 0, backs = 0;
        for (int i = 0; i < kRays; ++i) {
            double cz = 1.0 - (2.0 * i + 1.0) / kRays, r = std::sqrt(std::max(0.0, 1.0 - cz * cz));
            double phi = i * 2.39996322972865332;  // a Fibonacci sphere
            glm::dvec3 d(r * std::cos(phi), cz, r * std::sin(phi));
            EmbreeVisibility::Hit hit;
            if (!mVisibility->intersect(emitter.position + 1e-3 * z, d, hit)) continue;
            glm::dvec3 w;
            uint32_t p = mMesh.patchAt(hit.mesh, hit.triangle, hit.u, hit.v, w);
            if (p == UINT32_MAX) continue;
            // Its own body, seen from inside, takes none of its light (RadiosityMesh::body).
            int body = mMesh.patches[p].body;
            if (body >= 0 && insideBody(emitter.position, mMesh.bodyBounds[size_t(body)].first,
                                        mMesh.bodyBounds[size_t(body)].second))
                continue;
            ++hits;
            backs += glm::dot(mMesh.patches[p].normal, d) > 0.0;
        }
        if (hits > 0 && backs > hits / 4)
            return "luminaire \"" + l->name + "\" lights the back of surfaces (" +
                   std::to_string(100 * backs / hits) +
                   " % of the surfaces around it), which reflect nothing: surfaces reflect on "
                   "their normal's side "
                   "(a room: a box with \"inside\": true, planes with normals into the room)";
    }
    return {};
}

glm::dvec3 Interreflection::fromPatches(const glm::dvec3& p, const glm::dvec3& normal) const {
    glm::dvec3 unused;
    return patchLight(p, normal, false, unused);
}

glm::dvec3 Interreflection::fromPatches(const glm::dvec3& p, const glm::dvec3& normal,
                                        glm::dvec3& error) const {
    return patchLight(p, normal, true, error);
}

glm::dvec3 Interreflection::patchLight(const glm::dvec3& p, const glm::dvec3& normal, bool refine,
                                       glm::dvec3& error) const {
    error = glm::dvec3(0.0);
    double len = glm::length(normal);
    if (!(len > 0.0)) return glm::dvec3(0.0);
    glm::dvec3 n = normal / len, sum(0.0);
    // How much of a triangle p sees: its centroid and, where asked, three inner points (the
    // direct light's rule): the fraction of them visible.
    auto seen = [&](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, bool inner) {
        glm::dvec3 centre = (a + b + c) / 3.0;
        int visible = mVisibility->visibleBetweenSurfaces(p, centre), tried = 1;
        if (inner) {
            for (const glm::dvec3& x : rulePoints(a, b, c)) {
                visible += mVisibility->visibleBetweenSurfaces(p, x);
                ++tried;
            }
        }
        return double(visible) / double(tried);
    };
    for (size_t j = 0; j < mMesh.patches.size(); ++j) {
        const RadiosityMesh::Patch& q = mMesh.patches[j];
        if (!(q.albedo.x + q.albedo.y + q.albedo.z > 0.0)) continue;
        if (!(glm::dot(q.normal, p - q.centroid) > 0.0)) continue;  // p behind its reflecting side
        double f = mMesh.formFactorTo(p, n, uint32_t(j));
        if (!(f > 0.0)) continue;
        glm::dvec3 total = mDirectTotal[j] + mIndirect[j];
        if (q.cluster) {
            // Its stand-in is off the surface: seen or not at its centroid, never split; near
            // p, all of its share is unsure (a final gather takes over).
            double v = mVisibility->visibleBetweenSurfaces(p, q.centroid) ? 1.0 : 0.0;
            sum += v * f * q.albedo * total;
            if (refine && f > kRefineFormFactor) error += v * f * q.albedo * total;
            continue;
        }
        const glm::dvec3 a = mMesh.vertices[q.vertex[0]], b = mMesh.vertices[q.vertex[1]],
                         c = mMesh.vertices[q.vertex[2]];
        // Refined: near p (its form factor above kRefineFormFactor), or seen in part (an edge of
        // an occluder crosses it: its inner points disagree).
        bool inner = refine && f > kVisibilityFormFactor;
        double v = seen(a, b, c, inner);
        bool partial = v > 0.0 && v < 1.0;
        if (!refine || (f <= kRefineFormFactor && !partial)) {
            sum += v * f * q.albedo * total;
            continue;
        }
        // Split into four at the edges' midpoints, again wherever a part's form factor is above
        // the threshold or it is seen in part (down to kRefineDepth): each part valued at its
        // centroid by the vertices' linear interpolation there, less its mean over the patch
        // (the vertices' mean), plus the patch's own value, times the part of it p sees.
        const glm::dvec3 va = mTotalVertices[q.vertex[0]], vb = mTotalVertices[q.vertex[1]],
                         vc = mTotalVertices[q.vertex[2]];
        glm::dvec3 mean = (va + vb + vc) / 3.0;
        struct Part {
            glm::dvec3 corner[3], weight[3];  // positions, and barycentrics in (a, b, c)
            int depth;
        };
        Part stack[3 * kRefineDepth + 4];
        int top = 0;
        auto split = [&](const Part& t) {
            glm::dvec3 m[3], mw[3];
            for (int e = 0; e < 3; ++e) {
                m[e] = 0.5 * (t.corner[e] + t.corner[(e + 1) % 3]);
                mw[e] = 0.5 * (t.weight[e] + t.weight[(e + 1) % 3]);
            }
            int d = t.depth + 1;
            stack[top++] = {{t.corner[0], m[0], m[2]}, {t.weight[0], mw[0], mw[2]}, d};
            stack[top++] = {{m[0], t.corner[1], m[1]}, {mw[0], t.weight[1], mw[1]}, d};
            stack[top++] = {{m[2], m[1], t.corner[2]}, {mw[2], mw[1], t.weight[2]}, d};
            stack[top++] = {{m[0], m[1], m[2]}, {mw[0], mw[1], mw[2]}, d};
        };
        split({{a, b, c}, {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, 0});
        // `flat`: the same parts with the patch's own value: what the tilt alone changes.
        glm::dvec3 refined(0.0), flat(0.0), unsure(0.0);
        while (top > 0) {
            Part t = stack[--top];
            double fk = pointTriangleFormFactor(p, n, t.corner[0], t.corner[1], t.corner[2]);
            if (!(fk > 0.0)) continue;
            double vk = seen(t.corner[0], t.corner[1], t.corner[2], partial);
            bool partialPart = vk > 0.0 && vk < 1.0;
            if ((fk > kRefineFormFactor || partialPart) && t.depth < kRefineDepth) {
                split(t);
                continue;
            }
            glm::dvec3 w = (t.weight[0] + t.weight[1] + t.weight[2]) / 3.0;
            glm::dvec3 value =
                glm::max(total + w.x * va + w.y * vb + w.z * vc - mean, glm::dvec3(0.0));
            refined += vk * fk * q.albedo * value;
            flat += vk * fk * q.albedo * total;
            // A part still seen in part at the last level: its light is known to within
            // the unseen or seen share, whichever is smaller.
            if (partialPart) unsure += std::min(vk, 1.0 - vk) * fk * q.albedo * value;
        }
        sum += refined;
        error += glm::abs(refined - flat) + unsure;
    }
    return sum;
}

Estimate Interreflection::gather(const glm::dvec3& p, const glm::dvec3& normal,
                                 const EstimateOptions& options, int directSpp) const {
    Estimate out;
    double len = glm::length(normal);
    if (!(len > 0.0) || options.spp <= 0 || mMesh.patches.empty()) return out;
    glm::dvec3 n = normal / len;
    // An orthonormal frame around n (Duff et al. 2017).
    double sign = std::copysign(1.0, n.z), a = -1.0 / (sign + n.z), b = n.x * n.y * a;
    glm::dvec3 t(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        bt(b, sign + n.y * n.y * a, -n.y);
    // Stratified cosine-weighted directions: a k x k grid of jittered cells (Malley's method),
    // then the remainder unstratified.
    int k = int(std::floor(std::sqrt(double(options.spp))));
    Random rng(options.seed * 0x2545F4914F6CDD1Dull + 17);
    EstimateOptions direct;
    direct.spp = directSpp;
    direct.visibility = mVisibility.get();
    glm::dvec3 mean(0.0), m2(0.0);
    glm::dvec3 origin = p + n * (1e-4 * std::max(1.0, glm::length(p)));
    for (int i = 0; i < options.spp; ++i) {
        double u1 = rng.uniform(), u2 = rng.uniform();
        if (i < k * k) {
            u1 = (double(i % k) + u1) / k;
            u2 = (double(i / k) + u2) / k;
        }
        double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
        glm::dvec3 w = glm::normalize(r * std::cos(phi) * t + r * std::sin(phi) * bt +
                                      std::sqrt(std::max(0.0, 1.0 - u1)) * n);
        glm::dvec3 f(0.0);
        EmbreeVisibility::Hit hit;
        if (mVisibility->intersect(origin, w, hit)) {
            glm::dvec3 weights;
            uint32_t patch = mMesh.patchAt(hit.mesh, hit.triangle, hit.u, hit.v, weights);
            if (patch != UINT32_MAX) {
                const RadiosityMesh::Patch& q = mMesh.patches[patch];
                // Only the reflecting side sends light back (rays reach it against its normal).
                if (glm::dot(q.normal, w) < 0.0 && q.albedo.x + q.albedo.y + q.albedo.z > 0.0) {
                    glm::dvec3 h = origin + hit.t * w;
                    direct.seed = options.seed * 0x9E3779B97F4A7C15ull + uint64_t(i);
                    glm::dvec3 eInd = weights.x * mIndirectVertices[q.vertex[0]] +
                                      weights.y * mIndirectVertices[q.vertex[1]] +
                                      weights.z * mIndirectVertices[q.vertex[2]];
                    f = q.albedo * (directAt(h, q.normal, direct, q.body) + eInd);
                }
            }
        }
        glm::dvec3 d = f - mean;
        mean += d / double(i + 1);
        m2 += d * (f - mean);
    }
    out.irradiance = mean;
    if (options.spp > 1)
        out.stdError = glm::sqrt(glm::max(m2, 0.0) / double(options.spp - 1) / double(options.spp));
    return out;
}

}  // namespace candela
