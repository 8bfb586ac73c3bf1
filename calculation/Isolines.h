#pragma once
// Isolines (isolux lines) of values on a regular grid of points, by marching squares: in each
// cell of four neighbouring points, the line of a level crosses every edge whose two ends lie on
// either side of it, where the values interpolated linearly along the edge equal the level. A
// point counts as above a level when its value is at or above it. A cell whose two opposite
// corners are above and the other two below (a saddle) is resolved by the mean of its four
// values: at or above the level, the two corners above are joined through the cell's middle and
// the lines cut off the two below; otherwise the lines cut off the two above. A cell with a
// missing (non-finite) value at any corner has no line through it. The lines lie in the grid's
// own coordinates (a calculation surface's in-plane u, v, metres), for the viewport and the
// report alike.

#include <glm/glm.hpp>
#include <vector>

namespace candela {

/// Values at the points of a regular grid: point (i, j) at origin + (i, j) * spacing.
struct NodeGrid {
    glm::dvec2 origin{0.0};   ///< Point (0, 0), in the plane's (u, v), m.
    glm::dvec2 spacing{1.0};  ///< Between neighbouring points along u and v, m.
    int nx = 0, ny = 0;       ///< Points along u and v.
    /// Row after row (point (i, j) at j * nx + i), in the values' unit; NaN where a point has
    /// none (it lies in a surface's hole).
    std::vector<double> values;
    double at(int i, int j) const { return values[size_t(j) * size_t(nx) + size_t(i)]; }
    glm::dvec2 position(double i, double j) const { return origin + glm::dvec2(i, j) * spacing; }
};

/// One straight piece of an isoline within one cell; a and b in the grid's coordinates.
struct IsoSegment {
    glm::dvec2 a{0.0}, b{0.0};
};

/// One isoline: the segments of a level joined end to end, in the grid's coordinates.
struct Isoline {
    double level = 0.0;  ///< In the values' unit.
    std::vector<glm::dvec2> points;
    bool closed = false;  ///< It returns to its first point (which is not repeated).
};

/// The segments of the isoline at `level`, cells taken row after row (each cell's in the order of
/// its edges: bottom, right, top, left); none of zero length. Deterministic: a crossing on an edge
/// two cells share is the same point in both.
std::vector<IsoSegment> isolineSegments(const NodeGrid& grid, double level);
/// The isolines of every level, each level's segments joined into polylines (open ones first,
/// from an end, then closed ones); a level no cell crosses has none.
std::vector<Isoline> isolines(const NodeGrid& grid, const std::vector<double>& levels);

}  // namespace candela
