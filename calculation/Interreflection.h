#pragma once
// Interreflected light of a scene (issue 17, part 3): the radiosity solution of
// calculation/Radiosity.h fed by every source (each luminaire and the environment) through its own
// CPU estimator, kept per source so that one moved luminaire updates its share alone, and a final
// gather that turns it into the interreflected irradiance at any point:
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

#include "calculation/Radiosity.h"
#include "luminaires/Registry.h"

namespace candela {

struct Scene;
class EmbreeVisibility;

struct InterreflectionOptions {
    RadiositySettings mesh;
    /// Samples of each direct estimate at a patch point (stochastic techniques, visible
    /// fractions): low, since a patch's value is the mean of three points and the solution
    /// averages many patches.
    int directSpp = 32;
    /// The solver stops when an iteration adds less than this part of the reflected flux.
    double tolerance = 1e-6;
    int threads = 0;  ///< 0: the hardware's.
    /// Patch values (sources x patches) at most that keep each source's direct light apart, so
    /// that a changed luminaire recomputes its own light alone: 20 million (480 MB; 8 000
    /// luminaires at 2 500 patches). Beyond it the sources' light is summed as it is computed
    /// (the memory of one source) and any change recomputes every source.
    double maxKeptDirectValues = 2e7;
    /// As `candela probe --technique`: a technique name used by the luminaires whose kind has
    /// it; the others (and every luminaire when empty) use their own.
    std::string technique;
    /// The environment's technique; empty: balanced-mis (unbiased, robust for any map).
    std::string environmentTechnique;
};

class Interreflection {
  public:
    /// The patches and the shadow-ray scene of `scene`'s geometry (its luminaires and
    /// environment join with sync()). Nothing heavy runs yet.
    Interreflection(const Scene& scene, const InterreflectionOptions& options);
    ~Interreflection();

    /// Everything for `scene` (the one given to the constructor), in order: the transfer matrix,
    /// every source's direct light at options.directSpp, the solution. False when cancelled.
    bool compute(const Progress& progress = {});
    /// The form factors (once per geometry).
    bool buildTransfer(const Progress& progress = {});
    /// Takes the sources of `scene` (the same geometry; copies of its luminaires are kept): a
    /// source whose luminaire (or environment) is unchanged keeps its direct light, a new or
    /// changed one gets it computed at `spp` samples, a removed one is taken out, and the
    /// solution is updated by solving for the change alone. Throws InputError for a technique
    /// without a CPU estimator. False when cancelled (then call it again).
    bool sync(const Scene& scene, int spp, const Progress& progress = {});
    /// Recomputes the sources whose direct light has fewer than `spp` samples (the progressive
    /// refinement after a first, quick sync). False when cancelled.
    bool refine(int spp, const Progress& progress = {});
    size_t sourceCount() const;
    /// Fewest samples of any source's direct light (0 without sources).
    int samples() const;

    const RadiosityMesh& mesh() const { return mMesh; }
    const EmbreeVisibility& visibility() const { return *mVisibility; }
    bool transferBuilt() const { return mTransferBuilt; }
    /// Per patch, RGB in the scene's units: the direct light summed over sources, and the
    /// interreflected light.
    const std::vector<glm::dvec3>& direct() const { return mDirectTotal; }
    const std::vector<glm::dvec3>& indirect() const { return mIndirect; }
    /// The interreflected irradiance per vertex (display: Gouraud over the patches).
    const std::vector<glm::dvec3>& indirectAtVertices() const { return mIndirectVertices; }
    /// Iterations of the last solve.
    int lastIterations() const { return mLastIterations; }
    /// False when no surface reflects (every albedo 0) or no patch sees another: E_ind is 0.
    bool hasInterreflection() const;
    /// Empty, or a warning naming a luminaire most of whose light reaches surfaces from behind
    /// (surfaces reflect on their normal's side only, so such a room reflects nothing back).
    std::string orientationWarning(const Scene& scene) const;

    /// The final gather at p for the unit normal n with options.spp rays (seeded by
    /// options.seed; options.visibility is ignored: Embree is used). `directSpp` samples for
    /// each source's estimate at the hit points.
    Estimate gather(const glm::dvec3& p, const glm::dvec3& n, const EstimateOptions& options,
                    int directSpp = 16) const;
    /// The interreflected irradiance at p from the patches' solution alone (each patch's
    /// reflected light rho (E_dir + E_ind), Lambert's form factor from p, a shadow ray to its
    /// centroid): deterministic, smooth and fast (the editor's grid, the bench's work plane).
    glm::dvec3 fromPatches(const glm::dvec3& p, const glm::dvec3& n) const;
    /// The same, refined where p is close to a patch (its form factor above
    /// kRefineFormFactor) or sees only part of it (an occluder's edge across it: of its
    /// centroid and three inner points, some are seen and some not; looked for on patches
    /// whose form factor is above kVisibilityFormFactor): the patch is split into four, and
    /// each part again while either holds (kRefineDepth levels at most), each part with its own
    /// form factor, the share of those points p sees, and its value (the patch's, tilted by the
    /// vertices' values so that its mean stays the patch's). `error` gets an estimate of what
    /// the result leaves out at p (RGB, the scene's units), summed over the refined patches
    /// without cancelling: what the tilt changed, plus the smaller of the seen and unseen share
    /// of parts still seen in part at the last level. An occluder narrower than a patch can pass
    /// between all four points unseen: the estimate does not hold it.
    glm::dvec3 fromPatches(const glm::dvec3& p, const glm::dvec3& n, glm::dvec3& error) const;
    /// The form factor above which fromPatches refines a patch or a part: nearer than about six
    /// of its sizes. Beyond it the value and visibility vary little over its solid angle.
    static constexpr double kRefineFormFactor = 2e-3;
    /// The form factor above which fromPatches looks for an occluder's edge across a patch
    /// (its three inner points seen or not, against its centroid), refining it where one is.
    static constexpr double kVisibilityFormFactor = 1e-4;
    /// Levels of splitting at most: parts of 1/64 of a patch's size (3 mm of a 0.2 m patch).
    static constexpr int kRefineDepth = 6;

  private:
    /// Both fromPatches: the patches' light at p, refined near it when `refine`.
    glm::dvec3 patchLight(const glm::dvec3& p, const glm::dvec3& n, bool refine,
                          glm::dvec3& error) const;
    struct Source;
    /// The sources of `scene`, each with the key of what its light depends on (no light yet).
    std::vector<Source> currentSources(const Scene& scene) const;
    /// Every source's direct irradiance at point x with normal n, in the scene's units.
    /// `body`: the body (RadiosityMesh::bodyBounds) x lies on, whose luminaire's light it does
    /// not receive; -1 for none.
    glm::dvec3 directAt(const glm::dvec3& x, const glm::dvec3& n, const EstimateOptions& o,
                        int body = -1) const;
    /// The direct light of source s at `spp` samples into s's patch values.
    bool computeDirect(Source& s, int spp, std::vector<glm::dvec3>& out,
                       const Progress& progress) const;
    /// Adds the solution of a change of the direct light to the indirect one.
    bool solveChange(const std::vector<glm::dvec3>& change, const Progress& progress);
    /// sync() and refine() for more sources than keep their own light (maxKeptDirectValues):
    /// every source's light at `spp` samples, summed as it is computed, replaces the direct light.
    bool syncWhole(std::vector<Source> fresh, int spp, const Progress& progress);

    const Scene& mGeometry;
    InterreflectionOptions mOptions;
    std::unique_ptr<EmbreeVisibility> mVisibility;
    std::vector<Source> mSources;
    RadiosityMesh mMesh;
    TransferMatrix mTransfer;
    bool mTransferBuilt = false;
    std::vector<glm::dvec3> mDirectTotal, mIndirect;
    std::vector<glm::dvec3> mIndirectVertices;  ///< For display and the gather's interpolation.
    /// Direct plus interreflected light per vertex (fromPatches' refinement).
    std::vector<glm::dvec3> mTotalVertices;
    int mLastIterations = 0;
};

}  // namespace candela
