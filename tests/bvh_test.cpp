// BVH for shadow rays: layout invariants the GPU traversal relies on, and occluded() against a
// brute-force loop over every triangle.
#include "scene/Bvh.h"

#include <gtest/gtest.h>

#include <bit>
#include <limits>
#include <random>

#include "scene/GltfLoader.h"
#include "scene/SceneIo.h"

namespace candela {
namespace {

const std::string kCornell =
    std::string(CANDELA_SOURCE_DIR) + "/resources/gltf/cornellBox/cornellBox-2.80-Eevee-gltf.gltf";

gpu::BvhTriangle triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    return {glm::vec4(a, 0.f), glm::vec4(b - a, 0.f), glm::vec4(c - a, 0.f)};
}

/// The same test as Bvh::occluded(), over every triangle with no hierarchy.
bool bruteForceOccluded(const Bvh& bvh, const glm::dvec3& from, const glm::dvec3& to) {
    glm::dvec3 d = to - from;
    double distance = glm::length(d);
    double eps = Bvh::segmentEpsilon(distance);
    if (!(distance - eps > eps)) return false;
    for (const gpu::BvhTriangle& t : bvh.triangles)
        if (Bvh::intersects(t, from, d / distance, eps, distance - eps)) return true;
    return false;
}

Scene cornellScene() {
    Scene scene;
    loadGltf(kCornell, glm::dmat4(1.0), scene, {});
    return scene;
}

size_t triangleCount(const Scene& scene) {
    size_t n = 0;
    for (const Mesh& m : scene.meshes) n += m.triangleCount();
    return n;
}

/// Checks the flattened layout: children adjacent and in range, every triangle in exactly one
/// leaf of 1..4, bounds of each node containing its children and triangles.
void checkLayout(const Bvh& bvh) {
    ASSERT_FALSE(bvh.nodes.empty());
    std::vector<int> seen(bvh.triangles.size(), 0);
    for (const gpu::BvhNode& n : bvh.nodes) {
        int first = std::bit_cast<int32_t>(n.lo.w), count = std::bit_cast<int32_t>(n.hi.w);
        auto inside = [&](glm::vec3 p) {
            return glm::all(glm::greaterThanEqual(p, glm::vec3(n.lo))) &&
                   glm::all(glm::lessThanEqual(p, glm::vec3(n.hi)));
        };
        if (count == 0) {
            ASSERT_GT(first, 0);
            ASSERT_LT(size_t(first) + 1, bvh.nodes.size());
            for (int c : {first, first + 1}) {
                EXPECT_TRUE(inside(glm::vec3(bvh.nodes[size_t(c)].lo)));
                EXPECT_TRUE(inside(glm::vec3(bvh.nodes[size_t(c)].hi)));
            }
        } else {
            ASSERT_LE(count, Bvh::kMaxLeafTriangles);
            ASSERT_GE(first, 0);
            ASSERT_LE(size_t(first + count), bvh.triangles.size());
            for (int i = first; i < first + count; ++i) {
                ++seen[size_t(i)];
                const gpu::BvhTriangle& t = bvh.triangles[size_t(i)];
                glm::vec3 v0(t.v0);
                EXPECT_TRUE(inside(v0));
                EXPECT_TRUE(inside(v0 + glm::vec3(t.e1)));
                EXPECT_TRUE(inside(v0 + glm::vec3(t.e2)));
            }
        }
    }
    for (int s : seen) ASSERT_EQ(s, 1);
    EXPECT_LE(bvh.depth(), Bvh::kMaxDepth);
}

TEST(Bvh, TriangleTestIsTwoSidedAndRespectsTheRange) {
    gpu::BvhTriangle t = triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    glm::dvec3 down(0, 0, -1);
    EXPECT_TRUE(Bvh::intersects(t, {0.25, 0.25, 1}, down, 0.0, 2.0));
    EXPECT_TRUE(Bvh::intersects(t, {0.25, 0.25, -1}, -down, 0.0, 2.0));  // Back side.
    EXPECT_FALSE(Bvh::intersects(t, {0.75, 0.75, 1}, down, 0.0, 2.0));   // Past the hypotenuse.
    EXPECT_FALSE(Bvh::intersects(t, {-0.1, 0.25, 1}, down, 0.0, 2.0));
    EXPECT_FALSE(Bvh::intersects(t, {0.25, 0.25, 1}, down, 0.0, 0.99));  // Hit at t = 1.
    EXPECT_FALSE(Bvh::intersects(t, {0.25, 0.25, 1}, down, 1.01, 2.0));
    EXPECT_FALSE(Bvh::intersects(t, {0.25, 0.25, 1}, glm::dvec3(1, 0, 0), 0.0, 2.0));  // Parallel.
}

TEST(Bvh, SegmentEndsAreBiased) {
    Scene scene;
    addPlane(scene, {0, 0, 0}, {0, 1, 0}, {2, 2}, Material{});
    Bvh bvh = Bvh::build(scene);
    EXPECT_TRUE(bvh.occluded({0, 1, 0}, {0, -1, 0}));
    // A segment that starts or ends on the plane is not blocked by it (the end bias).
    EXPECT_FALSE(bvh.occluded({0, 0, 0}, {0.5, 2, 0}));
    EXPECT_FALSE(bvh.occluded({0.5, 2, 0}, {0.1, 0, 0.2}));
    // ...but an occluder 1 mm from the end (more than the 1e-4 m bias) still is.
    EXPECT_TRUE(bvh.occluded({0.5, 2, 0}, {0.1, -0.001, 0.2}));
    EXPECT_FALSE(bvh.occluded({0, 1, 0}, {0, 1, 0}));  // Zero length.
    BvhVisibility visibility(bvh);
    EXPECT_FALSE(visibility.visible({0, 1, 0}, {0, -1, 0}));
    EXPECT_TRUE(visibility.visible({0, 1, 0}, {3, -1, 0}));
}

TEST(Bvh, EmptySceneHasAValidRootAndBlocksNothing) {
    Scene scene;
    Bvh bvh = Bvh::build(scene);
    ASSERT_EQ(bvh.nodes.size(), 1u);
    ASSERT_EQ(bvh.triangles.size(), 1u);  // One degenerate triangle keeps the buffers non-empty.
    EXPECT_EQ(std::bit_cast<int32_t>(bvh.nodes[0].hi.w), 1);
    EXPECT_FALSE(bvh.occluded({-1, -1, -1}, {1, 1, 1}));
    EXPECT_FALSE(bvh.occluded({0, 0, -1}, {0, 0, 1}));
}

TEST(Bvh, CornellBoxLayout) {
    Scene scene = cornellScene();
    Bvh bvh = Bvh::build(scene);
    EXPECT_EQ(bvh.triangles.size(), triangleCount(scene));
    checkLayout(bvh);
}

TEST(Bvh, DegenerateInputsKeepTheDepthBound) {
    // 5000 copies of one triangle (all centroids equal: no SAH split exists) and a geometric
    // series of triangle sizes (lopsided SAH splits): both must stay within kMaxDepth.
    Scene same;
    Mesh m;
    for (int i = 0; i < 5000; ++i) {
        uint32_t base = uint32_t(m.positions.size());
        m.positions.insert(m.positions.end(), {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
        m.normals.insert(m.normals.end(), 3, glm::vec3(0, 0, 1));
        m.indices.insert(m.indices.end(), {base, base + 1, base + 2});
    }
    m.computeBounds();
    same.meshes.push_back(m);
    Bvh bvh = Bvh::build(same);
    checkLayout(bvh);
    EXPECT_TRUE(bvh.occluded({0.2, 0.2, 1}, {0.2, 0.2, -1}));

    Scene series;
    Mesh s;
    float x = 0.f, size = 1e-3f;
    for (int i = 0; i < 3000; ++i, x += size, size *= 1.004f) {
        uint32_t base = uint32_t(s.positions.size());
        s.positions.insert(s.positions.end(), {{x, 0, 0}, {x + size, 0, 0}, {x, size, 0}});
        s.normals.insert(s.normals.end(), 3, glm::vec3(0, 0, 1));
        s.indices.insert(s.indices.end(), {base, base + 1, base + 2});
    }
    s.computeBounds();
    series.meshes.push_back(s);
    Bvh lopsided = Bvh::build(series);
    checkLayout(lopsided);
}

TEST(Bvh, MatchesBruteForceInTheCornellBox) {
    Scene scene = cornellScene();
    Bvh bvh = Bvh::build(scene);
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    auto inRoom = [&] {
        return glm::dvec3(-2.2 + 4.4 * u01(rng), -0.2 + 3.4 * u01(rng), -2.2 + 4.4 * u01(rng));
    };
    // Points on random triangles: segments between surfaces, like real shadow rays.
    auto onSurface = [&] {
        const gpu::BvhTriangle& t = bvh.triangles[size_t(u01(rng) * double(bvh.triangles.size()))];
        double a = u01(rng), b = u01(rng);
        if (a + b > 1.0) a = 1.0 - a, b = 1.0 - b;
        return glm::dvec3(t.v0) + a * glm::dvec3(t.e1) + b * glm::dvec3(t.e2);
    };
    int mismatches = 0, blocked = 0;
    const int kSegments = 6000;
    for (int i = 0; i < kSegments; ++i) {
        glm::dvec3 from = i % 2 ? onSurface() : inRoom();
        glm::dvec3 to = i % 3 ? onSurface() : inRoom();
        bool fast = bvh.occluded(from, to);
        bool slow = bruteForceOccluded(bvh, from, to);
        mismatches += fast != slow;
        blocked += slow;
    }
    // Same triangle test in both; the BVH box test is conservative, so they agree exactly.
    EXPECT_EQ(mismatches, 0);
    // Both outcomes are common in this scene, so the comparison is meaningful.
    EXPECT_GT(blocked, kSegments / 10);
    EXPECT_LT(blocked, kSegments * 9 / 10);
}

TEST(Bvh, ClosestHitMatchesBruteForceInTheCornellBox) {
    // closestHit against the nearest of every triangle's own hit, for rays from inside and
    // outside the box; and the normal faces the ray's origin.
    Scene scene = cornellScene();
    Bvh bvh = Bvh::build(scene);
    std::mt19937_64 rng(777);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    int hits = 0, misses = 0;
    for (int i = 0; i < 4000; ++i) {
        glm::dvec3 origin(-4.0 + 8.0 * u01(rng), -1.0 + 5.0 * u01(rng), -4.0 + 8.0 * u01(rng));
        double z = 2.0 * u01(rng) - 1.0, phi = 6.283185307179586 * u01(rng),
               r = std::sqrt(1.0 - z * z);
        glm::dvec3 dir(r * std::cos(phi), z, r * std::sin(phi));
        double nearest = std::numeric_limits<double>::infinity();
        int nearestTriangle = -1;
        for (size_t k = 0; k < bvh.triangles.size(); ++k) {
            double t = Bvh::hitDistance(bvh.triangles[k], origin, dir, Bvh::kRayEpsilon, nearest);
            if (t >= 0.0) nearest = t, nearestTriangle = int(k);
        }
        std::optional<BvhHit> hit = bvh.closestHit(origin, dir);
        ASSERT_EQ(hit.has_value(), nearestTriangle >= 0) << "ray " << i;
        if (!hit) {
            ++misses;
            continue;
        }
        ++hits;
        EXPECT_EQ(hit->t, nearest) << "ray " << i;  // the same triangle test: exactly equal
        EXPECT_NEAR(glm::length(hit->point - (origin + nearest * dir)), 0.0, 1e-12);
        EXPECT_NEAR(glm::length(hit->normal), 1.0, 1e-12);
        EXPECT_LE(glm::dot(hit->normal, dir), 0.0) << "the normal must face the ray's origin";
    }
    EXPECT_GT(hits, 1000);  // both outcomes are common, so the comparison means something
    EXPECT_GT(misses, 500);
}

}  // namespace
}  // namespace candela
