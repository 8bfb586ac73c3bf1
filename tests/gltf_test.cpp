// glTF import: transforms, normals, materials, the real Cornell box, and malformed files that must
// fail with a message naming the file and the problem (never a crash).
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <sstream>

#include "scene/GltfLoader.h"
#include "util/Error.h"

namespace candela {
namespace {

namespace fs = std::filesystem;

std::string data(const std::string& relative) {
    return std::string(CANDELA_TEST_DATA) + "/" + relative;
}

const std::string kCornell =
    std::string(CANDELA_SOURCE_DIR) + "/resources/gltf/cornellBox/cornellBox-2.80-Eevee-gltf.gltf";

#define EXPECT_CONTAINS(text, part) \
    EXPECT_NE(std::string(text).find(part), std::string::npos) << "in: " << (text)

std::string loadError(const std::string& path) {
    Scene scene;
    try {
        loadGltf(path, glm::dmat4(1.0), scene, json::Where{"s.json", "geometry[3].gltf"});
    } catch (const InputError& e) {
        EXPECT_TRUE(scene.meshes.empty());  // A failed load adds nothing.
        EXPECT_TRUE(scene.materials.empty());
        return e.what();
    }
    ADD_FAILURE() << "expected an InputError for " << path;
    return {};
}

glm::vec3 faceNormal(const Mesh& m, size_t t) {
    glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
              c = m.positions[m.indices[t + 2]];
    return glm::normalize(glm::cross(b - a, c - a));
}

TEST(Gltf, TriangleWithNodeAndSceneTransform) {
    Scene scene;
    glm::dmat4 transform = glm::translate(glm::dmat4(1.0), glm::dvec3(0, 1, 0));
    loadGltf(data("gltf/triangle.gltf"), transform, scene, {});
    // The POINTS primitive is skipped (with a warning), the triangle list is kept.
    ASSERT_EQ(scene.meshes.size(), 1u);
    const Mesh& m = scene.meshes[0];
    EXPECT_EQ(m.name, "tri/0");
    EXPECT_EQ(m.shape, MeshShape::General);
    ASSERT_EQ(m.triangleCount(), 1u);
    ASSERT_EQ(m.positions.size(), 3u);
    EXPECT_EQ(m.positions[0], glm::vec3(0, 1, 2));  // Node translation (0,0,2) then (0,1,0).
    EXPECT_EQ(m.positions[1], glm::vec3(1, 1, 2));
    EXPECT_EQ(m.positions[2], glm::vec3(0, 2, 2));
    for (const glm::vec3& n : m.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));  // Flat, CCW.
    EXPECT_EQ(m.boundsMin, glm::vec3(0, 1, 2));
    EXPECT_EQ(m.boundsMax, glm::vec3(1, 2, 2));
    // Roughness 0.9 >= 0.6: diffuse only, base colour kept.
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].name, "red");
    EXPECT_NEAR(scene.materials[0].albedo.x, 0.8f, 1e-6f);
    EXPECT_NEAR(scene.materials[0].albedo.y, 0.1f, 1e-6f);
    EXPECT_FALSE(scene.materials[0].isGlossy());
    EXPECT_NEAR(scene.materials[0].roughness, 0.9f, 1e-6f);
}

TEST(Gltf, MirroringTransformKeepsCounterClockwiseWinding) {
    Scene scene;
    loadGltf(data("gltf/triangle.gltf"), glm::scale(glm::dmat4(1.0), glm::dvec3(-1, 1, 1)), scene,
             {});
    ASSERT_EQ(scene.meshes.size(), 1u);
    const Mesh& m = scene.meshes[0];
    // Mirrored in x, the face still faces +z and the stored normal agrees with the winding.
    EXPECT_NEAR(glm::dot(faceNormal(m, 0), glm::vec3(0, 0, 1)), 1.f, 1e-6f);
    EXPECT_EQ(m.normals[0], glm::vec3(0, 0, 1));
}

/// Writes triangle.gltf + tri.bin as one .glb (12-byte header, JSON chunk, BIN chunk).
fs::path writeGlb(const fs::path& dir) {
    nlohmann::json doc = nlohmann::json::parse(std::ifstream(data("gltf/triangle.gltf")));
    doc["buffers"][0].erase("uri");
    std::string json = doc.dump();
    while (json.size() % 4) json += ' ';
    std::ifstream binFile(data("gltf/tri.bin"), std::ios::binary);
    std::string bin((std::istreambuf_iterator<char>(binFile)), std::istreambuf_iterator<char>());
    while (bin.size() % 4) bin += '\0';
    auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    std::string glb =
        u32(0x46546C67) + u32(2) + u32(uint32_t(12 + 8 + json.size() + 8 + bin.size()));
    glb += u32(uint32_t(json.size())) + u32(0x4E4F534A) + json;
    glb += u32(uint32_t(bin.size())) + u32(0x004E4942) + bin;
    fs::path path = dir / ("candela-test-triangle-" + std::to_string(getpid()) + ".glb");
    std::ofstream(path, std::ios::binary) << glb;
    return path;
}

TEST(Gltf, BinaryGlb) {
    fs::path path = writeGlb(fs::temp_directory_path());
    Scene scene;
    loadGltf(path.string(), glm::dmat4(1.0), scene, {});
    fs::remove(path);
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].positions[2], glm::vec3(0, 1, 2));
}

TEST(Gltf, ErrorsNameTheFileAndTheProblem) {
    std::string m = loadError(data("gltf/no_such_file.gltf"));
    EXPECT_CONTAINS(m, "s.json: geometry[3].gltf: ");
    EXPECT_CONTAINS(m, "no_such_file.gltf: cannot open glTF file (No such file or directory)");

    m = loadError(data("gltf/draco_required.gltf"));
    EXPECT_CONTAINS(m,
                    "draco_required.gltf: requires the glTF extension "
                    "\"KHR_draco_mesh_compression\"");

    // 20-byte tri.bin copy where the glTF declares 64 bytes: tinygltf's own check.
    m = loadError(data("gltf/truncated.gltf"));
    EXPECT_CONTAINS(m, "truncated.gltf: invalid glTF (");
    EXPECT_CONTAINS(m, "truncated.bin");

    m = loadError(data("gltf/accessor_out_of_range.gltf"));
    EXPECT_CONTAINS(m,
                    "accessor_out_of_range.gltf: mesh \"tri/0\" POSITION (accessor 0): 4 "
                    "elements at offset 0 do not fit in bufferView 0 of 36 bytes");

    m = loadError(data("gltf/index_out_of_range.gltf"));
    EXPECT_CONTAINS(m,
                    "index_out_of_range.gltf: mesh \"tri\" indices: index 7 at position 2 is "
                    "out of range (3 vertices)");

    m = loadError(data("gltf/ushort_positions.gltf"));
    EXPECT_CONTAINS(m,
                    "ushort_positions.gltf: mesh \"tri\" POSITION (accessor 2): expected float "
                    "VEC3 data");

    m = loadError(data("scenes/malformed.json"));
    EXPECT_CONTAINS(m, "malformed.json: unsupported file type \".json\"");
}

TEST(Gltf, CorruptedCopiesNeverCrash) {
    // Every single-byte truncation point of the JSON and a few byte flips: each load either
    // succeeds or throws InputError (a crash or another exception fails the test).
    std::ifstream in(data("gltf/accessor_out_of_range.gltf"));
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    fs::path dir = fs::temp_directory_path() / ("candela-gltf-fuzz-" + std::to_string(getpid()));
    fs::create_directories(dir);
    fs::copy_file(data("gltf/tri.bin"), dir / "tri.bin", fs::copy_options::overwrite_existing);
    int failures = 0, loads = 0;
    auto attempt = [&](const std::string& variant) {
        std::ofstream(dir / "v.gltf") << variant;
        Scene scene;
        try {
            loadGltf((dir / "v.gltf").string(), glm::dmat4(1.0), scene, {});
            ++loads;
        } catch (const InputError&) {
            ++failures;
        }
    };
    for (size_t cut = 0; cut < text.size(); cut += 7) attempt(text.substr(0, cut));
    for (const char* from : {"\"count\": 3", "\"byteOffset\": 36", "\"byteLength\": 36",
                             "\"mesh\": 0", "\"POSITION\": 0", "\"bufferView\": 2"}) {
        for (const char* to :
             {"\"count\": 100000000000", "\"byteOffset\": 4000000000", "\"byteLength\": 99999",
              "\"mesh\": 9", "\"POSITION\": 7", "\"bufferView\": -5"}) {
            std::string variant = text;
            size_t at = variant.find(from);
            if (at == std::string::npos) continue;
            variant.replace(at, std::strlen(from), to);
            attempt(variant);
        }
    }
    fs::remove_all(dir);
    EXPECT_GT(failures, 10);
}

/// Triangle counts per primitive in node-traversal order, read from the glTF JSON directly
/// (independently of tinygltf): index accessor count / 3.
std::vector<size_t> expectedTriangleCounts(const std::string& path) {
    nlohmann::json doc = nlohmann::json::parse(std::ifstream(path));
    std::vector<size_t> counts;
    std::function<void(int)> visit = [&](int node) {
        const nlohmann::json& n = doc["nodes"][size_t(node)];
        if (n.contains("mesh"))
            for (const auto& p : doc["meshes"][n["mesh"].get<size_t>()]["primitives"])
                counts.push_back(
                    doc["accessors"][p["indices"].get<size_t>()]["count"].get<size_t>() / 3);
        if (n.contains("children"))
            for (int c : n["children"]) visit(c);
    };
    for (int root : doc["scenes"][doc["scene"].get<size_t>()]["nodes"]) visit(root);
    return counts;
}

/// Mean linear RGB of an 8-bit sRGB image, decoded with OpenImageIO.
glm::dvec3 meanLinearColour(const fs::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) throw std::runtime_error("cannot open " + path.string());
    const OIIO::ImageSpec& spec = in->spec();
    std::vector<unsigned char> pixels(size_t(spec.width) * size_t(spec.height) *
                                      size_t(spec.nchannels));
    in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, pixels.data());
    glm::dvec3 sum(0.0);
    for (size_t p = 0; p < size_t(spec.width) * size_t(spec.height); ++p) {
        for (int c = 0; c < 3; ++c) {
            double v =
                pixels[p * size_t(spec.nchannels) + size_t(spec.nchannels >= 3 ? c : 0)] / 255.0;
            sum[c] += v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
        }
    }
    return sum / double(spec.width * spec.height);
}

TEST(Gltf, CornellBox) {
    Scene scene;
    loadGltf(kCornell, glm::dmat4(1.0), scene, {});
    std::vector<size_t> expected = expectedTriangleCounts(kCornell);
    ASSERT_EQ(scene.meshes.size(), expected.size());
    EXPECT_EQ(expected.size(), 23u);  // 12 meshes, 23 primitives, all reachable from the scene.
    size_t total = 0;
    for (size_t i = 0; i < expected.size(); ++i) {
        EXPECT_EQ(scene.meshes[i].triangleCount(), expected[i]) << scene.meshes[i].name;
        total += scene.meshes[i].triangleCount();
    }
    EXPECT_GT(total, 4000u);

    // The room spans [-2, 2] x [0, 3] x [-2, 2] m; everything else is inside it. 1e-5 m: float
    // positions after the node transforms.
    glm::vec3 lo = scene.boundsMin(), hi = scene.boundsMax();
    EXPECT_NEAR(lo.x, -2.f, 1e-5f);
    EXPECT_NEAR(lo.y, 0.f, 1e-5f);
    EXPECT_NEAR(lo.z, -2.f, 1e-5f);
    EXPECT_NEAR(hi.x, 2.f, 1e-5f);
    EXPECT_NEAR(hi.y, 3.f, 1e-5f);
    EXPECT_NEAR(hi.z, 2.f, 1e-5f);

    for (const Mesh& m : scene.meshes) {
        ASSERT_EQ(m.normals.size(), m.positions.size());
        for (const glm::vec3& n : m.normals) EXPECT_NEAR(glm::length(n), 1.f, 1e-5f);
        for (uint32_t i : m.indices) ASSERT_LT(i, m.positions.size());
    }

    auto materialOf = [&](const std::string& meshName) -> const Material& {
        for (const Mesh& m : scene.meshes)
            if (m.name == meshName) return scene.materials[m.material];
        ADD_FAILURE() << "no mesh " << meshName;
        return scene.materials[0];
    };
    // Suzanne: base 0.8, metallic 0.5, roughness 0.25 -> albedo 0.8 * 0.5, specular
    // mix(0.04, 0.8, 0.5) = 0.42.
    const Material& suzanne = materialOf("suzanne.000");
    EXPECT_NEAR(suzanne.albedo.x, 0.4f, 1e-6f);
    EXPECT_NEAR(suzanne.specular.x, 0.42f, 1e-6f);
    EXPECT_TRUE(scene.hasGlossy());
    // The red wall stays diffuse (roughness 1).
    const Material& red = materialOf("cornellBox.000/2");
    EXPECT_NEAR(red.albedo.x, 0.9551045f, 1e-6f);
    EXPECT_FALSE(red.isGlossy());
    // Textured materials: base colour = the texture's mean linear colour. The expectation is
    // computed from the PNG decoded by OpenImageIO (not tinygltf's stb), converting each 8-bit
    // sRGB value to linear before averaging; 1e-4 allows for float accumulation.
    for (const char* name : {"bloc.000", "cornellBox.000/1"}) {
        std::string image =
            name == std::string("bloc.000") ? "checkerBJS.png" : "checker-meter.png";
        glm::dvec3 expected = meanLinearColour(fs::path(kCornell).parent_path() / image);
        const Material& textured = materialOf(name);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(textured.albedo[c], expected[c], 1e-4) << name;
    }
    // checker-meter.png is white but for its corner marks; checkerBJS.png is white and light
    // grey squares plus colour charts: averaging the sRGB values instead would give 0.875 (linear:
    // 0.821).
    EXPECT_GT(materialOf("cornellBox.000/1").albedo.x, 0.99f);
    EXPECT_LT(materialOf("cornellBox.000/1").albedo.x, 1.f);
    EXPECT_LT(materialOf("bloc.000").albedo.x, 0.85f);
    // Shared glTF materials become shared Candela materials: 13 in the file, all used.
    EXPECT_EQ(scene.materials.size(), 13u);
}

}  // namespace
}  // namespace candela
