#pragma once
// Which luminaires can cast a shadow onto something the camera sees. The renderer traces shadow
// rays only for those, so the answer must be conservative (never "no" when a shadow exists) while
// saying "no" for the simple cases: a room made of planes, a single ground plane, an object behind
// the luminaire.
//
// The rule, per luminaire L with emitter outline E (Luminaire::outline()):
//  - Receivers: meshes whose bounds are not entirely outside the left, right, bottom or top clip
//    plane of viewProj, nor entirely behind the eye (near and far planes are not used, so any
//    depth convention works).
//  - A shadow ray runs from a receiver point to an emitter point, so it stays inside
//    A = AABB(E, bounds of R). An occluder O can block light from L to receiver R only if
//      * O is R itself: only if O.shape == General (planes and convex solids cannot shadow
//        themselves);
//      * O is a Plane: E and the corners of R's bounds are not all on one closed side of O's
//        plane (within eps), and O's bounds intersect A;
//      * O is Convex or General: O's bounds shrunk by eps intersect A, and some corner of O's
//        bounds lies on the emitting side of L (in front of E's lowest point along the aim axis,
//        by more than eps).
//    The emitting-side test assumes L emits only into its +aim half-space; it is skipped when
//    L's radiance() is non-zero towards any of a set of backward directions at E's centroid.
//  - eps = 1e-6 m scaled by max(1, largest absolute coordinate involved), which absorbs the
//    rounding of float vertex positions.
// L needs shadows iff some (O, R) pair can block. Meshes without triangles take no part.

#include <glm/glm.hpp>
#include <vector>

#include "scene/Scene.h"

namespace candela {

/// One flag per Scene::luminaires entry: true when shadow rays are needed for it.
std::vector<bool> luminairesNeedingShadows(const Scene& scene, const glm::mat4& viewProj);

/// Whether the environment map can be shadowed on what the camera sees. Light comes from every
/// direction, so any other mesh may block some of it: the answer is yes when a receiver that may
/// be visible shares the scene with another mesh, or is a General mesh (it may shadow itself).
/// A single ground plane or a single convex box needs no shadow rays.
bool environmentNeedsShadows(const Scene& scene, const glm::mat4& viewProj);

/// One flag per source of Scene::sources(), in its order: the rule of luminairesNeedingShadows
/// for a placed luminaire, that of environmentNeedsShadows for a source at infinity.
std::vector<bool> sourcesNeedingShadows(const Scene& scene, const glm::mat4& viewProj);

}  // namespace candela
