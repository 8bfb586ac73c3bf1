#include "luminaires/SphericalPolygon.h"

#include <algorithm>
#include <cmath>

#include "shaders/shared/Constants.h"

namespace candela::spherical {

Polygon clip(const Polygon& in, const glm::dvec3& normal) {
    Polygon out;
    for (int i = 0; i < in.count; ++i) {
        const glm::dvec3& a = in.v[size_t(i)];
        const glm::dvec3& b = in.v[size_t((i + 1) % in.count)];
        double da = glm::dot(normal, a), db = glm::dot(normal, b);
        bool inA = da >= 0.0, inB = db >= 0.0;
        if (inA && out.count < kMaxPolygon) out.v[size_t(out.count++)] = a;
        if (inA != inB && out.count < kMaxPolygon) {
            double s = da / (da - db);  // the signs differ, so da - db is not zero
            out.v[size_t(out.count++)] = a + s * (b - a);
        }
    }
    return out.count >= 3 ? out : Polygon{};
}

double triangleSolidAngle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    if (!(la > 0.0 && lb > 0.0 && lc > 0.0)) return 0.0;
    glm::dvec3 ua = a / la, ub = b / lb, uc = c / lc;
    double num = std::abs(glm::dot(ua, glm::cross(ub, uc)));
    double den = 1.0 + glm::dot(ua, ub) + glm::dot(ub, uc) + glm::dot(uc, ua);
    double omega = 2.0 * std::atan2(num, den);  // den <= 0 only past a hemisphere: atan2 handles it
    return std::isfinite(omega) ? omega : 0.0;
}

double solidAngle(const Polygon& p) {
    double sum = 0.0;
    for (int i = 1; i + 1 < p.count; ++i)
        sum += triangleSolidAngle(p.v[0], p.v[size_t(i)], p.v[size_t(i + 1)]);
    return sum;
}

double projectedSolidAngle(const Polygon& p, const glm::dvec3& m) {
    double sum = 0.0;
    for (int i = 0; i < p.count; ++i) {
        const glm::dvec3& a = p.v[size_t(i)];
        const glm::dvec3& b = p.v[size_t((i + 1) % p.count)];
        // a x (b - a) = a x b, but keeps its digits when the edge is tiny beside the distance
        // (a x b of two nearly parallel vectors cancels: a 1e-6 m opening 2 m away lost 6 of
        // 16 digits of its projected solid angle).
        glm::dvec3 c = glm::cross(a, b - a);
        double lc = glm::length(c);
        if (!(lc > 0.0)) continue;  // zero-length edge or an edge through the receiver
        sum += std::atan2(lc, glm::dot(a, b)) * glm::dot(m, c) / lc;
    }
    // At most the whole hemisphere, pi (rounding at contact must not give more).
    double result = std::min(0.5 * std::abs(sum), gpu::kPi);
    return std::isfinite(result) ? result : 0.0;
}

ClosestPoint closestPoint(const Polygon& p, double tolerance) {
    ClosestPoint best;
    if (p.count == 0) return best;
    // The foot of the perpendicular, when it falls inside and clear of the boundary. Newell's
    // normal is zero for a degenerate polygon (a segment), which only has a boundary.
    glm::dvec3 normal(0.0);
    for (int i = 0; i < p.count; ++i)
        normal += glm::cross(p.v[size_t(i)], p.v[size_t((i + 1) % p.count)]);
    double ln = glm::length(normal);
    if (ln > 0.0 && p.count >= 3) {
        normal /= ln;
        glm::dvec3 foot = glm::dot(p.v[0], normal) * normal;
        double clearance = INFINITY;
        for (int i = 0; i < p.count; ++i) {
            const glm::dvec3& a = p.v[size_t(i)];
            glm::dvec3 e = p.v[size_t((i + 1) % p.count)] - a;
            double le = glm::length(e);
            if (!(le > 0.0)) continue;
            // Signed distance inside the edge (corners wind either way: the sign of the normal
            // follows the winding, so inside is always the positive side).
            clearance = std::min(clearance, glm::dot(glm::cross(e, foot - a), normal) / le);
        }
        if (clearance > tolerance) {
            best.point = foot;
            return best;
        }
    }
    // On the boundary: the nearest point of the edges to the receiver (for a foot inside but
    // within the tolerance this is also the nearest edge point to the foot).
    double bestDist = INFINITY;
    for (int i = 0; i < p.count; ++i) {
        const glm::dvec3& a = p.v[size_t(i)];
        glm::dvec3 e = p.v[size_t((i + 1) % p.count)] - a;
        double le2 = glm::dot(e, e);
        double t = le2 > 0.0 ? std::clamp(glm::dot(-a, e) / le2, 0.0, 1.0) : 0.0;
        glm::dvec3 q = a + t * e;
        double d = glm::length(q);
        if (!(d < bestDist)) continue;
        bestDist = d;
        double le = std::sqrt(le2);
        best.point = q;
        best.index = i;
        best.place = Place::Edge;
        if (t * le <= tolerance) {
            best.place = Place::Corner;
            best.point = a;
        } else if ((1.0 - t) * le <= tolerance) {
            best.place = Place::Corner;
            best.index = (i + 1) % p.count;
            best.point = p.v[size_t(best.index)];
        }
    }
    return best;
}

Triangulation initialTriangulation(int n, const ClosestPoint& cp) {
    Triangulation t;
    if (n < 3) return t;
    auto corner = [n](int i) { return 1 + ((i % n) + n) % n; };
    if (cp.place == Place::Corner) {
        for (int j = 1; j + 1 < n; ++j)
            t.tri[size_t(t.count++)] = {corner(cp.index), corner(cp.index + j),
                                        corner(cp.index + j + 1)};
        return t;
    }
    for (int i = 0; i < n; ++i) {
        if (cp.place == Place::Edge && i == cp.index) continue;
        t.tri[size_t(t.count++)] = {0, corner(i), corner(i + 1)};
    }
    return t;
}

bool inCircumcircle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                    const glm::dvec3& d) {
    // The circumcircle is where the plane through a, b, c cuts the sphere; its inside is the cap
    // beyond that plane, away from the centre (Prost Eq. 5.8 in sign-free form).
    glm::dvec3 n = glm::cross(b - a, c - a);
    double ln = glm::length(n);
    if (!(ln > 0.0)) return false;
    double centre = -glm::dot(n, a);
    double point = glm::dot(n, d - a);
    return (centre > 0.0 ? -point : point) > 1e-12 * ln;
}

namespace {

/// Sign of det(a, b, c): which side of the great circle through a and b c lies on.
double side(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    return glm::dot(glm::cross(a, b), c);
}

}  // namespace

void makeDelaunay(Triangulation& t, const glm::dvec3* dirs) {
    // Lawson's algorithm: flip any edge whose opposite vertex lies in the circumcircle, until
    // none does. Each flip strictly improves the triangulation, so it ends; the cap only guards
    // against rounding cycling on degenerate (cocircular) input.
    const int maxFlips = 4 * kMaxPolygon;
    bool changed = true;
    while (changed && t.flips < maxFlips) {
        changed = false;
        for (int i = 0; i < t.count && !changed; ++i) {
            for (int e = 0; e < 3 && !changed; ++e) {
                int a = t.tri[size_t(i)][size_t(e)], b = t.tri[size_t(i)][size_t((e + 1) % 3)];
                int c = t.tri[size_t(i)][size_t((e + 2) % 3)];
                for (int j = 0; j < t.count; ++j) {
                    if (j == i) continue;
                    const auto& o = t.tri[size_t(j)];
                    bool hasA = o[0] == a || o[1] == a || o[2] == a;
                    bool hasB = o[0] == b || o[1] == b || o[2] == b;
                    if (!hasA || !hasB) continue;
                    int d = o[0] != a && o[0] != b ? o[0] : (o[1] != a && o[1] != b ? o[1] : o[2]);
                    if (!inCircumcircle(dirs[a], dirs[b], dirs[c], dirs[d])) break;
                    // Only a convex quadrilateral can flip: c, d on opposite sides of ab and
                    // a, b on opposite sides of cd.
                    bool convex =
                        side(dirs[a], dirs[b], dirs[c]) * side(dirs[a], dirs[b], dirs[d]) < 0.0 &&
                        side(dirs[c], dirs[d], dirs[a]) * side(dirs[c], dirs[d], dirs[b]) < 0.0;
                    if (!convex) break;
                    // Triangle (a, b, c) and its neighbour (b, a, d) become (a, d, c), (d, b, c).
                    t.tri[size_t(i)] = {a, d, c};
                    t.tri[size_t(j)] = {d, b, c};
                    ++t.flips;
                    changed = true;
                    break;
                }
            }
        }
    }
}

}  // namespace candela::spherical
