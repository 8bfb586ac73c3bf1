// Rooms, openings and furniture (scene/RoomIo.h, scene/Procedural.h): the tessellation's area
// against the shoelace formula and the holes' areas, the room's surfaces against its dimensions,
// its openings against the light that leaves through them, and the classroom written as a room
// against the same classroom written as planes (an independent path through the plane parser).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "TestUtil.h"
#include "calculation/CalculationSurfaces.h"
#include "calculation/Validation.h"
#include "scene/Procedural.h"
#include "scene/RoomIo.h"
#include "scene/Scene.h"
#include "scene/SceneIo.h"
#include "util/Error.h"

namespace candela {
namespace {

double trianglesArea(const std::vector<glm::dvec2>& t) {
    double area = 0.0;
    for (size_t i = 0; i + 2 < t.size(); i += 3)
        area += 0.5 * std::abs((t[i + 1].x - t[i].x) * (t[i + 2].y - t[i].y) -
                               (t[i + 1].y - t[i].y) * (t[i + 2].x - t[i].x));
    return area;
}

TEST(Tessellation, AreaIsThePolygonsLessItsHoles) {
    // An L: 6 x 4 m less a 3 x 2 m corner, 18 m2; a 1 x 1 m hole inside, and one straddling the
    // inner corner's edges that only partly overlaps it.
    std::vector<glm::dvec2> l = {{0, 0}, {6, 0}, {6, 2}, {3, 2}, {3, 4}, {0, 4}};
    EXPECT_NEAR(signedArea(l), 18.0, 1e-12);
    EXPECT_NEAR(trianglesArea(tessellate(l, {})), 18.0, 1e-9);
    EXPECT_NEAR(trianglesArea(tessellate(l, {{{1, 1}, {2, 2}}})), 17.0, 1e-9);
    // Reversed corners: same area, signed negative.
    std::vector<glm::dvec2> reversed(l.rbegin(), l.rend());
    EXPECT_NEAR(signedArea(reversed), -18.0, 1e-12);
    EXPECT_NEAR(trianglesArea(tessellate(reversed, {{{1, 1}, {2, 2}}})), 17.0, 1e-9);
    // Overlapping holes count once: [1,2]x[1,2] and [1.5,2.5]x[1,2] cover 1.5 m2.
    EXPECT_NEAR(trianglesArea(tessellate(l, {{{1, 1}, {2, 2}}, {{1.5, 1}, {2.5, 2}}})), 16.5, 1e-9);
}

TEST(Tessellation, SlantedEdgesAndHolesThatCrossThem) {
    // A random star-shaped polygon (corners at increasing angles, random radii), so its edges
    // slant every way, and random holes anywhere in its bounds. Every triangle lies inside the
    // polygon and outside every hole (its centroid tested), and the areas sum to the polygon's
    // less the holes' part inside it, which is estimated by a fine point count (the count's
    // error on 1e6 points of a 40 m2 box is about 0.02 m2; 0.1 m2 is five of that).
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> radius(1.0, 3.0), unit(0.0, 1.0);
    for (int trial = 0; trial < 5; ++trial) {
        std::vector<glm::dvec2> star;
        const int corners = 7 + trial * 3;
        for (int k = 0; k < corners; ++k) {
            double a = 2.0 * 3.141592653589793 * (k + 0.5 * unit(rng)) / corners, r = radius(rng);
            star.push_back({r * std::cos(a), r * std::sin(a)});
        }
        ASSERT_EQ(polygonDefect(star), "");
        std::vector<Rect2> holes;
        for (int h = 0; h < 3; ++h) {
            glm::dvec2 c(-2.5 + 5.0 * unit(rng), -2.5 + 5.0 * unit(rng));
            glm::dvec2 s(0.3 + unit(rng), 0.3 + unit(rng));
            holes.push_back({c - 0.5 * s, c + 0.5 * s});
        }
        auto inHole = [&holes](const glm::dvec2& p) {
            for (const Rect2& h : holes)
                if (p.x > h.lo.x && p.x < h.hi.x && p.y > h.lo.y && p.y < h.hi.y) return true;
            return false;
        };
        std::vector<glm::dvec2> t = tessellate(star, holes);
        for (size_t i = 0; i + 2 < t.size(); i += 3) {
            glm::dvec2 c = (t[i] + t[i + 1] + t[i + 2]) / 3.0;
            EXPECT_TRUE(insidePolygon(star, c)) << "trial " << trial;
            EXPECT_FALSE(inHole(c)) << "trial " << trial;
        }
        const int n = 1000;
        int in = 0;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                glm::dvec2 p(-3.0 + 6.0 * (i + 0.5) / n, -3.0 + 6.0 * (j + 0.5) / n);
                in += insidePolygon(star, p) && !inHole(p);
            }
        EXPECT_NEAR(trianglesArea(t), 36.0 * in / (double(n) * n), 0.1) << "trial " << trial;
    }
}

TEST(Tessellation, OutlinesThatCrossThemselvesAreRefused) {
    EXPECT_NE(polygonDefect({{0, 0}, {2, 2}, {2, 0}, {0, 2}}), "");       // a bow tie
    EXPECT_NE(polygonDefect({{0, 0}, {1, 0}}), "");                       // two corners
    EXPECT_NE(polygonDefect({{0, 0}, {4, 0}, {4, 0.0001}, {0, 3}}), "");  // corners 0.1 mm apart
    EXPECT_NE(polygonDefect({{0, 0}, {4, 0}, {2, 0}, {2, 3}}), "");       // an edge folds back
    EXPECT_EQ(polygonDefect({{0, 0}, {6, 0}, {6, 2}, {3, 2}, {3, 4}, {0, 4}}), "");
}

Scene sceneOf(const std::string& geometry, const std::string& rest = "") {
    return parseScene(nlohmann::json::parse("{\"geometry\": [" + geometry + "]" + rest + "}"),
                      "room.json");
}

double meshArea(const Mesh& m) {
    double area = 0.0;
    for (size_t i = 0; i < m.indices.size(); i += 3) {
        glm::dvec3 a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]],
                   c = m.positions[m.indices[i + 2]];
        glm::dvec3 n = glm::cross(b - a, c - a);
        area += 0.5 * glm::length(n);
        // Wound counter-clockwise seen from the side the stored normal faces.
        EXPECT_GT(glm::dot(n, glm::dvec3(m.normals[m.indices[i]])), 0.0) << m.name;
    }
    return area;
}

const Mesh& meshNamed(const Scene& s, const std::string& name) {
    for (const Mesh& m : s.meshes)
        if (m.name == name) return m;
    throw std::runtime_error("no mesh " + name);
}

TEST(Room, SurfacesHaveTheRoomsAreasAndFaceIn) {
    for (const char* floor : {"[[-5,-4],[5,-4],[5,4],[-5,4]]", "[[-5,4],[5,4],[5,-4],[-5,-4]]"}) {
        Scene s = sceneOf(std::string(R"({"room": {"name": "C", "height": 3, "floor": )") + floor +
                          R"(, "reflectance": {"floor": 0.2, "walls": 0.5, "ceiling": 0.7,
                                               "wall 2": [0.8, 0.6, 0.4]}}})");
        ASSERT_EQ(s.meshes.size(), 6u);
        EXPECT_NEAR(meshArea(meshNamed(s, "C: floor")), 80.0, 1e-9);
        EXPECT_NEAR(meshArea(meshNamed(s, "C: ceiling")), 80.0, 1e-9);
        EXPECT_EQ(meshNamed(s, "C: floor").normals[0], glm::vec3(0, 1, 0));
        EXPECT_EQ(meshNamed(s, "C: ceiling").normals[0], glm::vec3(0, -1, 0));
        double walls = 0.0;
        for (int w = 1; w <= 4; ++w) {
            const Mesh& m = meshNamed(s, "C: wall " + std::to_string(w));
            walls += meshArea(m);
            // Facing the room's middle.
            glm::dvec3 centre = 0.5 * (glm::dvec3(m.boundsMin) + glm::dvec3(m.boundsMax));
            EXPECT_GT(glm::dot(glm::dvec3(m.normals[0]), glm::dvec3(0, 1.5, 0) - centre), 0.0);
        }
        EXPECT_NEAR(walls, 2.0 * (10 + 8) * 3, 1e-9);
        EXPECT_EQ(s.materials[meshNamed(s, "C: wall 2").material].albedo,
                  glm::vec3(0.8f, 0.6f, 0.4f));
        EXPECT_EQ(s.materials[meshNamed(s, "C: wall 1").material].albedo, glm::vec3(0.5f));
        EXPECT_EQ(s.materials[meshNamed(s, "C: floor").material].albedo, glm::vec3(0.2f));
    }
}

TEST(Room, OpeningsAreHoles) {
    Scene s = sceneOf(R"({"room": {"name": "C", "height": 3,
        "floor": [[-5,-4],[5,-4],[5,4],[-5,4]],
        "openings": [{"type": "window", "wall": 4, "offset": 0.5, "width": 2, "height": 1.6},
                     {"type": "window", "wall": 4, "offset": 3, "width": 2, "sill": 1, "height": 1.5,
                      "glazing": 0.7},
                     {"type": "door", "wall": 2, "offset": 6.5, "width": 1, "height": 2.1},
                     {"type": "skylight", "center": [0, 0], "size": [1.2, 2]}]}})");
    // Areas to 1e-6 m2: the vertices are stored in single precision.
    EXPECT_NEAR(meshArea(meshNamed(s, "C: wall 4")), 24.0 - 3.2 - 3.0, 1e-6);
    EXPECT_NEAR(meshArea(meshNamed(s, "C: wall 2")), 24.0 - 2.1, 1e-6);
    EXPECT_NEAR(meshArea(meshNamed(s, "C: ceiling")), 80.0 - 2.4, 1e-6);
    // The window's middle (wall 4 runs from (-5, 4) to (-5, -4): 1.5 m along is z = 2.5, its
    // sill 0.9 m and head 2.5 m) is open: a ray from inside through it meets nothing.
    glm::dvec3 hole(-5.0, 1.7, 2.5);
    for (const Mesh& m : s.meshes)
        for (size_t i = 0; i < m.indices.size(); i += 3) {
            glm::dvec3 a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]],
                       c = m.positions[m.indices[i + 2]];
            if (std::abs(a.x + 5.0) > 1e-9 || std::abs(b.x + 5.0) > 1e-9 ||
                std::abs(c.x + 5.0) > 1e-9)
                continue;
            // Barycentric test in the wall's (z, y) plane.
            auto cross = [](glm::dvec2 p, glm::dvec2 q, glm::dvec2 r) {
                return (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
            };
            glm::dvec2 p(hole.z, hole.y), A(a.z, a.y), B(b.z, b.y), C(c.z, c.y);
            double d1 = cross(A, B, p), d2 = cross(B, C, p), d3 = cross(C, A, p);
            bool inside = (d1 >= 0 && d2 >= 0 && d3 >= 0) || (d1 <= 0 && d2 <= 0 && d3 <= 0);
            EXPECT_FALSE(inside) << m.name;
        }
}

TEST(Room, MistakesNameTheField) {
    std::string e = test::inputError([] {
        sceneOf(R"({"room": {"height": 3, "floor": [[0,0],[4,0],[4,3],[0,3]],
            "openings": [{"type": "window", "wall": 2, "offset": 2, "width": 2, "height": 1}]}})");
    });
    EXPECT_NE(e.find("geometry[0].room.openings[0]"), std::string::npos) << e;
    EXPECT_NE(e.find("wall 2 is 3"), std::string::npos) << e;
    e = test::inputError(
        [] { sceneOf(R"({"room": {"height": 3, "floor": [[0,0],[2,2],[2,0],[0,2]]}})"); });
    EXPECT_NE(e.find("geometry[0].room.floor"), std::string::npos) << e;
    EXPECT_NE(e.find("cross"), std::string::npos) << e;
    e = test::inputError([] {
        sceneOf(R"({"room": {"height": 3, "floor": [[0,0],[4,0],[4,3],[0,3]],
                             "reflectance": {"wall 5": 0.5}}})");
    });
    EXPECT_NE(e.find("N from 1 to 4"), std::string::npos) << e;
    e = test::inputError([] {
        sceneOf(R"({"room": {"height": 3, "floor": [[0,0],[4,0],[4,3],[0,3]],
            "openings": [{"type": "skylight", "center": [4, 3], "size": [1, 1]}]}})");
    });
    EXPECT_NE(e.find("outside"), std::string::npos) << e;
    e = test::inputError([] { sceneOf(R"({"furniture": {"type": "sofa"}})"); });
    EXPECT_NE(e.find("\"desk\""), std::string::npos) << e;
    e = test::inputError([] {
        sceneOf(R"({"room": {"height": 3, "floor": [[0,0],[4,0],[4,3],[0,3]],
                             "reflectance": {"floor": 1.5}}})");
    });
    EXPECT_NE(e.find("reflectance.floor"), std::string::npos) << e;
}

TEST(Furniture, StandsOnItsPositionAndTurns) {
    // A desk 1.6 x 0.75 x 0.8 m turned a quarter: its footprint is 0.8 m along x, 1.6 m along z.
    Scene s =
        sceneOf(R"({"furniture": {"type": "desk", "position": [1, 0.1, 2], "rotate_y_deg": 90}})");
    ASSERT_EQ(s.meshes.size(), 1u);
    const Mesh& desk = s.meshes[0];
    EXPECT_NEAR(desk.boundsMin.x, 0.6, 1e-6);
    EXPECT_NEAR(desk.boundsMax.x, 1.4, 1e-6);
    EXPECT_NEAR(desk.boundsMin.z, 1.2, 1e-6);
    EXPECT_NEAR(desk.boundsMax.z, 2.8, 1e-6);
    EXPECT_NEAR(desk.boundsMin.y, 0.1, 1e-6);
    EXPECT_NEAR(desk.boundsMax.y, 0.85, 1e-6);
    EXPECT_EQ(s.materials[desk.material].albedo, glm::vec3(0.5f));
    for (const FurnitureType& type : furnitureTypes()) {
        Scene one = sceneOf(std::string(R"({"furniture": {"type": ")") + type.name + "\"}}");
        glm::dvec3 size = glm::dvec3(one.meshes[0].boundsMax - one.meshes[0].boundsMin);
        EXPECT_NEAR(glm::length(size - type.size), 0.0, 1e-6) << type.name;
    }
}

TEST(Room, SavingKeepsTheEntriesAsWritten) {
    nlohmann::json room = nlohmann::json::parse(R"({"room": {"name": "C", "height": 3,
        "floor": [[0,0],[4,0],[4,3],[0,3]],
        "openings": [{"type": "door", "wall": 1, "offset": 1, "width": 1, "height": 2}]}})");
    nlohmann::json desk = nlohmann::json::parse(R"({"furniture": {"type": "desk"}})");
    Scene s = sceneOf(room.dump() + "," + desk.dump());
    nlohmann::json doc = sceneToJson(s);
    EXPECT_EQ(doc["geometry"][0], room);
    EXPECT_EQ(doc["geometry"][1], desk);
}

/// Plane entries of a wall from `corner` along `along` (unit), `length` x `height` m, facing
/// `inward`, less its openings (each [offset, width, sill, height]; none overlapping along the
/// wall): full-height columns between the openings, and below and above each opening.
void addWallPlanes(nlohmann::json& geometry, glm::dvec3 corner, glm::dvec3 along, glm::dvec3 inward,
                   double length, double height, std::vector<std::array<double, 4>> openings,
                   double reflectance) {
    std::sort(openings.begin(), openings.end());
    auto plane = [&](double s0, double s1, double t0, double t1) {
        if (s1 - s0 < 1e-12 || t1 - t0 < 1e-12) return;
        glm::dvec3 c = corner + 0.5 * (s0 + s1) * along + glm::dvec3(0, 0.5 * (t0 + t1), 0);
        geometry.push_back({{"plane",
                             {{"center", {c.x, c.y, c.z}},
                              {"normal", {inward.x, inward.y, inward.z}},
                              {"size", {s1 - s0, t1 - t0}}}},
                            {"albedo", {reflectance, reflectance, reflectance}}});
    };
    double s = 0.0;
    for (const auto& [offset, width, sill, tall] : openings) {
        plane(s, offset, 0.0, height);
        plane(offset, offset + width, 0.0, sill);
        plane(offset, offset + width, sill + tall, height);
        s = offset + width;
    }
    plane(s, length, 0.0, height);
}

TEST(Room, TheClassroomAsARoomEqualsItAsPlanes) {
    // The classroom project (a room with three windows and a door, and furniture) against the
    // same room written as planes, which go through the plane parser instead: the same grid, and
    // every point within 0.5 % (the two tessellations make different radiosity patches; the
    // direct light is the same).
    const std::string path = test::sourceDir() + "/resources/scenes/classroom-project.json";
    Scene asRoom = loadScene(path);
    nlohmann::json doc = sceneToJson(asRoom);
    nlohmann::json room = doc["geometry"][0]["room"];
    ASSERT_EQ(room["floor"], nlohmann::json::parse("[[-5,-4],[5,-4],[5,4],[-5,4]]"));
    nlohmann::json planes = nlohmann::json::array();
    planes.push_back({{"plane", {{"center", {0, 0, 0}}, {"normal", {0, 1, 0}}, {"size", {10, 8}}}},
                      {"albedo", {0.2, 0.2, 0.2}}});
    planes.push_back({{"plane", {{"center", {0, 3, 0}}, {"normal", {0, -1, 0}}, {"size", {10, 8}}}},
                      {"albedo", {0.7, 0.7, 0.7}}});
    std::vector<std::vector<std::array<double, 4>>> openings(4);
    for (const nlohmann::json& o : room["openings"])
        openings[o["wall"].get<int>() - 1].push_back(
            {o["offset"].get<double>(), o["width"].get<double>(), o.value("sill", 0.0),
             o["height"].get<double>()});
    addWallPlanes(planes, {-5, 0, -4}, {1, 0, 0}, {0, 0, 1}, 10, 3, openings[0], 0.5);
    addWallPlanes(planes, {5, 0, -4}, {0, 0, 1}, {-1, 0, 0}, 8, 3, openings[1], 0.5);
    addWallPlanes(planes, {5, 0, 4}, {-1, 0, 0}, {0, 0, -1}, 10, 3, openings[2], 0.5);
    addWallPlanes(planes, {-5, 0, 4}, {0, 0, -1}, {1, 0, 0}, 8, 3, openings[3], 0.5);
    for (size_t i = 1; i < doc["geometry"].size(); ++i) planes.push_back(doc["geometry"][i]);
    doc["geometry"] = planes;
    Scene asPlanes = parseScene(doc, path);

    GridSpec how;
    applyLightChoice(asRoom, LightChoice{}, how);
    ASSERT_TRUE(how.visibility && how.indirect);
    SurfaceReport a = computeSurfaces(asRoom, how), b = computeSurfaces(asPlanes, how);
    ASSERT_EQ(a.surfaces.size(), b.surfaces.size());
    for (size_t k = 0; k < a.surfaces.size(); ++k) {
        const SurfaceResult &x = a.surfaces[k], &y = b.surfaces[k];
        ASSERT_EQ(x.points.size(), y.points.size()) << x.name;
        for (size_t i = 0; i < x.points.size(); ++i) {
            EXPECT_EQ(x.points[i], y.points[i]) << x.name;
            // 0.5 %, plus three standard errors where either point took the final gather
            // (the adaptive method gathers where its patches' error estimate is large, which
            // the two tessellations can judge differently near the door).
            double noise = std::hypot(x.stdError[i], y.stdError[i]);
            EXPECT_NEAR(x.E[i], y.E[i], 0.005 * y.E[i] + 3.0 * noise + 1e-9)
                << x.name << " point " << i;
        }
        EXPECT_NEAR(x.summary.eAvg, y.summary.eAvg, 0.005 * y.summary.eAvg) << x.name;
        EXPECT_NEAR(x.summary.eMin, y.summary.eMin, 0.005 * y.summary.eMin) << x.name;
        EXPECT_NEAR(x.summary.eMax, y.summary.eMax, 0.005 * y.summary.eMax) << x.name;
    }
    EXPECT_GT(a.surfaces[0].summary.eAvg, 300.0);  // lit: its layout of 15 pendants of 5134 lm
}

TEST(Room, AnLShapedRoomKeepsItsEnergyBalance) {
    // A closed L-shaped room with a point-like luminaire in each wing: every ray from the
    // luminaires meets a wall, and the light absorbed equals the light emitted
    // (validateClosedRoom's own tolerance).
    Scene s = sceneOf(R"({"room": {"name": "L", "height": 2.8,
        "floor": [[0,0],[6,0],[6,2.5],[2.5,2.5],[2.5,5],[0,5]],
        "reflectance": {"floor": 0.3, "walls": 0.6, "ceiling": 0.8}}})",
                      R"(, "luminaires": [
        {"type": "lambertian-rect", "name": "A", "size": [0.1, 0.1], "luminance": [1000, 1000, 1000],
         "position": [1.2, 2.7, 1.2], "aim": [0, -1, 0]},
        {"type": "lambertian-rect", "name": "B", "size": [0.1, 0.1], "luminance": [1000, 1000, 1000],
         "position": [1.2, 2.7, 4.0], "aim": [0, -1, 0]}])");
    ValidationResult r = validateClosedRoom(s);
    EXPECT_TRUE(r.pass) << r.description << ": " << r.deviation << " " << r.detail;
}

TEST(Room, AWindowLetsLightOut) {
    // The same L with a window: no longer closed, and the check says why.
    Scene s = sceneOf(R"({"room": {"name": "L", "height": 2.8,
        "floor": [[0,0],[6,0],[6,2.5],[2.5,2.5],[2.5,5],[0,5]],
        "openings": [{"type": "window", "wall": 6, "offset": 1, "width": 3, "sill": 0.2, "height": 2.4}]}})",
                      R"(, "luminaires": [
        {"type": "lambertian-rect", "name": "A", "size": [0.1, 0.1], "luminance": [1000, 1000, 1000],
         "position": [1.2, 1.4, 2.5], "aim": [-1, 0, 0]}])");
    std::string e = test::inputError([&s] { validateClosedRoom(s); });
    EXPECT_NE(e.find("not a closed room"), std::string::npos) << e;
}

}  // namespace
}  // namespace candela
