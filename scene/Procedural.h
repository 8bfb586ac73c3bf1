#pragma once
// Geometry built from a few numbers: boxes, flat polygons with rectangular holes (a room's floor
// and ceiling with skylights, a wall with windows and doors), and the surfaces of a room. No file
// reading here: scene/RoomIo.cpp reads the scene file's "room" and "furniture" entries and builds
// their meshes with these.
//
// The polygons are cut into trapezoids by horizontal strips (every corner, every hole edge and
// every crossing of an edge with a hole's side starts a strip), which handles any simple polygon
// and any set of axis-aligned rectangular holes with one short loop. Debian packages no C++
// polygon triangulator short of CGAL; this is written here because the shapes it takes (simple
// polygons, rectangular openings) need only this.

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "scene/Scene.h"
#include "util/Polygon.h"

namespace candela {

/// An axis-aligned rectangle in a polygon's plane, metres.
struct Rect2 {
    glm::dvec2 lo{0.0}, hi{0.0};
    double area() const { return (hi.x - lo.x) * (hi.y - lo.y); }
};

/// Triangles covering the simple polygon `outline` (either orientation) less the union of
/// `holes`, as consecutive triples of 2D points. Their areas sum to the polygon's area less the
/// holes' (within rounding), and no triangle overlaps another.
std::vector<glm::dvec2> tessellate(const std::vector<glm::dvec2>& outline,
                                   const std::vector<Rect2>& holes);

/// Whether `p` lies inside the polygon (even-odd rule; points on an edge count either way).
bool insidePolygon(const std::vector<glm::dvec2>& polygon, const glm::dvec2& p);
/// An empty string when `polygon` is simple (at least three corners, no edge shorter than 1 mm,
/// no two edges crossing or touching except neighbours at their shared corner), else what is
/// wrong ("edges 2 and 5 cross").
std::string polygonDefect(const std::vector<glm::dvec2>& polygon);

/// Appends to `mesh` triangles in 3D of the 2D points `triangles` (consecutive triples) mapped by
/// origin + x * axisU + y * axisV, with the stored normal `normal`; each triangle is wound
/// counter-clockwise seen from the normal's side.
void appendFlat(Mesh& mesh, const std::vector<glm::dvec2>& triangles, const glm::dvec3& origin,
                const glm::dvec3& axisU, const glm::dvec3& axisV, const glm::dvec3& normal);

/// Appends a box (six faces, flat normals, counter-clockwise seen from outside) of half sizes
/// `half` (m), turned by `rotation` and centred on `center`; `inside`: faces look inwards.
void appendBox(Mesh& mesh, const glm::dvec3& center, const glm::dvec3& half,
               const glm::dmat3& rotation, bool inside = false);

}  // namespace candela
