#include "scene/Occlusion.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "shaders/shared/Constants.h"

namespace candela {

namespace {

struct DBox {
    glm::dvec3 lo{0.0}, hi{0.0};
};

std::array<glm::dvec3, 8> corners(const DBox& b) {
    std::array<glm::dvec3, 8> out;
    for (int i = 0; i < 8; ++i)
        out[size_t(i)] =
            glm::dvec3(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z);
    return out;
}

bool overlaps(const DBox& a, const DBox& b) {
    for (int i = 0; i < 3; ++i)
        if (a.hi[i] < b.lo[i] || b.hi[i] < a.lo[i]) return false;
    return true;
}

double largestCoordinate(const DBox& b) {
    glm::dvec3 m = glm::max(glm::abs(b.lo), glm::abs(b.hi));
    return std::max({m.x, m.y, m.z});
}

/// Bounds not entirely outside one of the side clip planes, nor entirely behind the eye.
bool mayBeVisible(const DBox& box, const glm::dmat4& viewProj) {
    std::array<int, 5> outside{};  // x < -w, x > w, y < -w, y > w, w <= 0
    for (const glm::dvec3& p : corners(box)) {
        glm::dvec4 c = viewProj * glm::dvec4(p, 1.0);
        outside[0] += c.x < -c.w;
        outside[1] += c.x > c.w;
        outside[2] += c.y < -c.w;
        outside[3] += c.y > c.w;
        outside[4] += c.w <= 0.0;
    }
    return std::none_of(outside.begin(), outside.end(), [](int n) { return n == 8; });
}

/// What the test needs to know about one luminaire.
struct Emitter {
    DBox bounds;
    std::vector<glm::dvec3> outline;
    glm::dvec3 aim{0.0};
    double lowestAlongAim = 0.0;  ///< min over the outline of dot(p, aim), metres.
    bool oneSided = true;         ///< Emits only into the +aim half-space.
};

Emitter describe(const Luminaire& luminaire) {
    Emitter e;
    e.outline = luminaire.outline();
    glm::dvec3 x, y;
    luminaire.emitterPose().frame(x, y, e.aim);
    glm::dvec3 centroid(0.0);
    e.bounds.lo = e.bounds.hi = e.outline[0];
    e.lowestAlongAim = glm::dot(e.outline[0], e.aim);
    for (const glm::dvec3& p : e.outline) {
        e.bounds.lo = glm::min(e.bounds.lo, p);
        e.bounds.hi = glm::max(e.bounds.hi, p);
        e.lowestAlongAim = std::min(e.lowestAlongAim, glm::dot(p, e.aim));
        centroid += p / double(e.outline.size());
    }
    // Probe backward directions (behind the aim plane, up to 85 degrees from -aim) at the
    // outline's centroid; any emission there disables the emitting-side test.
    using gpu::kPi;
    for (double theta : {0.0, 30.0, 60.0, 85.0}) {
        for (int k = 0; k < 8; ++k) {
            double phi = 2.0 * kPi * k / 8.0, t = theta * kPi / 180.0;
            glm::dvec3 w =
                -std::cos(t) * e.aim + std::sin(t) * (std::cos(phi) * x + std::sin(phi) * y);
            glm::dvec3 L = luminaire.radiance(centroid, w);
            if (L.x > 0.0 || L.y > 0.0 || L.z > 0.0) e.oneSided = false;
        }
    }
    return e;
}

DBox boundsOf(const Mesh& mesh) {
    return {glm::dvec3(mesh.boundsMin), glm::dvec3(mesh.boundsMax)};
}

/// Can occluder `o` block light from `e` to receiver `r`? (see the rule in Occlusion.h)
bool canBlock(const Mesh& o, size_t oIndex, const Mesh& r, size_t rIndex, const Emitter& e) {
    if (oIndex == rIndex) return o.shape == MeshShape::General;
    DBox ob = boundsOf(o), rb = boundsOf(r);
    DBox region{glm::min(e.bounds.lo, rb.lo), glm::max(e.bounds.hi, rb.hi)};
    double eps = 1e-6 * std::max({1.0, largestCoordinate(region), largestCoordinate(ob)});

    if (o.shape == MeshShape::Plane) {
        glm::dvec3 n = o.normals.empty() ? glm::dvec3(0.0) : glm::dvec3(o.normals[0]);
        if (glm::length(n) < 1e-12) return overlaps(ob, region);  // No usable plane: be safe.
        n = glm::normalize(n);
        glm::dvec3 p0(o.positions[0]);
        bool anyAbove = false, anyBelow = false;
        auto classify = [&](const glm::dvec3& p) {
            double s = glm::dot(p - p0, n);
            anyAbove = anyAbove || s > eps;
            anyBelow = anyBelow || s < -eps;
        };
        for (const glm::dvec3& p : e.outline) classify(p);
        for (const glm::dvec3& p : corners(rb)) classify(p);
        if (!(anyAbove && anyBelow)) return false;  // All on one closed side.
        return overlaps(ob, region);
    }

    DBox shrunk{ob.lo + eps, ob.hi - eps};
    shrunk.hi = glm::max(shrunk.hi, shrunk.lo);  // Thin boxes keep their middle.
    if (!overlaps(shrunk, region)) return false;
    if (!e.oneSided) return true;
    for (const glm::dvec3& c : corners(ob))
        if (glm::dot(c, e.aim) > e.lowestAlongAim + eps) return true;
    return false;
}

}  // namespace

std::vector<bool> luminairesNeedingShadows(const Scene& scene, const glm::mat4& viewProj) {
    std::vector<size_t> solid, receivers;
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        if (mesh.triangleCount() == 0 || mesh.positions.empty()) continue;
        solid.push_back(m);
        if (!mesh.hidden && mayBeVisible(boundsOf(mesh), glm::dmat4(viewProj)))
            receivers.push_back(m);
    }

    std::vector<bool> needs(scene.luminaires.size(), false);
    for (size_t l = 0; l < scene.luminaires.size(); ++l) {
        const Luminaire& luminaire = *scene.luminaires[l];
        if (receivers.empty()) continue;
        if (luminaire.outline().empty()) {
            needs[l] = true;  // Unknown emitter extent: cannot rule anything out.
            continue;
        }
        Emitter e = describe(luminaire);
        // Its own body casts no shadow on its light (insideBody, at every outline point).
        auto own = [&](const Mesh& m) {
            return m.luminaireBody &&
                   std::all_of(e.outline.begin(), e.outline.end(), [&](const glm::dvec3& p) {
                       return insideBody(p, glm::dvec3(m.boundsMin), glm::dvec3(m.boundsMax));
                   });
        };
        for (size_t r : receivers) {
            for (size_t o : solid) {
                if (own(scene.meshes[o])) continue;
                if (canBlock(scene.meshes[o], o, scene.meshes[r], r, e)) {
                    needs[l] = true;
                    break;
                }
            }
            if (needs[l]) break;
        }
    }
    return needs;
}

}  // namespace candela

namespace candela {

bool environmentNeedsShadows(const Scene& scene, const glm::mat4& viewProj) {
    std::vector<size_t> solid;
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        if (mesh.triangleCount() > 0 && !mesh.positions.empty()) solid.push_back(m);
    }
    for (size_t r : solid) {
        const Mesh& receiver = scene.meshes[r];
        DBox rb = boundsOf(receiver);
        if (!mayBeVisible(rb, glm::dmat4(viewProj))) continue;
        if (receiver.shape == MeshShape::General) return true;
        for (size_t o : solid) {
            if (o == r) continue;
            const Mesh& occluder = scene.meshes[o];
            // A plane cannot block a receiver lying in it (the rays would graze it); anything
            // else may block some direction of a light that comes from everywhere.
            if (occluder.shape == MeshShape::Plane && !occluder.normals.empty()) {
                glm::dvec3 n = glm::dvec3(occluder.normals[0]);
                if (glm::length(n) > 1e-12) {
                    n = glm::normalize(n);
                    glm::dvec3 p0(occluder.positions[0]);
                    double eps = 1e-6 * std::max(1.0, largestCoordinate(rb));
                    bool inPlane = true;
                    for (const glm::dvec3& c : corners(rb))
                        inPlane = inPlane && std::abs(glm::dot(c - p0, n)) <= eps;
                    if (inPlane) continue;
                }
            }
            return true;
        }
    }
    return false;
}

std::vector<bool> sourcesNeedingShadows(const Scene& scene, const glm::mat4& viewProj) {
    std::vector<bool> placed = luminairesNeedingShadows(scene, viewProj), out;
    for (const Luminaire* source : scene.sources()) {
        if (source->atInfinity()) {
            out.push_back(environmentNeedsShadows(scene, viewProj));
            continue;
        }
        for (size_t i = 0; i < scene.luminaires.size(); ++i)
            if (scene.luminaires[i].get() == source) out.push_back(placed[i]);
    }
    return out;
}

}  // namespace candela
