#include "scene/Bvh.h"

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "util/Error.h"

namespace candela {

namespace {

constexpr int kBins = 16;

/// Relative widening of a box's exit distance that makes the slab test conservative under
/// rounding (pbrt-v4's 1 + 2 * gamma(3) for doubles).
constexpr double kBoxSlack = 1.0 + 2.0 * (3.0 * std::numeric_limits<double>::epsilon() * 0.5) /
                                       (1.0 - 3.0 * std::numeric_limits<double>::epsilon() * 0.5);

struct Box {
    glm::vec3 lo{std::numeric_limits<float>::max()};
    glm::vec3 hi{-std::numeric_limits<float>::max()};

    void grow(const glm::vec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void grow(const Box& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    float halfArea() const {
        glm::vec3 e = glm::max(hi - lo, glm::vec3(0.f));
        return e.x * e.y + e.y * e.z + e.z * e.x;
    }
};

/// A triangle while building: its bounds, centroid and index into the input list.
struct Ref {
    Box bounds;
    glm::vec3 centroid;
    uint32_t triangle;
};

/// Inner levels a subtree of n triangles needs when every split halves it.
int levelsNeeded(size_t n) {
    int levels = 0;
    for (size_t capacity = Bvh::kMaxLeafTriangles; capacity < n; capacity *= 2) ++levels;
    return levels;
}

class Builder {
  public:
    Builder(std::vector<gpu::BvhTriangle> input, Bvh& out) : mInput(std::move(input)), mOut(out) {}

    void run() {
        mRefs.resize(mInput.size());
        for (uint32_t i = 0; i < mInput.size(); ++i) {
            const gpu::BvhTriangle& t = mInput[i];
            glm::vec3 v0(t.v0), v1 = v0 + glm::vec3(t.e1), v2 = v0 + glm::vec3(t.e2);
            Ref& r = mRefs[i];
            r.bounds.grow(v0);
            r.bounds.grow(v1);
            r.bounds.grow(v2);
            r.centroid = (r.bounds.lo + r.bounds.hi) * 0.5f;
            r.triangle = i;
        }
        mOut.nodes.clear();
        mOut.triangles.clear();
        mOut.triangles.reserve(mInput.size());
        mOut.nodes.emplace_back();
        buildNode(0, 0, mRefs.size(), 0);
    }

  private:
    void buildNode(size_t node, size_t begin, size_t end, int depth) {
        Box bounds, centroids;
        for (size_t i = begin; i < end; ++i) {
            bounds.grow(mRefs[i].bounds);
            centroids.grow(mRefs[i].centroid);
        }
        mOut.nodes[node].lo = glm::vec4(bounds.lo, 0.f);
        mOut.nodes[node].hi = glm::vec4(bounds.hi, 0.f);
        size_t count = end - begin;
        if (count <= size_t(Bvh::kMaxLeafTriangles)) {
            mOut.nodes[node].lo.w = std::bit_cast<float>(int32_t(mOut.triangles.size()));
            mOut.nodes[node].hi.w = std::bit_cast<float>(int32_t(count));
            for (size_t i = begin; i < end; ++i)
                mOut.triangles.push_back(mInput[mRefs[i].triangle]);
            return;
        }
        size_t mid = split(begin, end, centroids, depth);
        size_t left = mOut.nodes.size();
        mOut.nodes.emplace_back();
        mOut.nodes.emplace_back();
        mOut.nodes[node].lo.w = std::bit_cast<float>(int32_t(left));
        mOut.nodes[node].hi.w = std::bit_cast<float>(int32_t(0));
        buildNode(left, begin, mid, depth + 1);
        buildNode(left + 1, mid, end, depth + 1);
    }

    /// Partitions refs [begin, end) in two non-empty halves; returns the first of the second.
    size_t split(size_t begin, size_t end, const Box& centroids, int depth) {
        size_t count = end - begin;
        glm::vec3 extent = centroids.hi - centroids.lo;
        int bestAxis = -1, bestBin = -1;
        float bestCost = std::numeric_limits<float>::max();
        size_t bestLeftCount = 0;
        for (int axis = 0; axis < 3; ++axis) {
            if (!(extent[axis] > 0.f)) continue;
            std::array<Box, kBins> bins;
            std::array<size_t, kBins> counts{};
            for (size_t i = begin; i < end; ++i) {
                int b = binOf(mRefs[i].centroid[axis], centroids.lo[axis], extent[axis]);
                bins[size_t(b)].grow(mRefs[i].bounds);
                ++counts[size_t(b)];
            }
            // Sweep: cost of splitting after bin b = halfArea(left) * nLeft + halfArea(right) *
            // nRight.
            std::array<float, kBins> leftArea{};
            std::array<size_t, kBins> leftCount{};
            Box acc;
            size_t n = 0;
            for (int b = 0; b < kBins; ++b) {
                acc.grow(bins[size_t(b)]);
                n += counts[size_t(b)];
                leftArea[size_t(b)] = acc.halfArea();
                leftCount[size_t(b)] = n;
            }
            acc = Box();
            n = 0;
            for (int b = kBins - 1; b > 0; --b) {
                acc.grow(bins[size_t(b)]);
                n += counts[size_t(b)];
                size_t nLeft = leftCount[size_t(b - 1)];
                if (nLeft == 0 || n == 0) continue;
                float cost = leftArea[size_t(b - 1)] * float(nLeft) + acc.halfArea() * float(n);
                if (cost < bestCost) {
                    bestCost = cost;
                    bestAxis = axis;
                    bestBin = b - 1;
                    bestLeftCount = nLeft;
                }
            }
        }
        // The SAH split is used only if its larger side still fits in the depth budget.
        bool sahFits = bestAxis >= 0 &&
                       depth + 1 + levelsNeeded(std::max(bestLeftCount, count - bestLeftCount)) <=
                           Bvh::kMaxDepth;
        if (sahFits) {
            auto first = mRefs.begin() + std::ptrdiff_t(begin);
            auto last = mRefs.begin() + std::ptrdiff_t(end);
            float lo = centroids.lo[bestAxis], width = extent[bestAxis];
            auto mid = std::partition(first, last, [&](const Ref& r) {
                return binOf(r.centroid[bestAxis], lo, width) <= bestBin;
            });
            return size_t(mid - mRefs.begin());
        }
        // Median split along the widest centroid axis: halves the count, so depth stays bounded.
        int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
        size_t mid = begin + count / 2;
        std::nth_element(mRefs.begin() + std::ptrdiff_t(begin), mRefs.begin() + std::ptrdiff_t(mid),
                         mRefs.begin() + std::ptrdiff_t(end), [axis](const Ref& a, const Ref& b) {
                             return a.centroid[axis] < b.centroid[axis];
                         });
        return mid;
    }

    static int binOf(float c, float lo, float extent) {
        int b = int(float(kBins) * ((c - lo) / extent));
        return std::clamp(b, 0, kBins - 1);
    }

    std::vector<gpu::BvhTriangle> mInput;
    Bvh& mOut;
    std::vector<Ref> mRefs;
};

/// Slab test of the ray against [lo, hi] for t in [tMin, tMax], conservative under rounding.
bool hitsBox(const gpu::BvhNode& node, const glm::dvec3& origin, const glm::dvec3& dir, double tMin,
             double tMax) {
    double tNear = tMin, tFar = tMax;
    for (int i = 0; i < 3; ++i) {
        double lo = node.lo[i], hi = node.hi[i];
        if (dir[i] == 0.0) {
            if (origin[i] < lo || origin[i] > hi) return false;
            continue;
        }
        double t0 = (lo - origin[i]) / dir[i], t1 = (hi - origin[i]) / dir[i];
        tNear = std::max(tNear, std::min(t0, t1));
        tFar = std::min(tFar, std::max(t0, t1));
    }
    return tNear <= tFar * kBoxSlack;
}

}  // namespace

Bvh Bvh::build(const Scene& scene) {
    std::vector<gpu::BvhTriangle> input;
    std::vector<gpu::BvhNode> bodies;
    for (const Mesh& mesh : scene.meshes) {
        float body = 0.f;  // see the layout in Bvh.h: the body's number from 1 until built
        if (mesh.luminaireBody) {
            bodies.push_back({glm::vec4(mesh.boundsMin, 0.f), glm::vec4(mesh.boundsMax, 0.f)});
            body = float(bodies.size());
        }
        for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
            size_t n = mesh.positions.size();
            if (a >= n || b >= n || c >= n) continue;  // Malformed mesh: nothing to trace.
            glm::vec3 v0 = mesh.positions[a];
            gpu::BvhTriangle tri;
            tri.v0 = glm::vec4(v0, body);
            tri.e1 = glm::vec4(mesh.positions[b] - v0, 0.f);
            tri.e2 = glm::vec4(mesh.positions[c] - v0, 0.f);
            input.push_back(tri);
        }
    }
    if (input.size() > size_t(std::numeric_limits<int32_t>::max()))
        throw RuntimeError("BVH: too many triangles (" + std::to_string(input.size()) + ")");
    if (input.empty()) input.push_back({glm::vec4(0.f), glm::vec4(0.f), glm::vec4(0.f)});

    Bvh bvh;
    Builder(std::move(input), bvh).run();
    // Body triangles point at their box in nodes-then-bodies order (exact in a float below 2^24).
    if (bvh.nodes.size() + bodies.size() >= (size_t(1) << 24))
        throw RuntimeError("BVH: too many nodes for the luminaire bodies' indices");
    for (gpu::BvhTriangle& t : bvh.triangles)
        if (t.v0.w > 0.f) t.v0.w = float(bvh.nodes.size()) + t.v0.w;
    bvh.bodies = std::move(bodies);
    return bvh;
}

std::vector<gpu::BvhNode> Bvh::gpuNodes() const {
    std::vector<gpu::BvhNode> out = nodes;
    out.insert(out.end(), bodies.begin(), bodies.end());
    return out;
}

double Bvh::hitDistance(const gpu::BvhTriangle& triangle, const glm::dvec3& origin,
                        const glm::dvec3& dir, double tMin, double tMax) {
    // Moller and Trumbore 1997, without back-face culling (triangles are two-sided).
    glm::dvec3 e1(triangle.e1), e2(triangle.e2);
    glm::dvec3 p = glm::cross(dir, e2);
    double det = glm::dot(e1, p);
    if (std::abs(det) < 1e-20) return -1.0;  // Ray parallel to the plane, or degenerate.
    double invDet = 1.0 / det;
    glm::dvec3 s = origin - glm::dvec3(triangle.v0);
    double u = glm::dot(s, p) * invDet;
    // Barycentric slack: a ray through an edge or vertex shared by two triangles could miss
    // both by rounding and leak out of a closed mesh; a hair of overlap closes it.
    if (u < -kEdgeSlack || u > 1.0 + kEdgeSlack) return -1.0;
    glm::dvec3 q = glm::cross(s, e1);
    double v = glm::dot(dir, q) * invDet;
    if (v < -kEdgeSlack || u + v > 1.0 + kEdgeSlack) return -1.0;
    double t = glm::dot(e2, q) * invDet;
    return t > tMin && t < tMax ? t : -1.0;
}

bool Bvh::intersects(const gpu::BvhTriangle& triangle, const glm::dvec3& origin,
                     const glm::dvec3& dir, double tMin, double tMax) {
    return hitDistance(triangle, origin, dir, tMin, tMax) >= 0.0;
}

std::optional<BvhHit> Bvh::closestHit(const glm::dvec3& origin, const glm::dvec3& dir) const {
    if (nodes.empty()) return std::nullopt;
    BvhHit best;
    best.t = std::numeric_limits<double>::infinity();
    // Depth first, every node whose box the ray meets before the best hit so far.
    std::vector<int> stack{0};
    while (!stack.empty()) {
        const gpu::BvhNode& n = nodes[size_t(stack.back())];
        stack.pop_back();
        if (!hitsBox(n, origin, dir, kRayEpsilon, best.t)) continue;
        int first = std::bit_cast<int32_t>(n.lo.w);
        int count = std::bit_cast<int32_t>(n.hi.w);
        if (count == 0) {
            stack.push_back(first);
            stack.push_back(first + 1);
            continue;
        }
        for (int i = first; i < first + count; ++i) {
            double t = hitDistance(triangles[size_t(i)], origin, dir, kRayEpsilon, best.t);
            if (t >= 0.0) best.t = t, best.triangle = i;
        }
    }
    if (best.triangle < 0) return std::nullopt;
    const gpu::BvhTriangle& tri = triangles[size_t(best.triangle)];
    best.point = origin + best.t * dir;
    best.normal = glm::normalize(glm::cross(glm::dvec3(tri.e1), glm::dvec3(tri.e2)));
    if (glm::dot(best.normal, dir) > 0.0) best.normal = -best.normal;
    return best;
}

bool Bvh::segmentRay(const glm::dvec3& from, const glm::dvec3& to, glm::dvec3& dir, double& tMin,
                     double& tMax) {
    glm::dvec3 d = to - from;
    double distance = glm::length(d);
    double eps = segmentEpsilon(distance);
    tMin = eps;
    tMax = distance - eps;
    if (!(tMax > tMin)) return false;  // Shorter than the bias (or NaN): nothing in between.
    dir = d / distance;
    return true;
}

bool Bvh::occluded(const glm::dvec3& from, const glm::dvec3& to) const {
    glm::dvec3 dir;
    double tMin, tMax;
    if (nodes.empty() || !segmentRay(from, to, dir, tMin, tMax)) return false;
    return occludedAlong(from, dir, tMin, tMax, &to);
}

bool Bvh::occludedBetweenSurfaces(const glm::dvec3& from, const glm::dvec3& to) const {
    glm::dvec3 dir;
    double tMin, tMax;
    if (nodes.empty() || !segmentRay(from, to, dir, tMin, tMax)) return false;
    return occludedAlong(from, dir, tMin, tMax, nullptr);
}

bool Bvh::occludedToward(const glm::dvec3& from, const glm::dvec3& dir) const {
    return occludedAlong(from, dir, kRayEpsilon, std::numeric_limits<double>::infinity(), nullptr);
}

bool Bvh::occludedAlong(const glm::dvec3& from, const glm::dvec3& dir, double tMin, double tMax,
                        const glm::dvec3* light) const {
    // A body's triangles cast no shadow on the light of a point inside its box.
    auto ownBody = [&](const gpu::BvhTriangle& t) {
        if (!light || !(t.v0.w > 0.f)) return false;
        const gpu::BvhNode& box = bodies[size_t(t.v0.w) - 1 - nodes.size()];
        return insideBody(*light, glm::dvec3(box.lo), glm::dvec3(box.hi));
    };
    if (nodes.empty()) return false;
    int stack[kMaxDepth + 1];
    int top = 0;
    int node = 0;
    while (true) {
        const gpu::BvhNode& n = nodes[size_t(node)];
        if (hitsBox(n, from, dir, tMin, tMax)) {
            int first = std::bit_cast<int32_t>(n.lo.w);
            int count = std::bit_cast<int32_t>(n.hi.w);
            if (count > 0) {
                for (int i = first; i < first + count; ++i)
                    if (intersects(triangles[size_t(i)], from, dir, tMin, tMax) &&
                        !ownBody(triangles[size_t(i)]))
                        return true;
            } else {
                if (top == kMaxDepth + 1) return true;  // Never happens for trees from build().
                stack[top++] = first + 1;
                node = first;
                continue;
            }
        }
        if (top == 0) return false;
        node = stack[--top];
    }
}

int Bvh::depth() const {
    if (nodes.empty()) return 0;
    int deepest = 0;
    std::vector<std::pair<int, int>> pending{{0, 0}};
    while (!pending.empty()) {
        auto [node, level] = pending.back();
        pending.pop_back();
        deepest = std::max(deepest, level);
        if (std::bit_cast<int32_t>(nodes[size_t(node)].hi.w) == 0) {
            int left = std::bit_cast<int32_t>(nodes[size_t(node)].lo.w);
            pending.push_back({left, level + 1});
            pending.push_back({left + 1, level + 1});
        }
    }
    return deepest;
}

}  // namespace candela
