#include "scene/Interreflection.h"

#include <cmath>

#include "luminaires/EnvironmentSampling.h"
#include "luminaires/Random.h"
#include "scene/EmbreeVisibility.h"
#include "scene/Scene.h"
#include "util/Error.h"

namespace candela {

namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

struct Interreflection::Source {
    const Luminaire* luminaire = nullptr;               ///< null: the environment
    IrradianceFn irradiance = nullptr;
    const EnvironmentTechniqueInfo* environment = nullptr;
    double scale = 1.0;                                 ///< The scene's unit conversion.

    Estimate estimate(const EnvironmentLighting* lighting, const glm::dvec3& p, const glm::dvec3& n,
                      const EstimateOptions& o) const {
        Estimate e = luminaire ? irradiance(*luminaire, p, n, o) : environment->irradiance(*lighting, p, n, o);
        e.irradiance *= scale;
        e.stdError *= scale;
        return e;
    }
};

Interreflection::Interreflection(const Scene& scene, const InterreflectionOptions& options)
    : mScene(scene), mOptions(options), mVisibility(std::make_unique<EmbreeVisibility>(scene)) {
    for (const auto& l : scene.luminaires) {
        // As `candela probe --technique`: the named technique where the kind has it, else the
        // luminaire's own.
        std::string name = findTechnique(l->kind(), options.technique) ? options.technique : l->technique;
        const TechniqueInfo* t = findTechnique(l->kind(), name);
        if (!t || !t->irradiance)
            throw InputError("--technique: \"" + name + "\" is not a technique of " + std::string(l->kind()) +
                             " with a CPU estimator (available: " + techniqueNames(l->kind()) + ")");
        Source s;
        s.luminaire = l.get();
        s.irradiance = t->irradiance;
        s.scale = scene.unitScale(*l);
        mSources.push_back(s);
    }
    if (scene.environmentMap) {
        std::string name = options.environmentTechnique.empty() ? "balanced-mis" : options.environmentTechnique;
        Source s;
        s.environment = findEnvironmentTechnique(name);
        if (!s.environment)
            throw InputError("--env-technique: \"" + name + "\" is not an environment technique (available: " +
                             environmentTechniqueNames() + ")");
        s.scale = scene.environmentUnitScale();
        mLighting = std::make_unique<EnvironmentLighting>(scene.environmentMap);
        mSources.push_back(s);
    }
    mMesh = RadiosityMesh::build(scene, options.mesh);
    mDirect.assign(mSources.size(), std::vector<glm::dvec3>(mMesh.patches.size(), glm::dvec3(0.0)));
    mDirectTotal.assign(mMesh.patches.size(), glm::dvec3(0.0));
    mIndirect.assign(mMesh.patches.size(), glm::dvec3(0.0));
    mIndirectVertices.assign(mMesh.vertices.size(), glm::dvec3(0.0));
}

Interreflection::~Interreflection() = default;

size_t Interreflection::sourceCount() const { return mSources.size(); }

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

bool Interreflection::updateSource(size_t source, int spp, const Progress& progress) {
    if (source >= mSources.size()) return true;
    if (!mTransferBuilt && !buildTransfer(progress)) return false;
    EstimateOptions o;
    o.spp = spp > 0 ? spp : mOptions.directSpp;
    o.seed = 0x5eed0000ull + source * 7919ull + uint64_t(o.spp);
    o.visibility = mVisibility.get();
    const Source& s = mSources[source];
    const EnvironmentLighting* lighting = mLighting.get();
    std::vector<glm::dvec3> fresh;
    bool done = directOnPatches(
        mMesh, [&](const glm::dvec3& p, const glm::dvec3& n, const EstimateOptions& opt) { return s.estimate(lighting, p, n, opt); },
        o, mOptions.threads, fresh, progress);
    if (!done) return false;
    // E_ind is linear in E_dir: solve for the change and add it (the other sources keep theirs).
    std::vector<glm::dvec3> change(fresh.size()), delta;
    for (size_t i = 0; i < fresh.size(); ++i) change[i] = fresh[i] - mDirect[source][i];
    int iterations = solveRadiosity(mTransfer, mMesh, change, delta, mOptions.tolerance, mOptions.threads, progress);
    if (iterations < 0) return false;
    mLastIterations = iterations;
    for (size_t i = 0; i < fresh.size(); ++i) {
        mDirectTotal[i] += change[i];
        mIndirect[i] += delta[i];
        mIndirect[i] = glm::max(mIndirect[i], glm::dvec3(0.0));  // rounding of differences
    }
    mDirect[source] = std::move(fresh);
    mIndirectVertices = vertexValues(mMesh, mIndirect);
    return true;
}

bool Interreflection::compute(const Progress& progress) {
    if (!mTransferBuilt && !buildTransfer(progress)) return false;
    // All sources at once: one solve for their sum.
    EstimateOptions o;
    o.spp = mOptions.directSpp;
    o.visibility = mVisibility.get();
    std::vector<glm::dvec3> sum(mMesh.patches.size(), glm::dvec3(0.0));
    for (size_t s = 0; s < mSources.size(); ++s) {
        o.seed = 0x5eed0000ull + s * 7919ull + uint64_t(o.spp);
        const Source& src = mSources[s];
        const EnvironmentLighting* lighting = mLighting.get();
        bool done = directOnPatches(
            mMesh,
            [&](const glm::dvec3& p, const glm::dvec3& n, const EstimateOptions& opt) { return src.estimate(lighting, p, n, opt); },
            o, mOptions.threads, mDirect[s], progress);
        if (!done) return false;
        for (size_t i = 0; i < sum.size(); ++i) sum[i] += mDirect[s][i];
    }
    mDirectTotal = sum;
    std::vector<glm::dvec3> indirect;
    int iterations = solveRadiosity(mTransfer, mMesh, mDirectTotal, indirect, mOptions.tolerance, mOptions.threads, progress);
    if (iterations < 0) return false;
    mLastIterations = iterations;
    mIndirect = std::move(indirect);
    mIndirectVertices = vertexValues(mMesh, mIndirect);
    return true;
}

glm::dvec3 Interreflection::directAt(const glm::dvec3& x, const glm::dvec3& n, const EstimateOptions& o) const {
    glm::dvec3 sum(0.0);
    for (size_t s = 0; s < mSources.size(); ++s) {
        EstimateOptions so = o;
        so.seed = o.seed * 31ull + s;
        Estimate e = mSources[s].estimate(mLighting.get(), x, n, so);
        if (std::isfinite(e.irradiance.x + e.irradiance.y + e.irradiance.z)) sum += e.irradiance;
    }
    return sum;
}

Estimate Interreflection::gather(const glm::dvec3& p, const glm::dvec3& normal, const EstimateOptions& options,
                                 int directSpp) const {
    Estimate out;
    double len = glm::length(normal);
    if (!(len > 0.0) || options.spp <= 0 || mMesh.patches.empty()) return out;
    glm::dvec3 n = normal / len;
    // An orthonormal frame around n (Duff et al. 2017).
    double sign = std::copysign(1.0, n.z), a = -1.0 / (sign + n.z), b = n.x * n.y * a;
    glm::dvec3 t(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x), bt(b, sign + n.y * n.y * a, -n.y);
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
        glm::dvec3 w = glm::normalize(r * std::cos(phi) * t + r * std::sin(phi) * bt + std::sqrt(std::max(0.0, 1.0 - u1)) * n);
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
                    f = q.albedo * (directAt(h, q.normal, direct) + eInd);
                }
            }
        }
        glm::dvec3 d = f - mean;
        mean += d / double(i + 1);
        m2 += d * (f - mean);
    }
    out.irradiance = mean;
    if (options.spp > 1) out.stdError = glm::sqrt(glm::max(m2, 0.0) / double(options.spp - 1) / double(options.spp));
    return out;
}

}  // namespace candela
