// L3D geometry (formats/L3d.h): the eight examples of the format's repository load, with the
// sizes their README states; every light-emitting object lies on the OBJ faces its
// LightEmittingSurfaces assign to it and faces the way they face (a check of the transform
// conventions that shares nothing with the reader: the faces' positions and windings come from
// the OBJ files, the object's frame from structure.xml); GLDF's complete container's geometry
// loads; defects are one-line errors naming the member.
#include "formats/L3d.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "formats/Gldf.h"
#include "tests/TempDir.h"
#include "util/Error.h"

namespace candela {
namespace {

namespace fs = std::filesystem;

const std::string kData = CANDELA_TEST_DATA;

std::string example(int n) {
    char name[32];
    std::snprintf(name, sizeof name, "/l3d/examples/example_%03d", n);
    return kData + name;
}

TEST(L3d, EveryExampleLoadsWithItsPartsAndOpenings) {
    // Geometry and LightEmittingObject elements of each structure.xml, counted by hand.
    const int parts[] = {1, 1, 5, 1, 1, 2, 9, 5};
    const int openings[] = {1, 1, 1, 1, 2, 1, 4, 2};
    for (int n = 0; n < 8; ++n) {
        SCOPED_TRACE(example(n));
        L3dLuminaire l = loadL3d(example(n));
        EXPECT_EQ(int(l.parts.size()), parts[n]);
        EXPECT_EQ(int(l.emitters.size()), openings[n]);
        EXPECT_GT(l.triangleCount(), 0u);
        for (const L3dEmitter& e : l.emitters) {
            EXPECT_GT(e.area(), 0.0) << e.name;
            EXPECT_FALSE(e.triangles.empty()) << e.name << " has no light-emitting surface";
        }
    }
}

TEST(L3d, UnitsScaleTheModelToMetres) {
    // example_000's README: a cube 0.5 m long, 0.25 m wide, 0.1 m high, its bottom face's centre
    // at the insertion point; the opening is that whole bottom face.
    L3dLuminaire cube = loadL3d(example(0));
    glm::dvec3 lo, hi;
    cube.bounds(lo, hi);
    // The OBJ's decimals in metres, read by tinyobjloader as float: 1e-8 m of rounding.
    const double eps = 1e-7;
    EXPECT_NEAR(hi.x - lo.x, 0.5, eps);
    EXPECT_NEAR(hi.y - lo.y, 0.25, eps);
    EXPECT_NEAR(hi.z - lo.z, 0.1, eps);
    EXPECT_NEAR(lo.z, 0.0, eps);
    // example_003 is in millimetres: a round luminaire whose opening is 0.2 m across.
    L3dLuminaire round = loadL3d(example(3));
    round.bounds(lo, hi);
    EXPECT_GT(hi.x - lo.x, 0.2);
    EXPECT_LT(hi.x - lo.x, 1.0);
    EXPECT_EQ(round.emitters[0].shape, L3dEmitter::Shape::Circle);
    EXPECT_NEAR(round.emitters[0].area(), M_PI * 0.01, 1e-12);
}

/// How each opening sits on its assigned faces: the distance from the opening's plane of the face
/// vertex nearest to it, where the faces' area-weighted centroid falls in the opening's frame,
/// and the cosine between the opening's normal and the faces' area-weighted normal (from their
/// winding, counter-clockwise seen from outside).
struct Fit {
    double nearest = 1e300;    ///< Metres.
    glm::dvec2 centroid{0.0};  ///< Metres, along the opening's x and y from its centre.
    double cosine = 0.0;
};

Fit fit(const L3dLuminaire& l, const L3dEmitter& e) {
    Fit f;
    glm::dvec3 n(0.0), centroid(0.0);
    double area = 0.0;
    for (auto [p, t] : e.triangles) {
        const L3dPart& part = l.parts[p];
        glm::dvec3 v[3];
        for (int k = 0; k < 3; ++k) v[k] = part.positions[part.indices[3 * t + k]];
        glm::dvec3 c = glm::cross(v[1] - v[0], v[2] - v[0]);
        n += c;
        area += 0.5 * glm::length(c);
        centroid += 0.5 * glm::length(c) * (v[0] + v[1] + v[2]) / 3.0;
        for (const glm::dvec3& q : v)
            f.nearest = std::min(f.nearest, std::abs(glm::dot(q - e.centre, e.normal)));
    }
    centroid = centroid / area - e.centre;
    f.centroid = {glm::dot(centroid, e.x), glm::dot(centroid, e.y)};
    f.cosine = glm::dot(glm::normalize(n), e.normal);
    return f;
}

TEST(L3d, EveryOpeningLiesOnItsFacesAndFacesTheirWay) {
    for (int n = 0; n < 8; ++n) {
        L3dLuminaire l = loadL3d(example(n));
        for (const L3dEmitter& e : l.emitters) {
            SCOPED_TRACE(example(n) + " " + e.name);
            Fit f = fit(l, e);
            // The opening's plane touches its surfaces: the examples' nearest vertices lie on it
            // to the OBJ's decimals (0.1 mm) except example_006's, 4.8 mm behind; 5 mm allows
            // that and nothing a wrong translation (centimetres to decimetres here) would give.
            // (The surfaces need not be flat: example_005's span 32 mm along the normal.)
            EXPECT_LT(f.nearest, 5e-3);
            // The surfaces are under the opening: their centroid falls inside its outline.
            if (e.shape == L3dEmitter::Shape::Circle)
                EXPECT_LE(glm::length(f.centroid), 0.5 * e.sizeX);
            else
                EXPECT_TRUE(std::abs(f.centroid.x) <= 0.5 * e.sizeX &&
                            std::abs(f.centroid.y) <= 0.5 * e.sizeY)
                    << f.centroid.x << ", " << f.centroid.y;
            // They face the way it emits. A wrong rotation order turns example_002's (90, 0, 180)
            // opening to face the other way (cosine -1).
            EXPECT_GT(f.cosine, 0.999);
        }
    }
}

/// A copy of example_000 in a temporary folder with structure.xml's `from` replaced by `to`.
std::string brokenCube(const test::TempDir& dir, const std::string& from, const std::string& to) {
    fs::copy(example(0), dir.path(), fs::copy_options::recursive);
    fs::permissions(dir / "structure.xml", fs::perms::owner_write, fs::perm_options::add);
    std::string xml;
    {
        std::ifstream in(dir / "structure.xml");
        xml.assign(std::istreambuf_iterator<char>(in), {});
    }
    size_t at = xml.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) xml.replace(at, from.size(), to);
    std::ofstream(dir / "structure.xml") << xml;
    return dir.path().string();
}

std::string refusal(const std::string& path) {
    try {
        loadL3d(path);
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        return e.what();
    }
    ADD_FAILURE() << "no InputError for " << path;
    return "";
}

TEST(L3d, TrianglesAreCountedOverEveryPartThatSharesAnObj) {
    // 1100 parts share one OBJ of 4000 triangles: 4.4 million triangles, over kMaxL3dTriangles,
    // although the OBJ is parsed once (a small L3D that shares a large OBJ among its parts took
    // gigabytes). Refused at the part that would pass the limit, naming it.
    test::TempDir dir;
    fs::create_directories(dir / "g");
    {
        std::ofstream obj(dir / "g" / "fan.obj");
        obj << "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
        for (int i = 0; i < 4000; ++i) obj << "f 1 2 3\n";
    }
    std::string xml =
        "<Luminaire><GeometryDefinitions><GeometryFileDefinition id=\"g\" filename=\"fan.obj\" "
        "units=\"m\"/></GeometryDefinitions><Structure>";
    for (int i = 0; i < 1100; ++i)
        xml += "<Geometry partName=\"p" + std::to_string(i) +
               "\"><Position x=\"0\" y=\"0\" z=\"0\"/><Rotation x=\"0\" y=\"0\" z=\"0\"/>"
               "<GeometryReference geometryId=\"g\"/></Geometry>";
    std::ofstream(dir / "structure.xml") << xml + "</Structure></Luminaire>";
    std::string m = refusal(dir.path().string());
    EXPECT_NE(m.find("g/fan.obj: more than the 4194304 triangles an L3D may hold here (all its "
                     "parts together; part \"p1048\" would bring them to 4196000)"),
              std::string::npos)
        << m;
    // One OBJ alone with more faces than that is refused before it is parsed.
    {
        std::ofstream obj(dir / "g" / "fan.obj");
        obj << "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
        for (int i = 0; i < 4200000; ++i) obj << "f 1 2 3\n";
    }
    m = refusal(dir.path().string());
    EXPECT_NE(m.find("g/fan.obj: more than the 4194304 triangles an L3D may hold here (all its "
                     "parts together): 4200000 faces"),
              std::string::npos)
        << m;
}

TEST(L3d, DefectsAreOneLineErrorsNamingTheMember) {
    struct Case {
        std::string from, to, message;
    } cases[] = {
        {"units=\"m\"", "units=\"furlong\"",
         "structure.xml: geometry \"cube\": units \"furlong\" (expected m, dm, cm, mm, yd, ft "
         "or in)"},
        {"filename=\"cube.obj\"", "filename=\"gone.obj\"",
         "cube/gone.obj: missing (geometry \"cube\")"},
        {"faceIndex=\"3\"", "faceIndex=\"12\"",
         "structure.xml: light-emitting surface \"les\": faceIndex 12 is outside [0, 5]"},  // cube.obj:
                                                                                            // 6
                                                                                            // quads
        {"lightEmittingPartName=\"leo\"", "lightEmittingPartName=\"nothing\"",
         "refers to light-emitting object \"nothing\", which no part defines"},
        {"<Rectangle sizeX=\"0.5\" sizeY=\"0.25\" />", "",
         "light-emitting object \"leo\": neither <Rectangle> nor <Circle>"},
        {"<Position x=\"0\" y=\"0\" z=\"0\" />", "<Position x=\"nan\" y=\"0\" z=\"0\" />",
         "part \"luminaire\" <Position>: x: expected a number, found \"nan\""},
        {"<Structure>",
         "<Structure><Geometry partName=\"luminaire\"><Position x=\"0\" y=\"0\" "
         "z=\"0\"/><Rotation x=\"0\" y=\"0\" z=\"0\"/><GeometryReference geometryId=\"cube\"/>"
         "</Geometry>",
         "two parts named \"luminaire\""},
        {"<Luminaire", "<Lamp", "not well-formed XML"},
        // A folder's members stay inside it, as an archive's do.
        {"filename=\"cube.obj\"", "filename=\"../cube/cube.obj\"",
         "cube/../cube/cube.obj: missing (geometry \"cube\")"},
    };
    for (const Case& c : cases) {
        test::TempDir dir;
        std::string path = brokenCube(dir, c.from, c.to);
        std::string m = refusal(path);
        EXPECT_EQ(m.rfind(path + ":", 0), 0u) << m;  // names the folder first
        EXPECT_NE(m.find(c.message), std::string::npos) << m;
    }
    test::TempDir empty;
    EXPECT_NE(refusal(empty.path().string()).find("structure.xml: missing"), std::string::npos);
    EXPECT_NE(
        refusal(empty.file("nothing.l3d")).find("cannot open L3D file (No such file or directory)"),
        std::string::npos);
    std::ofstream(empty / "structure.xml") << "";
    EXPECT_NE(refusal(empty.path().string()).find("structure.xml: not well-formed XML"),
              std::string::npos);
    std::ofstream(empty / "lamp.l3d") << "not a zip";
    EXPECT_NE(refusal(empty.file("lamp.l3d")).find("lamp.l3d: not an L3D archive"),
              std::string::npos);
}

}  // namespace
}  // namespace candela
