// Scene files: parsing, error messages that name the file and the problem, procedural geometry,
// round trips and the atomic save.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "scene/SceneIo.h"
#include "tests/TempDir.h"
#include "tests/TestUtil.h"
#include "util/Error.h"

namespace candela {
namespace {

namespace fs = std::filesystem;

std::string data(const std::string& relative) {
    return std::string(CANDELA_TEST_DATA) + "/" + relative;
}

using test::inputError;

#define EXPECT_CONTAINS(text, part) \
    EXPECT_NE(std::string(text).find(part), std::string::npos) << "in: " << (text)

Scene parse(const std::string& text) {
    return parseScene(nlohmann::json::parse(text), "t.json");
}

std::string readText(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

using test::TempDir;

// --- Errors: each names the file and the problem -------------------------------------------

TEST(SceneIo, MissingFile) {
    std::string m = inputError([] { loadScene(data("scenes/no_such_scene.json")); });
    EXPECT_CONTAINS(m, "no_such_scene.json: cannot open scene file (No such file or directory)");
}

TEST(SceneIo, UnsupportedExtension) {
    std::string m = inputError([] { loadScene(data("scenes/scene.txt")); });
    EXPECT_CONTAINS(m, "scene.txt: unsupported scene file type \".txt\"");
}

TEST(SceneIo, MalformedJsonGivesLineAndColumn) {
    // Line 4 starts a second entry without the comma after the first: the '{' in column 5 is
    // where the parser gives up.
    std::string m = inputError([] { loadScene(data("scenes/malformed.json")); });
    EXPECT_CONTAINS(m, "malformed.json:4:5: invalid JSON (");
    EXPECT_CONTAINS(m, "syntax error");
}

TEST(SceneIo, NanLiteralIsInvalidJson) {
    // JSON has no NaN: the parser stops at the 'N' in line 4, column 17.
    std::string m = inputError([] { loadScene(data("scenes/nan_literal.json")); });
    EXPECT_CONTAINS(m, "nan_literal.json:4:17: invalid JSON (");
}

TEST(SceneIo, NanStringWhereANumberIsExpected) {
    std::string m = inputError([] { loadScene(data("scenes/nan_string.json")); });
    EXPECT_CONTAINS(m,
                    "nan_string.json: geometry[0].albedo[0]: expected a finite number, got "
                    "the string \"NaN\"");
}

TEST(SceneIo, NegativeSize) {
    std::string m = inputError([] { loadScene(data("scenes/negative_size.json")); });
    EXPECT_CONTAINS(m, "negative_size.json: geometry[0].box.size[1]: expected a positive size");
}

TEST(SceneIo, UnknownField) {
    std::string m = inputError([] { loadScene(data("scenes/unknown_field.json")); });
    EXPECT_CONTAINS(m, "unknown_field.json: geometry[0]: unknown field \"colour\"");
}

TEST(SceneIo, MissingGltf) {
    std::string m = inputError([] { loadScene(data("scenes/missing_gltf.json")); });
    EXPECT_CONTAINS(m, "missing_gltf.json: geometry[0].gltf: ");
    EXPECT_CONTAINS(m, "does_not_exist.gltf: cannot open glTF file (No such file or directory)");
}

TEST(SceneIo, EnvironmentMapFileMustExist) {
    // Environment maps load now (tests/environment_test.cpp); this scene names a missing file.
    std::string m = inputError([] { loadScene(data("scenes/environment.json")); });
    EXPECT_CONTAINS(m, "environment.json: environment.file: ");
    EXPECT_CONTAINS(m, "sky.hdr: cannot open environment map (No such file or directory)");
}

TEST(SceneIo, ValueErrorsNameTheField) {
    // The environment is a kind without a parser (a scene's "environment" field makes it): as a
    // luminaire type it is refused, where the loader used to call its null parser.
    EXPECT_CONTAINS(inputError([] { parse(R"({"luminaires": [{"type": "environment"}]})"); }),
                    "t.json: luminaires[0].type: unknown luminaire type \"environment\"");
    EXPECT_CONTAINS(inputError([] { parse(R"({"luminaires": [{"type": "spot"}]})"); }),
                    "t.json: luminaires[0].type: unknown luminaire type \"spot\" (expected one "
                    "of lambertian-rect, lightfield, photometric, gldf)");
    EXPECT_CONTAINS(inputError([] { parse(R"({"luminaires": [{"position": [0,1,0]}]})"); }),
                    "t.json: luminaires[0].type: expected a luminaire type");
    EXPECT_CONTAINS(
        inputError(
            [] { parse(R"({"luminaires": [{"type": "lambertian-rect", "technique": "x"}]})"); }),
        "t.json: luminaires[0].technique: unknown technique \"x\" for lambertian-rect (expected "
        "one of analytic, reference)");
    EXPECT_CONTAINS(inputError([] {
                        parse(R"({"luminaires": [{"type": "lambertian-rect", "aim": [0,0,0]}]})");
                    }),
                    "t.json: luminaires[0].aim: expected a non-zero direction");
    EXPECT_CONTAINS(inputError([] {
                        parse(R"({"luminaires": [{"type": "lambertian-rect", "c0": [0,0,0]}]})");
                    }),
                    "t.json: luminaires[0].c0: expected a non-zero direction");
    EXPECT_CONTAINS(inputError([] {
                        parse(R"({"geometry": [{"plane": {"size": [1,1]}, "albedo": [1.2,0,0]}]})");
                    }),
                    "t.json: geometry[0].albedo[0]: expected a value in [0, 1]");
    EXPECT_CONTAINS(inputError([] {
                        parse(R"({"geometry": [{"box": {"size": [1,1,1]}, "roughness": -0.1}]})");
                    }),
                    "t.json: geometry[0].roughness: expected a value in [0, 1]");
    EXPECT_CONTAINS(inputError([] { parse(R"({"geometry": [{"plane": {"size": [0,1]}}]})"); }),
                    "t.json: geometry[0].plane.size[0]: expected a positive size");
    EXPECT_CONTAINS(inputError([] {
                        parse(R"({"geometry": [{"plane": {"normal": [0,0,0], "size": [1,1]}}]})");
                    }),
                    "t.json: geometry[0].plane.normal: expected a non-zero direction");
    EXPECT_CONTAINS(
        inputError([] {
            parse(R"({"geometry": [{"plane": {"size": [1,1]}, "box": {"size": [1,1,1]}}]})");
        }),
        "t.json: geometry[0]: expected exactly one of");
    EXPECT_CONTAINS(inputError([] {
                        parse(R"({"geometry": [{"gltf": "a.gltf", "transform": {"scale": 0}}]})");
                    }),
                    "t.json: geometry[0].transform.scale: expected a scale factor from 1e-06 to "
                    "1e+06, got 0");
    EXPECT_CONTAINS(inputError([] { parse(R"({"camera": {"fov_deg": 0}})"); }),
                    "t.json: camera.fov_deg: expected a field of view in (0, 180)");
    EXPECT_CONTAINS(inputError([] { parse(R"({"camera": {"exposure": 0}})"); }),
                    "t.json: camera.exposure: expected a tone-mapping exposure k in [1e-4, 1e4], "
                    "got 0");
    EXPECT_CONTAINS(inputError([] { parse(R"({"camera": {"exposure": "bright"}})"); }),
                    "t.json: camera.exposure: expected a finite number, got the string");
    EXPECT_CONTAINS(inputError([] { parse(R"({"lights": []})"); }),
                    "t.json: unknown field \"lights\"");
}

// --- Values -----------------------------------------------------------------------------------

// The camera's exposure: absent is 0 (the renderer's default) and stays absent when saved; given,
// it is read and written back.
TEST(SceneIo, CameraExposureIsOptionalAndRoundTrips) {
    EXPECT_EQ(parse(R"({"camera": {"fov_deg": 50}})").camera.exposure, 0.0);
    EXPECT_FALSE(sceneToJson(parse(R"({})"))["camera"].contains("exposure"));
    Scene scene = parse(R"({"camera": {"exposure": 0.4}})");
    EXPECT_EQ(scene.camera.exposure, 0.4);
    EXPECT_EQ(sceneToJson(scene)["camera"]["exposure"], 0.4);
}

TEST(SceneIo, LuminaireDefaults) {
    Scene s = parse(R"({"luminaires": [{"type": "lambertian-rect", "name": "A"},
                                       {"type": "lambertian-rect"}]})");
    ASSERT_EQ(s.luminaires.size(), 2u);
    EXPECT_EQ(s.luminaires[0]->name, "A");
    EXPECT_EQ(s.luminaires[1]->name, "lambertian-rect 1");
    const Pose& pose = s.luminaires[1]->pose;
    EXPECT_EQ(pose.position, glm::dvec3(0, 2, 0));
    EXPECT_EQ(pose.aim, glm::dvec3(0, -1, 0));
    EXPECT_EQ(pose.c0, glm::dvec3(1, 0, 0));
    EXPECT_EQ(s.luminaires[1]->technique, "analytic");
    EXPECT_TRUE(s.environment.is_null());
}

TEST(SceneIo, PlaneTangentConventionAndWinding) {
    Scene s = parse(R"({"geometry": [
        {"plane": {"center": [0,0,0], "normal": [0,1,0], "size": [6,4]}},
        {"plane": {"center": [0,1.5,-3], "normal": [0,0,1], "size": [6,3]}},
        {"plane": {"center": [2,1,0], "normal": [-1,0,0], "size": [4,2]}}]})");
    ASSERT_EQ(s.meshes.size(), 3u);
    // Floor: size[0] along X, size[1] along Z.
    EXPECT_EQ(s.meshes[0].boundsMin, glm::vec3(-3, 0, -2));
    EXPECT_EQ(s.meshes[0].boundsMax, glm::vec3(3, 0, 2));
    // Walls: size[0] horizontal, size[1] vertical.
    EXPECT_EQ(s.meshes[1].boundsMin, glm::vec3(-3, 0, -3));
    EXPECT_EQ(s.meshes[1].boundsMax, glm::vec3(3, 3, -3));
    EXPECT_EQ(s.meshes[2].boundsMin, glm::vec3(2, 0, -2));
    EXPECT_EQ(s.meshes[2].boundsMax, glm::vec3(2, 2, 2));
    for (const Mesh& m : s.meshes) {
        EXPECT_EQ(m.shape, MeshShape::Plane);
        ASSERT_EQ(m.triangleCount(), 2u);
        ASSERT_EQ(m.normals.size(), 4u);
        for (size_t t = 0; t < 6; t += 3) {
            glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                      c = m.positions[m.indices[t + 2]];
            glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
            // Counter-clockwise seen from the normal side; 1e-6 is float rounding of unit vectors.
            EXPECT_NEAR(glm::dot(n, m.normals[0]), 1.f, 1e-6f);
        }
    }
}

TEST(SceneIo, DiscIsARegularPolygonFacingItsNormal) {
    Scene s = parse(R"({"geometry": [{"disc": {"center": [1,2,3], "normal": [0,0,-1], "radius": 0.5,
                                                "segments": 64}}]})");
    ASSERT_EQ(s.meshes.size(), 1u);
    const Mesh& m = s.meshes[0];
    EXPECT_EQ(m.shape, MeshShape::Plane);
    ASSERT_EQ(m.triangleCount(), 64u);
    double area = 0.0;
    for (size_t t = 0; t < m.indices.size(); t += 3) {
        glm::dvec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                   c = m.positions[m.indices[t + 2]];
        glm::dvec3 cross = glm::cross(b - a, c - a);
        area += 0.5 * glm::length(cross);
        // Counter-clockwise seen from the normal's side; 1e-5: float vertices.
        EXPECT_NEAR(glm::dot(glm::normalize(cross), glm::dvec3(0, 0, -1)), 1.0, 1e-5);
    }
    for (size_t i = 1; i < m.positions.size(); ++i) {
        EXPECT_NEAR(glm::length(glm::dvec3(m.positions[i]) - glm::dvec3(1, 2, 3)), 0.5, 1e-6);
        EXPECT_NEAR(m.positions[i].z, 3.f, 1e-6f);
    }
    // The inscribed 64-gon: (n / 2) sin(2 pi / n) r^2.
    EXPECT_NEAR(area, 32.0 * std::sin(2.0 * 3.141592653589793 / 64.0) * 0.25, 1e-6);
    EXPECT_CONTAINS(inputError([] { parse(R"({"geometry": [{"disc": {"radius": 0}}]})"); }),
                    "t.json: geometry[0].disc.radius");
    EXPECT_CONTAINS(
        inputError([] { parse(R"({"geometry": [{"disc": {"radius": 1, "segments": 2.5}}]})"); }),
        "t.json: geometry[0].disc.segments: expected a whole number of segments from 3 to 65536");
    EXPECT_CONTAINS(inputError([] { parse(R"({"geometry": [{"disc": {"center": [0,0,0]}}]})"); }),
                    "t.json: geometry[0].disc.radius");
}

TEST(SceneIo, BoxHasOutwardFlatFaces) {
    Scene s = parse(R"({"geometry": [{"box": {"center": [1,0.5,-1], "size": [2,1,0.5],
                                               "rotate_y_deg": 90}}]})");
    ASSERT_EQ(s.meshes.size(), 1u);
    const Mesh& m = s.meshes[0];
    EXPECT_EQ(m.shape, MeshShape::Convex);
    EXPECT_EQ(m.positions.size(), 24u);
    EXPECT_EQ(m.triangleCount(), 12u);
    // Turned by 90 degrees about Y: the 2 m edge now runs along Z. 1e-6: float rounding.
    EXPECT_NEAR(m.boundsMin.x, 0.75f, 1e-6f);
    EXPECT_NEAR(m.boundsMax.x, 1.25f, 1e-6f);
    EXPECT_NEAR(m.boundsMin.z, -2.f, 1e-6f);
    EXPECT_NEAR(m.boundsMax.z, 0.f, 1e-6f);
    EXPECT_NEAR(m.boundsMin.y, 0.f, 1e-6f);
    EXPECT_NEAR(m.boundsMax.y, 1.f, 1e-6f);
    glm::vec3 center(1, 0.5, -1);
    for (size_t t = 0; t < m.indices.size(); t += 3) {
        glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                  c = m.positions[m.indices[t + 2]];
        glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
        EXPECT_NEAR(glm::dot(n, m.normals[m.indices[t]]), 1.f, 1e-6f);
        EXPECT_GT(glm::dot((a + b + c) / 3.f - center, n), 0.f);  // Outward.
    }
}

TEST(SceneIo, MaterialsOfPlanesAndBoxes) {
    Scene s = parse(R"({"geometry": [
        {"plane": {"size": [1,1]}},
        {"box": {"size": [1,1,1]}, "name": "crate", "albedo": [0.6,0.5,0.4],
         "specular": [0.1,0.1,0.1], "roughness": 0.5}]})");
    ASSERT_EQ(s.materials.size(), 2u);
    EXPECT_EQ(s.materials[0].name, "plane 0");
    EXPECT_EQ(s.materials[0].albedo, glm::vec3(0.5f));
    EXPECT_FALSE(s.materials[0].isGlossy());
    EXPECT_EQ(s.materials[1].name, "crate");
    EXPECT_EQ(s.meshes[1].name, "crate");
    EXPECT_EQ(s.meshes[1].material, 1u);
    EXPECT_TRUE(s.materials[1].isGlossy());
    EXPECT_TRUE(s.hasGlossy());
    // alpha = 0.25, n = 2 / 0.0625 - 2 = 30.
    EXPECT_FLOAT_EQ(s.materials[1].phongExponent(), 30.f);
    EXPECT_FLOAT_EQ(s.materials[0].phongExponent(), 0.f);  // alpha = 1.
    Material mirror;
    mirror.roughness = 0.f;  // alpha clamped to 1e-3: n = 2e6 - 2.
    EXPECT_FLOAT_EQ(mirror.phongExponent(), 2e6f - 2.f);
}

TEST(SceneIo, GeometryItemsRecordTheirMeshes) {
    Scene s = loadScene(data("scenes/roundtrip.json"));
    ASSERT_EQ(s.geometry.size(), 3u);
    EXPECT_EQ(s.geometry[0].meshes, std::vector<uint32_t>{0});  // The points primitive is skipped.
    EXPECT_EQ(s.geometry[1].meshes, std::vector<uint32_t>{1});
    EXPECT_EQ(s.geometry[2].meshes, std::vector<uint32_t>{2});
    // glTF triangle (0,0,2), (1,0,2), (0,1,2) scaled by 2, turned 90 degrees about Y (x -> -z,
    // z -> x), moved by (1,0,-1). 1e-5: float positions of a double transform.
    const Mesh& tri = s.meshes[0];
    ASSERT_EQ(tri.positions.size(), 3u);
    EXPECT_NEAR(glm::distance(tri.positions[0], glm::vec3(5, 0, -1)), 0.f, 1e-5f);
    EXPECT_NEAR(glm::distance(tri.positions[1], glm::vec3(5, 0, -3)), 0.f, 1e-5f);
    EXPECT_NEAR(glm::distance(tri.positions[2], glm::vec3(5, 2, -1)), 0.f, 1e-5f);
    EXPECT_NEAR(s.boundsMin().y, 0.f, 1e-6f);
    EXPECT_NEAR(s.boundsMax().x, 5.f, 1e-5f);
}

// --- Round trip and saving -----------------------------------------------------------------------

/// Copies roundtrip.json and the glTF it uses into `dir` with the same relative layout.
fs::path copyRoundTripScene(const fs::path& dir) {
    fs::create_directories(dir / "scenes");
    fs::create_directories(dir / "gltf");
    fs::copy_file(data("scenes/roundtrip.json"), dir / "scenes/roundtrip.json");
    fs::copy_file(data("gltf/triangle.gltf"), dir / "gltf/triangle.gltf");
    fs::copy_file(data("gltf/tri.bin"), dir / "gltf/tri.bin");
    return dir / "scenes/roundtrip.json";
}

void expectSameScene(const Scene& a, const Scene& b) {
    ASSERT_EQ(a.luminaires.size(), b.luminaires.size());
    for (size_t i = 0; i < a.luminaires.size(); ++i)
        EXPECT_EQ(luminaireToJson(*a.luminaires[i]), luminaireToJson(*b.luminaires[i]));
    EXPECT_EQ(a.camera.position, b.camera.position);
    EXPECT_EQ(a.camera.target, b.camera.target);
    EXPECT_EQ(a.camera.fovDeg, b.camera.fovDeg);
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    for (size_t i = 0; i < a.meshes.size(); ++i) {
        EXPECT_EQ(a.meshes[i].positions, b.meshes[i].positions);
        EXPECT_EQ(a.meshes[i].indices, b.meshes[i].indices);
    }
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (size_t i = 0; i < a.materials.size(); ++i) {
        EXPECT_EQ(a.materials[i].albedo, b.materials[i].albedo);
        EXPECT_EQ(a.materials[i].specular, b.materials[i].specular);
        EXPECT_EQ(a.materials[i].roughness, b.materials[i].roughness);
    }
}

TEST(SceneIo, RoundTripInPlaceKeepsEntriesAsWritten) {
    TempDir tmp;
    fs::path path = copyRoundTripScene(tmp.path());
    Scene first = loadScene(path.string());
    saveScene(first, path.string());
    Scene second = loadScene(path.string());
    ASSERT_EQ(first.geometry.size(), second.geometry.size());
    for (size_t i = 0; i < first.geometry.size(); ++i)
        EXPECT_EQ(first.geometry[i].source, second.geometry[i].source);
    // The original file's entries, byte for byte as values (the relative glTF path included).
    nlohmann::json original = nlohmann::json::parse(readText(data("scenes/roundtrip.json")));
    EXPECT_EQ(sceneToJson(second)["geometry"], original["geometry"]);
    expectSameScene(first, second);
    // Saved luminaires carry every field, so defaults cannot drift between versions.
    nlohmann::json saved = nlohmann::json::parse(readText(path));
    EXPECT_EQ(saved["luminaires"][1]["name"], "lambertian-rect 1");
    EXPECT_EQ(saved["luminaires"][1]["technique"], "reference");
}

TEST(SceneIo, SaveToAnotherFolderRebasesRelativeGltfPaths) {
    TempDir tmp;
    fs::path path = copyRoundTripScene(tmp.path());
    Scene first = loadScene(path.string());
    fs::create_directories(tmp.path() / "elsewhere/deeper");
    fs::path moved = tmp.path() / "elsewhere/deeper/moved.json";
    saveScene(first, moved.string());
    nlohmann::json saved = nlohmann::json::parse(readText(moved));
    EXPECT_EQ(saved["geometry"][0]["gltf"], "../../gltf/triangle.gltf");
    Scene second = loadScene(moved.string());
    expectSameScene(first, second);
}

TEST(SceneIo, SaveToAnotherFolderRebasesRelativeLuminaireFiles) {
    TempDir tmp;
    fs::create_directories(tmp.path() / "photometry");
    fs::create_directories(tmp.path() / "scenes");
    fs::copy_file(data("photometric/lambert.ies"), tmp.path() / "photometry/lambert.ies");
    fs::path path = tmp.path() / "scenes/lamp.json";
    std::ofstream(path) << R"({"luminaires": [{"type": "photometric", "name": "Lamp",
        "file": "../photometry/lambert.ies", "position": [0, 2, 0]}]})";
    Scene first = loadScene(path.string());
    fs::create_directories(tmp.path() / "elsewhere/deeper");
    fs::path moved = tmp.path() / "elsewhere/deeper/moved.json";
    saveScene(first, moved.string());
    nlohmann::json saved = nlohmann::json::parse(readText(moved));
    EXPECT_EQ(saved["luminaires"][0]["file"], "../../photometry/lambert.ies");
    Scene second = loadScene(moved.string());  // throws if the file no longer resolves
    ASSERT_EQ(second.luminaires.size(), 1u);
    // Saved in place, the path stays as written.
    saveScene(first, path.string());
    EXPECT_EQ(nlohmann::json::parse(readText(path))["luminaires"][0]["file"],
              "../photometry/lambert.ies");
}

TEST(SceneIo, SaveLeavesNoTemporaryFile) {
    TempDir tmp;
    Scene scene = loadScene(data("scenes/roundtrip.json"));
    saveScene(scene, (tmp.path() / "a.json").string());
    saveScene(scene, (tmp.path() / "a.json").string());  // Over an existing file.
    EXPECT_EQ(tmp.entries(), std::vector<std::string>{"a.json"});
}

TEST(SceneIo, FailedWriteKeepsTheOldFile) {
    // Simulates a full disk: with RLIMIT_FSIZE at 64 bytes, write() fails with EFBIG part-way
    // through the temporary file (this works for root too, unlike read-only folders).
    TempDir tmp;
    fs::path path = tmp.path() / "scene.json";
    const std::string old = "{\"geometry\": []}\n";
    std::ofstream(path) << old;
    Scene scene = loadScene(data("scenes/roundtrip.json"));

    auto previousHandler = std::signal(SIGXFSZ, SIG_IGN);
    rlimit saved{};
    ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &saved), 0);
    rlimit small = saved;
    small.rlim_cur = 64;
    ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
    std::string m = inputError([&] { saveScene(scene, path.string()); });
    setrlimit(RLIMIT_FSIZE, &saved);
    std::signal(SIGXFSZ, previousHandler);

    EXPECT_CONTAINS(m, "scene.json: cannot save scene (write: File too large)");
    EXPECT_EQ(readText(path), old);
    EXPECT_EQ(tmp.entries(), std::vector<std::string>{"scene.json"});
}

TEST(SceneIo, UnwritableTargetFolder) {
    TempDir tmp;
    Scene scene = loadScene(data("scenes/roundtrip.json"));
    std::string m = inputError([&] { saveScene(scene, (tmp.path() / "no/such/x.json").string()); });
    EXPECT_CONTAINS(m, "x.json: cannot save scene (cannot create a temporary file in ");

    // A read-only folder: only meaningful without root's override of permissions.
    if (geteuid() != 0) {
        fs::path path = tmp.path() / "kept.json";
        std::ofstream(path) << "old";
        fs::permissions(tmp.path(), fs::perms::owner_read | fs::perms::owner_exec);
        std::string denied = inputError([&] { saveScene(scene, path.string()); });
        fs::permissions(tmp.path(), fs::perms::owner_all);
        EXPECT_CONTAINS(denied, "Permission denied");
        EXPECT_EQ(readText(path), "old");
        EXPECT_EQ(tmp.entries(), std::vector<std::string>{"kept.json"});
    }
}

TEST(SceneIo, RenameOntoAFolderFailsCleanly) {
    TempDir tmp;
    fs::create_directories(tmp.path() / "target.json/inside");
    Scene scene = loadScene(data("scenes/roundtrip.json"));
    std::string m = inputError([&] { saveScene(scene, (tmp.path() / "target.json").string()); });
    EXPECT_CONTAINS(m, "target.json: cannot save scene (rename: ");
    EXPECT_EQ(tmp.entries(), std::vector<std::string>{"target.json"});
    EXPECT_TRUE(fs::exists(tmp.path() / "target.json/inside"));
}

// --- Shipped scenes ------------------------------------------------------------------------------

TEST(SceneIo, ShippedScenesLoad) {
    for (const auto& entry :
         fs::directory_iterator(std::string(CANDELA_SOURCE_DIR) + "/resources/scenes")) {
        if (entry.path().extension() != ".json") continue;
        SCOPED_TRACE(entry.path().string());
        Scene scene = loadScene(entry.path().string());
        EXPECT_FALSE(scene.meshes.empty());
        EXPECT_FALSE(scene.luminaires.empty());
    }
}

TEST(SceneIo, CornellSceneLightSitsUnderTheLampAndTheCameraSeesTheBox) {
    Scene scene = loadScene(std::string(CANDELA_SOURCE_DIR) + "/resources/scenes/cornell.json");
    ASSERT_EQ(scene.luminaires.size(), 1u);
    const Mesh* lamp = nullptr;
    for (const Mesh& m : scene.meshes)
        if (m.name == "lamp.000") lamp = &m;
    ASSERT_NE(lamp, nullptr);
    // The emitter faces down just below the lamp mesh and within its footprint.
    for (const glm::dvec3& p : scene.luminaires[0]->outline()) {
        EXPECT_LT(p.y, lamp->boundsMin.y);
        EXPECT_GT(p.y, lamp->boundsMin.y - 0.02);
        EXPECT_GE(p.x, lamp->boundsMin.x - 1e-6);
        EXPECT_LE(p.x, lamp->boundsMax.x + 1e-6);
        EXPECT_GE(p.z, lamp->boundsMin.z - 1e-6);
        EXPECT_LE(p.z, lamp->boundsMax.z + 1e-6);
    }
    EXPECT_LT(scene.luminaires[0]->pose.aim.y, 0.0);
    // The camera is in front of the open side (z = +2) and its vertical field of view covers the
    // room's 3 m height at the opening.
    const Camera& c = scene.camera;
    EXPECT_GT(c.position.z, 2.0);
    double halfHeight = (c.position.z - 2.0) * std::tan(glm::radians(c.fovDeg / 2.0));
    EXPECT_GE(halfHeight, 1.5);
    EXPECT_NEAR(c.position.y, 1.5, 0.5);
}

// --- Programmatic geometry and copies ------------------------------------------------------------

TEST(SceneIo, AddPlaneAndBoxMatchTheFileFormat) {
    Scene built;
    Material grey;
    grey.albedo = glm::vec3(0.25f);
    EXPECT_EQ(addPlane(built, {0, 0, 0}, {0, 1, 0}, {4, 3}, grey), 0u);
    Material wood;
    wood.name = "wood";
    wood.albedo = glm::vec3(0.5f, 0.25f, 0.125f);
    EXPECT_EQ(addBox(built, {0, 0.5, 0}, {1, 1, 2}, 30.0, wood), 1u);
    ASSERT_EQ(built.meshes.size(), 2u);
    EXPECT_EQ(built.meshes[0].shape, MeshShape::Plane);
    EXPECT_EQ(built.meshes[1].shape, MeshShape::Convex);
    EXPECT_EQ(built.materials[1].name, "wood");
    EXPECT_EQ(built.geometry[1].source["box"]["rotate_y_deg"], 30.0);

    Scene reread = parseScene(sceneToJson(built), "t.json");
    expectSameScene(built, reread);
    EXPECT_THROW(addPlane(built, {0, 0, 0}, {0, 0, 0}, {1, 1}, grey), InputError);
    EXPECT_THROW(addBox(built, {0, 0, 0}, {1, -1, 1}, 0.0, grey), InputError);
    EXPECT_EQ(built.geometry.size(), 2u);  // Failed additions add nothing.
}

TEST(SceneIo, CloneIsDeep) {
    Scene scene = loadScene(data("scenes/roundtrip.json"));
    Scene copy = scene.clone();
    ASSERT_EQ(copy.luminaires.size(), scene.luminaires.size());
    EXPECT_NE(copy.luminaires[0].get(), scene.luminaires[0].get());
    copy.luminaires[0]->pose.position.y = 5.0;
    copy.meshes[0].positions[0].x = 100.f;
    EXPECT_EQ(scene.luminaires[0]->pose.position.y, 2.0);
    EXPECT_NE(scene.meshes[0].positions[0].x, 100.f);
    EXPECT_EQ(copy.path, scene.path);
    EXPECT_EQ(luminaireToJson(*copy.luminaires[1]), luminaireToJson(*scene.luminaires[1]));
}

TEST(SceneIo, EveryListIsCountedBeforeItsEntriesAreRead) {
    // Each list one entry over its limit: refused by its count, naming the field, the limit and
    // the count, before any entry is read (the entries are empty objects, which would fail on
    // their own fields). At the limit, the count passes and the first entry is what fails.
    const SceneLimits defaults;
    struct List {
        const char* key;
        size_t limit;
    } lists[] = {{"geometry", defaults.geometryEntries},
                 {"luminaires", defaults.luminaires},
                 {"task_areas", defaults.taskAreas},
                 {"calculation_points", defaults.calculationPoints},
                 {"glare_observers", defaults.glareObservers}};
    for (const List& list : lists) {
        SCOPED_TRACE(list.key);
        nlohmann::json doc = nlohmann::json::object();
        doc[list.key] = nlohmann::json::array();
        for (size_t i = 0; i < list.limit; ++i) doc[list.key].push_back(nlohmann::json::object());
        std::string atLimit = inputError([&] { parseScene(doc, "t.json"); });
        EXPECT_CONTAINS(atLimit, std::string("t.json: ") + list.key + "[0]");
        doc[list.key].push_back(nlohmann::json::object());
        std::string over = inputError([&] { parseScene(doc, "t.json"); });
        EXPECT_CONTAINS(over, std::string("t.json: ") + list.key + ": expected at most " +
                                  std::to_string(list.limit));
        EXPECT_CONTAINS(over, ", found " + std::to_string(list.limit + 1));
    }
}

TEST(SceneIo, TrianglesAreCountedOverEveryEntryAndBody) {
    // The geometry's triangles over all entries: three boxes of 12 under a limit of 30 fail at
    // the third entry.
    SceneLimits limits;
    limits.triangles = 30;
    auto box = [](double x) {
        return R"({"box": {"center": [)" + std::to_string(x) + R"(, 0.5, 0], "size": [1, 1, 1]}})";
    };
    nlohmann::json three =
        nlohmann::json::parse(R"({"geometry": [)" + box(0) + "," + box(2) + "," + box(4) + "]}");
    std::string m = inputError([&] { parseScene(three, "t.json", limits); });
    EXPECT_CONTAINS(m,
                    "t.json: geometry[2]: expected geometry of at most 30 triangles in all, "
                    "reached 36");
    limits.triangles = 36;
    EXPECT_EQ(parseScene(three, "t.json", limits).meshes.size(), 3u);
    // With the luminaires' bodies: the office-gldf product's L3D housing, three times, on 36
    // triangles of boxes: refused at the luminaire that passes the limit, naming it.
    std::string lamp = R"({"type": "gldf", "file": ")" + data("gldf/GldfWithFilesComplete.gldf") +
                       R"(", "position": [0, 2.5, 0]})";
    nlohmann::json withLamps = three;
    withLamps["luminaires"] = nlohmann::json::array();
    for (int i = 0; i < 3; ++i) {
        nlohmann::json l = nlohmann::json::parse(lamp);
        l["name"] = "Lamp " + std::to_string(i);
        withLamps["luminaires"].push_back(l);
    }
    Scene unlimited = parseScene(withLamps, "t.json");
    size_t bodyTriangles = 0;
    for (const Mesh& mesh : unlimited.meshes)
        if (mesh.luminaireBody) bodyTriangles += mesh.triangleCount();
    ASSERT_GT(bodyTriangles, 0u);
    limits.triangles = 36 + bodyTriangles - 1;
    m = inputError([&] { parseScene(withLamps, "t.json", limits); });
    EXPECT_CONTAINS(m,
                    "t.json: luminaire \"Lamp 2\": the geometry and the luminaires' bodies "
                    "make more than " +
                        std::to_string(limits.triangles) + " triangles");
    limits.triangles = 36 + bodyTriangles;
    EXPECT_EQ(parseScene(withLamps, "t.json", limits).luminaires.size(), 3u);
}

}  // namespace
}  // namespace candela
