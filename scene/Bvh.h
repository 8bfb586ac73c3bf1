#pragma once
// Bounding volume hierarchy over every scene triangle, for shadow rays. Built on the CPU, used by
// Bvh::occluded() (probe, tests, CPU estimators) and uploaded unchanged for
// shaders/bvh_traverse.glsl, which runs the same traversal on the GPU.
//
// Layout (gpu::BvhNode, shaders/shared/GpuTypes.h): node 0 is the root. An inner node stores
// intBitsToFloat(left child index) in lo.w and intBitsToFloat(0) in hi.w; its right child is
// left + 1. A leaf stores its first triangle in lo.w and its triangle count (1 to 4) in hi.w,
// both as int bits. Trees are at most kMaxDepth levels deep, so a traversal stack of
// kMaxDepth + 1 entries never overflows. An empty scene gets one degenerate (never hit) triangle
// in a root leaf, so both buffers are non-empty and the root is always valid.
//
// Luminaire bodies (Scene::updateBodies): each body's bounds is a box in `bodies`, and each of its
// triangles holds in v0.w the float nodes.size() + body + 1 (0 for other triangles), so that
// the GPU, given nodes followed by bodies in one buffer, finds the box at int(v0.w) - 1. A body
// casts no shadow on a segment whose light end `to` is inside its box (insideBody): the light
// of its own openings.
//
// Shadow-ray bias: occluded(from, to) tests the open segment shrunk by
// eps = 1e-4 m * max(1, |to - from|) at both ends, so the surfaces the segment starts and ends
// on (receiver and emitter) do not shadow themselves through rounding; occluders closer than eps
// to either end are missed. occludedToward(from, dir) tests the ray to infinity (distant
// lights: the environment), biased by kRayEpsilon at its start only; a segment of 1e6 m would
// have skipped its first 100 m.

#include <algorithm>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "luminaires/Registry.h"
#include "scene/Scene.h"
#include "shaders/shared/GpuTypes.h"

namespace candela {

/// The nearest surface along a ray (Bvh::closestHit).
struct BvhHit {
    double t = 0.0;          ///< Distance along the unit direction, metres.
    glm::dvec3 point{0.0};   ///< World position, metres.
    glm::dvec3 normal{0.0};  ///< Unit geometric normal, turned to face the ray's origin.
    int triangle = -1;       ///< Index into Bvh::triangles.
};

struct Bvh {
    std::vector<gpu::BvhNode> nodes;          ///< Node 0 is the root; see the layout above.
    std::vector<gpu::BvhTriangle> triangles;  ///< World space (metres), in leaf order.
    std::vector<gpu::BvhNode> bodies;         ///< Each luminaire body's bounds (w unused).
    /// What the GPU's node buffer holds: nodes, then bodies.
    std::vector<gpu::BvhNode> gpuNodes() const;

    static constexpr int kMaxLeafTriangles = 4;
    /// Most inner levels on any root-to-leaf path (shared with the GLSL traversal's stack).
    static constexpr int kMaxDepth = gpu::kBvhMaxDepth;

    /// Binned SAH build over all triangles of all meshes (falls back to median splits where
    /// needed to respect kMaxDepth).
    static Bvh build(const Scene& scene);

    /// True when a triangle (either side) cuts the segment between from and to (metres), with
    /// the end bias described above, leaving out the bodies whose box holds `to`.
    bool occluded(const glm::dvec3& from, const glm::dvec3& to) const;
    /// The same with every triangle, bodies included: between two surface points.
    bool occludedBetweenSurfaces(const glm::dvec3& from, const glm::dvec3& to) const;
    /// True when a triangle cuts the ray from `from` along the unit `dir`, beyond kRayEpsilon.
    bool occludedToward(const glm::dvec3& from, const glm::dvec3& dir) const;

    /// The nearest triangle (either side) along the ray from `origin` along the unit `dir`,
    /// beyond kRayEpsilon; empty when the ray leaves the scene. For picking (the editor, probe
    /// --pixel), not for shading.
    std::optional<BvhHit> closestHit(const glm::dvec3& origin, const glm::dvec3& dir) const;

    /// Two-sided Moller-Trumbore: does origin + t * dir hit the triangle with tMin < t < tMax?
    /// (t in metres for a unit dir.)
    static bool intersects(const gpu::BvhTriangle& triangle, const glm::dvec3& origin,
                           const glm::dvec3& dir, double tMin, double tMax);
    /// The same test, giving the hit's t, or a negative value for no hit.
    static double hitDistance(const gpu::BvhTriangle& triangle, const glm::dvec3& origin,
                              const glm::dvec3& dir, double tMin, double tMax);
    /// End bias of a segment of `distance` metres, metres.
    static double segmentEpsilon(double distance) { return 1e-4 * std::max(1.0, distance); }
    /// The ray a shadow segment from `from` to `to` tests: unit dir and tMin < t < tMax, shrunk by
    /// segmentEpsilon at both ends. False when nothing is left to test (shorter than the bias,
    /// or NaN). Shared by every visibility implementation, so all have the same bias.
    static bool segmentRay(const glm::dvec3& from, const glm::dvec3& to, glm::dvec3& dir,
                           double& tMin, double& tMax);
    /// Start bias of a ray to infinity, metres (a segment's bias for lengths up to 1 m).
    static constexpr double kRayEpsilon = 1e-4;
    /// Barycentric slack of the triangle test (double here, 1e-6 in the float GLSL twin): rays
    /// through a shared edge or vertex hit, so closed meshes do not leak (tests/visibility_test).
    static constexpr double kEdgeSlack = 1e-9;

    /// Inner levels on the longest root-to-leaf path (0 for a single leaf).
    int depth() const;

  private:
    /// `light`: the light end of a segment (bodies whose box holds it cast no shadow), or null.
    bool occludedAlong(const glm::dvec3& from, const glm::dvec3& dir, double tMin, double tMax,
                       const glm::dvec3* light) const;
};

/// Visibility through a BVH, for the CPU estimators' EstimateOptions::visibility. Holds a
/// reference: the Bvh must outlive it (temporaries are rejected at compile time).
class BvhVisibility : public Visibility {
  public:
    explicit BvhVisibility(const Bvh& bvh) : mBvh(bvh) {}
    explicit BvhVisibility(Bvh&&) = delete;
    bool visible(const glm::dvec3& from, const glm::dvec3& to) const override {
        return !mBvh.occluded(from, to);
    }
    bool visibleBetweenSurfaces(const glm::dvec3& from, const glm::dvec3& to) const override {
        return !mBvh.occludedBetweenSurfaces(from, to);
    }
    bool visibleToward(const glm::dvec3& from, const glm::dvec3& dir) const override {
        return !mBvh.occludedToward(from, dir);
    }
    const Bvh& bvh() const { return mBvh; }

  private:
    const Bvh& mBvh;
};

}  // namespace candela
