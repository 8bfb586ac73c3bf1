// Isolines by marching squares (calculation/Isolines.h) against closed forms: a linear field's
// isoline is the straight line where it equals the level, a paraboloid's are circles, a saddle
// cell is resolved by its mean, and no line passes through a cell with a missing value; and a
// calculation surface's points on their grid (surfaceNodes), its hole missing.
#include "calculation/Isolines.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "calculation/CalculationSurfaces.h"
#include "shaders/shared/Constants.h"

namespace candela {
namespace {

using gpu::kPi;

NodeGrid sampled(glm::dvec2 origin, glm::dvec2 spacing, int nx, int ny,
                 const std::function<double(glm::dvec2)>& f) {
    NodeGrid g;
    g.origin = origin, g.spacing = spacing, g.nx = nx, g.ny = ny;
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) g.values.push_back(f(g.position(i, j)));
    return g;
}

double length(const std::vector<IsoSegment>& segments) {
    double sum = 0.0;
    for (const IsoSegment& s : segments) sum += glm::distance(s.a, s.b);
    return sum;
}

// f = 100 + 37 u + 21 v: each level's line is a u + b v = level - 100, cut by the rectangle the
// grid's points span.
constexpr double kA = 37.0, kB = 21.0, kC = 100.0;
double linear(glm::dvec2 p) {
    return kC + kA * p.x + kB * p.y;
}

/// Length of the line a u + b v = c inside [lo, hi], from where it meets the rectangle's sides.
double clippedLength(glm::dvec2 lo, glm::dvec2 hi, double c) {
    std::vector<glm::dvec2> ends;
    for (double u : {lo.x, hi.x}) {
        double v = (c - kA * u) / kB;
        if (v >= lo.y && v <= hi.y) ends.push_back({u, v});
    }
    for (double v : {lo.y, hi.y}) {
        double u = (c - kB * v) / kA;
        if (u > lo.x && u < hi.x) ends.push_back({u, v});
    }
    return ends.size() == 2 ? glm::distance(ends[0], ends[1]) : 0.0;
}

TEST(Isolines, ALinearFieldsLineIsWhereItEqualsTheLevel) {
    const glm::dvec2 origin(-1.0, -0.5), spacing(0.3, 0.2);
    NodeGrid g = sampled(origin, spacing, 11, 9, linear);
    const glm::dvec2 far = g.position(10, 8);
    // Levels between points, and 109.5 (100 + 37 x 0.2 + 21 x 0.1) at point (4, 3), up to the
    // rounding of its position.
    for (double level : {80.0, 96.3, 109.5, 125.25, 150.0}) {
        std::vector<IsoSegment> segments = isolineSegments(g, level);
        ASSERT_FALSE(segments.empty()) << level;
        for (const IsoSegment& s : segments)
            for (glm::dvec2 p : {s.a, s.b})
                // Linear along every edge, the interpolation is exact: only rounding remains
                // (values near 150 carry about 3e-14 of it).
                EXPECT_NEAR(linear(p), level, 1e-9) << level << " at " << p.x << ", " << p.y;
        // The pieces add up to the whole line across the grid, with no piece twice.
        EXPECT_NEAR(length(segments), clippedLength(origin, far, level - kC), 1e-9) << level;
        // Joined, they are one open line from one side of the grid to another.
        std::vector<Isoline> lines = isolines(g, {level});
        ASSERT_EQ(lines.size(), 1u) << level;
        EXPECT_FALSE(lines[0].closed);
        EXPECT_EQ(lines[0].level, level);
        for (glm::dvec2 end : {lines[0].points.front(), lines[0].points.back()}) {
            bool onBorder = std::abs(end.x - origin.x) < 1e-12 || std::abs(end.x - far.x) < 1e-12 ||
                            std::abs(end.y - origin.y) < 1e-12 || std::abs(end.y - far.y) < 1e-12;
            EXPECT_TRUE(onBorder) << level << ": " << end.x << ", " << end.y;
        }
    }
    // Levels outside the field's range cross no cell.
    EXPECT_TRUE(isolineSegments(g, 10.0).empty());
    EXPECT_TRUE(isolines(g, {1000.0, std::nan("")}).empty());
}

TEST(Isolines, AParaboloidsLinesAreCirclesWithinTheInterpolationBound) {
    // f = |p - c|^2 on a grid of 0.1 m: the level R^2 is the circle of radius R about c. Along a
    // cell's edge f is a parabola of second derivative 2, so the linear interpolation is off by
    // s (h - s) <= h^2 / 4 at a distance s from an end: each crossing p has |f(p) - R^2| <= h^2/4,
    // hence ||p - c| - R| = |f(p) - R^2| / (|p - c| + R) <= h^2 / (4 R).
    const glm::dvec2 c(0.013, -0.021);
    const double h = 0.1;
    NodeGrid g =
        sampled({-1.0, -1.0}, {h, h}, 21, 21, [&](glm::dvec2 p) { return glm::dot(p - c, p - c); });
    for (double radius : {0.23, 0.5, 0.87}) {
        const double bound = h * h / (4.0 * radius);
        std::vector<Isoline> lines = isolines(g, {radius * radius});
        ASSERT_EQ(lines.size(), 1u) << radius;
        EXPECT_TRUE(lines[0].closed) << radius;
        double worst = 0.0;
        for (glm::dvec2 p : lines[0].points)
            worst = std::max(worst, std::abs(glm::distance(p, c) - radius));
        EXPECT_LE(worst, bound) << radius;
        // It goes round: a closed polygon about c whose area is the disc's within the ring of
        // the bound and the chords' sagitta (a chord of at most h sqrt 2 misses the arc by at
        // most h^2 / (4 R)).
        double area = 0.0;
        const std::vector<glm::dvec2>& q = lines[0].points;
        for (size_t k = 0; k < q.size(); ++k) {
            glm::dvec2 a = q[k] - c, b = q[(k + 1) % q.size()] - c;
            area += 0.5 * (a.x * b.y - a.y * b.x);
        }
        double ring = 2.0 * kPi * radius * (bound + h * h / (4.0 * radius));
        EXPECT_NEAR(std::abs(area), kPi * radius * radius, ring) << radius;
    }
}

TEST(Isolines, ASaddleCellIsResolvedByItsMean) {
    // Corners (0, 0) and (1, 1) at 1, (1, 0) and (0, 1) at 0: the mean is 0.5.
    NodeGrid g;
    g.nx = g.ny = 2;
    g.values = {1.0, 0.0, 0.0, 1.0};
    auto has = [](const std::vector<IsoSegment>& s, glm::dvec2 a, glm::dvec2 b) {
        return std::any_of(s.begin(), s.end(), [&](const IsoSegment& x) {
            auto near = [](glm::dvec2 p, glm::dvec2 q) { return glm::distance(p, q) < 1e-12; };
            return (near(x.a, a) && near(x.b, b)) || (near(x.a, b) && near(x.b, a));
        });
    };
    // At 0.5 the mean counts as above: the high corners join through the middle and the lines
    // cut off the low corners (1, 0) and (0, 1).
    std::vector<IsoSegment> s = isolineSegments(g, 0.5);
    ASSERT_EQ(s.size(), 2u);
    EXPECT_TRUE(has(s, {0.5, 0.0}, {1.0, 0.5}));
    EXPECT_TRUE(has(s, {0.5, 1.0}, {0.0, 0.5}));
    // At 0.6 the mean is below: the lines cut off the high corners (0, 0) and (1, 1).
    s = isolineSegments(g, 0.6);
    ASSERT_EQ(s.size(), 2u);
    EXPECT_TRUE(has(s, {0.4, 0.0}, {0.0, 0.4}));
    EXPECT_TRUE(has(s, {1.0, 0.6}, {0.6, 1.0}));
    // The other diagonal high, at 0.5: the lines cut off the low corners (0, 0) and (1, 1).
    g.values = {0.0, 1.0, 1.0, 0.0};
    s = isolineSegments(g, 0.5);
    ASSERT_EQ(s.size(), 2u);
    EXPECT_TRUE(has(s, {0.5, 0.0}, {0.0, 0.5}));
    EXPECT_TRUE(has(s, {1.0, 0.5}, {0.5, 1.0}));
}

TEST(Isolines, NoLinePassesThroughACellWithAMissingValue) {
    const glm::dvec2 origin(0.0), spacing(0.25);
    NodeGrid full = sampled(origin, spacing, 9, 7, linear);
    NodeGrid holed = full;
    holed.values[size_t(3 * 9 + 4)] = std::numeric_limits<double>::quiet_NaN();  // point (4, 3)
    // The four cells around point (4, 3): u 0.75..1.25 m, v 0.5..1 m.
    const glm::dvec2 lo = full.position(3, 2), hi = full.position(5, 4);
    auto inside = [&](glm::dvec2 p) {
        return p.x > lo.x + 1e-12 && p.x < hi.x - 1e-12 && p.y > lo.y + 1e-12 && p.y < hi.y - 1e-12;
    };
    // 120 passes beside those cells (it leaves v = 0.5 at u = 0.26 m); 145 and 150 cross them
    // (at v = 0.75: u = 0.79 and 0.93 m).
    for (double level : {120.0, 145.0, 150.0}) {
        std::vector<IsoSegment> all = isolineSegments(full, level), kept;
        for (const IsoSegment& s : all)
            if (!inside(0.5 * (s.a + s.b))) kept.push_back(s);
        std::vector<IsoSegment> got = isolineSegments(holed, level);
        for (const IsoSegment& s : got) EXPECT_FALSE(inside(0.5 * (s.a + s.b))) << level;
        // Everything else is as without the gap.
        ASSERT_EQ(got.size(), kept.size()) << level;
        for (size_t k = 0; k < got.size(); ++k) {
            EXPECT_EQ(got[k].a, kept[k].a);
            EXPECT_EQ(got[k].b, kept[k].b);
        }
    }
    // The line through the gap is cut in two open pieces.
    ASSERT_LT(isolineSegments(holed, 150.0).size(), isolineSegments(full, 150.0).size());
    ASSERT_EQ(isolines(full, {150.0}).size(), 1u);
    std::vector<Isoline> pieces = isolines(holed, {150.0});
    ASSERT_EQ(pieces.size(), 2u);
    EXPECT_FALSE(pieces[0].closed);
    EXPECT_FALSE(pieces[1].closed);
}

TEST(Isolines, ASurfacesPointsOnTheirGridWithTheHoleMissing) {
    // A background-like surface: 2 x 1.5 m in 8 x 6 cells, less a hole over the middle.
    SurfaceResult s;
    s.lo = {-1.0, 0.0}, s.hi = {1.0, 1.5};
    s.cells = {8, 6};
    s.spacing = {0.25, 0.25};
    s.holeLo = {-0.3, 0.4}, s.holeHi = {0.3, 1.1};
    auto inHole = [&](glm::dvec2 q) {
        return q.x > s.holeLo.x && q.x < s.holeHi.x && q.y > s.holeLo.y && q.y < s.holeHi.y;
    };
    for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 8; ++i) {
            glm::dvec2 q = s.lo + (glm::dvec2(i, j) + 0.5) * s.spacing;
            if (inHole(q)) continue;
            s.points.push_back(q);
            s.E.push_back(linear(q));
        }
    ASSERT_EQ(s.points.size(), 48u - 4u);  // the hole takes u -0.125, 0.125 by v 0.625, 0.875
    NodeGrid g = surfaceNodes(s);
    ASSERT_EQ(g.nx, 8);
    ASSERT_EQ(g.ny, 6);
    for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 8; ++i) {
            glm::dvec2 q = g.position(i, j);
            if (inHole(q))
                EXPECT_TRUE(std::isnan(g.at(i, j))) << i << ", " << j;
            else
                EXPECT_NEAR(g.at(i, j), linear(q), 1e-12) << i << ", " << j;
        }
}

}  // namespace
}  // namespace candela
