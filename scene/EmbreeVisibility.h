#pragma once
// Ray-traced visibility through Intel Embree 3 (Debian's libembree-dev), for the CPU reference:
// `candela probe --visibility` and the techniques' reference visibility in tests and benches.
// It is a second, independent implementation of what scene/Bvh.h does for the GPU, and the tests
// hold the two against each other.
//
// Same conventions as Bvh: triangles are two-sided; visible(from, to) tests the open segment
// shrunk by Bvh::segmentEpsilon(|to - from|) at both ends; visibleToward(from, dir) the ray to
// infinity beyond Bvh::kRayEpsilon. Embree works in single precision: coordinates of up to ~100 m
// keep rounding (~1e-5 m) well inside those biases.
//
// Thread-safe after construction: the estimators may query it from several threads.

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "luminaires/Registry.h"
#include "scene/Scene.h"

namespace candela {

class EmbreeVisibility : public Visibility {
  public:
    /// Builds an Embree scene of every mesh of `scene` (world space). Throws std::runtime_error
    /// if Embree cannot create its device.
    explicit EmbreeVisibility(const Scene& scene);
    ~EmbreeVisibility() override;
    EmbreeVisibility(const EmbreeVisibility&) = delete;
    EmbreeVisibility& operator=(const EmbreeVisibility&) = delete;

    /// `to` is on a light: a luminaire body whose bounds hold it casts no shadow (Bvh.h).
    bool visible(const glm::dvec3& from, const glm::dvec3& to) const override;
    bool visibleBetweenSurfaces(const glm::dvec3& from, const glm::dvec3& to) const override;
    bool visibleToward(const glm::dvec3& from, const glm::dvec3& dir) const override;

    /// The first surface along a ray from `origin` (biased by Bvh::kRayEpsilon) in the unit
    /// direction `dir`: false when it escapes. For the final gather of interreflected light.
    struct Hit {
        double t = 0.0;           ///< Distance along dir, metres.
        uint32_t mesh = 0;        ///< Index into Scene::meshes.
        uint32_t triangle = 0;    ///< Triangle of that mesh.
        double u = 0.0, v = 0.0;  ///< Barycentrics: p = (1-u-v) a + u b + v c.
    };
    bool intersect(const glm::dvec3& origin, const glm::dvec3& dir, Hit& hit) const;

    /// Triangles in the Embree scene.
    size_t triangleCount() const { return mTriangles; }

  private:
    bool occluded(const glm::dvec3& origin, const glm::dvec3& dir, double tNear, double tFar,
                  const glm::dvec3* light) const;

    struct Handles;
    std::unique_ptr<Handles> mHandles;
    size_t mTriangles = 0;
    std::vector<uint32_t> mMeshOfGeometry;  ///< Embree geometry id -> Scene::meshes index.
};

}  // namespace candela
