#pragma once
// Interreflected light of a scene (issue 17, part 3): the radiosity solution of scene/Radiosity.h
// fed by every source (each luminaire and the environment) through its own CPU estimator, kept
// per source so that one moved luminaire updates its share alone, and a final gather that turns it
// into the interreflected irradiance at any point:
//
//   E_ind(p) = (1/N) sum_i rho(h_i) (E_dir(h_i) + E_ind(h_i))
//
// over N cosine-distributed rays from p (stratified) that hit surfaces h_i from their reflecting
// side (Embree), with E_dir(h_i) evaluated at h_i by every source's own estimator and E_ind(h_i)
// interpolated from the radiosity solution: the first bounce is as exact as the direct light
// (near-field light fields and area photometry included), the later ones come from the patches.
// Its standard error is the sample error of the N terms (conservative for stratified rays).
//
// Units: the scene's (Scene::units(): lx, or W/m2 for a radiometric scene).

#include <glm/glm.hpp>

#include <memory>
#include <string>
#include <vector>

#include "luminaires/Registry.h"
#include "scene/Radiosity.h"

namespace candela {

struct Scene;
class EmbreeVisibility;
class EnvironmentLighting;
struct EnvironmentTechniqueInfo;

struct InterreflectionOptions {
    RadiositySettings mesh;
    /// Samples of each direct estimate at a patch point (stochastic techniques, visible
    /// fractions): low, since a patch's value is the mean of three points and the solution
    /// averages many patches.
    int directSpp = 32;
    /// The solver stops when an iteration adds less than this part of the reflected flux.
    double tolerance = 1e-6;
    int threads = 0;  ///< 0: the hardware's.
    /// As `candela probe --technique`: a technique name used by the luminaires whose kind has
    /// it; the others (and every luminaire when empty) use their own.
    std::string technique;
    /// The environment's technique; empty: balanced-mis (unbiased, robust for any map).
    std::string environmentTechnique;
};

class Interreflection {
public:
    /// Sets up the patches and the sources of `scene` (which must outlive this object); throws
    /// InputError for a technique without a CPU estimator. Nothing heavy runs yet.
    Interreflection(const Scene& scene, const InterreflectionOptions& options);
    ~Interreflection();

    /// Everything, in order: the transfer matrix, every source's direct light, the solution.
    /// False when cancelled.
    bool compute(const Progress& progress = {});
    /// The form factors (once per geometry).
    bool buildTransfer(const Progress& progress = {});
    /// Source s's direct light on the patches at `spp` samples (0: options.directSpp), and the
    /// solution updated for the change (by solving for the difference). Sources are the
    /// luminaires in scene order, then the environment when there is one.
    bool updateSource(size_t source, int spp, const Progress& progress = {});
    size_t sourceCount() const;

    const RadiosityMesh& mesh() const { return mMesh; }
    const EmbreeVisibility& visibility() const { return *mVisibility; }
    /// Per patch, RGB in the scene's units: the direct light summed over sources, and the
    /// interreflected light.
    const std::vector<glm::dvec3>& direct() const { return mDirectTotal; }
    const std::vector<glm::dvec3>& indirect() const { return mIndirect; }
    /// The interreflected irradiance per vertex (display: Gouraud over the patches).
    std::vector<glm::dvec3> indirectAtVertices() const { return vertexValues(mMesh, mIndirect); }
    /// Iterations of the last solve.
    int lastIterations() const { return mLastIterations; }
    /// False when no surface reflects (every albedo 0) or no patch sees another: E_ind is 0.
    bool hasInterreflection() const;

    /// The final gather at p for the unit normal n with options.spp rays (seeded by
    /// options.seed; options.visibility is ignored: Embree is used). `directSpp` samples for
    /// each source's estimate at the hit points.
    Estimate gather(const glm::dvec3& p, const glm::dvec3& n, const EstimateOptions& options, int directSpp = 16) const;

private:
    struct Source;
    /// Every source's direct irradiance at point x with normal n, in the scene's units.
    glm::dvec3 directAt(const glm::dvec3& x, const glm::dvec3& n, const EstimateOptions& o) const;

    const Scene& mScene;
    InterreflectionOptions mOptions;
    std::unique_ptr<EmbreeVisibility> mVisibility;
    std::unique_ptr<EnvironmentLighting> mLighting;
    std::vector<Source> mSources;
    RadiosityMesh mMesh;
    TransferMatrix mTransfer;
    bool mTransferBuilt = false;
    std::vector<std::vector<glm::dvec3>> mDirect;  ///< [source][patch]
    std::vector<glm::dvec3> mDirectTotal, mIndirect;
    std::vector<glm::dvec3> mIndirectVertices;     ///< For the gather's interpolation.
    int mLastIterations = 0;
};

}  // namespace candela
