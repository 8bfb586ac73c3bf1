#pragma once
// Diffuse interreflection by radiosity over patches of the scene's surfaces (issue 17, part 3),
// in double precision on the CPU, with Embree visibility.
//
// The surfaces are cut into small triangles (patches). Each patch reflects on the side its normal
// faces (a plane's `normal`, a box's outside, a glTF mesh's winding), diffusely, with its
// material's `albedo` (a glossy material reflects its diffuse part; specular interreflection and
// transmission are not modelled). Light arrives at each patch directly from every source, each
// through its own CPU estimator (luminaires/Registry.h) at three points of the patch, and from the
// other patches through form factors:
//
//   F_jk  = the form factor from patch j's centroid to patch k's triangle (Lambert's polygon
//           formula after clipping at j's horizon), times the visibility of the centroids;
//   T_kj  = A_j F_jk / A_k: the part of the flux leaving j that lands on k, per unit area of k;
//   E_ind = T (rho o (E_dir + E_ind)), solved by iteration (rho < 1 makes it converge).
//
// T spreads each patch's flux over the others, so in a closed room (where every row of F sums to
// one) no energy is created or lost: the area-weighted mean illuminance over all surfaces is
// exactly Phi / (S (1 - rho)) for uniform rho, the validation suite's integrating cube.
//
// E_ind is linear in E_dir, so each source's share can be updated alone (Interreflection.h).

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <vector>

#include "luminaires/Registry.h"

namespace candela {

struct Scene;
class EmbreeVisibility;

struct RadiositySettings {
    /// The patch edge is chosen so the scene's surfaces give about this many patches.
    int targetPatches = 2500;
    /// > 0: this longest patch edge (metres) instead.
    double patchSize = 0.0;
};

/// The scene's surfaces as patches, with vertices shared between the patches of one flat surface
/// (for smooth display) but not across creases.
///
/// The patch count follows the surfaces' area, not their tessellation. A triangle about the patch
/// size or larger is cut into patches of that size. Triangles much smaller than a patch (a finely
/// tessellated glTF model) are gathered into clusters: those of one mesh whose centroids fall in
/// one cube of the patch's edge and whose normals lean towards one of the six axis directions.
/// A cluster is one patch: its area the sum of its triangles', its normal their area-weighted
/// mean, its centroid the centroid of its member nearest to their mean position (a point on the
/// surface, so shadow rays to it are not blocked by the surface itself), and its direct light
/// the mean at three of its triangles' centroids. The form factor to it is a disc's of its area
/// at that mean facing its normal, A cos cos / (pi r^2 + A) (formFactorTo): bounded where its
/// neighbours' centroids come close to it, which a flat stand-in for a curved piece would not be
/// (a neighbour's centroid over its footprint, a millimetre in front of it, saw half its
/// hemisphere filled). The display draws its triangles themselves (displayTriangles) with the
/// cluster's value; `vertex` holds a stand-in triangle of its area at the mean, in the plane of
/// its normal, whose corners carry its value for interpolation.
struct RadiosityMesh {
    /// The most patches a solution may have: its transfer coefficients take 4 bytes for every
    /// pair of patches (1.6 GB at 20 000). A scene whose surfaces make more (a patch size asked
    /// for that is small against the scene's area) is refused by build() with a message.
    static constexpr size_t kMaxPatches = 20000;
    struct Patch {
        /// Counter-clockwise seen from the normal's side; a cluster's stand-in triangle.
        std::array<uint32_t, 3> vertex{};
        glm::dvec3 centroid{0.0};  ///< Metres; a cluster's: on one of its triangles.
        glm::dvec3 normal{0.0};    ///< Unit, the reflecting side.
        double area = 0.0;         ///< m2.
        glm::dvec3 albedo{0.0};    ///< Diffuse reflectance, RGB in [0, 1].
        bool hidden = false;       ///< On a mesh the camera does not see (Mesh::hidden).
        int body = -1;  ///< On a luminaire's body: its index into bodyBounds; -1 elsewhere.
        /// A cluster of small triangles (above): its stand-in triangle is not on the surface, so
        /// it is neither drawn, nor split into parts, nor a form factor's target.
        bool cluster = false;
        /// Where its direct light is sampled, on the surface: the degree-2 rule's points of its
        /// triangle (barycentrics 2/3, 1/6, 1/6 and permutations), or three of a cluster's
        /// triangles' centroids.
        std::array<glm::dvec3, 3> samples{};
    };
    /// The luminaire bodies' bounds (lo, hi), metres: a body receives no light of its own
    /// luminaire (insideBody), whose photometry already holds it.
    std::vector<std::pair<glm::dvec3, glm::dvec3>> bodyBounds;
    std::vector<glm::dvec3> vertices;  ///< Metres.
    std::vector<Patch> patches;
    /// The clustered triangles as the mesh has them (indices into vertices), for display, each
    /// with its cluster (displayPatch): they, not the clusters' stand-ins, are drawn.
    std::vector<std::array<uint32_t, 3>> displayTriangles;
    std::vector<uint32_t> displayPatch;
    double patchSize = 0.0;  ///< Longest edge asked for, metres.
    /// Every patch sees every other unobstructed: all vertices lie on or in front of every
    /// patch's plane (a convex room seen from inside, such as a closed box or sphere). Then the
    /// form factors need no shadow rays.
    bool convexRoom = false;

    /// Where each mesh triangle's patches start and how many times its edges were divided:
    /// triangle t of mesh m has subdivisions^2 patches from firstPatch on (a clustered triangle:
    /// its cluster, subdivisions 1).
    struct Split {
        uint32_t firstPatch = 0;
        uint32_t subdivisions = 1;
    };
    std::vector<std::vector<Split>> splits;  ///< [mesh][triangle]

    /// The patches around each vertex, the display triangles' included (compressed rows:
    /// vertexPatches[vertexStart[v] .. vertexStart[v + 1]]).
    std::vector<uint32_t> vertexStart, vertexPatches;

    /// Patches of the scene's meshes, `settings` choosing their size. Throws InputError naming
    /// the scene and its largest surface when they would make more than kMaxPatches.
    static RadiosityMesh build(const Scene& scene, const RadiositySettings& settings);
    /// The patch that holds the point of barycentric (u, v) (Embree's: p = (1-u-v) a + u b + v c)
    /// on triangle `triangle` of mesh `mesh`, and the point's barycentrics within that patch
    /// (1/3 each on a cluster: its stand-in's corners all hold its own value).
    uint32_t patchAt(uint32_t mesh, uint32_t triangle, double u, double v,
                     glm::dvec3& weights) const;
    /// The form factor from a point x with unit normal n to patch `patch` (metres): its
    /// triangle's (pointTriangleFormFactor), or a cluster's disc's (above).
    double formFactorTo(const glm::dvec3& x, const glm::dvec3& n, uint32_t patch) const;
    /// True when some patch reflects light (a non-zero albedo).
    bool reflects() const;
    double totalArea() const;
};

/// Cooperative cancellation and progress of a long computation (all optional).
struct Progress {
    const std::atomic<bool>* cancel = nullptr;    ///< Stop early when it becomes true.
    std::function<void(double fraction)> report;  ///< 0..1, from the calling thread.
    bool cancelled() const { return cancel && cancel->load(std::memory_order_relaxed); }
};

/// T of the header comment: N x N single-precision transfer coefficients, row k the receiver.
struct TransferMatrix {
    size_t size = 0;
    std::vector<float> t;  ///< t[k * size + j] = A_j F_jk V_jk / A_k.
    /// Builds it with one shadow ray between each pair of patch centroids (biased 1e-4 m off the
    /// surfaces), over `threads` threads (0: the hardware's). Returns false when cancelled.
    bool build(const RadiosityMesh& mesh, const EmbreeVisibility& visibility, int threads,
               const Progress& progress = {});
};

/// Direct irradiance on every patch from one source, in the scene's units, RGB: the mean of its
/// estimator at the patch's three sample points (Patch::samples), each with `options` (seeded per
/// patch and point) and Embree visibility.
/// `estimate` is the source's estimator at (p, n); patches `dark` names get none (the source's
/// own body) without asking it. Returns false when cancelled.
using PointEstimator =
    std::function<Estimate(const glm::dvec3& p, const glm::dvec3& n, const EstimateOptions& o)>;
bool directOnPatches(const RadiosityMesh& mesh, const PointEstimator& estimate,
                     const EstimateOptions& options, int threads, std::vector<glm::dvec3>& out,
                     const Progress& progress = {},
                     const std::function<bool(size_t patch)>& dark = {});

/// Solves E_ind = T (rho o (E_dir + E_ind)) for the patches' interreflected irradiance, starting
/// from `indirect` (zero, or a previous solution of a nearby problem), until an iteration adds
/// less than `tolerance` of the flux reflected so far. Returns the iterations it took (-1 when
/// cancelled).
int solveRadiosity(const TransferMatrix& transfer, const RadiosityMesh& mesh,
                   const std::vector<glm::dvec3>& direct, std::vector<glm::dvec3>& indirect,
                   double tolerance, int threads, const Progress& progress = {});

/// Per-vertex values for display: the area-weighted mean of the patches around each vertex.
std::vector<glm::dvec3> vertexValues(const RadiosityMesh& mesh,
                                     const std::vector<glm::dvec3>& perPatch);

/// The form factor from a point x with unit normal n to the triangle (a, b, c), all in metres:
/// 1 / pi times Lambert's integral of cos over the part of the triangle above x's horizon.
double pointTriangleFormFactor(const glm::dvec3& x, const glm::dvec3& n, const glm::dvec3& a,
                               const glm::dvec3& b, const glm::dvec3& c);

/// The degree-2 rule's points of triangle (a, b, c): barycentrics (2/3, 1/6, 1/6) and
/// permutations (a patch's samples; its inner points where visibility is tested).
std::array<glm::dvec3, 3> rulePoints(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

/// Threads to use for `requested` (0: the hardware's, at least 1).
int workerThreads(int requested);

}  // namespace candela
