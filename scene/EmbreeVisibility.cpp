#include "scene/EmbreeVisibility.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "scene/Bvh.h"

namespace candela {

namespace {

/// A luminaire body's bounds (Scene::updateBodies), the user data of its Embree geometry.
struct BodyBox {
    glm::dvec3 lo, hi;
};

/// What occluded() hands Embree: its context, then the light end of the segment (null for
/// rays that are not towards a light). Embree passes the filter a pointer to the first member.
struct LightContext {
    RTCIntersectContext context;
    const glm::dvec3* light = nullptr;
};

/// A body's triangle casts no shadow on light leaving a point inside its box (insideBody).
void bodyFilter(const RTCFilterFunctionNArguments* args) {
    const auto* c = reinterpret_cast<const LightContext*>(args->context);
    const auto* box = static_cast<const BodyBox*>(args->geometryUserPtr);
    if (!c->light || !insideBody(*c->light, box->lo, box->hi)) return;
    for (unsigned i = 0; i < args->N; ++i) args->valid[i] = 0;
}

}  // namespace

struct EmbreeVisibility::Handles {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::vector<std::unique_ptr<BodyBox>> bodies;  ///< Stable addresses for the filter.
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
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        if (mesh.triangleCount() == 0) continue;
        RTCGeometry geometry = rtcNewGeometry(mHandles->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<float*>(
            rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                    3 * sizeof(float), mesh.positions.size()));
        auto* indices = static_cast<unsigned*>(
            rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                    3 * sizeof(unsigned), mesh.triangleCount()));
        for (size_t i = 0; i < mesh.positions.size(); ++i)
            for (int k = 0; k < 3; ++k) vertices[3 * i + size_t(k)] = mesh.positions[i][k];
        for (size_t i = 0; i < mesh.indices.size(); ++i) indices[i] = mesh.indices[i];
        if (mesh.luminaireBody) {
            mHandles->bodies.push_back(std::make_unique<BodyBox>(
                BodyBox{glm::dvec3(mesh.boundsMin), glm::dvec3(mesh.boundsMax)}));
            rtcSetGeometryUserData(geometry, mHandles->bodies.back().get());
            rtcSetGeometryOccludedFilterFunction(geometry, bodyFilter);
        }
        rtcCommitGeometry(geometry);
        unsigned id = rtcAttachGeometry(mHandles->scene, geometry);
        if (id >= mMeshOfGeometry.size()) mMeshOfGeometry.resize(id + 1, 0);
        mMeshOfGeometry[id] = uint32_t(m);
        rtcReleaseGeometry(geometry);
        mTriangles += mesh.triangleCount();
    }
    rtcCommitScene(mHandles->scene);
    RTCError error = rtcGetDeviceError(mHandles->device);
    if (error != RTC_ERROR_NONE)
        throw std::runtime_error("Embree: building the scene failed (error " +
                                 std::to_string(int(error)) + ")");
}

EmbreeVisibility::~EmbreeVisibility() = default;

bool EmbreeVisibility::occluded(const glm::dvec3& origin, const glm::dvec3& dir, double tNear,
                                double tFar, const glm::dvec3* light) const {
    LightContext c;
    rtcInitIntersectContext(&c.context);
    c.light = light;
    RTCRay ray{};
    ray.org_x = float(origin.x), ray.org_y = float(origin.y), ray.org_z = float(origin.z);
    ray.dir_x = float(dir.x), ray.dir_y = float(dir.y), ray.dir_z = float(dir.z);
    ray.tnear = float(tNear);
    ray.tfar = std::isfinite(tFar) ? float(tFar) : std::numeric_limits<float>::infinity();
    ray.mask = 0xffffffffu;
    ray.time = 0.f;
    ray.flags = 0;
    rtcOccluded1(mHandles->scene, &c.context, &ray);
    return ray.tfar == -std::numeric_limits<float>::infinity();  // Embree's mark of a hit
}

bool EmbreeVisibility::intersect(const glm::dvec3& origin, const glm::dvec3& dir, Hit& hit) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray.org_x = float(origin.x), rh.ray.org_y = float(origin.y), rh.ray.org_z = float(origin.z);
    rh.ray.dir_x = float(dir.x), rh.ray.dir_y = float(dir.y), rh.ray.dir_z = float(dir.z);
    rh.ray.tnear = float(Bvh::kRayEpsilon);
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(mHandles->scene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID || rh.hit.geomID >= mMeshOfGeometry.size())
        return false;
    hit.t = rh.ray.tfar;
    hit.mesh = mMeshOfGeometry[rh.hit.geomID];
    hit.triangle = rh.hit.primID;
    hit.u = rh.hit.u;
    hit.v = rh.hit.v;
    return true;
}

bool EmbreeVisibility::visible(const glm::dvec3& from, const glm::dvec3& to) const {
    glm::dvec3 dir;
    double tMin, tMax;
    return !Bvh::segmentRay(from, to, dir, tMin, tMax) || !occluded(from, dir, tMin, tMax, &to);
}

bool EmbreeVisibility::visibleBetweenSurfaces(const glm::dvec3& from, const glm::dvec3& to) const {
    glm::dvec3 dir;
    double tMin, tMax;
    return !Bvh::segmentRay(from, to, dir, tMin, tMax) || !occluded(from, dir, tMin, tMax, nullptr);
}

bool EmbreeVisibility::visibleToward(const glm::dvec3& from, const glm::dvec3& dir) const {
    return !occluded(from, dir, Bvh::kRayEpsilon, std::numeric_limits<double>::infinity(), nullptr);
}

}  // namespace candela
