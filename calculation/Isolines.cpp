// Marching squares over a grid of values (calculation/Isolines.h).
#include "calculation/Isolines.h"

#include <array>
#include <cmath>
#include <unordered_map>

namespace candela {

namespace {

/// A segment between crossings on two edges of one cell, each edge named by its id.
struct EdgeSegment {
    size_t edgeA = 0, edgeB = 0;
    glm::dvec2 a{0.0}, b{0.0};
};

/// Edge ids: the edge from point (i, j) towards +u is 2 (j nx + i), towards +v 2 (j nx + i) + 1.
size_t edgeId(const NodeGrid& g, int i, int j, bool alongV) {
    return 2 * (size_t(j) * size_t(g.nx) + size_t(i)) + (alongV ? 1 : 0);
}

/// Where the values interpolated linearly from point (i, j) to its neighbour along u (or v) equal
/// the level; one end is at or above it, the other below. Always from the lower point, so the
/// two cells sharing the edge find the same point.
glm::dvec2 crossing(const NodeGrid& g, int i, int j, bool alongV, double level) {
    double from = g.at(i, j), to = alongV ? g.at(i, j + 1) : g.at(i + 1, j);
    double t = (level - from) / (to - from);
    return alongV ? g.position(i, j + t) : g.position(i + t, j);
}

/// Every cell's segments, zero-length ones included (they join a line through a point whose value
/// is the level exactly).
std::vector<EdgeSegment> cellSegments(const NodeGrid& g, double level) {
    std::vector<EdgeSegment> out;
    if (!std::isfinite(level) || g.nx < 2 || g.ny < 2 ||
        g.values.size() != size_t(g.nx) * size_t(g.ny))
        return out;
    for (int j = 0; j + 1 < g.ny; ++j)
        for (int i = 0; i + 1 < g.nx; ++i) {
            // Corners counter-clockwise from (i, j); edge e runs from corner e to corner e + 1.
            const double v[4] = {g.at(i, j), g.at(i + 1, j), g.at(i + 1, j + 1), g.at(i, j + 1)};
            if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]) ||
                !std::isfinite(v[3]))
                continue;
            bool above[4];
            for (int k = 0; k < 4; ++k) above[k] = v[k] >= level;
            // Bottom, right, top, left: each as (point it starts from, along v).
            const std::array<std::array<int, 3>, 4> edges = {
                {{i, j, 0}, {i + 1, j, 1}, {i, j + 1, 0}, {i, j, 1}}};
            bool crossed[4];
            for (int e = 0; e < 4; ++e) crossed[e] = above[e] != above[(e + 1) % 4];
            auto segment = [&](int e, int f) {
                const auto &p = edges[size_t(e)], &q = edges[size_t(f)];
                out.push_back({edgeId(g, p[0], p[1], p[2] != 0), edgeId(g, q[0], q[1], q[2] != 0),
                               crossing(g, p[0], p[1], p[2] != 0, level),
                               crossing(g, q[0], q[1], q[2] != 0, level)});
            };
            int count = crossed[0] + crossed[1] + crossed[2] + crossed[3];
            if (count == 2) {
                int e = 0;
                while (!crossed[e]) ++e;
                int f = e + 1;
                while (!crossed[f]) ++f;
                segment(e, f);
            } else if (count == 4) {
                // A saddle: the mean decides whether the corners above meet in the middle (the
                // lines then cut off the corners below) or stay apart (they cut off those above).
                bool middleAbove = 0.25 * (v[0] + v[1] + v[2] + v[3]) >= level;
                if (above[0] == middleAbove) {  // cut off corners 1 and 3
                    segment(0, 1);
                    segment(2, 3);
                } else {  // cut off corners 0 and 2
                    segment(0, 3);
                    segment(1, 2);
                }
            }
        }
    return out;
}

/// Adds p to the polyline unless it repeats the last point (a zero-length segment).
void append(std::vector<glm::dvec2>& points, const glm::dvec2& p) {
    if (points.empty() || points.back() != p) points.push_back(p);
}

}  // namespace

std::vector<IsoSegment> isolineSegments(const NodeGrid& grid, double level) {
    std::vector<IsoSegment> out;
    for (const EdgeSegment& s : cellSegments(grid, level))
        if (s.a != s.b) out.push_back({s.a, s.b});
    return out;
}

std::vector<Isoline> isolines(const NodeGrid& grid, const std::vector<double>& levels) {
    std::vector<Isoline> out;
    for (double level : levels) {
        std::vector<EdgeSegment> segs = cellSegments(grid, level);
        // The segments at each crossing: one at the grid's border or beside a missing value,
        // two inside.
        std::unordered_map<size_t, std::array<int, 2>> at;
        for (int k = 0; k < int(segs.size()); ++k)
            for (size_t edge : {segs[size_t(k)].edgeA, segs[size_t(k)].edgeB}) {
                auto [it, fresh] = at.try_emplace(edge, std::array<int, 2>{-1, -1});
                it->second[it->second[0] < 0 ? 0 : 1] = k;
            }
        std::vector<bool> used(segs.size(), false);
        // Follows the line from segment `first`, entering it through `edge`.
        auto follow = [&](int first, size_t edge) {
            Isoline line;
            line.level = level;
            int k = first;
            while (k >= 0 && !used[size_t(k)]) {
                used[size_t(k)] = true;
                const EdgeSegment& s = segs[size_t(k)];
                bool forward = s.edgeA == edge;
                append(line.points, forward ? s.a : s.b);
                append(line.points, forward ? s.b : s.a);
                edge = forward ? s.edgeB : s.edgeA;
                const std::array<int, 2>& next = at[edge];
                k = next[0] == k ? next[1] : next[0];
            }
            line.closed = k == first;
            if (line.closed && line.points.size() > 1 && line.points.back() == line.points[0])
                line.points.pop_back();
            if (line.points.size() >= 2) out.push_back(std::move(line));
        };
        // Open lines from their ends, then the closed ones.
        for (int k = 0; k < int(segs.size()); ++k)
            for (size_t edge : {segs[size_t(k)].edgeA, segs[size_t(k)].edgeB})
                if (!used[size_t(k)] && at[edge][1] < 0) follow(k, edge);
        for (int k = 0; k < int(segs.size()); ++k)
            if (!used[size_t(k)]) follow(k, segs[size_t(k)].edgeA);
    }
    return out;
}

}  // namespace candela
