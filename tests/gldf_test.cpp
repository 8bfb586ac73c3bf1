// GLDF containers (formats/Gldf.h): each of the twelve gldf.net test containers either loads
// (product data, variants, photometry) or is refused with a message naming the member and the
// defect; containers this test writes with libzip cover what those do not (a URL photometry, a
// dangling file id, a damaged or oversized member, IES inside, two emitters, code page 850
// names); and a "gldf" scene entry loads, renders as photometric and round-trips through save.
#include "formats/Gldf.h"

#include <gtest/gtest.h>
#include <zip.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <utility>
#include <vector>

#include "calculation/CalculationGrid.h"
#include "luminaires/photometric/PhotometricLuminaire.h"
#include "scene/SceneIo.h"
#include "tests/TempDir.h"
#include "util/Error.h"
#include "util/TextEncoding.h"

namespace candela {
namespace {

namespace fs = std::filesystem;

const std::string kData = CANDELA_TEST_DATA;

std::string container(const std::string& name) {
    return kData + "/gldf/" + name + ".gldf";
}

using test::TempDir;

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

/// One member's bytes read with libzip directly (not through the reader under test).
std::string memberOf(const std::string& path, const std::string& member) {
    int error = 0;
    zip_t* z = zip_open(path.c_str(), ZIP_RDONLY, &error);
    if (!z) throw std::runtime_error("cannot open " + path);
    zip_stat_t st;
    zip_file_t* f =
        zip_stat(z, member.c_str(), 0, &st) == 0 ? zip_fopen(z, member.c_str(), 0) : nullptr;
    if (!f) throw std::runtime_error("no " + member + " in " + path);
    std::string out(size_t(st.size), '\0');
    zip_int64_t n = zip_fread(f, out.data(), st.size);
    zip_fclose(f);
    zip_discard(z);
    if (n != zip_int64_t(st.size)) throw std::runtime_error("short read of " + member);
    return out;
}

struct Member {
    std::string name;  ///< Raw bytes of the name (code page 850 when `cp850`).
    std::string bytes;
    bool cp850 = false;
    bool store = false;  ///< Uncompressed (so a test can damage its bytes in place).
};

/// Writes a container with libzip.
void writeZip(const std::string& path, const std::vector<Member>& members) {
    int error = 0;
    zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
    ASSERT_NE(z, nullptr);
    for (const Member& m : members) {
        zip_source_t* s = zip_source_buffer(z, m.bytes.data(), m.bytes.size(), 0);
        ASSERT_NE(s, nullptr);
        zip_int64_t index =
            zip_file_add(z, m.name.c_str(), s, m.cp850 ? ZIP_FL_ENC_CP437 : ZIP_FL_ENC_UTF_8);
        ASSERT_GE(index, 0) << zip_strerror(z);
        if (m.store) zip_set_file_compression(z, zip_uint64_t(index), ZIP_CM_STORE, 0);
    }
    ASSERT_EQ(zip_close(z), 0);
}

/// A minimal product.xml: one fixed emitter e1 (2000 lm, light source ls1 at 20 W) with
/// photometry p1 from file f1 (ldc/lamp.ldt), one variant v1 placing it.
std::string productXml() {
    return R"(<?xml version="1.0" encoding="utf-8"?>
<Root>
  <Header>
    <Manufacturer>Acme</Manufacturer><FormatVersion major="1" minor="0"/>
    <CreatedWithApplication>gldf_test</CreatedWithApplication>
    <GldfCreationTimeCode>2024-01-01T00:00:00Z</GldfCreationTimeCode><UniqueGldfId>x</UniqueGldfId>
  </Header>
  <GeneralDefinitions>
    <Files><File id="f1" contentType="ldc/eulumdat" type="localFileName">lamp.ldt</File></Files>
    <Photometries><Photometry id="p1"><PhotometryFileReference fileId="f1"/></Photometry></Photometries>
    <LightSources>
      <FixedLightSource id="ls1"><Name><Locale language="en">LED</Locale></Name>
        <RatedInputPower>20</RatedInputPower>
        <LightSourceMaintenance><LedMaintenanceFactor hours="50000">0.8</LedMaintenanceFactor></LightSourceMaintenance>
      </FixedLightSource>
    </LightSources>
    <Emitters>
      <Emitter id="e1"><FixedLightEmitter><PhotometryReference photometryId="p1"/>
        <LightSourceReference fixedLightSourceId="ls1"/><RatedLuminousFlux>2000</RatedLuminousFlux>
      </FixedLightEmitter></Emitter>
    </Emitters>
  </GeneralDefinitions>
  <ProductDefinitions>
    <ProductMetaData><UniqueProductId>u</UniqueProductId>
      <ProductNumber><Locale language="en">P-1</Locale></ProductNumber>
      <Name><Locale language="de">Strahler</Locale><Locale language="en">Spot</Locale></Name>
    </ProductMetaData>
    <Variants><Variant id="v1"><Name><Locale language="en">V1</Locale></Name>
      <Geometry><EmitterReference emitterId="e1"/></Geometry></Variant></Variants>
  </ProductDefinitions>
</Root>
)";
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
    size_t at = s.find(from);
    if (at == std::string::npos) throw std::runtime_error("no " + from + " in the template");
    return s.replace(at, from.size(), to);
}

/// The message of the InputError `f` throws ("" and a test failure when it throws none).
template <typename F>
std::string refusal(F f) {
    try {
        f();
    } catch (const InputError& e) {
        EXPECT_TRUE(isValidUtf8(e.what())) << e.what();
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        return e.what();
    }
    ADD_FAILURE() << "no InputError";
    return "";
}

/// The photometry of `variant` ("" for the first) of the container at `path`.
GldfPhotometry photometryOf(const std::string& path, const std::string& variant = "") {
    std::string bytes = readGldfBytes(path);
    GldfProduct product = parseGldf(bytes, path);
    const GldfVariant* v = variant.empty() ? &product.variants.front() : product.variant(variant);
    GldfPhotometry p = gldfVariantPhotometry(bytes, product, *v);
    p.emitter = nullptr;  // points into `product`, gone at return
    p.file = nullptr;
    return p;
}

std::string realLdt() {
    return memberOf(container("GldfWithFilesComplete"), "ldc/photometry.ldt");
}

// --- Emitter rotation
// -----------------------------------------------------------------------------

TEST(Gldf, EmitterRotationIsRead) {
    GldfProduct p = loadGldf(container("GldfWithFilesComplete"));
    const GldfEmitter* e = p.emitter("emitter-1");
    ASSERT_TRUE(e && e->lights.size() == 2);
    EXPECT_EQ(e->lights[0].rotationXyz, glm::dvec3(1, 2, 3));
    EXPECT_EQ(e->lights[0].rotationG0, 4.0);
    EXPECT_EQ(e->lights[1].rotationXyz, glm::dvec3(5, 6, 7));
    EXPECT_EQ(e->lights[1].rotationG0, 8.0);
    EXPECT_TRUE(e->lights[0].rotated());
}

TEST(Gldf, EmitterRotationTurnsTheFrameRightHanded) {
    // Worked by hand in the luminaire frame (C0 along +x, aiming down -z, C90 = c0 x aim = +y).
    struct Case {
        glm::dvec3 xyz;
        double g0;
        glm::dvec3 c0, aim;
    };
    for (const Case& c : {
             Case{{0, 0, 0}, 90, {0, 1, 0}, {0, 0, -1}},    // G0: C0 to where C90 was
             Case{{0, 0, 0}, 180, {-1, 0, 0}, {0, 0, -1}},  // C0 to C180
             Case{{90, 0, 0}, 0, {1, 0, 0}, {0, 1, 0}},     // about x: -z to +y
             Case{{0, 90, 0}, 0, {0, 0, -1}, {-1, 0, 0}},   // about y: x to -z, -z to -x
             Case{{0, 0, 90}, 0, {0, 1, 0}, {0, 0, -1}},    // about z: x to y
             // Rz Rx Ry: Ry first (x to -z, -z to -x), then Rx (-z to +y; -x stays), then Rz
             // (+y to -x; -x to -y).
             Case{{90, 90, 90}, 0, {-1, 0, 0}, {0, -1, 0}},
         }) {
        GldfLightEmitter light;
        light.rotationXyz = c.xyz;
        light.rotationG0 = c.g0;
        glm::dvec3 c0{1, 0, 0}, aim{0, 0, -1};
        gldfRotateEmitter(light, c0, aim);
        for (int i = 0; i < 3; ++i) {
            EXPECT_NEAR(c0[i], c.c0[i], 1e-12) << c.xyz.x << c.xyz.y << c.xyz.z << " G0 " << c.g0;
            EXPECT_NEAR(aim[i], c.aim[i], 1e-12) << c.xyz.x << c.xyz.y << c.xyz.z << " G0 " << c.g0;
        }
    }
}

TEST(Gldf, EmitterRotationAboutG0TurnsTheLight) {
    // cplanes.ies has 100, 200, 300, 400 cd at C 0, 90, 180, 270. Placed in a scene as GLDF
    // luminaires, one with <G0>90</G0>: the rotated one sends C0's 100 cd where C90 was, C90's
    // 200 cd to C180, and so on, read against the unrotated luminaire's own frame.
    TempDir tmp;
    std::string ies = readBytes(kData + "/photometric/cplanes.ies");
    std::string xml =
        replaced(productXml(), R"(contentType="ldc/eulumdat" type="localFileName">lamp.ldt)",
                 R"(contentType="ldc/ies" type="localFileName">lamp.ies)");
    writeZip(tmp.file("plain.gldf"), {{"product.xml", xml}, {"ldc/lamp.ies", ies}});
    xml = replaced(xml, "<FixedLightEmitter>",
                   "<FixedLightEmitter><Rotation><X>0</X><Y>0</Y><Z>0</Z><G0>90</G0></Rotation>");
    writeZip(tmp.file("turned.gldf"), {{"product.xml", xml}, {"ldc/lamp.ies", ies}});
    std::string scene = tmp.file("scene.json");
    std::ofstream(scene) << R"({"luminaires": [
        {"type": "gldf", "file": "plain.gldf", "position": [0, 3, 0]},
        {"type": "gldf", "file": "turned.gldf", "position": [0, 3, 0]}]})";
    Scene s = loadScene(scene);
    const Luminaire& plainLight = *s.luminaires.at(0);
    const Luminaire& turnedLight = *s.luminaires.at(1);
    ASSERT_TRUE(photometricModel(plainLight) && photometricModel(turnedLight));
    const PhotometricLuminaire& plain = *photometricModel(plainLight);
    const PhotometricLuminaire& turned = *photometricModel(turnedLight);
    glm::dvec3 c0, c90, aim;
    plain.photometricFrame(plainLight.pose, c0, c90, aim);
    const double h = std::sqrt(0.5);  // gamma 45 degrees
    const double cd[4] = {100, 200, 300, 400};
    for (int k = 0; k < 4; ++k) {
        double c = k * 0.5 * 3.14159265358979;
        glm::dvec3 w = h * (std::cos(c) * c0 + std::sin(c) * c90) + h * aim;
        EXPECT_NEAR(plain.intensity(plainLight.pose, w), cd[k], 1e-9) << "C " << 90 * k;
        EXPECT_NEAR(turned.intensity(turnedLight.pose, w), cd[(k + 3) % 4], 1e-9) << "C " << 90 * k;
    }
}

// --- The gldf.net containers -------------------------------------------------------------------

TEST(Gldf, CompleteContainerProductData) {
    GldfProduct p = loadGldf(container("GldfWithFilesComplete"));
    EXPECT_EQ(p.manufacturer, "DIAL");
    EXPECT_EQ(p.author, "Author");
    EXPECT_EQ(p.formatVersion, "1.0 (pre-release 3)");
    EXPECT_EQ(p.creationTime, "2021-03-29T14:30:00Z");
    EXPECT_EQ(p.productName, "Product name");  // the English Locale
    EXPECT_EQ(p.productNumber, "Product number");
    EXPECT_EQ(p.uniqueProductId, "Product 1");
    ASSERT_EQ(p.files.size(), 9u);
    const GldfFile* ldt = p.file("eulumdatFile");
    ASSERT_NE(ldt, nullptr);
    EXPECT_EQ(ldt->contentType, "ldc/eulumdat");
    EXPECT_EQ(ldt->member(), "ldc/photometry.ldt");
    EXPECT_EQ(p.file("customFile1")->member(), "other/custom file 1.txt");

    ASSERT_EQ(p.emitters.size(), 2u);
    const GldfEmitter& e1 = p.emitters[0];
    EXPECT_EQ(e1.id, "emitter-1");
    ASSERT_EQ(e1.lights.size(), 2u);  // two interchangeable ChangeableLightEmitters
    EXPECT_FALSE(e1.lights[0].fixed);
    EXPECT_EQ(e1.lights[0].fileId, "eulumdatFile");
    EXPECT_EQ(e1.lights[0].lightSourceId, "lightSource");
    EXPECT_EQ(e1.lights[0].ratedFlux, 800.0);   // the light source's RatedLuminousFlux
    EXPECT_EQ(e1.lights[0].ratedPower, 110.0);  // equipment-1's RatedInputPower
    EXPECT_EQ(e1.lights[1].ratedPower, 115.0);  // equipment-2's
    ASSERT_EQ(e1.lights[0].maintenance.size(), 4u);
    EXPECT_EQ(e1.lights[0].maintenance[0].what, "LLMF after 125 h");
    EXPECT_EQ(e1.lights[0].maintenance[0].factor, 0.9);
    EXPECT_EQ(e1.lights[0].maintenance[3].what, "LSF after 150 h");
    EXPECT_EQ(e1.lights[0].maintenance[3].factor, 0.82);
    EXPECT_EQ(e1.lights[0].maintenance[2].factor, 0.8);  // "\n 0.8" in the file: trimmed
    EXPECT_TRUE(p.emitters[1].lights.empty());
    EXPECT_EQ(p.emitters[1].sensors, 1);

    ASSERT_EQ(p.variants.size(), 2u);
    EXPECT_EQ(p.variants[0].id, "variant-1");
    EXPECT_EQ(p.variants[0].name, "Variant name 1");
    EXPECT_EQ(p.variants[0].description, "Variant description 1");
    EXPECT_EQ(p.variants[0].emitters, std::vector<std::string>{"emitter-1"});
    // Simple and model geometry are two levels of detail of one placement.
    EXPECT_EQ(p.variants[1].emitters, std::vector<std::string>{"emitter-1"});
    EXPECT_EQ(p.variants[1].geometryIds, (std::vector<std::string>{"geometry-2", "geometry-1"}));
}

TEST(Gldf, CompleteContainerPhotometryEqualsTheExtractedLdt) {
    TempDir tmp;
    std::string ldt = tmp.file("photometry.ldt");
    std::ofstream(ldt, std::ios::binary) << realLdt();
    PhotometricData alone = loadPhotometry(ldt);
    GldfPhotometry inside = photometryOf(container("GldfWithFilesComplete"), "variant-2");
    EXPECT_EQ(inside.data.path, container("GldfWithFilesComplete") + ":ldc/photometry.ldt");
    EXPECT_EQ(inside.data.format, "EULUMDAT");
    ASSERT_GT(alone.fluxFromTable(), 0.0);
    // The brief's bound for the flux `info` prints; the same bytes through the same parser give
    // the same table, so anything beyond rounding is a bug in how the member was read.
    EXPECT_NEAR(inside.data.fluxFromTable(), alone.fluxFromTable(), 1e-3 * alone.fluxFromTable());
    EXPECT_EQ(inside.data.candela, alone.candela);
}

TEST(Gldf, MissingProductXml) {
    EXPECT_EQ(refusal([] { loadGldf(container("GldfWithMissingProduct")); }),
              container("GldfWithMissingProduct") + ": product.xml: missing");
}

TEST(Gldf, ProductXmlWithoutProductDefinitions) {
    std::string m = refusal([] { loadGldf(container("GldfWithFiles")); });
    EXPECT_NE(m.find("GldfWithFiles.gldf: product.xml: no <ProductDefinitions>"), std::string::npos)
        << m;
}

TEST(Gldf, UnknownContentType) {
    // Read with a warning (the type matters only where the file is used); this one's photometry
    // is only a URL besides, so its variant cannot be placed, and says why.
    GldfProduct p = loadGldf(container("GldfWithInvalidRoot"));
    ASSERT_EQ(p.warnings.size(), 1u);
    EXPECT_NE(p.warnings[0].find("product.xml: file \"eulumdat\": unknown contentType \"invalid\""),
              std::string::npos)
        << p.warnings[0];
    std::string m = refusal([] { photometryOf(container("GldfWithInvalidRoot")); });
    EXPECT_NE(m.find("is only a URL"), std::string::npos) << m;
    EXPECT_NE(m.find("download it and place it as a photometric luminaire"), std::string::npos)
        << m;
}

TEST(Gldf, UrlOnlyPhotometries) {
    for (const char* name : {"GldfWithHeaderMandatory", "GldfWithNoFiles", "GldfWithLargeFiles"}) {
        GldfProduct p = loadGldf(container(name));
        EXPECT_EQ(p.manufacturer, "DIAL") << name;
        EXPECT_EQ(p.variants.size(), 1u) << name;
        std::string m = refusal([&] { photometryOf(container(name)); });
        std::string url = std::string(name) == "GldfWithLargeFiles"
                              ? "eulumdat1.ldt"
                              : "https://example.org/eulumdat.ldt";
        EXPECT_NE(m.find("is only a URL (" + url + "), not in the container"), std::string::npos)
            << m;
    }
}

TEST(Gldf, LargeMembersAreListedNotRead) {
    GldfProduct p = loadGldf(container("GldfWithLargeFiles"));
    EXPECT_EQ(p.members, (std::vector<std::string>{"doc/4MbTextFile.txt", "doc/5MbTextFile.txt",
                                                   "product.xml"}));
}

TEST(Gldf, MetaInformationOnlyVariantHasNoEmitter) {
    GldfProduct p = loadGldf(container("GldfWithMetaInfo"));
    EXPECT_EQ(p.productName, "Product name");
    std::string m = refusal([] { photometryOf(container("GldfWithMetaInfo")); });
    EXPECT_NE(m.find("variant \"variant-1\" places no emitter"), std::string::npos) << m;
    EXPECT_NE(m.find("the product defines no light emitter"), std::string::npos) << m;
}

TEST(Gldf, AnEmptyGeometryPlacesTheOnlyEmitter) {
    // RZB's FLAT POLYMERO KREIS writes <Geometry/> although the product has one light emitter:
    // it is placed, with a warning; with two light emitters which one is unknown, and refused.
    TempDir tmp;
    std::string one = tmp.file("one.gldf"), two = tmp.file("two.gldf");
    std::string xml = replaced(
        productXml(), "<Geometry><EmitterReference emitterId=\"e1\"/></Geometry>", "<Geometry/>");
    writeZip(one, {{"product.xml", xml}, {"ldc/lamp.ldt", realLdt()}});
    GldfPhotometry placed = photometryOf(one);
    EXPECT_EQ(placed.data.fluxFromTable(),
              photometryOf(container("GldfWithFilesComplete")).data.fluxFromTable());
    bool warned = false;
    for (const std::string& w : placed.data.warnings)
        warned |= w.find("placing the product's only light emitter, \"e1\"") != std::string::npos;
    EXPECT_TRUE(warned);
    std::string second = replaced(xml, "</Emitters>",
                                  "<Emitter id=\"e2\"><FixedLightEmitter><PhotometryReference "
                                  "photometryId=\"p1\"/></FixedLightEmitter></Emitter></Emitters>");
    writeZip(two, {{"product.xml", second}, {"ldc/lamp.ldt", realLdt()}});
    std::string m = refusal([&] { photometryOf(two); });
    EXPECT_NE(m.find("the product has 2 light emitters"), std::string::npos) << m;
}

TEST(Gldf, EveryTestContainerPlacesItsEmbeddedPhotometryOrSaysWhatIsWrong) {
    // Each container of the format's reference tests: every variant whose photometry is a
    // member of the container is placed; any other is refused with a one-line message naming
    // the container and a defect the test knows the container to have.
    const std::vector<std::pair<std::string, std::string>> defects = {
        {"GldfWithCodepage850", "not in the container (it holds"},
        {"GldfWithEncodingUtf8", "not in the container (it holds"},
        {"GldfWithFiles", "no <ProductDefinitions>"},
        {"GldfWithFilesComplete", ""},
        {"GldfWithHeaderMandatory", "only a URL"},
        {"GldfWithInvalidRoot", "only a URL"},
        {"GldfWithLargeFiles", "only a URL"},
        {"GldfWithMetaInfo", "defines no light emitter"},
        {"GldfWithMissingFiles", "not in the container"},
        {"GldfWithMissingProduct", "product.xml: missing"},
        {"GldfWithNoFiles", "only a URL"},
        {"GldfWithOrphanedFiles", "0 bytes, not a EULUMDAT file"},
    };
    size_t seen = 0;
    for (const auto& entry : fs::directory_iterator(kData + "/gldf")) {
        // The reference library's containers (the others here are this project's own).
        if (entry.path().extension() != ".gldf" ||
            entry.path().stem().string().rfind("GldfWith", 0) != 0)
            continue;
        ++seen;
        const std::string name = entry.path().stem().string(), path = entry.path().string();
        auto known = std::find_if(defects.begin(), defects.end(),
                                  [&name](const auto& d) { return d.first == name; });
        ASSERT_NE(known, defects.end()) << name << ": a container the test does not know";
        std::string message;
        try {
            std::string bytes = readGldfBytes(path);
            GldfProduct product = parseGldf(bytes, path);
            for (const GldfVariant& v : product.variants)
                for (size_t k = 0; k < std::max<size_t>(v.emitters.size(), 1); ++k)
                    gldfVariantPhotometry(bytes, product, v, defaultPhotometryOptions(), k);
        } catch (const InputError& e) {
            message = e.what();
        }
        if (known->second.empty()) {
            EXPECT_EQ(message, "") << name;
        } else {
            EXPECT_NE(message.find(path), std::string::npos) << message;
            EXPECT_NE(message.find(known->second), std::string::npos) << message;
        }
    }
    EXPECT_EQ(seen, defects.size());
}

TEST(Gldf, MissingMember) {
    std::string m = refusal([] { photometryOf(container("GldfWithMissingFiles")); });
    EXPECT_EQ(m, container("GldfWithMissingFiles") +
                     ": ldc/file.ldt (file \"eulumdat\", referenced by emitter \"emitter\"): not "
                     "in the container; the container is incomplete: ask the manufacturer for a "
                     "corrected one");
}

TEST(Gldf, EmptyPlaceholderMember) {
    std::string m = refusal([] { photometryOf(container("GldfWithOrphanedFiles")); });
    EXPECT_NE(m.find(": ldc/file.ldt (file \"eulumdat\", referenced by emitter \"emitter\"): 0 "
                     "bytes, not a EULUMDAT file: "),
              std::string::npos)
        << m;
}

TEST(Gldf, CodePage850AndUtf8MemberNamesReadAlike) {
    // Both hold ldc/Äöü°§.ldt (one in code page 850, one flagged UTF-8) while product.xml names
    // Äöü.ldt: the message shows what the folder holds, decoded the same way from both.
    for (const char* name : {"GldfWithCodepage850", "GldfWithEncodingUtf8"}) {
        GldfProduct p = loadGldf(container(name));
        EXPECT_EQ(p.manufacturer, "Manufacturer XY") << name;
        ASSERT_EQ(p.members.size(), 2u) << name;
        EXPECT_NE(
            std::find(p.members.begin(), p.members.end(), "ldc/\u00c4\u00f6\u00fc\u00b0\u00a7.ldt"),
            p.members.end())
            << name;
        std::string m = refusal([&] { photometryOf(container(name)); });
        EXPECT_NE(
            m.find(": ldc/\u00c4\u00f6\u00fc.ldt (file \"eulumdatFile\", referenced by emitter "
                   "\"emitter\"): not in the container (it holds "
                   "ldc/\u00c4\u00f6\u00fc\u00b0\u00a7.ldt)"),
            std::string::npos)
            << m;
    }
}

// --- Containers written here -------------------------------------------------------------------

TEST(Gldf, WrittenContainerLoads) {
    TempDir tmp;
    std::string path = tmp.file("lamp.gldf");
    writeZip(path, {{"product.xml", productXml()}, {"ldc/lamp.ldt", realLdt()}});
    GldfProduct p = loadGldf(path);
    EXPECT_EQ(p.productName, "Spot");  // English preferred over the first Locale
    ASSERT_EQ(p.emitters.size(), 1u);
    const GldfLightEmitter& light = p.emitters[0].lights.at(0);
    EXPECT_TRUE(light.fixed);
    EXPECT_EQ(light.ratedFlux, 2000.0);
    EXPECT_EQ(light.ratedPower, 20.0);
    ASSERT_EQ(light.maintenance.size(), 1u);
    EXPECT_EQ(light.maintenance[0].what, "LED maintenance after 50000 h");
    EXPECT_EQ(light.maintenance[0].factor, 0.8);
    GldfPhotometry photometry = photometryOf(path);
    EXPECT_EQ(photometry.data.format, "EULUMDAT");
}

TEST(Gldf, PhotometryOnlyAsUrl) {
    TempDir tmp;
    std::string path = tmp.file("lamp.gldf");
    writeZip(path, {{"product.xml", replaced(productXml(), R"(type="localFileName">lamp.ldt)",
                                             R"(type="url">https://example.com/lamp.ldt)")}});
    EXPECT_EQ(refusal([&] { photometryOf(path); }),
              path +
                  ": photometry file \"f1\" is only a URL (https://example.com/lamp.ldt), not "
                  "in the container: download it and place it as a photometric luminaire, or "
                  "ask the manufacturer for a container that holds it");
}

TEST(Gldf, PhotometryFileIdMissingFromFiles) {
    TempDir tmp;
    std::string path = tmp.file("lamp.gldf");
    writeZip(path,
             {{"product.xml", replaced(productXml(), R"(<PhotometryFileReference fileId="f1"/>)",
                                       R"(<PhotometryFileReference fileId="f2"/>)")},
              {"ldc/lamp.ldt", realLdt()}});
    EXPECT_EQ(refusal([&] { loadGldf(path); }),
              path +
                  ": product.xml: photometry \"p1\" refers to file \"f2\", which <Files> does "
                  "not list");
}

TEST(Gldf, EmitterReferencesUnknownPhotometryAndVariantUnknownEmitter) {
    TempDir tmp;
    std::string path = tmp.file("lamp.gldf");
    writeZip(path, {{"product.xml",
                     replaced(productXml(), R"(photometryId="p1")", R"(photometryId="p9")")}});
    EXPECT_EQ(refusal([&] { loadGldf(path); }),
              path +
                  ": product.xml: emitter \"e1\" refers to photometry \"p9\", which "
                  "<Photometries> does not define");
    writeZip(path,
             {{"product.xml", replaced(productXml(), R"(emitterId="e1")", R"(emitterId="e7")")}});
    EXPECT_EQ(refusal([&] { loadGldf(path); }),
              path +
                  ": product.xml: variant \"v1\" refers to emitter \"e7\", which <Emitters> "
                  "does not define");
}

TEST(Gldf, DamagedMember) {
    TempDir tmp;
    std::string path = tmp.file("lamp.gldf");
    std::string ldt = realLdt();
    writeZip(path, {{"product.xml", productXml()}, {"ldc/lamp.ldt", ldt, false, true}});
    // Stored uncompressed: change a byte of its data in place, so its CRC no longer matches.
    std::string bytes = readBytes(path);
    size_t at = bytes.find(ldt.substr(0, 40));
    ASSERT_NE(at, std::string::npos);
    bytes[at + 20] = bytes[at + 20] == '7' ? '8' : '7';
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
    std::string m = refusal([&] { photometryOf(path); });
    EXPECT_EQ(m, path +
                     ": ldc/lamp.ldt (file \"f1\", referenced by emitter \"e1\"): damaged (CRC "
                     "error)");
}

TEST(Gldf, TruncatedMember) {
    TempDir tmp;
    std::string path = tmp.file("lamp.gldf");
    std::string ldt = realLdt();
    writeZip(path, {{"product.xml", productXml()}, {"ldc/lamp.ldt", ldt}});
    // The central directory's uncompressed size of ldc/lamp.ldt raised by 100 bytes: its
    // compressed data ends before that many bytes come out.
    std::string bytes = readBytes(path);
    size_t entry = bytes.rfind(std::string("PK\x01\x02", 4));
    ASSERT_NE(entry, std::string::npos);
    ASSERT_EQ(bytes.compare(entry + 46, 12, "ldc/lamp.ldt"), 0);
    uint32_t size = 0;
    for (int i = 3; i >= 0; --i) size = size << 8 | uint8_t(bytes[entry + 24 + size_t(i)]);
    ASSERT_EQ(size, ldt.size());
    size += 100;
    for (int i = 0; i < 4; ++i) bytes[entry + 24 + size_t(i)] = char(size >> (8 * i));
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
    EXPECT_EQ(refusal([&] { photometryOf(path); }),
              path + ": ldc/lamp.ldt (file \"f1\", referenced by emitter \"e1\"): truncated (" +
                  std::to_string(ldt.size()) + " bytes of the " + std::to_string(size) +
                  " its entry declares)");
}

TEST(Gldf, TruncatedContainer) {
    TempDir tmp;
    std::string path = tmp.file("lamp.gldf");
    writeZip(path, {{"product.xml", productXml()}, {"ldc/lamp.ldt", realLdt()}});
    std::string bytes = readBytes(path);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes.substr(0, bytes.size() / 2);
    std::string m = refusal([&] { loadGldf(path); });
    EXPECT_EQ(m.rfind(path + ": not a GLDF container (a ZIP archive): ", 0), 0u) << m;
}

TEST(Gldf, OversizedMemberIsRefusedUnread) {
    TempDir tmp;
    std::string path = tmp.file("lamp.gldf");
    // 65 MB of spaces deflate to about 64 kB; the reader must refuse it from its size field.
    writeZip(path, {{"product.xml", productXml()},
                    {"ldc/lamp.ldt", std::string(size_t(kMaxGldfMember) + (1 << 20), ' ')}});
    std::string m = refusal([&] { photometryOf(path); });
    EXPECT_EQ(m, path +
                     ": ldc/lamp.ldt (file \"f1\", referenced by emitter \"e1\"): 65.0 MB "
                     "uncompressed, more than the 64.0 MB a member may hold");
}

TEST(Gldf, IesPhotometryInside) {
    TempDir tmp;
    std::string path = tmp.file("lamp.gldf");
    std::string iesPath = kData + "/photometry/ies/lidrs/iesna2002_example_typec.ies";
    std::string xml =
        replaced(productXml(), R"(contentType="ldc/eulumdat" type="localFileName">lamp.ldt)",
                 R"(contentType="ldc/ies" type="localFileName">lamp.ies)");
    writeZip(path, {{"product.xml", xml}, {"ldc/lamp.ies", readBytes(iesPath)}});
    GldfPhotometry inside = photometryOf(path);
    PhotometricData alone = loadPhotometry(iesPath);
    EXPECT_EQ(inside.data.format, alone.format);
    // The same bytes through the same parser: the same table exactly.
    EXPECT_EQ(inside.data.candela, alone.candela);
    EXPECT_EQ(inside.data.fluxFromTable(), alone.fluxFromTable());
}

// GLDF's content type ldc/iesxml is IES TM-33: read by the TM-33 reader, and a member that is not
// TM-33 is refused naming the container, the member and what the reader expected.
TEST(Gldf, Tm33PhotometryInside) {
    TempDir tmp;
    std::string path = tmp.file("lamp.gldf");
    std::string tm33Path = kData + "/tm33/cosine_downlight_tm33-18.xml";
    std::string xml =
        replaced(productXml(), R"(contentType="ldc/eulumdat" type="localFileName">lamp.ldt)",
                 R"(contentType="ldc/iesxml" type="localFileName">lamp.xml)");
    writeZip(path, {{"product.xml", xml}, {"ldc/lamp.xml", readBytes(tm33Path)}});
    GldfPhotometry inside = photometryOf(path);
    PhotometricData alone = loadPhotometry(tm33Path);
    EXPECT_EQ(inside.data.format, "IES TM-33-18");
    EXPECT_EQ(inside.data.candela, alone.candela);  // the same bytes through the same parser
    EXPECT_EQ(inside.data.fluxFromTable(), alone.fluxFromTable());

    writeZip(path, {{"product.xml", xml}, {"ldc/lamp.xml", "<Root/>"}});
    std::string m = refusal([&] { photometryOf(path); });
    EXPECT_NE(m.find(": ldc/lamp.xml (file \"f1\", referenced by emitter \"e1\"): 7 bytes, not "
                     "an IES TM-33 file: "),
              std::string::npos)
        << m;
    EXPECT_NE(m.find("expected a TM-33 document (root element <IESTM33> or <IESTM33-22>), found "
                     "<Root>"),
              std::string::npos)
        << m;
}

TEST(Gldf, IesBytesLabelledEulumdatAreRefusedWithTheParsersMessage) {
    TempDir tmp;
    std::string path = tmp.file("lamp.gldf");
    writeZip(path, {{"product.xml", productXml()}, {"ldc/lamp.ldt", "hello"}});
    std::string m = refusal([&] { photometryOf(path); });
    std::string head = path +
                       ": ldc/lamp.ldt (file \"f1\", referenced by emitter \"e1\"): 5 "
                       "bytes, not a EULUMDAT file: " +
                       path + ":ldc/lamp.ldt:";
    EXPECT_EQ(m.rfind(head, 0), 0u) << m;
}

TEST(Gldf, TwoEmitterVariantNeedsItsGeometry) {
    TempDir tmp;
    std::string path = tmp.file("lamp.gldf");
    std::string xml = replaced(productXml(), R"(<EmitterReference emitterId="e1"/>)",
                               R"(<ModelGeometryReference geometryId="g1">
          <EmitterReference emitterId="e1"><EmitterObjectExternalName>a</EmitterObjectExternalName></EmitterReference>
          <EmitterReference emitterId="e1"><EmitterObjectExternalName>b</EmitterObjectExternalName></EmitterReference>
        </ModelGeometryReference>)");
    // Without the model geometry it names, the product is refused as it is read.
    writeZip(path, {{"product.xml", xml}, {"ldc/lamp.ldt", realLdt()}});
    EXPECT_EQ(refusal([&] { loadGldf(path); }),
              path +
                  ": product.xml: variant \"v1\" refers to model geometry \"g1\", which "
                  "<Geometries> does not define");
    xml = replaced(xml, "</Emitters>", R"(</Emitters>
    <Geometries><ModelGeometry id="g1"><GeometryFileReference fileId="geo"/></ModelGeometry></Geometries>)");
    xml = replaced(
        xml, "</Files>",
        R"(<File id="geo" contentType="geo/l3d" type="localFileName">lamp.l3d</File></Files>)");
    writeZip(path, {{"product.xml", xml}, {"ldc/lamp.ldt", realLdt()}});
    GldfProduct product = loadGldf(path);
    EXPECT_EQ(product.variants[0].emitters.size(), 2u);
    EXPECT_EQ(product.variants[0].emitterObjects, (std::vector<std::string>{"a", "b"}));
    EXPECT_EQ(product.variants[0].modelGeometryId, "g1");
    // Its placements name objects of an L3D member the container lacks.
    EXPECT_EQ(refusal([&] { photometryOf(path); }),
              path +
                  ": geo/lamp.l3d (file \"geo\", model geometry \"g1\"): not in the container; "
                  "the container is incomplete: ask the manufacturer for a corrected one");
    // And from a scene entry, naming the container and the member.
    std::string scene = tmp.file("scene.json");
    std::ofstream(scene) << R"({"luminaires": [{"type": "gldf", "file": "lamp.gldf"}]})";
    std::string m = refusal([&] { loadScene(scene); });
    EXPECT_NE(m.find("lamp.gldf: geo/lamp.l3d (file \"geo\", model geometry \"g1\"): not in the "
                     "container"),
              std::string::npos)
        << m;
}

TEST(Gldf, CodePage850MemberNameMatchesAndMessagesAreUtf8) {
    TempDir tmp;
    std::string path = tmp.file("lamp.gldf");
    // "ldc/Ä.ldt" written in code page 850 (Ä = 0x8E), named in UTF-8 by product.xml.
    std::string xml = replaced(productXml(), ">lamp.ldt<", ">\u00c4.ldt<");
    writeZip(path, {{"product.xml", xml}, {"ldc/\x8e.ldt", realLdt(), true}});
    EXPECT_EQ(photometryOf(path).data.format, "EULUMDAT");
    // Named otherwise, the message lists the member decoded: valid UTF-8, not the raw byte.
    writeZip(path, {{"product.xml", xml}, {"ldc/\x8e\xf5.ldt", realLdt(), true}});
    std::string m = refusal([&] { photometryOf(path); });
    EXPECT_NE(m.find("not in the container (it holds ldc/\u00c4\u00a7.ldt)"), std::string::npos)
        << m;
    // A container path that is not UTF-8 either still gives a UTF-8 message.
    std::string latin1 = tmp.file("l\xe4mp.gldf");
    writeZip(latin1, {{"product.xml", xml}});
    m = refusal([&] { photometryOf(latin1); });
    EXPECT_NE(m.find("l\u00e4mp.gldf: ldc/\u00c4.ldt"), std::string::npos) << m;
}

TEST(Gldf, MissingMemberNamesAtMostFiveOfItsFolder) {
    TempDir tmp;
    std::string path = tmp.file("lamp.gldf");
    std::vector<Member> members = {{"product.xml", productXml()}};
    for (int i = 0; i < 7; ++i) members.push_back({"ldc/other" + std::to_string(i) + ".ldt", "x"});
    writeZip(path, members);
    EXPECT_EQ(refusal([&] { photometryOf(path); }),
              path +
                  ": ldc/lamp.ldt (file \"f1\", referenced by emitter \"e1\"): not in the "
                  "container (it holds ldc/other0.ldt, ldc/other1.ldt, ldc/other2.ldt, "
                  "ldc/other3.ldt, ldc/other4.ldt and 2 more); the container is incomplete: ask "
                  "the manufacturer for a corrected one");
}

TEST(Gldf, ValueWithLineBreaksGivesOneLineMessage) {
    // Found by fuzzing: a value quoted from product.xml broke the message over two lines.
    TempDir tmp;
    std::string path = tmp.file("lamp.gldf");
    writeZip(path, {{"product.xml", replaced(productXml(), "<RatedInputPower>20<",
                                             "<RatedInputPower>twenty\n  watts<")}});
    EXPECT_EQ(refusal([&] { loadGldf(path); }),
              path +
                  ": product.xml: <RatedInputPower> of light source \"ls1\": expected a number, "
                  "found \"twenty   watts\"");
}

TEST(Gldf, NotAZipAndNotXml) {
    TempDir tmp;
    std::string path = tmp.file("lamp.gldf");
    std::ofstream(path) << "not a zip";
    EXPECT_EQ(refusal([&] { loadGldf(path); }).rfind(path + ": not a GLDF container", 0), 0u);
    writeZip(path, {{"product.xml", "<Root><Header>"}});
    std::string m = refusal([&] { loadGldf(path); });
    EXPECT_EQ(m.rfind(path + ": product.xml: not well-formed XML (", 0), 0u) << m;
    writeZip(path, {{"product.xml", "<Product/>"}});
    EXPECT_EQ(refusal([&] { loadGldf(path); }),
              path + ": product.xml: the root element is <Product>, expected <Root>");
    EXPECT_EQ(refusal([&] { loadGldf(tmp.file("none.gldf")); }),
              tmp.file("none.gldf") + ": cannot open GLDF file (No such file or directory)");
}

// --- Scene files -------------------------------------------------------------------------------

TEST(Gldf, SceneEntryLoadsRendersAsPhotometricAndRoundTrips) {
    TempDir tmp;
    fs::create_directories(tmp.file("lamps"));
    std::string lamp = tmp.file("lamps/lamp.gldf");
    std::string xml = replaced(productXml(), "</Variants>",
                               R"(<Variant id="v2"><Name><Locale language="en">V2</Locale></Name>
      <Geometry><EmitterReference emitterId="e1"/></Geometry></Variant></Variants>)");
    writeZip(lamp, {{"product.xml", xml}, {"ldc/lamp.ldt", realLdt()}});
    std::string scenePath = tmp.file("scene.json");
    std::ofstream(scenePath) << R"({"luminaires": [
        {"type": "gldf", "file": "lamps/lamp.gldf", "position": [0, 3, 0]},
        {"type": "gldf", "file": "lamps/lamp.gldf", "variant": "v2", "scale": 0.5,
         "technique": "point"}]})";
    Scene scene = loadScene(scenePath);
    ASSERT_EQ(scene.luminaires.size(), 2u);
    const Luminaire& firstLight = *scene.luminaires[0];
    const PhotometricLuminaire* first = photometricModel(firstLight);
    ASSERT_NE(first, nullptr);
    // Rendered by the photometric techniques.
    EXPECT_EQ(firstLight.kind(), LuminaireKind::Photometric);
    EXPECT_EQ(firstLight.technique, "adaptive");  // the photometric kind's default
    EXPECT_EQ(first->gldfVariant, "v1");          // the first variant when none is named
    ASSERT_NE(first->gldf, nullptr);
    EXPECT_EQ(first->gldf->manufacturer, "Acme");
    EXPECT_GT(firstLight.power().x, 0.0);
    EXPECT_EQ(sourceFiles(firstLight),
              std::vector<std::string>{(fs::path(tmp.file("")) / "lamps/lamp.gldf").string()});
    EXPECT_NE(describe(firstLight).find("GLDF lamps/lamp.gldf variant \"v1\" (Acme Spot)"),
              std::string::npos)
        << describe(firstLight);
    const Luminaire& secondLight = *scene.luminaires[1];
    const PhotometricLuminaire* second = photometricModel(secondLight);
    ASSERT_NE(second, nullptr);
    EXPECT_EQ(second->gldfVariant, "v2");
    EXPECT_EQ(secondLight.technique, "point");

    // Saved into another folder: the container path is rebased, the entry stays a "gldf" one.
    fs::create_directories(tmp.file("out"));
    std::string saved = tmp.file("out/saved.json");
    saveScene(scene, saved);
    nlohmann::json doc = nlohmann::json::parse(readBytes(saved));
    const nlohmann::json& entry = doc["luminaires"][1];
    EXPECT_EQ(entry["type"], "gldf");
    EXPECT_EQ(entry["file"], "../lamps/lamp.gldf");
    EXPECT_EQ(entry["variant"], "v2");
    EXPECT_EQ(entry["scale"], 0.5);
    Scene again = loadScene(saved);
    ASSERT_EQ(again.luminaires.size(), 2u);
    const Luminaire& reloadedLight = *again.luminaires[1];
    const PhotometricLuminaire* reloaded = photometricModel(reloadedLight);
    ASSERT_NE(reloaded, nullptr);
    EXPECT_EQ(reloaded->gldfVariant, "v2");
    EXPECT_EQ(reloaded->scale, 0.5);
    EXPECT_EQ(reloadedLight.pose.position, secondLight.pose.position);
    EXPECT_EQ(luminaireToJson(reloadedLight).dump(), [&] {
        nlohmann::json j = luminaireToJson(secondLight);
        j["file"] = "../lamps/lamp.gldf";
        return j.dump();
    }());
}

TEST(Gldf, SceneEntryErrorsNameTheEntry) {
    TempDir tmp;
    std::string lamp = tmp.file("lamp.gldf");
    writeZip(lamp, {{"product.xml", productXml()}, {"ldc/lamp.ldt", realLdt()}});
    std::string scenePath = tmp.file("scene.json");
    std::ofstream(scenePath)
        << R"({"luminaires": [{"type": "gldf", "file": "lamp.gldf", "variant": "v9"}]})";
    EXPECT_EQ(refusal([&] { loadScene(scenePath); }), lamp + ": no variant \"v9\" (it has v1)");
    std::ofstream(scenePath, std::ios::trunc)
        << R"({"luminaires": [{"type": "gldf", "file": "lamp.gldf", "technique": "analytic"}]})";
    std::string m = refusal([&] { loadScene(scenePath); });
    EXPECT_NE(m.find("unknown technique \"analytic\" for gldf"), std::string::npos) << m;
    std::ofstream(scenePath, std::ios::trunc)
        << R"({"luminaires": [{"type": "gldf", "file": "lamp.gldf", "bogus": 1}]})";
    m = refusal([&] { loadScene(scenePath); });
    EXPECT_NE(m.find("bogus"), std::string::npos) << m;
}

// The complete container's variant-2 places emitter-1 at its L3D geometry's object "LEO":
// structure.xml puts the part at (-0.006, 0.003, -0.041) m turned 90 degrees about z, and the
// object 0.003 m above the part's origin turned back -90 degrees: a 0.17 x 1.17 m rectangle, its x
// (sizeX) along the luminaire's x, at (-0.006, 0.003, -0.038) m, facing down (-z).
TEST(GldfGeometry, CompleteContainerVariantTakesItsOpeningFromTheL3dObject) {
    GldfPhotometry p = photometryOf(container("GldfWithFilesComplete"), "variant-2");
    ASSERT_NE(p.geometry, nullptr);
    EXPECT_EQ(p.geometry->path, container("GldfWithFilesComplete") + ":geo/geometry.l3d");
    ASSERT_EQ(p.geometry->parts.size(), 1u);
    EXPECT_EQ(p.geometry->parts[0].name, "Floodlight");
    EXPECT_EQ(p.geometry->triangleCount(), 92u);  // Floodlight.obj's 92 triangles ("f" lines)
    ASSERT_NE(p.opening, nullptr);
    EXPECT_EQ(p.opening->name, "LEO");
    const double eps = 1e-12;  // Sums and products of the file's decimals and of cos/sin 90.
    EXPECT_NEAR(p.opening->sizeX, 0.17, eps);
    EXPECT_NEAR(p.opening->sizeY, 1.17, eps);
    EXPECT_NEAR(glm::distance(p.opening->centre, glm::dvec3(-0.006, 0.003, -0.038)), 0.0, eps);
    EXPECT_NEAR(glm::distance(p.opening->x, glm::dvec3(1, 0, 0)), 0.0, eps);
    EXPECT_NEAR(glm::distance(p.opening->normal, glm::dvec3(0, 0, -1)), 0.0, eps);
    // variant-1 places the emitter with no geometry: the photometry's own opening.
    GldfPhotometry plain = photometryOf(container("GldfWithFilesComplete"), "variant-1");
    EXPECT_EQ(plain.geometry, nullptr);
    EXPECT_EQ(plain.opening, nullptr);
}

TEST(GldfGeometry, PlacedVariantEmitsFromTheObjectWhereTheProductHasIt) {
    TempDir tmp;
    std::string scenePath = tmp.file("scene.json");
    std::ofstream(scenePath) << R"({"luminaires": [{"type": "gldf", "file": ")" +
                                    container("GldfWithFilesComplete") +
                                    R"(", "variant": "variant-2", "position": [0, 3, 0],
        "aim": [0, -1, 0], "c0": [1, 0, 0]}]})";
    Scene scene = loadScene(scenePath);
    const Luminaire& light = *scene.luminaires.at(0);
    const PhotometricLuminaire* l = photometricModel(light);
    ASSERT_NE(l, nullptr);
    ASSERT_TRUE(l->placement.has_value());
    // By hand: the L3D frame at this pose has x = c0 = (1, 0, 0), y = C90 = c0 x aim = (0, 0, -1)
    // and z = -aim = (0, 1, 0), so the object's (-0.006, 0.003, -0.038) m is world
    // (0, 3, 0) + (-0.006, -0.038, -0.003) m.
    auto world = [](const glm::dvec3& v) { return glm::dvec3(v.x, v.z, -v.y); };
    Pose e = light.emitterPose();
    EXPECT_NEAR(glm::distance(e.position, glm::dvec3(-0.006, 2.962, -0.003)), 0.0, 1e-12);
    // The emitter's <Rotation> (X 1, Y 2, Z 3, G0 4 degrees) turns the object's frame (C0 +x,
    // aim -z): G0 about the aim, then Rz Rx Ry, here with glm's rotation matrices.
    const double deg = 3.14159265358979323846 / 180.0;
    glm::dmat4 r = glm::rotate(glm::dmat4(1.0), 3 * deg, glm::dvec3(0, 0, 1)) *
                   glm::rotate(glm::dmat4(1.0), 1 * deg, glm::dvec3(1, 0, 0)) *
                   glm::rotate(glm::dmat4(1.0), 2 * deg, glm::dvec3(0, 1, 0));
    glm::dvec3 aim = world(glm::dvec3(r * glm::dvec4(0, 0, -1, 0)));
    glm::dvec3 c0 = world(glm::dvec3(r * glm::dvec4(std::cos(4 * deg), std::sin(4 * deg), 0, 0)));
    EXPECT_NEAR(glm::distance(glm::normalize(e.aim), aim), 0.0, 1e-12);
    EXPECT_NEAR(glm::distance(glm::normalize(e.c0), c0), 0.0, 1e-12);
    EXPECT_EQ(light.pose.position, glm::dvec3(0, 3, 0));  // the insertion point stays the pose
    // The opening is the object's rectangle, not the EULUMDAT's, turned with the aim: its
    // sides are sizeX along C0 and sizeY along C90, in the plane across the aim.
    EXPECT_NEAR(l->area(), 0.17 * 1.17, 1e-12);
    std::vector<glm::dvec3> outline = light.outline();
    ASSERT_EQ(outline.size(), 4u);
    for (size_t k = 0; k < 4; ++k) {
        EXPECT_NEAR(glm::dot(outline[k] - e.position, aim), 0.0, 1e-12) << k;
        glm::dvec3 side = outline[(k + 1) % 4] - outline[k];
        double along = std::abs(glm::dot(side, c0));
        double across = std::abs(glm::dot(side, glm::cross(c0, aim)));
        bool lengthwise = std::abs(along - 0.17) < 1e-12 && across < 1e-12;
        bool crosswise = along < 1e-12 && std::abs(across - 1.17) < 1e-12;
        EXPECT_TRUE(lengthwise || crosswise) << k << ": " << along << " m, " << across << " m";
    }
    // Its flux is the photometry's: the geometry moves the light, it does not change it.
    std::string ldt = tmp.file("photometry.ldt");
    std::ofstream(ldt, std::ios::binary) << realLdt();
    PhotometricData alone = loadPhotometry(ldt);
    EXPECT_NEAR(light.power().x, alone.fluxFromTable(), 1e-9 * alone.fluxFromTable());
    EXPECT_NE(describe(light).find("opening from its L3D object \"LEO\""), std::string::npos)
        << describe(light);
}

TEST(GldfGeometry, PlacementNamingAnObjectTheGeometryLacksIsRefused) {
    TempDir tmp;
    std::string xml = memberOf(container("GldfWithFilesComplete"), "product.xml");
    std::string wrong =
        replaced(xml, "<EmitterObjectExternalName>LEO<", "<EmitterObjectExternalName>Nowhere<");
    std::string lamp = tmp.file("lamp.gldf");
    writeZip(lamp, {{"product.xml", wrong},
                    {"ldc/photometry.ldt", realLdt()},
                    {"geo/geometry.l3d",
                     memberOf(container("GldfWithFilesComplete"), "geo/geometry.l3d")}});
    std::string m = refusal([&] { photometryOf(lamp, "variant-2"); });
    EXPECT_NE(m.find("at object \"Nowhere\", which its geometry"), std::string::npos) << m;
    EXPECT_NE(m.find("geo/geometry.l3d does not hold (it has LEO)"), std::string::npos) << m;
    // A geometry member that is not an L3D archive names the member.
    writeZip(lamp, {{"product.xml", xml},
                    {"ldc/photometry.ldt", realLdt()},
                    {"geo/geometry.l3d", "not a zip"}});
    m = refusal([&] { photometryOf(lamp, "variant-2"); });
    EXPECT_NE(m.find("lamp.gldf:geo/geometry.l3d: not an L3D archive"), std::string::npos) << m;
}

/// example_004's L3D (two objects: leo_bottom emitting down, leo_top up) packed with libzip.
std::string pendantL3d() {
    TempDir tmp;
    std::string dir = kData + "/l3d/examples/example_004/";
    std::string path = tmp.file("pendant.l3d");
    writeZip(path, {{"structure.xml", readBytes(dir + "structure.xml")},
                    {"luminaire/luminaire.obj", readBytes(dir + "luminaire/luminaire.obj")}});
    return readBytes(path);
}

/// A product whose variant v1 places emitter e1 at leo_bottom and e2 at leo_top of the pendant.
std::string pendantProductXml() {
    std::string xml = replaced(productXml(), R"(<EmitterReference emitterId="e1"/>)",
                               R"(<ModelGeometryReference geometryId="g1">
          <EmitterReference emitterId="e1"><EmitterObjectExternalName>leo_bottom</EmitterObjectExternalName></EmitterReference>
          <EmitterReference emitterId="e2"><EmitterObjectExternalName>leo_top</EmitterObjectExternalName></EmitterReference>
        </ModelGeometryReference>)");
    xml = replaced(
        xml, "</Emitters>",
        R"(<Emitter id="e2"><FixedLightEmitter><PhotometryReference photometryId="p1"/></FixedLightEmitter></Emitter></Emitters>
    <Geometries><ModelGeometry id="g1"><GeometryFileReference fileId="geo"/></ModelGeometry></Geometries>)");
    return replaced(
        xml, "</Files>",
        R"(<File id="geo" contentType="geo/l3d" type="localFileName">pendant.l3d</File></Files>)");
}

TEST(GldfGeometry, SensorEmittersAreListedAndSkipped) {
    // The pendant's variant places a light at leo_bottom and a presence sensor at leo_top (SLV's
    // NEW TRIA 2 has such variants): the light alone is placed, where the product has it, with
    // a warning naming the sensor; a variant of sensors alone is refused with what to do.
    TempDir tmp;
    std::string both = tmp.file("both.gldf"), sensor = tmp.file("sensor.gldf");
    const std::string light =
        R"(<Emitter id="e2"><FixedLightEmitter><PhotometryReference photometryId="p1"/></FixedLightEmitter></Emitter>)";
    const std::string presence =
        R"(<Emitter id="e2"><SensorEmitter><SensorReference sensorId="x"/></SensorEmitter></Emitter>)";
    std::string xml = replaced(pendantProductXml(), light, presence);
    writeZip(
        both,
        {{"product.xml", xml}, {"ldc/lamp.ldt", realLdt()}, {"geo/pendant.l3d", pendantL3d()}});
    GldfProduct p = loadGldf(both);
    EXPECT_EQ(p.variants[0].emitters, std::vector<std::string>{"e1"});
    EXPECT_EQ(p.variants[0].emitterObjects, std::vector<std::string>{"leo_bottom"});
    EXPECT_EQ(p.variants[0].sensorEmitters, std::vector<std::string>{"e2"});
    GldfPhotometry placed = photometryOf(both);
    ASSERT_NE(placed.opening, nullptr);
    EXPECT_EQ(placed.opening->name, "leo_bottom");
    bool warned = false;
    for (const std::string& w : placed.data.warnings)
        warned |= w.find("sensor emitter \"e2\" skipped") != std::string::npos;
    EXPECT_TRUE(warned);
    // A variant that places only the sensor.
    std::string only = replaced(
        xml,
        R"(<EmitterReference emitterId="e1"><EmitterObjectExternalName>leo_bottom</EmitterObjectExternalName></EmitterReference>)",
        "");
    writeZip(
        sensor,
        {{"product.xml", only}, {"ldc/lamp.ldt", realLdt()}, {"geo/pendant.l3d", pendantL3d()}});
    std::string m = refusal([&] { photometryOf(sensor); });
    EXPECT_NE(m.find("has only sensor emitters (e2)"), std::string::npos) << m;
    EXPECT_NE(m.find("choose another variant"), std::string::npos) << m;
}

TEST(GldfGeometry, TwoObjectsEmitEachThroughItsOwnOpening) {
    TempDir tmp;
    writeZip(tmp.file("lamp.gldf"), {{"product.xml", pendantProductXml()},
                                     {"ldc/lamp.ldt", realLdt()},
                                     {"geo/pendant.l3d", pendantL3d()}});
    std::ofstream(tmp.file("lamp.ldt"), std::ios::binary) << realLdt();
    std::ofstream(tmp.file("pair.json"))
        << R"({"luminaires": [{"type": "gldf", "file": "lamp.gldf", "name": "pendant",
              "position": [0, 3, 0], "aim": [0, -1, 0], "c0": [1, 0, 0], "technique": "scattered"}]})";
    Scene pair = loadScene(tmp.file("pair.json"));
    ASSERT_EQ(pair.luminaires.size(), 2u);  // one per emitter the variant places
    const Luminaire& bottomLight = *pair.luminaires[0];
    const Luminaire& topLight = *pair.luminaires[1];
    const PhotometricLuminaire* bottom = photometricModel(bottomLight);
    const PhotometricLuminaire* top = photometricModel(topLight);
    ASSERT_TRUE(bottom && top);
    EXPECT_EQ(bottomLight.name, "pendant #0");
    EXPECT_EQ(topLight.name, "pendant #1");
    EXPECT_EQ(topLight.pose.position, bottomLight.pose.position);
    EXPECT_EQ(topLight.technique, "scattered");
    ASSERT_TRUE(bottom->placement && top->placement);
    EXPECT_EQ(bottom->placement->object, "leo_bottom");
    EXPECT_EQ(top->placement->object, "leo_top");
    // The container's product and L3D geometry are read once for the pair.
    EXPECT_EQ(bottom->gldf, top->gldf);
    EXPECT_EQ(bottom->geometry, top->geometry);

    // The same two openings placed by hand, each as a plain photometric luminaire. From
    // structure.xml: the part sits at z = -0.5 m; leo_bottom 0.0025 m above it turned -90 degrees
    // about z (its x along the luminaire's -y), 0.17 x 1.175 m, facing down; leo_top 0.0375 m
    // above it turned 180 degrees about x then 90 about z (its x along +y), 0.15 x 1 m, facing
    // up. At this pose the luminaire's x is world x, its y world -z (C90 = c0 x aim) and its z
    // world y, so: bottom centre (0, 2.5025, 0), aim down, C0 world +z; top centre
    // (0, 2.5375, 0), aim up, C0 world -z.
    std::ofstream(tmp.file("alone.json")) << R"({"luminaires": [
        {"type": "photometric", "file": "lamp.ldt", "position": [0, 2.5025, 0], "aim": [0, -1, 0],
         "c0": [0, 0, 1], "opening": [0.17, 1.175], "technique": "scattered"},
        {"type": "photometric", "file": "lamp.ldt", "position": [0, 2.5375, 0], "aim": [0, 1, 0],
         "c0": [0, 0, -1], "opening": [0.15, 1.0], "technique": "scattered"}]})";
    Scene alone = loadScene(tmp.file("alone.json"));
    const double eps = 1e-12;  // Sums and products of the file's decimals and cos/sin 90, 180.
    for (size_t k = 0; k < 2; ++k) {
        Pose want = alone.luminaires[k]->pose, got = pair.luminaires[k]->emitterPose();
        EXPECT_NEAR(glm::distance(got.position, want.position), 0.0, eps) << k;
        EXPECT_NEAR(glm::distance(glm::normalize(got.aim), want.aim), 0.0, eps) << k;
        EXPECT_NEAR(glm::distance(glm::normalize(got.c0), want.c0), 0.0, eps) << k;
    }
    EXPECT_NEAR(bottom->area(), 0.17 * 1.175, eps);
    EXPECT_NEAR(top->area(), 0.15 * 1.0, eps);

    // Light from both: below, the downward opening lights a floor; above, the upward one a
    // ceiling; at each receiver the pair gives what the two hand-placed openings give.
    std::vector<Receiver> receivers = {{{0.0, 0.8, 0.0}, {0, 1, 0}},
                                       {{0.7, 0.8, -0.3}, {0, 1, 0}},
                                       {{0.0, 4.2, 0.0}, {0, -1, 0}},
                                       {{-0.5, 4.2, 0.4}, {0, -1, 0}}};
    GridSpec how;
    ReceiverResult fromPair = computeReceivers(pair, how, receivers);
    ReceiverResult fromHand = computeReceivers(alone, how, receivers);
    for (size_t i = 0; i < receivers.size(); ++i) {
        EXPECT_GT(fromPair.E[i], 1.0) << i;  // lux: well lit
        // The same estimator on the same openings: equal to rounding of the poses (1e-15 m).
        EXPECT_NEAR(fromPair.E[i], fromHand.E[i], 1e-9 * fromHand.E[i]) << i;
    }
    // Each side is lit by its own opening: with only the top one, the floor gets nothing.
    alone.luminaires.erase(alone.luminaires.begin());
    ReceiverResult topAlone = computeReceivers(alone, how, receivers);
    EXPECT_EQ(topAlone.E[0], 0.0);
    EXPECT_NEAR(topAlone.E[2], fromPair.E[2], 1e-9 * fromPair.E[2]);

    // Saved, the pair is two entries naming their emitter; loaded again, still two.
    saveScene(pair, tmp.file("saved.json"));
    nlohmann::json doc = nlohmann::json::parse(readBytes(tmp.file("saved.json")));
    ASSERT_EQ(doc["luminaires"].size(), 2u);
    EXPECT_EQ(doc["luminaires"][0]["emitter"], 0);
    EXPECT_EQ(doc["luminaires"][1]["emitter"], 1);
    EXPECT_EQ(loadScene(tmp.file("saved.json")).luminaires.size(), 2u);
}

TEST(GldfGeometry, SeveralEmittersWithoutObjectsAreRefused) {
    TempDir tmp;
    std::string xml = replaced(
        pendantProductXml(), "<EmitterObjectExternalName>leo_top</EmitterObjectExternalName>", "");
    writeZip(
        tmp.file("lamp.gldf"),
        {{"product.xml", xml}, {"ldc/lamp.ldt", realLdt()}, {"geo/pendant.l3d", pendantL3d()}});
    EXPECT_NE(photometryOf(tmp.file("lamp.gldf")).opening, nullptr);  // emitter 0 is placed
    std::string m = refusal([&] {
        std::string bytes = readGldfBytes(tmp.file("lamp.gldf"));
        GldfProduct product = parseGldf(bytes, tmp.file("lamp.gldf"));
        gldfVariantPhotometry(bytes, product, product.variants[0], defaultPhotometryOptions(), 1);
    });
    EXPECT_NE(m.find("places 2 emitters (e1, e2) but does not say where emitter 1 is"),
              std::string::npos)
        << m;
}

// EN 12464-1's maintenance factor from the product's data, MF = LLMF x LSF x LMF x RSMF: the
// complete container's light source states LLMF 0.9 and LSF 0.91 at 125 h, 0.8 and 0.82 at 150 h.
TEST(GldfMaintenance, FactorFromTheLightSourceDataScalesEveryIlluminance) {
    TempDir tmp;
    auto scene = [&](const std::string& extra) {
        std::ofstream(tmp.file("scene.json"))
            << R"({"luminaires": [{"type": "gldf", "file": ")" +
                   container("GldfWithFilesComplete") +
                   R"(", "variant": "variant-1", "position": [0, 3, 0], "technique": "scattered")" +
                   extra + "}]}";
        return loadScene(tmp.file("scene.json"));
    };
    Scene initial = scene("");
    Scene maintained = scene(R"(, "maintenance": {"hours": 150, "lmf": 0.9, "rsmf": 0.95})");
    const double mf = 0.8 * 0.82 * 0.9 * 0.95;  // by hand from product.xml
    ASSERT_TRUE(maintained.luminaires[0]->maintenanceFactor.has_value());
    EXPECT_NEAR(*maintained.luminaires[0]->maintenanceFactor, mf, 1e-15);
    std::string d = describe(*maintained.luminaires[0]);
    EXPECT_NE(d.find("maintenance factor 0.5609 = LLMF 0.8 x LSF 0.82 (150 h) x LMF 0.9 x RSMF "
                     "0.95 (from the GLDF data)"),
              std::string::npos)
        << d;
    std::vector<Receiver> receivers = {{{0, 0, 0}, {0, 1, 0}}, {{1, 0, 0.5}, {0, 1, 0}}};
    GridSpec how;
    ReceiverResult a = computeReceivers(initial, how, receivers);
    ReceiverResult b = computeReceivers(maintained, how, receivers);
    for (size_t i = 0; i < receivers.size(); ++i) {
        ASSERT_GT(a.E[i], 0.0);
        EXPECT_NEAR(b.E[i], mf * a.E[i], 1e-12 * a.E[i]) << i;  // a product of doubles
    }
    EXPECT_NE(b.maintenance.find("maintained values"), std::string::npos) << b.maintenance;

    // Saved and loaded again: the same entry, the factor stated beside it.
    saveScene(maintained, tmp.file("saved.json"));
    nlohmann::json doc = nlohmann::json::parse(readBytes(tmp.file("saved.json")));
    EXPECT_EQ(doc["luminaires"][0]["maintenance"],
              nlohmann::json::parse(R"({"hours": 150, "lmf": 0.9, "rsmf": 0.95})"));
    EXPECT_EQ(*loadScene(tmp.file("saved.json")).luminaires[0]->maintenanceFactor,
              *maintained.luminaires[0]->maintenanceFactor);

    // What the data does not hold is refused, saying what it holds.
    std::string m = refusal([&] { scene(R"(, "maintenance": {"hours": 200, "lmf": 0.9})"); });
    EXPECT_NE(m.find("states no lumen maintenance factor at 200 h (it states them at 125 h, "
                     "150 h)"),
              std::string::npos)
        << m;
    m = refusal([&] { scene(R"(, "maintenance": {"hours": 150})"); });
    EXPECT_NE(m.find("\"lmf\", or \"years\" and \"room\""), std::string::npos) << m;
    m = refusal([&] { scene(R"(, "maintenance": {"hours": 150, "years": 3, "room": "Clean"})"); });
    EXPECT_NE(m.find("states no CIE luminaire maintenance factor for 3 years in a \"Clean\" room "
                     "(it states none: give \"lmf\")"),
              std::string::npos)
        << m;
    m = refusal([&] {
        scene(R"(, "maintenance": {"hours": 150, "lmf": 0.9}, "maintenance_factor": 0.5)");
    });
    EXPECT_NE(m.find("no maintenance_factor beside \"maintenance\""), std::string::npos) << m;
}

TEST(GldfMaintenance, LedFactorAndTheProductsLuminaireFactor) {
    TempDir tmp;
    // productXml's light source states an LED factor of 0.8 at 50000 h; the product here adds a
    // CIE luminaire maintenance factor of 0.85 after 3 years in a clean room.
    std::string xml = replaced(productXml(), "</ProductMetaData>",
                               R"(<LuminaireMaintenance><CieLuminaireMaintenanceFactors>
        <LuminaireMaintenanceFactor years="3" roomCondition="Clean">0.85</LuminaireMaintenanceFactor>
      </CieLuminaireMaintenanceFactors></LuminaireMaintenance></ProductMetaData>)");
    writeZip(tmp.file("lamp.gldf"), {{"product.xml", xml}, {"ldc/lamp.ldt", realLdt()}});
    auto load = [&](const std::string& maintenance) {
        std::ofstream(tmp.file("scene.json"))
            << R"({"luminaires": [{"type": "gldf", "file": "lamp.gldf", "maintenance": )" +
                   maintenance + "}]}";
        return loadScene(tmp.file("scene.json"));
    };
    Scene s = load(R"({"hours": 50000, "years": 3, "room": "Clean"})");
    EXPECT_NEAR(*s.luminaires[0]->maintenanceFactor, 0.8 * 0.85, 1e-15);
    std::string m = refusal([&] { load(R"({"hours": 50000, "years": 2, "room": "Clean"})"); });
    EXPECT_NE(m.find("for 2 years in a \"Clean\" room (it states 3 years (Clean); or give "
                     "\"lmf\")"),
              std::string::npos)
        << m;
}

}  // namespace
}  // namespace candela
