#pragma once
// Geometry of a convex planar polygon seen from a receiver point: clipping at the receiver's
// (possibly tilted) horizon, solid angle, projected solid angle (Lambert / Baum), closest point,
// and the spherical Delaunay triangulation by edge flips that scattered sampling integrates on
// (Prost 2019, seed 004, Sec. 5.1-5.2). Vectors are relative to the receiver. The GLSL twin is
// shaders/photometric.glsl; tests/photometric_test.cpp checks both against closed forms.

#include <array>
#include <glm/glm.hpp>

#include "shaders/shared/Photometric.h"

namespace candela::spherical {

/// Most vertices of a polygon (shared with GLSL): a 16-gon cut by one plane, plus rounding slack.
using gpu::kMaxPolygon;

struct Polygon {
    std::array<glm::dvec3, kMaxPolygon> v{};
    int count = 0;
};

/// Keeps the part of `in` where dot(normal, v) >= 0 (Sutherland-Hodgman against one plane
/// through the receiver).
Polygon clip(const Polygon& in, const glm::dvec3& normal);

/// Solid angle of the spherical triangle of three directions (any length, not zero), steradians:
/// Van Oosterom and Strackee (1983), tan(Omega/2) = |a.(b x c)| / (1 + a.b + b.c + c.a) on unit
/// vectors. Never negative, never NaN.
double triangleSolidAngle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

/// Solid angle of a convex polygon (fan of triangles), steradians.
double solidAngle(const Polygon& p);

/// Integral over the polygon's solid angle of dot(m, w) for unit m (Lambert's polygon formula,
/// Baum, Rushmeier and Winget 1989, Eq. 2): pi times the form factor. The polygon must already be
/// clipped to dot(m, v) >= 0. Independent of the winding; never negative.
double projectedSolidAngle(const Polygon& p, const glm::dvec3& m);

/// Where the closest point of a convex polygon lies relative to its corners.
enum class Place { Inside, Edge, Corner };

struct ClosestPoint {
    glm::dvec3 point{0.0};
    Place place = Place::Inside;
    int index = 0;  ///< Edge from corner index to index+1, or the corner.
};

/// Closest point to the origin of a convex planar polygon (either winding; a degenerate one,
/// such as a segment, works too). Within `tolerance` (metres) of a corner or an edge it snaps
/// there, so that a dynamic sample never nearly coincides with a structured one (Sec. 5.2.2).
ClosestPoint closestPoint(const Polygon& p, double tolerance);

/// A triangulation of at most kMaxPolygon + 1 points, as vertex indices.
struct Triangulation {
    std::array<std::array<int, 3>, 2 * kMaxPolygon> tri{};
    int count = 0;
    int flips = 0;  ///< Edge flips the Delaunay step made (frame statistics, tests).
};

/// Initial triangulation of the scattered sample set (Prost, Fig. 5.8): vertex 0 is the dynamic
/// sample, vertices 1..n the polygon's corners counter-clockwise. Inside: a fan from the dynamic
/// sample; on an edge: the fan without the triangle over that edge; on a corner: the dynamic
/// sample is dropped and the polygon is fanned from that corner.
Triangulation initialTriangulation(int corners, const ClosestPoint& cp);

/// Lawson's flip algorithm (Prost, Alg. 5.1) with the spherical empty-circumcircle test on the
/// directions `dirs`: an edge is flipped when the opposite vertex lies inside the circumcircle of
/// the triangle across it and the quadrilateral is convex. Terminates after a bounded number of
/// flips even on degenerate input.
void makeDelaunay(Triangulation& t, const glm::dvec3* dirs);

/// True when d lies strictly inside the circumcircle of the spherical triangle (a, b, c): on the
/// far side of the plane through a, b, c from the sphere's centre. Inputs are unit vectors.
bool inCircumcircle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                    const glm::dvec3& d);

}  // namespace candela::spherical
