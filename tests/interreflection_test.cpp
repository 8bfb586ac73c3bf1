// Interreflected light (issue 17, part 3): radiosity over patches with Embree form factors,
// their pieces: hit lookup, convex rooms, per-source updates, black surfaces, the final gather.
// (Energy balance in closed rooms is the validation suite's, tests/validation_test.cpp.)
#include "scene/Interreflection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "TestUtil.h"
#include "scene/EmbreeVisibility.h"
#include "scene/SceneIo.h"
#include "util/Error.h"

namespace candela {
namespace {

Scene withLamp(const std::string& geometry, const std::string& lamps) {
    return parseScene(nlohmann::json::parse(R"({"geometry": [)" + geometry +
                                            R"(], "luminaires": [)" + lamps + "]}"),
                      test::dataDir() + "/scene.json");
}

std::string lampAt(double x, double y, double z) {
    return R"({"type": "photometric", "name": "Lamp", "file": ")" + test::dataDir() +
           R"(/photometric/lambert.ies", "position": [)" + std::to_string(x) + "," +
           std::to_string(y) + "," + std::to_string(z) + R"(], "technique": "scattered"})";
}

const char* kRoom =
    R"({"box": {"center": [0, 1.4, 0], "size": [4, 2.8, 3], "inside": true}, "albedo": [0.6, 0.5, 0.4]})";
const char* kDesk =
    R"({"box": {"center": [0.5, 0.4, 0.2], "size": [1.2, 0.8, 0.7]}, "albedo": [0.3, 0.3, 0.3]})";

TEST(Interreflection, EveryHitFindsThePatchThatHoldsIt) {
    // Points of known barycentrics on every triangle of a room and a desk: the patch patchAt
    // names must contain the point, and its weights must rebuild it (to 1e-9 m).
    Scene s = withLamp(std::string(kRoom) + "," + kDesk, lampAt(0, 2.7, 0));
    RadiositySettings settings;
    settings.targetPatches = 800;
    RadiosityMesh mesh = RadiosityMesh::build(s, settings);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    int checked = 0;
    size_t triangles = 0;
    for (const Mesh& m : s.meshes) triangles += m.triangleCount();
    EXPECT_EQ(triangles, 26u);  // the room's 12, the desk's 12 and the lamp's flat body's 2
    for (size_t m = 0; m < s.meshes.size(); ++m)
        for (size_t t = 0; t < s.meshes[m].triangleCount(); ++t)
            for (int k = 0; k < 50; ++k) {
                double u = u01(rng), v = u01(rng);
                if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
                const Mesh& mm = s.meshes[m];
                glm::dvec3 a(mm.positions[mm.indices[3 * t]]),
                    b(mm.positions[mm.indices[3 * t + 1]]), c(mm.positions[mm.indices[3 * t + 2]]);
                glm::dvec3 p = (1.0 - u - v) * a + u * b + v * c, w;
                uint32_t patch = mesh.patchAt(uint32_t(m), uint32_t(t), u, v, w);
                ASSERT_LT(patch, mesh.patches.size());
                const auto& q = mesh.patches[patch];
                glm::dvec3 rebuilt = w.x * mesh.vertices[q.vertex[0]] +
                                     w.y * mesh.vertices[q.vertex[1]] +
                                     w.z * mesh.vertices[q.vertex[2]];
                EXPECT_NEAR(glm::length(rebuilt - p), 0.0, 1e-9)
                    << "mesh " << m << " triangle " << t;
                EXPECT_GE(std::min({w.x, w.y, w.z}), -1e-9);
                ++checked;
            }
    EXPECT_EQ(checked, int(50 * triangles));
}

TEST(Interreflection, AConvexRoomNeedsNoShadowRays) {
    RadiositySettings settings;
    settings.targetPatches = 400;
    std::string bare = lampAt(0, 2.7, 0);
    bare.insert(bare.size() - 1, R"(, "body": false)");
    EXPECT_TRUE(RadiosityMesh::build(withLamp(kRoom, bare), settings).convexRoom);
    // The lamp's body (its flat opening, facing down) hides the ceiling above it from the floor.
    EXPECT_FALSE(RadiosityMesh::build(withLamp(kRoom, lampAt(0, 2.7, 0)), settings).convexRoom);
    EXPECT_FALSE(RadiosityMesh::build(withLamp(std::string(kRoom) + "," + kDesk, lampAt(0, 2.7, 0)),
                                      settings)
                     .convexRoom);
    // Patches face their normals: a box seen from outside is no room.
    EXPECT_FALSE(RadiosityMesh::build(withLamp(kDesk, lampAt(0, 2.7, 0)), settings).convexRoom);
}

TEST(Interreflection, WarnsOfARoomTurnedInsideOutButNotOfALampsOwnBody) {
    // A lamp inside a room whose walls face out lights their backs: warned. A lamp with its
    // body in a proper room sees the body's inside first on many rays, which is no mistake.
    std::string outside = kRoom;
    outside.replace(outside.find(R"("inside": true)"), 14, R"("inside": false)");
    InterreflectionOptions o;
    o.mesh.targetPatches = 200;
    Scene wrong = withLamp(outside, lampAt(0, 2.7, 0));
    Scene right = withLamp(kRoom, lampAt(0, 2.7, 0));
    ASSERT_EQ(right.bodyCount(), 1u);
    EXPECT_NE(Interreflection(wrong, o).orientationWarning(wrong).find("lights the back"),
              std::string::npos);
    EXPECT_EQ(Interreflection(right, o).orientationWarning(right), "");
}

TEST(Interreflection, MovingOneLuminaireUpdatesItsShareAlone) {
    // Two lamps in a room with a desk: after computing everything, one lamp moves and only its
    // share is recomputed (its direct light, then the solution for the change). The result must
    // equal a fresh computation of the moved scene, to the solver's tolerance (1e-6 of the flux
    // per iteration, so 1e-5 relative with these reflectances) on every patch.
    Scene s =
        withLamp(std::string(kRoom) + "," + kDesk, lampAt(-1, 2.7, 0) + "," + lampAt(1, 2.7, 0.5));
    InterreflectionOptions o;
    o.mesh.targetPatches = 700;
    Interreflection live(s, o);
    ASSERT_TRUE(live.compute());
    std::vector<glm::dvec3> before = live.indirect();
    s.luminaires[1]->pose.position = {1.2, 2.7, -0.8};
    ASSERT_TRUE(live.sync(s, o.directSpp));
    Interreflection fresh(s, o);
    ASSERT_TRUE(fresh.compute());
    double largest = 0.0, changed = 0.0;
    for (size_t i = 0; i < fresh.indirect().size(); ++i) {
        largest = std::max(largest, fresh.indirect()[i].y);
        changed = std::max(changed, std::abs(fresh.indirect()[i].y - before[i].y));
    }
    ASSERT_GT(changed, 0.01 * largest);  // the move matters
    for (size_t i = 0; i < fresh.indirect().size(); ++i)
        ASSERT_NEAR(live.indirect()[i].y, fresh.indirect()[i].y, 1e-5 * largest) << "patch " << i;
}

TEST(Interreflection, NothingIsReflectedByBlackOrLonelySurfaces) {
    InterreflectionOptions o;
    o.mesh.targetPatches = 300;
    // Black walls reflect nothing.
    Scene black = withLamp(
        R"({"box": {"center": [0, 1.4, 0], "size": [4, 2.8, 3], "inside": true}, "albedo": [0, 0, 0]})",
        lampAt(0, 2.7, 0));
    Interreflection a(black, o);
    EXPECT_FALSE(a.hasInterreflection());
    // A lone floor cannot see itself: its form factors are all 0.
    Scene floor =
        withLamp(R"({"plane": {"center": [0, 0, 0], "normal": [0, 1, 0], "size": [4, 4]}})",
                 lampAt(0, 2, 0));
    Interreflection b(floor, o);
    ASSERT_TRUE(b.compute());
    EXPECT_FALSE(b.hasInterreflection());
    for (const glm::dvec3& e : b.indirect()) EXPECT_EQ(e, glm::dvec3(0.0));
}

TEST(Interreflection, TooManyTrianglesAreRefusedBeforeAnythingIsBuilt) {
    // A geodesic sphere of 327 680 facets: a patch each at least, far over kMaxPatches (its
    // solution would take 4 x 327680^2 bytes, 430 GB). Refused with a message naming the scene,
    // the count and the surface, instead of std::bad_alloc.
    Scene fine = withLamp(
        R"({"name": "Dome", "sphere": {"center": [0, 0, 0], "radius": 2, "subdivisions": 7, "inside": true}})",
        lampAt(0, 0, 0));
    InterreflectionOptions o;
    o.mesh.targetPatches = 1500;
    try {
        Interreflection ir(fine, o);
        FAIL() << "built " << ir.mesh().patches.size() << " patches";
    } catch (const InputError& e) {
        std::string m = e.what();
        // 327 680 of the sphere's and the few of the lamp's body.
        EXPECT_NE(m.find("scene.json: interreflected light: its surfaces make 3276"),
                  std::string::npos)
            << m;
        EXPECT_NE(m.find(" patches, more than the 20000 whose solution fits in memory"),
                  std::string::npos)
            << m;
        EXPECT_NE(m.find("\"Dome\" alone has 327680 triangles"), std::string::npos) << m;
    }
    // At subdivision 4 (5120 facets) it is built.
    Scene coarse = withLamp(
        R"({"sphere": {"center": [0, 0, 0], "radius": 2, "subdivisions": 4, "inside": true}})",
        lampAt(0, 0, 0));
    Interreflection ok(coarse, o);
    EXPECT_LE(ok.mesh().patches.size(), RadiosityMesh::kMaxPatches);
    EXPECT_GE(ok.mesh().patches.size(), 5120u);
}

TEST(Interreflection, ZeroAreaTrianglesAddNothingAndBreakNothing) {
    // A room, then the same room with a mesh of zero-area triangles (three points on a line, a
    // repeated vertex, one point three times) inside it: they get no patches, block no light,
    // and every value stays finite and the same.
    Scene clean = withLamp(kRoom, lampAt(0.3, 2.7, -0.2));
    Scene degenerate = withLamp(kRoom, lampAt(0.3, 2.7, -0.2));
    Mesh m;
    m.name = "slivers";
    m.positions = {{0, 1, 0}, {1, 1, 0}, {2, 1, 0}, {0.5, 1.5, 0.5}, {0.5, 1.5, 0.5}};
    m.normals.assign(m.positions.size(), glm::vec3(0, 1, 0));
    m.indices = {0, 1, 2, 3, 4, 0, 3, 3, 3};
    m.material = degenerate.meshes.front().material;
    m.computeBounds();
    degenerate.meshes.push_back(m);
    InterreflectionOptions o;
    o.mesh.targetPatches = 400;
    Interreflection a(clean, o), b(degenerate, o);
    ASSERT_EQ(a.mesh().patches.size(), b.mesh().patches.size());
    ASSERT_TRUE(a.compute());
    ASSERT_TRUE(b.compute());
    for (size_t i = 0; i < a.indirect().size(); ++i) {
        ASSERT_TRUE(std::isfinite(b.indirect()[i].x + b.direct()[i].x)) << "patch " << i;
        // The same estimators and seeds: only rounding may differ.
        EXPECT_NEAR(b.indirect()[i].x, a.indirect()[i].x, 1e-9 * (1.0 + a.indirect()[i].x));
    }
    glm::dvec3 error;
    glm::dvec3 p(0.0, 0.8, 0.0), up(0, 1, 0);
    glm::dvec3 e = b.fromPatches(p, up, error);
    EXPECT_TRUE(std::isfinite(e.x + error.x));
    EXPECT_NEAR(e.x, a.fromPatches(p, up, error).x, 1e-9 * (1.0 + e.x));
}

TEST(Interreflection, TheFinalGatherAgreesWithThePatches) {
    // In a closed room the gather at a wall point (its first bounce from the exact direct light,
    // later ones from the patches) and the patch's own value differ only by the patches'
    // discretisation: within 3 % plus three standard errors of the gather.
    Scene s = withLamp(kRoom, lampAt(0.3, 2.7, -0.2));
    InterreflectionOptions o;
    o.mesh.targetPatches = 2000;
    Interreflection ir(s, o);
    ASSERT_TRUE(ir.compute());
    for (glm::dvec3 p :
         {glm::dvec3(0.1, 0.0, 0.2), glm::dvec3(-2.0, 1.2, 0.4), glm::dvec3(0.7, 2.8, 1.1)}) {
        glm::dvec3 n = p.y == 0.0 ? glm::dvec3(0, 1, 0)
                                  : (p.y == 2.8 ? glm::dvec3(0, -1, 0) : glm::dvec3(1, 0, 0));
        EstimateOptions g;
        g.spp = 8192;
        Estimate e = ir.gather(p, n, g);
        // The patch under p: the nearest centroid on the same wall.
        size_t best = 0;
        double bestDistance = 1e30;
        for (size_t i = 0; i < ir.mesh().patches.size(); ++i) {
            const auto& q = ir.mesh().patches[i];
            double d = glm::length(q.centroid - p);
            if (glm::dot(q.normal, n) > 0.99 && d < bestDistance) bestDistance = d, best = i;
        }
        double patch = ir.indirect()[best].y;
        std::printf("gather at (%.1f, %.1f, %.1f): %.4g lx +- %.2g, patch %.4g lx\n", p.x, p.y, p.z,
                    e.irradiance.y, e.stdError.y, patch);
        EXPECT_NEAR(e.irradiance.y, patch, 0.03 * patch + 3.0 * e.stdError.y);
        EXPECT_GT(e.stdError.y, 0.0);
    }
}

}  // namespace
}  // namespace candela
