#include "calculation/Radiosity.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <thread>

#include "scene/EmbreeVisibility.h"
#include "scene/Scene.h"
#include "shaders/shared/Constants.h"
#include "util/Error.h"
#include "util/Threads.h"

namespace candela {

namespace {

using gpu::kPi;

/// Largest number of divisions of one triangle edge (a 1 km plane at 1 cm patches stops here).
constexpr uint32_t kMaxSubdivisions = 256;

double luminance(const glm::dvec3& c) {
    return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

/// Runs body(i) for i in [0, count) on `threads` threads, in chunks taken in order; stops early
/// when `progress` is cancelled (returns false then). Progress is reported from the calling thread.
template <class Body>
bool parallelFor(size_t count, int threads, const Progress& progress, Body&& body) {
    std::atomic<size_t> next{0}, done{0};
    std::atomic<bool> stop{false};
    const size_t chunk = std::max<size_t>(1, count / (64 * size_t(std::max(1, threads))));
    auto work = [&] {
        while (!stop.load(std::memory_order_relaxed)) {
            size_t begin = next.fetch_add(chunk);
            if (begin >= count) return;
            size_t end = std::min(count, begin + chunk);
            for (size_t i = begin; i < end; ++i) body(i);
            done.fetch_add(end - begin);
            if (progress.cancelled()) stop = true;
        }
    };
    runInParallel(threads, work);
    if (progress.report && !stop) progress.report(1.0);
    return !stop && !progress.cancelled();
}

/// Index of sub-triangle (i, j) of a triangle divided n times per edge (rows j of 2 (n - j) - 1
/// triangles: up(i) then down(i)).
uint32_t localIndex(uint32_t i, uint32_t j, bool down, uint32_t n) {
    return 2 * n * j - j * j + 2 * i + (down ? 1 : 0);
}

}  // namespace

double pointTriangleFormFactor(const glm::dvec3& x, const glm::dvec3& n, const glm::dvec3& a,
                               const glm::dvec3& b, const glm::dvec3& c) {
    glm::dvec3 in[3] = {a - x, b - x, c - x}, poly[4];
    int count = 0;
    for (int i = 0; i < 3; ++i) {
        const glm::dvec3& p = in[i];
        const glm::dvec3& q = in[(i + 1) % 3];
        double dp = glm::dot(n, p), dq = glm::dot(n, q);
        if (dp >= 0.0) poly[count++] = p;
        if ((dp >= 0.0) != (dq >= 0.0)) poly[count++] = p + (dp / (dp - dq)) * (q - p);
    }
    if (count < 3) return 0.0;
    double sum = 0.0;
    for (int i = 0; i < count; ++i) {
        glm::dvec3 cr = glm::cross(poly[i], poly[(i + 1) % count]);
        double lc = glm::length(cr);
        if (!(lc > 0.0)) continue;
        sum += std::atan2(lc, glm::dot(poly[i], poly[(i + 1) % count])) * glm::dot(n, cr) / lc;
    }
    double f = 0.5 * std::abs(sum) / kPi;
    return std::isfinite(f) ? f : 0.0;
}

std::array<glm::dvec3, 3> rulePoints(const glm::dvec3& a, const glm::dvec3& b,
                                     const glm::dvec3& c) {
    const double kNear = 2.0 / 3.0, kFar = 1.0 / 6.0;
    return {kNear * a + kFar * b + kFar * c, kFar * a + kNear * b + kFar * c,
            kFar * a + kFar * b + kNear * c};
}

int workerThreads(int requested) {
    if (requested > 0) return requested;
    return std::max(1, int(std::thread::hardware_concurrency()));
}

namespace {

/// Total area of the scene's triangles, m2.
double sceneArea(const Scene& scene) {
    double total = 0.0;
    for (const Mesh& m : scene.meshes)
        for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
            glm::dvec3 a(m.positions[m.indices[t]]), b(m.positions[m.indices[t + 1]]),
                c(m.positions[m.indices[t + 2]]);
            total += 0.5 * glm::length(glm::cross(b - a, c - a));
        }
    return total;
}

/// Welds patch vertices within a mesh and a flat surface: the key is the position rounded to a
/// millionth of the patch size; vertices with one key but normals apart stay separate.
class VertexWelder {
  public:
    VertexWelder(std::vector<glm::dvec3>& vertices, double h)
        : mVertices(vertices), mQuantum(1e-6 * h) {}

    /// The index of the vertex at p on a surface of this normal in mesh `mesh`, added if new.
    uint32_t vertexOf(const glm::dvec3& p, const glm::dvec3& normal, uint32_t mesh) {
        auto key = std::make_tuple(std::llround(p.x / mQuantum), std::llround(p.y / mQuantum),
                                   std::llround(p.z / mQuantum), mesh);
        std::vector<uint32_t>& same = mWeld[key];
        for (uint32_t v : same)
            if (glm::dot(mVertexNormal[v], normal) > 0.999) return v;
        uint32_t v = uint32_t(mVertices.size());
        mVertices.push_back(p);
        mVertexNormal.push_back(normal);
        same.push_back(v);
        return v;
    }

  private:
    std::vector<glm::dvec3>& mVertices;
    double mQuantum;
    std::map<std::tuple<int64_t, int64_t, int64_t, uint32_t>, std::vector<uint32_t>> mWeld;
    std::vector<glm::dvec3> mVertexNormal;
};

/// How many times the edges of triangle (a, b, c) are divided for patches of edge about h (area
/// patchArea): its n^2 patches are about the patch area (half a square's triangle of edge h gets
/// n = s / h), and no patch edge is over 1.5 h (slivers, such as a disc's fan, get split
/// lengthwise). 0 for a degenerate triangle (no patch).
uint32_t triangleSubdivisions(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                              double h, double patchArea) {
    double twiceArea = glm::length(glm::cross(b - a, c - a));
    if (!(twiceArea > 1e-18) || !std::isfinite(twiceArea)) return 0;
    double longest = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
    double divisions = std::max(std::sqrt(0.5 * twiceArea / patchArea), longest / (1.5 * h));
    return uint32_t(std::clamp(std::ceil(divisions - 1e-9), 1.0, double(kMaxSubdivisions)));
}

/// A triangle of a mesh: its corners, its unit normal on the reflecting side (the vertex
/// normals' side where the mesh has them, else the winding's: counter-clockwise seen from
/// outside), whether that is against the winding, and its area.
struct Facet {
    uint32_t index[3];
    glm::dvec3 corner[3], normal{0.0};
    bool flip = false;
    double area = 0.0;

    Facet(const Mesh& m, size_t t) {
        for (int k = 0; k < 3; ++k) {
            index[k] = m.indices[t + k];
            corner[k] = glm::dvec3(m.positions[index[k]]);
        }
        glm::dvec3 g = glm::cross(corner[1] - corner[0], corner[2] - corner[0]);
        double twice = glm::length(g);
        if (!(twice > 0.0) || !std::isfinite(twice)) return;
        area = 0.5 * twice;
        normal = g / twice;
        if (index[0] < m.normals.size() && index[1] < m.normals.size() &&
            index[2] < m.normals.size()) {
            glm::dvec3 nv = glm::dvec3(m.normals[index[0]]) + glm::dvec3(m.normals[index[1]]) +
                            glm::dvec3(m.normals[index[2]]);
            flip = glm::dot(nv, normal) < 0.0;
        }
        if (flip) normal = -normal;
    }
    glm::dvec3 centroid() const { return (corner[0] + corner[1] + corner[2]) / 3.0; }
};

/// A triangle smaller than this part of a patch's area is gathered into a cluster (Radiosity.h):
/// a quarter, so that a triangle kept whole is at least a quarter of a patch and a mesh's
/// patches stay within four times its area's share of the target.
constexpr double kClusterAreaFraction = 0.25;

/// The clusters of one mesh: the cluster of each triangle (kNoCluster for one cut into patches
/// of its own), how many clusters, and how many patches its other triangles make.
constexpr uint32_t kNoCluster = UINT32_MAX;
struct MeshClusters {
    std::vector<uint32_t> of;
    uint32_t count = 0;
    size_t trianglePatches = 0;
};

MeshClusters findClusters(const Mesh& m, double h, double patchArea) {
    MeshClusters out;
    out.of.assign(m.triangleCount(), kNoCluster);
    // Key: the cube of edge h holding the centroid, and the axis direction the normal leans to.
    using Key = std::tuple<int64_t, int64_t, int64_t, int>;
    std::map<Key, uint32_t> ids;
    // Cells beyond 1e12 patch edges are one: the scene's coordinates are bounded far below.
    const double kCell = 1e12;
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        Facet f(m, t);
        uint32_t n = triangleSubdivisions(f.corner[0], f.corner[1], f.corner[2], h, patchArea);
        if (n != 1 || !(f.area < kClusterAreaFraction * patchArea)) {
            out.trianglePatches += size_t(n) * n;
            continue;
        }
        glm::dvec3 c = f.centroid() / h;
        glm::dvec3 a = glm::abs(f.normal);
        int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
        Key key{int64_t(std::floor(std::clamp(c.x, -kCell, kCell))),
                int64_t(std::floor(std::clamp(c.y, -kCell, kCell))),
                int64_t(std::floor(std::clamp(c.z, -kCell, kCell))),
                2 * axis + (f.normal[axis] < 0.0 ? 1 : 0)};
        auto [it, added] = ids.emplace(key, out.count);
        if (added) ++out.count;
        out.of[t / 3] = it->second;
    }
    return out;
}

/// Splits triangle t of mesh mi into patches of about `patchArea` (edge h), appending them and
/// the triangle's Split to `out`.
void addTrianglePatches(RadiosityMesh& out, VertexWelder& welder, const Mesh& m, size_t mi,
                        size_t t, const glm::dvec3& albedo, double h, double patchArea) {
    using Split = RadiosityMesh::Split;
    using Patch = RadiosityMesh::Patch;
    Facet f(m, t);
    const glm::dvec3 &a = f.corner[0], &b = f.corner[1], &c = f.corner[2];
    Split split;
    split.firstPatch = uint32_t(out.patches.size());
    uint32_t n = triangleSubdivisions(a, b, c, h, patchArea);
    if (n == 0) {
        split.subdivisions = 0;  // degenerate: no patch
        out.splits[mi].push_back(split);
        return;
    }
    split.subdivisions = n;
    out.splits[mi].push_back(split);
    // Grid points a + i/n (b - a) + j/n (c - a), i + j <= n.
    std::vector<uint32_t> grid(size_t(n + 1) * size_t(n + 2) / 2);
    auto gridIndex = [n](uint32_t i, uint32_t j) { return size_t(j) * (2 * n + 3 - j) / 2 + i; };
    for (uint32_t j = 0; j <= n; ++j)
        for (uint32_t i = 0; i + j <= n; ++i) {
            glm::dvec3 p = a + (double(i) / n) * (b - a) + (double(j) / n) * (c - a);
            grid[gridIndex(i, j)] = welder.vertexOf(p, f.normal, uint32_t(mi));
        }
    double area = f.area / double(n * n);
    auto add = [&](uint32_t v0, uint32_t v1, uint32_t v2) {
        Patch p;
        p.vertex =
            f.flip ? std::array<uint32_t, 3>{v0, v2, v1} : std::array<uint32_t, 3>{v0, v1, v2};
        const glm::dvec3 &x0 = out.vertices[v0], &x1 = out.vertices[v1], &x2 = out.vertices[v2];
        p.centroid = (x0 + x1 + x2) / 3.0;
        p.samples = rulePoints(x0, x1, x2);
        p.normal = f.normal;
        p.area = area;
        p.albedo = albedo;
        p.hidden = m.hidden;
        out.patches.push_back(p);
    };
    for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i + j < n; ++i) {
            add(grid[gridIndex(i, j)], grid[gridIndex(i + 1, j)], grid[gridIndex(i, j + 1)]);
            if (i + j < n - 1)
                add(grid[gridIndex(i + 1, j)], grid[gridIndex(i + 1, j + 1)],
                    grid[gridIndex(i, j + 1)]);
        }
}

/// The clusters of mesh mi (findClusters) as patches (Radiosity.h), with their triangles for
/// display and the Splits of those triangles pointing at them.
void addClusterPatches(RadiosityMesh& out, const Mesh& m, size_t mi, const MeshClusters& clusters,
                       const glm::dvec3& albedo) {
    if (clusters.count == 0) return;
    const uint32_t first = uint32_t(out.patches.size());
    struct Sum {
        double area = 0.0;
        glm::dvec3 at{0.0}, normal{0.0};
    };
    std::vector<Sum> sums(clusters.count);
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        uint32_t id = clusters.of[t / 3];
        if (id == kNoCluster) continue;
        Facet f(m, t);
        sums[id].area += f.area;
        sums[id].at += f.area * f.centroid();
        sums[id].normal += f.area * f.normal;
    }
    // The stand-ins: an equilateral triangle of the cluster's area around its mean position, in
    // the plane of its mean normal, counter-clockwise seen from that side.
    std::vector<glm::dvec3> mean(clusters.count);
    for (uint32_t id = 0; id < clusters.count; ++id) {
        const Sum& s = sums[id];
        RadiosityMesh::Patch p;
        p.cluster = true;
        p.area = s.area;
        p.normal = glm::length(s.normal) > 0.0 ? glm::normalize(s.normal) : glm::dvec3(0, 1, 0);
        mean[id] = s.area > 0.0 ? s.at / s.area : glm::dvec3(0.0);
        glm::dvec3 helper = std::abs(p.normal.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        glm::dvec3 u = glm::normalize(glm::cross(helper, p.normal)), v = glm::cross(p.normal, u);
        // Circumradius of the equilateral triangle of this area: side sqrt(4 A / sqrt 3).
        double r = std::sqrt(4.0 * s.area / std::sqrt(3.0)) / std::sqrt(3.0);
        for (int k = 0; k < 3; ++k) {
            double angle = 0.5 * kPi + 2.0 * kPi * k / 3.0;
            p.vertex[k] = uint32_t(out.vertices.size());
            out.vertices.push_back(mean[id] + r * (std::cos(angle) * u + std::sin(angle) * v));
        }
        p.centroid = mean[id];
        p.albedo = albedo;
        p.hidden = m.hidden;
        out.patches.push_back(p);
    }
    // On the surface: the centroid is its member's nearest the mean (preferring members that
    // face its way), the samples its members' nearest the stand-in's rule points.
    std::vector<double> best(clusters.count, std::numeric_limits<double>::infinity());
    std::vector<std::array<double, 3>> bestSample(
        clusters.count,
        {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
         std::numeric_limits<double>::infinity()});
    std::vector<std::array<glm::dvec3, 3>> rule(clusters.count);
    for (uint32_t id = 0; id < clusters.count; ++id) {
        const RadiosityMesh::Patch& p = out.patches[first + id];
        rule[id] = rulePoints(out.vertices[p.vertex[0]], out.vertices[p.vertex[1]],
                              out.vertices[p.vertex[2]]);
    }
    const uint32_t displayBase = uint32_t(out.vertices.size());
    for (const glm::vec3& x : m.positions) out.vertices.push_back(glm::dvec3(x));
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        uint32_t id = clusters.of[t / 3];
        if (id == kNoCluster) continue;
        Facet f(m, t);
        RadiosityMesh::Patch& p = out.patches[first + id];
        glm::dvec3 c = f.centroid();
        // Distance squared, plus the cluster's area for a member facing 90 degrees away.
        double score = glm::dot(c - mean[id], c - mean[id]) +
                       sums[id].area * (1.0 - glm::dot(f.normal, p.normal));
        if (score < best[id]) best[id] = score, p.centroid = c;
        for (int k = 0; k < 3; ++k) {
            double d = glm::dot(c - rule[id][k], c - rule[id][k]);
            if (d < bestSample[id][k]) bestSample[id][k] = d, p.samples[k] = c;
        }
        out.splits[mi][t / 3] = {first + id, 1};
        out.displayTriangles.push_back(
            {displayBase + f.index[0], displayBase + f.index[1], displayBase + f.index[2]});
        out.displayPatch.push_back(first + id);
    }
}

/// A convex room: no vertex behind any patch (within rounding of the coordinates).
bool isConvexRoom(const RadiosityMesh& out) {
    double extent = 0.0;
    for (const glm::dvec3& v : out.vertices) extent = std::max(extent, glm::length(v));
    bool convexRoom = !out.patches.empty();
    for (size_t p = 0; p < out.patches.size() && convexRoom; ++p) {
        const RadiosityMesh::Patch& patch = out.patches[p];
        for (const glm::dvec3& v : out.vertices)
            if (glm::dot(patch.normal, v - patch.centroid) < -1e-9 * std::max(1.0, extent)) {
                convexRoom = false;
                break;
            }
    }
    return convexRoom;
}

/// Patches around each vertex (out.vertexStart, out.vertexPatches), the display triangles'
/// with their clusters.
void indexVertexPatches(RadiosityMesh& out) {
    std::vector<uint32_t> counts(out.vertices.size() + 1, 0);
    for (const RadiosityMesh::Patch& p : out.patches)
        for (uint32_t v : p.vertex) ++counts[v + 1];
    for (const auto& t : out.displayTriangles)
        for (uint32_t v : t) ++counts[v + 1];
    out.vertexStart.assign(out.vertices.size() + 1, 0);
    for (size_t v = 0; v < out.vertices.size(); ++v)
        out.vertexStart[v + 1] = out.vertexStart[v] + counts[v + 1];
    out.vertexPatches.assign(out.vertexStart.back(), 0);
    std::vector<uint32_t> fill(out.vertexStart.begin(), out.vertexStart.end() - 1);
    for (uint32_t p = 0; p < out.patches.size(); ++p)
        for (uint32_t v : out.patches[p].vertex) out.vertexPatches[fill[v]++] = p;
    for (size_t t = 0; t < out.displayTriangles.size(); ++t)
        for (uint32_t v : out.displayTriangles[t])
            out.vertexPatches[fill[v]++] = out.displayPatch[t];
}

}  // namespace

RadiosityMesh RadiosityMesh::build(const Scene& scene, const RadiositySettings& settings) {
    RadiosityMesh out;
    double total = sceneArea(scene);
    // A quad of edge h splits into two patches of h^2 / 2.
    out.patchSize = settings.patchSize > 0.0
                        ? settings.patchSize
                        : std::sqrt(2.0 * total / double(std::max(1, settings.targetPatches)));
    double h = std::max(out.patchSize, 1e-9), patchArea = 0.5 * h * h;
    // Counted before anything is built: the solution keeps a coefficient for every pair of
    // patches.
    std::vector<MeshClusters> clusters(scene.meshes.size());
    size_t count = 0, most = 0, mostMesh = 0;
    for (size_t mi = 0; mi < scene.meshes.size(); ++mi) {
        clusters[mi] = findClusters(scene.meshes[mi], h, patchArea);
        size_t own = clusters[mi].trianglePatches + clusters[mi].count;
        count += own;
        if (own > most) most = own, mostMesh = mi;
    }
    if (count > kMaxPatches) {
        const Mesh& m = scene.meshes[mostMesh];
        char size[32];
        std::snprintf(size, sizeof size, "%.3g", h);
        throw InputError(
            (scene.path.empty() ? std::string("the scene") : scene.path) +
            ": interreflected light: its surfaces make " + std::to_string(count) + " patches of " +
            size + " m, more than the " + std::to_string(kMaxPatches) +
            " whose solution fits in memory (" +
            (m.name.empty() ? "one surface" : "\"" + m.name + "\"") + " alone makes " +
            std::to_string(most) +
            "); ask for fewer or larger patches, or leave the interreflected light out");
    }
    VertexWelder welder(out.vertices, h);
    out.splits.resize(scene.meshes.size());
    for (size_t mi = 0; mi < scene.meshes.size(); ++mi) {
        const Mesh& m = scene.meshes[mi];
        glm::dvec3 albedo = m.material < scene.materials.size()
                                ? glm::dvec3(scene.materials[m.material].albedo)
                                : glm::dvec3(0.0);
        albedo = glm::clamp(albedo, 0.0, 1.0);
        size_t first = out.patches.size();
        for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
            if (clusters[mi].of[t / 3] == kNoCluster)
                addTrianglePatches(out, welder, m, mi, t, albedo, h, patchArea);
            else
                out.splits[mi].push_back({});  // set by addClusterPatches
        }
        addClusterPatches(out, m, mi, clusters[mi], albedo);
        clusters[mi] = {};
        if (m.luminaireBody) {
            for (size_t p = first; p < out.patches.size(); ++p)
                out.patches[p].body = int(out.bodyBounds.size());
            out.bodyBounds.emplace_back(glm::dvec3(m.boundsMin), glm::dvec3(m.boundsMax));
        }
    }
    // Clusters' stand-ins are off their surfaces: no room with them counts as convex.
    out.convexRoom = out.displayTriangles.empty() && isConvexRoom(out);
    indexVertexPatches(out);
    return out;
}

uint32_t RadiosityMesh::patchAt(uint32_t mesh, uint32_t triangle, double u, double v,
                                glm::dvec3& weights) const {
    const Split& s = splits.at(mesh).at(triangle);
    uint32_t n = s.subdivisions;
    if (n == 0) {
        weights = glm::dvec3(1.0 / 3.0);
        return UINT32_MAX;
    }
    double fu = std::clamp(u, 0.0, 1.0) * n, fv = std::clamp(v, 0.0, 1.0) * n;
    uint32_t j = std::min(uint32_t(fv), n - 1);
    uint32_t i = std::min(uint32_t(fu), n - 1 - j);
    double r = std::clamp(fu - i, 0.0, 1.0), q = std::clamp(fv - j, 0.0, 1.0);
    bool down = r + q > 1.0 && i + j < n - 1;
    uint32_t index = s.firstPatch + localIndex(i, j, down, n);
    if (patches[index].cluster) {
        weights = glm::dvec3(1.0 / 3.0);
        return index;
    }
    // Weights of the patch's corners in the order of the grid points that made it.
    if (down)
        weights = {1.0 - q, r + q - 1.0, 1.0 - r};
    else
        weights = {std::max(0.0, 1.0 - r - q), r, q};
    // A patch stored with the other winding (its vertices 1 and 2 swapped).
    const Patch& p = patches[index];
    glm::dvec3 e1 = vertices[p.vertex[1]] - vertices[p.vertex[0]],
               e2 = vertices[p.vertex[2]] - vertices[p.vertex[0]];
    if (glm::dot(glm::cross(e1, e2), p.normal) < 0.0) std::swap(weights.y, weights.z);
    return index;
}

double RadiosityMesh::formFactorTo(const glm::dvec3& x, const glm::dvec3& n, uint32_t patch) const {
    const Patch& q = patches[patch];
    const glm::dvec3 &a = vertices[q.vertex[0]], &b = vertices[q.vertex[1]],
                     &c = vertices[q.vertex[2]];
    double polygon = pointTriangleFormFactor(x, n, a, b, c);
    if (!q.cluster) return polygon;
    glm::dvec3 d = (a + b + c) / 3.0 - x;
    double r2 = glm::dot(d, d);
    if (!(r2 > 0.0)) return 0.0;
    glm::dvec3 dir = d / std::sqrt(r2);
    double cosHere = glm::dot(n, dir), cosThere = -glm::dot(q.normal, dir);
    if (!(cosHere > 0.0) || !(cosThere > 0.0)) return 0.0;
    return std::min(polygon, q.area * cosHere * cosThere / (kPi * r2));
}

bool RadiosityMesh::reflects() const {
    for (const Patch& p : patches)
        if (p.albedo.x + p.albedo.y + p.albedo.z > 0.0) return true;
    return false;
}

double RadiosityMesh::totalArea() const {
    double a = 0.0;
    for (const Patch& p : patches) a += p.area;
    return a;
}

bool TransferMatrix::build(const RadiosityMesh& mesh, const EmbreeVisibility& visibility,
                           int threads, const Progress& progress) {
    size = mesh.patches.size();
    t.assign(size * size, 0.f);
    const auto& patches = mesh.patches;
    std::atomic<size_t> rows{0};
    Progress inner = progress;
    inner.report = nullptr;
    int workers = workerThreads(threads);
    std::thread::id caller = std::this_thread::get_id();
    return parallelFor(size, workers, inner, [&](size_t j) {
        const RadiosityMesh::Patch& shooter = patches[j];
        if (shooter.area > 0.0) {
            for (size_t k = 0; k < size; ++k) {
                if (k == j) continue;
                const RadiosityMesh::Patch& receiver = patches[k];
                // A receiver reflects on its normal's side only: the shooter must be in front.
                if (!(glm::dot(receiver.normal, shooter.centroid - receiver.centroid) > 0.0))
                    continue;
                // From the shooter's centroid: over a closed room of triangle patches the row
                // sums to exactly one.
                double f = mesh.formFactorTo(shooter.centroid, shooter.normal, uint32_t(k));
                if (!(f > 0.0)) continue;
                if (!mesh.convexRoom &&
                    !visibility.visibleBetweenSurfaces(shooter.centroid, receiver.centroid))
                    continue;
                t[k * size + j] = float(shooter.area * f / receiver.area);
            }
        }
        size_t done = rows.fetch_add(1) + 1;
        if (progress.report && std::this_thread::get_id() == caller && done % 64 == 0)
            progress.report(double(done) / double(size));
    });
}

bool directOnPatches(const RadiosityMesh& mesh, const PointEstimator& estimate,
                     const EstimateOptions& options, int threads, std::vector<glm::dvec3>& out,
                     const Progress& progress, const std::function<bool(size_t)>& dark) {
    out.assign(mesh.patches.size(), glm::dvec3(0.0));
    std::atomic<size_t> count{0};
    std::thread::id caller = std::this_thread::get_id();
    Progress inner = progress;
    inner.report = nullptr;
    return parallelFor(mesh.patches.size(), workerThreads(threads), inner, [&](size_t i) {
        const RadiosityMesh::Patch& p = mesh.patches[i];
        glm::dvec3 sum(0.0);
        for (int q = 0; q < 3 && !(dark && dark(i)); ++q) {
            const glm::dvec3& x = p.samples[q];
            EstimateOptions o = options;
            o.seed = options.seed * 0x9E3779B97F4A7C15ull + uint64_t(i) * 3 + uint64_t(q) + 1;
            Estimate e = estimate(x, p.normal, o);
            if (std::isfinite(e.irradiance.x + e.irradiance.y + e.irradiance.z))
                sum += e.irradiance;
        }
        out[i] = sum / 3.0;
        size_t done = count.fetch_add(1) + 1;
        if (progress.report && std::this_thread::get_id() == caller && done % 256 == 0)
            progress.report(double(done) / double(mesh.patches.size()));
    });
}

int solveRadiosity(const TransferMatrix& transfer, const RadiosityMesh& mesh,
                   const std::vector<glm::dvec3>& direct, std::vector<glm::dvec3>& indirect,
                   double tolerance, int threads, const Progress& progress) {
    const size_t n = mesh.patches.size();
    if (indirect.size() != n) indirect.assign(n, glm::dvec3(0.0));
    if (n == 0 || transfer.size != n) return 0;
    std::vector<glm::dvec3> exitance(n), next(n);
    int workers = workerThreads(threads);
    const int kMaxIterations = 100000;  // rho < 1 converges long before; a guard only
    for (int iteration = 1; iteration <= kMaxIterations; ++iteration) {
        // M_j = rho_j (E_dir + E_ind), then E_ind'_k = sum_j T_kj M_j.
        for (size_t j = 0; j < n; ++j)
            exitance[j] = mesh.patches[j].albedo * (direct[j] + indirect[j]);
        Progress quiet;
        quiet.cancel = progress.cancel;
        bool finished = parallelFor(n, workers, quiet, [&](size_t k) {
            const float* row = &transfer.t[k * n];
            glm::dvec3 sum(0.0);
            for (size_t j = 0; j < n; ++j)
                if (row[j] != 0.f) sum += double(row[j]) * exitance[j];
            next[k] = sum;
        });
        if (!finished) return -1;
        double change = 0.0, flux = 0.0;
        for (size_t k = 0; k < n; ++k) {
            change += mesh.patches[k].area * std::abs(luminance(next[k] - indirect[k]));
            flux += mesh.patches[k].area * luminance(next[k]);
        }
        indirect.swap(next);
        if (!(flux > 0.0) || change <= tolerance * flux) return iteration;
    }
    return kMaxIterations;
}

std::vector<glm::dvec3> vertexValues(const RadiosityMesh& mesh,
                                     const std::vector<glm::dvec3>& perPatch) {
    std::vector<glm::dvec3> out(mesh.vertices.size(), glm::dvec3(0.0));
    for (size_t v = 0; v < mesh.vertices.size(); ++v) {
        glm::dvec3 sum(0.0);
        double area = 0.0;
        for (uint32_t k = mesh.vertexStart[v]; k < mesh.vertexStart[v + 1]; ++k) {
            uint32_t p = mesh.vertexPatches[k];
            sum += mesh.patches[p].area * perPatch[p];
            area += mesh.patches[p].area;
        }
        out[v] = area > 0.0 ? sum / area : glm::dvec3(0.0);
    }
    return out;
}

}  // namespace candela
