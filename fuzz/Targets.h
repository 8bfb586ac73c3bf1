#pragma once
// The fuzz targets' bodies, one function per input format, so that the libFuzzer targets
// (fuzz_NAME.cpp) and the regression test of the normal build (tests/fuzz_regressions_test.cpp)
// run the same checks. Each takes any bytes; it returns normally when the parser loaded them or
// threw InputError, and aborts (a crash for libFuzzer, a failed test) when a check fails.

#include <algorithm>
#include <cstring>
#include <nlohmann/json.hpp>

#include "formats/Gldf.h"
#include "formats/L3d.h"
#include "formats/Tm25RayFile.h"
#include "fuzz/FuzzSupport.h"
#include "fuzz/PhotometryChecks.h"
#include "luminaires/Adapter.h"
#include "luminaires/environment/Environment.h"
#include "luminaires/lightfield/LightField.h"
#include "scene/GltfLoader.h"
#include "scene/SceneIo.h"
#include "util/Error.h"

namespace candela::fuzz {

/// The IES LM-63 parser (formats/IesFile.cpp), lenient and strict.
inline void ies(const uint8_t* data, size_t size) {
    checkPhotometry(data, size, PhotometryFormat::Ies);
}

/// The EULUMDAT parser (formats/LdtFile.cpp), lenient and strict.
inline void ldt(const uint8_t* data, size_t size) {
    checkPhotometry(data, size, PhotometryFormat::Ldt);
}

/// The IES TM-33 parser (formats/Tm33File.cpp), lenient and strict.
inline void tm33(const uint8_t* data, size_t size) {
    checkPhotometry(data, size, PhotometryFormat::Tm33);
}

/// The IES TM-25 ray file reader (formats/Tm25RayFile.cpp). It reads files, so
/// each input is written to a scratch file first.
inline void tm25(const uint8_t* data, size_t size) {
    const std::string path = writeScratch("fuzz.tm25ray", data, size);
    try {
        Tm25RayFile f = readTm25(path);
        const Tm25Header& h = f.header;
        if (f.rays.size() != h.rayCount) violated("ray count differs from the header's");
        for (const Tm25Ray& r : f.rays) {
            checkFinite(std::vector<double>{r.position.x, r.position.y, r.position.z},
                        "ray position");
            if (!(std::abs(glm::length(r.direction) - 1.0) < 1e-9))
                violated("ray direction not unit");
        }
        for (const std::string& s : h.description)
            if (!isValidUtf8(s)) violated("description is not valid UTF-8");
        for (const std::string& s : h.additionalLabels)
            if (!isValidUtf8(s)) violated("additional label is not valid UTF-8");
        if (!isValidUtf8(h.additionalText)) violated("additional text is not valid UTF-8");
    } catch (const InputError& e) {
        checkMessage(e.what(), path);
    }
}

/// The light-field manifest (NAME.lf.json, luminaires/lightfield/LightField.cpp). The input
/// is the manifest; the scratch folder holds the nine images of tests/data/lightfield/tiny.lf.json,
/// so manifests that name them load through OpenImageIO and the precomputation.
inline void lightfield(const uint8_t* data, size_t size) {
    static const bool ready = [] {
        std::vector<std::string> images;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                images.push_back("tests/data/lightfield/tiny_" + std::to_string(i) + "_" +
                                 std::to_string(j) + ".exr");
        copyIntoScratch(images);
        return true;
    }();
    (void)ready;
    const std::string path = writeScratch("fuzz.lf.json", data, size);
    try {
        std::shared_ptr<LightFieldData> lf = LightFieldData::load(path);
        glm::dvec3 p = lf->power();
        checkFinite(std::vector<double>{p.x, p.y, p.z}, "light-field power", 0.0);
    } catch (const InputError&) {
    }
}

/// Scene files (scene/SceneIo.cpp) with everything they load: luminaires of each
/// kind through the registry, glTF geometry, environment maps. The scratch folder holds small
/// files a scene may name: lambert.ies, example.ldt, tiny.lf.json and its images, triangle.gltf
/// and tri.bin, constant_2.exr.
inline void scene(const uint8_t* data, size_t size) {
    static const bool ready = [] {
        std::vector<std::string> files = {
            "tests/data/photometric/lambert.ies", "tests/data/lightfield/tiny.lf.json",
            "tests/data/gltf/tri.bin", "tests/data/environment/constant_2.exr",
            "tests/data/photometry/ldt/lidrs/example.ldt"};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                files.push_back("tests/data/lightfield/tiny_" + std::to_string(i) + "_" +
                                std::to_string(j) + ".exr");
        copyIntoScratch(files);
        // triangle.gltf without its point primitive, whose warning would flood the log.
        std::ifstream in(fs::path(CANDELA_SOURCE_DIR) / "tests/data/gltf/triangle.gltf");
        nlohmann::json gltf = nlohmann::json::parse(in);
        gltf["meshes"][0]["primitives"].erase(1);
        std::ofstream(scratchDir() / "triangle.gltf") << gltf.dump();
        return true;
    }();
    (void)ready;
    // A sky of at most 512 texels across (users keep 16384): a valid sky 5126 texels wide took
    // 7 s under ASan (26 million texels of the sky model; fuzz/regressions/scene/
    // sky-resolution-5126-slow.json), and one 2048 wide still 1.3 s. The same code, at a size
    // that computes in milliseconds.
    std::string text(reinterpret_cast<const char*>(data), size);
    try {
        nlohmann::json doc = nlohmann::json::parse(text);
        nlohmann::json* sky = nullptr;
        if (doc.is_object() && doc.contains("environment") && doc["environment"].is_object() &&
            doc["environment"].contains("sky") && doc["environment"]["sky"].is_object())
            sky = &doc["environment"]["sky"];
        if (sky && sky->contains("resolution") && (*sky)["resolution"].is_number() &&
            (*sky)["resolution"].get<double>() > 512.0) {
            (*sky)["resolution"] = 512;
            text = doc.dump();
        }
    } catch (const std::exception&) {
        // Not JSON (or not dumpable): the parser under test says so from the bytes as they are.
    }
    const std::string path =
        writeScratch("fuzz.json", reinterpret_cast<const uint8_t*>(text.data()), text.size());
    try {
        Scene scene = loadScene(path);
        for (const Mesh& m : scene.meshes) {
            for (const glm::vec3& v : m.positions)
                checkFinite(std::vector<double>{v.x, v.y, v.z}, "mesh position");
            for (uint32_t i : m.indices)
                if (i >= m.positions.size()) violated("mesh index out of range");
        }
        for (const auto& l : scene.luminaires) {
            glm::dvec3 p = l->power();
            checkFinite(std::vector<double>{p.x, p.y, p.z}, "luminaire power", 0.0);
            (void)describe(*l);
        }
    } catch (const InputError&) {
    }
}

/// glTF import (scene/GltfLoader.cpp over tinygltf). Inputs starting with the
/// binary magic "glTF" are read as .glb, others as .gltf; the scratch folder holds tri.bin, the
/// buffer the test files name.
inline void gltf(const uint8_t* data, size_t size) {
    static const bool ready = [] {
        copyIntoScratch({"tests/data/gltf/tri.bin"});
        return true;
    }();
    (void)ready;
    bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    const std::string path = writeScratch(binary ? "fuzz.glb" : "fuzz.gltf", data, size);
    try {
        Scene scene;
        loadGltf(path, glm::dmat4(1.0), scene, json::Where{path, ""});
        for (const Mesh& m : scene.meshes) {
            for (const glm::vec3& v : m.positions)
                checkFinite(std::vector<double>{v.x, v.y, v.z}, "mesh position");
            for (const glm::vec3& n : m.normals)
                checkFinite(std::vector<double>{n.x, n.y, n.z}, "mesh normal");
            for (uint32_t i : m.indices)
                if (i >= m.positions.size()) violated("mesh index out of range");
            if (m.material >= scene.materials.size()) violated("material index out of range");
        }
    } catch (const InputError&) {
    }
}

/// Environment-map loading (luminaires/environment/Environment.cpp over OpenImageIO), the
/// image path a scene file or a dropped file reaches. Inputs starting with "#?" (Radiance) are
/// written as .hdr, others as .exr.
inline void image(const uint8_t* data, size_t size) {
    bool radiance = size >= 2 && std::memcmp(data, "#?", 2) == 0;
    const std::string path = writeScratch(radiance ? "fuzz.hdr" : "fuzz.exr", data, size);
    try {
        // At most 2048 texels wide: a valid map of one colour compresses to a few kilobytes
        // whatever its size (a 14 KB DWAB file is 8192x4096 and takes 3 s and 1 GB to decode in
        // Release, far more under ASan), so the full 16384 limit spent the target's time
        // decoding valid constant images, on code that is the same at every size.
        std::shared_ptr<EnvironmentMap> map = EnvironmentMap::load(path, 1.0, 0.0, 2048);
        if (map->width() != 2 * map->height()) violated("not a lat-long map");
        for (int y = 0; y < map->height(); y += std::max(1, map->height() / 8))
            for (int x = 0; x < map->width(); x += std::max(1, map->width() / 8)) {
                glm::dvec3 t = map->texel(x, y);
                checkFinite(std::vector<double>{t.x, t.y, t.z}, "texel", 0.0);
            }
    } catch (const InputError&) {
    }
}

/// What the GLDF reader returns: every string shown is valid UTF-8 and every reference resolves.
inline void checkGldf(const GldfProduct& p) {
    for (const std::string* s : {&p.manufacturer, &p.author, &p.productName, &p.productNumber,
                                 &p.description, &p.formatVersion, &p.creationTime})
        if (!isValidUtf8(*s)) violated("product text is not valid UTF-8: " + toValidUtf8(*s));
    for (const std::string& m : p.members)
        if (!isValidUtf8(m)) violated("member name is not valid UTF-8");
    for (const GldfEmitter& e : p.emitters)
        for (const GldfLightEmitter& l : e.lights)
            if (!l.fileId.empty() && !p.file(l.fileId)) violated("dangling file id " + l.fileId);
    for (const GldfVariant& v : p.variants)
        for (const std::string& id : v.emitters)
            if (!p.emitter(id)) violated("dangling emitter id " + id);
}

/// The GLDF reader (formats/Gldf.cpp): a ZIP container ("PK" first) through parseGldf and
/// each variant's photometry; any other input as product.xml alone (so mutations reach the XML
/// reader without breaking a ZIP checksum).
inline void gldf(const uint8_t* data, size_t size) {
    const std::string path = "/nonexistent-candela-fuzz/fuzz.gldf";
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    try {
        GldfProduct product;
        product.path = path;
        if (bytes.compare(0, 2, "PK") == 0)
            product = parseGldf(bytes, path);
        else
            gldf_detail::readProductXml(bytes, product);
        checkGldf(product);
        for (const GldfVariant& v : product.variants) {
            try {
                GldfPhotometry p = gldfVariantPhotometry(bytes, product, v);
                checkTable(p.data);
            } catch (const InputError& e) {
                checkMessage(e.what(), path);
            }
        }
    } catch (const InputError& e) {
        checkMessage(e.what(), path);
    }
}

/// What joins structure.xml and the OBJ text in the l3d target's text inputs.
inline constexpr std::string_view kL3dObjMark = "\n#candela-fuzz-obj\n";

/// The invariants L3d.h promises of a loaded geometry.
inline void checkL3d(const L3dLuminaire& l) {
    for (const L3dPart& p : l.parts) {
        size_t n = p.triangleCount();
        if (p.indices.size() != 3 * n || p.triangleFace.size() != n ||
            p.triangleGroup.size() != n || p.triangleFileFace.size() != n)
            violated("triangle arrays of different sizes");
        for (uint32_t i : p.indices)
            if (i >= p.positions.size()) violated("a triangle names a vertex it does not have");
        for (const glm::dvec3& v : p.positions)
            checkFinite(std::vector<double>{v.x, v.y, v.z}, "vertex");
    }
    for (const L3dEmitter& e : l.emitters) {
        checkFinite(std::vector<double>{e.sizeX, e.sizeY, e.area()}, "opening size", 0.0);
        checkFinite(std::vector<double>{e.centre.x, e.centre.y, e.centre.z}, "opening centre");
        for (const glm::dvec3& axis : {e.x, e.y, e.normal})
            if (!(std::abs(glm::length(axis) - 1.0) < 1e-9)) violated("opening axis not unit");
        for (auto [part, triangle] : e.triangles)
            if (part >= l.parts.size() || triangle >= l.parts[part].triangleCount())
                violated("a light-emitting surface names a triangle that is not there");
    }
}

/// The L3D reader (formats/L3d.cpp): an .l3d archive ("PK..."), or, so that mutations reach
/// the XML and OBJ parsers past the archive's checksums, structure.xml and one OBJ text joined by
/// kL3dObjMark (every geometry definition reads that text; without the mark, none has one).
inline void l3d(const uint8_t* data, size_t size) {
    const std::string path = "/nonexistent-candela-fuzz/fuzz.l3d";
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    try {
        L3dLuminaire l;
        if (bytes.compare(0, 2, "PK") == 0) {
            l = parseL3d(bytes, path);
        } else {
            size_t cut = bytes.find(kL3dObjMark);
            std::string xml = bytes.substr(0, cut);
            std::string obj =
                cut == std::string::npos ? "" : bytes.substr(cut + kL3dObjMark.size());
            l = l3d_detail::readMembers(
                path, [&](const std::string& member) -> std::optional<std::string> {
                    if (member == "structure.xml") return xml;
                    if (cut != std::string::npos && member.size() > 4 &&
                        member.compare(member.size() - 4, 4, ".obj") == 0)
                        return obj;
                    return std::nullopt;
                });
        }
        checkL3d(l);
    } catch (const InputError& e) {
        checkMessage(e.what(), path);
    }
}

/// Every target by name.
struct Target {
    const char* name;
    void (*run)(const uint8_t* data, size_t size);
};
inline constexpr Target kTargets[] = {
    {"ies", ies},     {"ldt", ldt},   {"tm25", tm25},   {"lightfield", lightfield},
    {"scene", scene}, {"gltf", gltf}, {"image", image}, {"gldf", gldf},
    {"l3d", l3d},     {"tm33", tm33}};

}  // namespace candela::fuzz
