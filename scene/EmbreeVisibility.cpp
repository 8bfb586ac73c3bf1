#include "scene/EmbreeVisibility.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "scene/Bvh.h"

namespace candela {

struct EmbreeVisibility::Handles {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    ~Handles() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

EmbreeVisibility::EmbreeVisibility(const Scene& scene) : mHandles(std::make_unique<Handles>()) {
    // Embree's own thread pool stays small: the callers already run one query per thread.
    mHandles->device = rtcNewDevice("threads=1");
    if (!mHandles->device)
        throw std::runtime_error("Embree: cannot create a device (error " +
                                 std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
    mHandles->scene = rtcNewScene(mHandles->device);
    // Robust traversal: no rays slip between triangles that share an edge (a closed box stays
    // closed), and high build quality (a reference, built once per scene).
    rtcSetSceneFlags(mHandles->scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(mHandles->scene, RTC_BUILD_QUALITY_HIGH);
    for (const Mesh& mesh : scene.meshes) {
        if (mesh.triangleCount() == 0) continue;
        RTCGeometry geometry = rtcNewGeometry(mHandles->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positions.size()));
        auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangleCount()));
        for (size_t i = 0; i < mesh.positions.size(); ++i)
            for (int k = 0; k < 3; ++k) vertices[3 * i + size_t(k)] = mesh.positions[i][k];
        for (size_t i = 0; i < mesh.indices.size(); ++i) indices[i] = mesh.indices[i];
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(mHandles->scene, geometry);
        rtcReleaseGeometry(geometry);
        mTriangles += mesh.triangleCount();
    }
    rtcCommitScene(mHandles->scene);
    RTCError error = rtcGetDeviceError(mHandles->device);
    if (error != RTC_ERROR_NONE)
        throw std::runtime_error("Embree: building the scene failed (error " + std::to_string(int(error)) + ")");
}

EmbreeVisibility::~EmbreeVisibility() = default;

bool EmbreeVisibility::occluded(const glm::dvec3& origin, const glm::dvec3& dir, double tNear,
                                double tFar) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray{};
    ray.org_x = float(origin.x), ray.org_y = float(origin.y), ray.org_z = float(origin.z);
    ray.dir_x = float(dir.x), ray.dir_y = float(dir.y), ray.dir_z = float(dir.z);
    ray.tnear = float(tNear);
    ray.tfar = std::isfinite(tFar) ? float(tFar) : std::numeric_limits<float>::infinity();
    ray.mask = 0xffffffffu;
    ray.time = 0.f;
    ray.flags = 0;
    rtcOccluded1(mHandles->scene, &context, &ray);
    return ray.tfar == -std::numeric_limits<float>::infinity();  // Embree's mark of a hit
}

bool EmbreeVisibility::visible(const glm::dvec3& from, const glm::dvec3& to) const {
    glm::dvec3 dir;
    double tMin, tMax;
    return !Bvh::segmentRay(from, to, dir, tMin, tMax) || !occluded(from, dir, tMin, tMax);
}

bool EmbreeVisibility::visibleToward(const glm::dvec3& from, const glm::dvec3& dir) const {
    return !occluded(from, dir, Bvh::kRayEpsilon, std::numeric_limits<double>::infinity());
}

}  // namespace candela
