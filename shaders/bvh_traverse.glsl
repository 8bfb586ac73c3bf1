// Shadow rays through the scene BVH built by scene/Bvh.cpp: the same traversal and tests as
// Bvh::occluded() (see scene/Bvh.h for the node layout and the end bias). Needs
// shared/GpuTypes.h (BvhNode, BvhTriangle, binding points) included before this file.

layout(std430, binding = kBindingBvhNodes) readonly buffer BvhNodes { BvhNode bvhNodes[]; };
layout(std430, binding = kBindingBvhTris) readonly buffer BvhTris { BvhTriangle bvhTris[]; };

/// Entries of the traversal stack; trees from Bvh::build() are at most kBvhMaxDepth inner levels
/// deep.
const int kBvhStackSize = kBvhMaxDepth + 1;
/// Relative widening of a box's exit distance so rounding never culls a box the ray touches.
/// Larger than the C++ side's 1 + 2 * gamma(3) (pbrt-v4) because GLSL division is only accurate
/// to 2.5 ULP; it only makes the traversal visit a few more boxes.
const float kBvhBoxSlack = 1.0 + 1e-5;

/// Slab test of origin + t * dir against [lo, hi] for t in [tMin, tMax].
bool bvhHitsBox(vec3 lo, vec3 hi, vec3 origin, vec3 dir, float tMin, float tMax) {
    float tNear = tMin;
    float tFar = tMax;
    for (int i = 0; i < 3; ++i) {
        if (dir[i] == 0.0) {
            if (origin[i] < lo[i] || origin[i] > hi[i]) return false;
            continue;
        }
        float t0 = (lo[i] - origin[i]) / dir[i];
        float t1 = (hi[i] - origin[i]) / dir[i];
        tNear = max(tNear, min(t0, t1));
        tFar = min(tFar, max(t0, t1));
    }
    return tNear <= tFar * kBvhBoxSlack;
}

/// Two-sided Moller-Trumbore (1997): does origin + t * dir hit the triangle with tMin < t < tMax?
bool bvhHitsTriangle(BvhTriangle tri, vec3 origin, vec3 dir, float tMin, float tMax) {
    vec3 e1 = tri.e1.xyz;
    vec3 e2 = tri.e2.xyz;
    vec3 p = cross(dir, e2);
    float det = dot(e1, p);
    if (abs(det) < 1e-20) return false;
    float invDet = 1.0 / det;
    vec3 s = origin - tri.v0.xyz;
    float u = dot(s, p) * invDet;
    // Barycentric slack (Bvh::kEdgeSlack in float): rays through shared edges do not leak.
    const float kEdgeSlack = 1e-6;
    if (u < -kEdgeSlack || u > 1.0 + kEdgeSlack) return false;
    vec3 q = cross(s, e1);
    float v = dot(dir, q) * invDet;
    if (v < -kEdgeSlack || u + v > 1.0 + kEdgeSlack) return false;
    float t = dot(e2, q) * invDet;
    return t > tMin && t < tMax;
}

/// A luminaire body's triangle (v0.w > 0: its box is bvhNodes[int(v0.w) - 1], scene/Bvh.h)
/// casts no shadow on light leaving a point inside that box, widened by kBodyMargin.
bool bvhOwnBody(BvhTriangle tri, vec3 light) {
    if (!(tri.v0.w > 0.0)) return false;
    BvhNode box = bvhNodes[int(tri.v0.w) - 1];
    return all(greaterThanEqual(light, box.lo.xyz - kBodyMargin)) &&
           all(lessThanEqual(light, box.hi.xyz + kBodyMargin));
}

/// True when a triangle cuts origin + t * dir (unit dir) for tMin < t < tMax, bodies whose box
/// holds `light` (the segment's light end) left out.
bool bvhOccludedAlong(vec3 from, vec3 dir, float tMin, float tMax, vec3 light) {
    int stack[kBvhStackSize];
    int top = 0;
    int node = 0;
    while (true) {
        BvhNode n = bvhNodes[node];
        if (bvhHitsBox(n.lo.xyz, n.hi.xyz, from, dir, tMin, tMax)) {
            int first = floatBitsToInt(n.lo.w);
            int count = floatBitsToInt(n.hi.w);
            if (count > 0) {
                for (int i = first; i < first + count; ++i)
                    if (bvhHitsTriangle(bvhTris[i], from, dir, tMin, tMax) &&
                        !bvhOwnBody(bvhTris[i], light))
                        return true;
            } else {
                if (top == kBvhStackSize) return true;  // Cannot happen for Bvh::build() trees.
                stack[top++] = first + 1;
                node = first;
                continue;
            }
        }
        if (top == 0) return false;
        node = stack[--top];
    }
    return false;
}

/// True when scene geometry cuts the segment from `from` to `to` (metres), ignoring the first and
/// last 1e-4 m * max(1, length) of it (shadow-ray bias, as Bvh::segmentEpsilon).
bool bvhOccluded(vec3 from, vec3 to) {
    vec3 d = to - from;
    float dist = length(d);
    float eps = 1e-4 * max(1.0, dist);
    float tMin = eps;
    float tMax = dist - eps;
    if (!(tMax > tMin)) return false;
    return bvhOccludedAlong(from, d / dist, tMin, tMax, to);
}

/// True when scene geometry cuts the ray from `from` along the unit `dir` to infinity (distant
/// light), ignoring its first 1e-4 m (Bvh::kRayEpsilon). A long segment would not do: its end
/// bias grows with its length.
bool bvhOccludedToward(vec3 from, vec3 dir) {
    return bvhOccludedAlong(from, dir, 1e-4, 1e30, vec3(1e30));  // no body holds infinity
}
