#include "scene/Procedural.h"

#include <algorithm>
#include <cmath>

namespace candela {

namespace {

/// Where one side of a trapezoid runs within a strip: its x at the strip's bottom and top.
struct Side {
    double x0 = 0.0, x1 = 0.0;
    double mid() const { return 0.5 * (x0 + x1); }
};

/// Twice the signed area of the triangle a, b, c (positive counter-clockwise).
double orient(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

/// Whether segments ab and cd share a point (touching counts). `eps`: the distance below which
/// points count as on a line, m.
bool segmentsMeet(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c,
                  const glm::dvec2& d, double eps) {
    auto side = [eps](double o, double len) {
        return std::abs(o) <= eps * len ? 0 : (o > 0 ? 1 : -1);
    };
    double lab = glm::length(b - a), lcd = glm::length(d - c);
    int s1 = side(orient(a, b, c), lab), s2 = side(orient(a, b, d), lab);
    int s3 = side(orient(c, d, a), lcd), s4 = side(orient(c, d, b), lcd);
    if (s1 * s2 < 0 && s3 * s4 < 0) return true;
    // A point of one on the other (collinear or touching).
    auto onSegment = [eps](const glm::dvec2& p, const glm::dvec2& q, const glm::dvec2& r) {
        glm::dvec2 lo = glm::min(p, q) - eps, hi = glm::max(p, q) + eps;
        return r.x >= lo.x && r.x <= hi.x && r.y >= lo.y && r.y <= hi.y;
    };
    return (s1 == 0 && onSegment(a, b, c)) || (s2 == 0 && onSegment(a, b, d)) ||
           (s3 == 0 && onSegment(c, d, a)) || (s4 == 0 && onSegment(c, d, b));
}

/// Appends the piece of a strip between `left` and `right` as two triangles (one, or none, where
/// it narrows to a point).
void emitPiece(const Side& left, const Side& right, double y0, double y1,
               std::vector<glm::dvec2>& out) {
    glm::dvec2 p0(left.x0, y0), p1(right.x0, y0), p2(right.x1, y1), p3(left.x1, y1);
    // Below a square micrometre, a triangle is rounding where a side narrows to a corner.
    constexpr double kTwiceSmallest = 2e-12;  // m2
    if (std::abs(orient(p0, p1, p2)) > kTwiceSmallest) out.insert(out.end(), {p0, p1, p2});
    if (std::abs(orient(p0, p2, p3)) > kTwiceSmallest) out.insert(out.end(), {p0, p2, p3});
}

}  // namespace

bool insidePolygon(const std::vector<glm::dvec2>& polygon, const glm::dvec2& p) {
    bool inside = false;
    for (size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
        const glm::dvec2& a = polygon[i];
        const glm::dvec2& b = polygon[j];
        if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x))
            inside = !inside;
    }
    return inside;
}

std::string polygonDefect(const std::vector<glm::dvec2>& polygon) {
    const size_t n = polygon.size();
    if (n < 3) return "at least three corners, got " + std::to_string(n);
    constexpr double kShortest = 1e-3;  // m: an edge shorter than a millimetre is a typing slip
    for (size_t i = 0; i < n; ++i)
        if (glm::length(polygon[(i + 1) % n] - polygon[i]) < kShortest)
            return "corners " + std::to_string(i + 1) + " and " + std::to_string((i + 1) % n + 1) +
                   " less than 1 mm apart";
    // Points within a micrometre of a line count as on it.
    constexpr double kOnLine = 1e-6;
    for (size_t i = 0; i < n; ++i) {
        const glm::dvec2 &a = polygon[i], &b = polygon[(i + 1) % n];
        for (size_t j = i + 1; j < n; ++j) {
            const glm::dvec2 &c = polygon[j], &d = polygon[(j + 1) % n];
            bool neighbours = j == i + 1 || (i == 0 && j == n - 1);
            if (neighbours) {
                // Neighbours share a corner; they must not fold back over each other.
                const glm::dvec2& shared = j == i + 1 ? b : a;
                glm::dvec2 u = (j == i + 1 ? a : b) - shared, v = (j == i + 1 ? d : c) - shared;
                if (std::abs(orient(glm::dvec2(0.0), u, v)) <= kOnLine * glm::length(u) &&
                    glm::dot(u, v) > 0.0)
                    return "edges " + std::to_string(i + 1) + " and " + std::to_string(j + 1) +
                           " fold back over each other";
                continue;
            }
            if (segmentsMeet(a, b, c, d, kOnLine))
                return "edges " + std::to_string(i + 1) + " and " + std::to_string(j + 1) +
                       " cross or touch (the outline must not cross itself)";
        }
    }
    if (std::abs(signedArea(polygon)) < kShortest * kShortest) return "no area";
    return "";
}

std::vector<glm::dvec2> tessellate(const std::vector<glm::dvec2>& outline,
                                   const std::vector<Rect2>& holes) {
    const size_t n = outline.size();
    std::vector<glm::dvec2> out;
    if (n < 3) return out;
    // Strips start at every corner, every hole's bottom and top, and every height where an edge
    // crosses a hole's side: within a strip, no two sides change order.
    std::vector<double> ys;
    for (const glm::dvec2& p : outline) ys.push_back(p.y);
    for (const Rect2& h : holes) {
        ys.push_back(h.lo.y);
        ys.push_back(h.hi.y);
        for (size_t i = 0; i < n; ++i) {
            const glm::dvec2 &a = outline[i], &b = outline[(i + 1) % n];
            if (std::max(a.y, b.y) < h.lo.y || std::min(a.y, b.y) > h.hi.y) continue;
            for (double x : {h.lo.x, h.hi.x})
                if ((a.x < x && x < b.x) || (b.x < x && x < a.x))
                    ys.push_back(a.y + (x - a.x) / (b.x - a.x) * (b.y - a.y));
        }
    }
    std::sort(ys.begin(), ys.end());
    ys.erase(std::unique(ys.begin(), ys.end()), ys.end());

    std::vector<Side> crossing;
    std::vector<std::pair<double, double>> cuts;
    for (size_t s = 0; s + 1 < ys.size(); ++s) {
        const double y0 = ys[s], y1 = ys[s + 1];
        crossing.clear();
        for (size_t i = 0; i < n; ++i) {
            const glm::dvec2 &a = outline[i], &b = outline[(i + 1) % n];
            if (std::min(a.y, b.y) > y0 || std::max(a.y, b.y) < y1 || a.y == b.y) continue;
            auto xAt = [&](double y) { return a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x); };
            crossing.push_back({xAt(y0), xAt(y1)});
        }
        std::sort(crossing.begin(), crossing.end(),
                  [](const Side& p, const Side& q) { return p.mid() < q.mid(); });
        cuts.clear();
        for (const Rect2& h : holes)
            if (h.lo.y <= y0 && h.hi.y >= y1 && h.hi.x > h.lo.x) cuts.push_back({h.lo.x, h.hi.x});
        std::sort(cuts.begin(), cuts.end());
        // Even-odd: the polygon's inside lies between the first and second crossing, the third
        // and fourth, and so on.
        for (size_t k = 0; k + 1 < crossing.size(); k += 2) {
            Side left = crossing[k];
            const Side right = crossing[k + 1];
            bool open = true;
            for (const auto& [a, b] : cuts) {
                if (b <= left.mid()) continue;
                if (a >= right.mid()) break;
                if (a > left.mid()) emitPiece(left, {a, a}, y0, y1, out);
                if (b >= right.mid()) {
                    open = false;
                    break;
                }
                left = {b, b};
            }
            if (open) emitPiece(left, right, y0, y1, out);
        }
    }
    return out;
}

void appendFlat(Mesh& mesh, const std::vector<glm::dvec2>& triangles, const glm::dvec3& origin,
                const glm::dvec3& axisU, const glm::dvec3& axisV, const glm::dvec3& normal) {
    for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
        glm::dvec3 p[3];
        for (int k = 0; k < 3; ++k)
            p[k] = origin + triangles[t + k].x * axisU + triangles[t + k].y * axisV;
        if (glm::dot(glm::cross(p[1] - p[0], p[2] - p[0]), normal) < 0.0) std::swap(p[1], p[2]);
        uint32_t base = uint32_t(mesh.positions.size());
        for (const glm::dvec3& q : p) {
            mesh.positions.push_back(glm::vec3(q));
            mesh.normals.push_back(glm::vec3(normal));
        }
        mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
    }
}

void appendBox(Mesh& mesh, const glm::dvec3& center, const glm::dvec3& half,
               const glm::dmat3& rotation, bool inside) {
    // Six faces, four vertices each (flat normals). For axis a, e_b x e_c = e_a with b = a + 1,
    // c = a + 2 (mod 3); swapping u and v on the negative face keeps u x v = outward normal.
    for (int a = 0; a < 3; ++a) {
        for (double sign : {1.0, -1.0}) {
            glm::dvec3 n(0.0), u(0.0), v(0.0);
            n[a] = sign;
            u[(a + 1) % 3] = half[(a + 1) % 3];
            v[(a + 2) % 3] = half[(a + 2) % 3];
            if (sign < 0.0) std::swap(u, v);
            glm::dvec3 faceCenter = n * half[a];
            uint32_t base = uint32_t(mesh.positions.size());
            for (glm::dvec3 corner :
                 {faceCenter - u - v, faceCenter + u - v, faceCenter + u + v, faceCenter - u + v}) {
                mesh.positions.push_back(glm::vec3(center + rotation * corner));
                mesh.normals.push_back(glm::vec3(rotation * (inside ? -n : n)));
            }
            if (inside)
                for (uint32_t k : {0u, 2u, 1u, 0u, 3u, 2u}) mesh.indices.push_back(base + k);
            else
                for (uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(base + k);
        }
    }
}

}  // namespace candela
