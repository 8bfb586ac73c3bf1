#include "formats/L3d.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <optional>
#include <pugixml.hpp>
#include <set>
#include <sstream>

#include "formats/Photometry.h"
#include "util/Error.h"
#include "util/FileInput.h"
#include "util/TextEncoding.h"
#include "util/ZipArchive.h"

namespace candela {

namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& message) {
    throw InputError(oneLine(message));
}

std::string inQuotes(const std::string& s) {
    return "\"" + s + "\"";
}

/// Metres per unit of a GeometryFileDefinition's `units` (the schema's list).
std::optional<double> metresPer(const std::string& units) {
    static const std::map<std::string, double> kUnits = {
        {"m", 1.0},     {"dm", 0.1},    {"cm", 0.01},   {"mm", 0.001},
        {"yd", 0.9144}, {"ft", 0.3048}, {"in", 0.0254},
    };
    auto it = kUnits.find(units);
    if (it == kUnits.end()) return std::nullopt;
    return it->second;
}

/// Largest position or size a structure.xml may give, metres (a luminaire is not a kilometre).
constexpr double kMaxL3dLength = 1e3;
/// Largest coordinate an OBJ part may hold, in its own units (a millimetre model of a kilometre).
constexpr double kMaxObjCoordinate = 1e6;

using l3d_detail::MemberReader;

class StructureReader {
  public:
    StructureReader(L3dLuminaire& out, MemberReader read) : mOut(out), mRead(std::move(read)) {}

    void read(const std::string& xml) {
        pugi::xml_document doc;
        pugi::xml_parse_result parsed =
            doc.load_buffer(xml.data(), xml.size(), pugi::parse_default, pugi::encoding_auto);
        if (!parsed)
            defect("not well-formed XML (" + std::string(parsed.description()) + " at byte " +
                   std::to_string(parsed.offset) + ")");
        pugi::xml_node root = doc.document_element();
        if (std::string(root.name()) != "Luminaire")
            defect("the root element is <" + toValidUtf8(root.name()) + ">, expected <Luminaire>");
        pugi::xml_node header = root.child("Header");
        mOut.name = text(header.child("Name"));
        mOut.description = text(header.child("Description"));
        mOut.createdWithApplication = text(header.child("CreatedWithApplication"));
        if (pugi::xml_node v = header.child("FormatVersion"))
            mOut.formatVersion = attribute(v, "major") + "." + attribute(v, "minor");
        for (pugi::xml_node g : root.child("GeometryDefinitions").children()) {
            std::string gid = attribute(g, "id");
            if (gid.empty()) defect("a <" + toValidUtf8(g.name()) + "> without its id");
            if (mDefinitions.count(gid))
                defect("two geometry definitions with the id " + inQuotes(gid));
            Definition& d = mDefinitions[gid];
            d.file = attribute(g, "filename");
            std::string units = attribute(g, "units");
            std::optional<double> scale = metresPer(units);
            if (!scale)
                defect("geometry " + inQuotes(gid) + ": units " + inQuotes(units) +
                       " (expected m, dm, cm, mm, yd, ft or in)");
            d.scale = *scale;
        }
        pugi::xml_node structure = root.child("Structure");
        if (!structure.child("Geometry")) defect("no <Geometry> in <Structure>");
        for (pugi::xml_node g : structure.children("Geometry")) geometry(g, glm::dmat4(1.0), 0);
        // Light-emitting surfaces may name objects of other parts: resolved once all are read.
        for (const PendingSurface& s : mSurfaces) surface(s);
        if (mOut.parts.empty()) defect("no geometry part");
    }

  private:
    struct Definition {
        std::string file;
        double scale = 1.0;  ///< Metres per OBJ unit.
        /// The OBJ read once (several parts may show one definition).
        std::optional<tinyobj::ObjReader> obj;
    };
    struct PendingSurface {
        pugi::xml_node node;
        size_t part;
    };

    [[noreturn]] void defect(const std::string& what) const {
        fail(mOut.path + ": structure.xml: " + what);
    }

    static std::string text(const pugi::xml_node& node) {
        std::string s = oneLine(node.text().get());
        size_t begin = s.find_first_not_of(' ');
        if (begin == std::string::npos) return "";
        return s.substr(begin, s.find_last_not_of(' ') - begin + 1);
    }
    static std::string attribute(const pugi::xml_node& node, const char* name) {
        return oneLine(node.attribute(name).value());
    }

    double number(const pugi::xml_node& node, const char* name, const std::string& owner, double lo,
                  double hi) const {
        pugi::xml_attribute a = node.attribute(name);
        std::string s = attribute(node, name);
        double v = 0.0;
        if (!a) defect(owner + ": no " + name + " attribute");
        if (!photometry_detail::parseNumber(s, v))
            defect(owner + ": " + name + ": expected a number, found " + inQuotes(s));
        if (!(v >= lo && v <= hi))
            defect(owner + ": " + name + " " + s + " is outside [" +
                   photometry_detail::formatNumber(lo) + ", " +
                   photometry_detail::formatNumber(hi) + "]");
        return v;
    }

    glm::dvec3 vector(const pugi::xml_node& node, const std::string& owner, double limit) const {
        return {number(node, "x", owner, -limit, limit), number(node, "y", owner, -limit, limit),
                number(node, "z", owner, -limit, limit)};
    }

    /// Rotation by the element's x, y, z degrees, order Z, X, Y (R = Rz Rx Ry, so a vector turns
    /// about y first); identity when the element is absent and `required` is false.
    glm::dmat4 rotation(const pugi::xml_node& node, const std::string& owner,
                        bool required = true) const {
        if (!node) {
            if (required) defect(owner + ": no <Rotation>");
            return glm::dmat4(1.0);
        }
        glm::dvec3 deg = vector(node, owner + " <" + node.name() + ">", 360.0 * 1e3);
        glm::dmat4 r(1.0);
        r = glm::rotate(r, glm::radians(deg.z), glm::dvec3(0, 0, 1));
        r = glm::rotate(r, glm::radians(deg.x), glm::dvec3(1, 0, 0));
        r = glm::rotate(r, glm::radians(deg.y), glm::dvec3(0, 1, 0));
        return r;
    }

    /// Position then rotation of a Geometry, Joint or LightEmittingObject: its frame in its
    /// parent's.
    glm::dmat4 local(const pugi::xml_node& node, const std::string& owner) const {
        pugi::xml_node p = node.child("Position");
        if (!p) defect(owner + ": no <Position>");
        glm::dmat4 t =
            glm::translate(glm::dmat4(1.0), vector(p, owner + " <Position>", kMaxL3dLength));
        return t * rotation(node.child("Rotation"), owner);
    }

    void geometry(const pugi::xml_node& g, const glm::dmat4& parent, int depth) {
        // Joints nest geometries; a deeper tree than any luminaire has is a defect, not a stack
        // overflow.
        if (depth > 64) defect("geometry parts nested more than 64 deep");
        std::string name = attribute(g, "partName");
        std::string owner = "part " + inQuotes(name);
        if (name.empty()) defect("a <Geometry> without its partName");
        if (!mNames.insert(name).second) defect("two parts named " + inQuotes(name));
        glm::dmat4 frame = parent * local(g, owner);
        std::string gid = attribute(g.child("GeometryReference"), "geometryId");
        auto def = mDefinitions.find(gid);
        if (def == mDefinitions.end())
            defect(owner + " refers to geometry " + inQuotes(gid) +
                   ", which <GeometryDefinitions> does not define");
        size_t index = mOut.parts.size();
        mOut.parts.push_back(part(name, gid, def->second, frame));
        for (pugi::xml_node leo : g.child("LightEmittingObjects").children("LightEmittingObject"))
            emitter(leo, name, frame);
        for (pugi::xml_node s : g.child("LightEmittingSurfaces").children("LightEmittingSurface"))
            mSurfaces.push_back({s, index});
        for (pugi::xml_node j : g.child("Joints").children("Joint")) {
            std::string jname = attribute(j, "partName");
            std::string jowner = "joint " + inQuotes(jname);
            if (!mNames.insert(jname).second) defect("two parts named " + inQuotes(jname));
            ++mOut.joints;
            glm::dmat4 jframe =
                frame * local(j, jowner) * rotation(j.child("DefaultRotation"), jowner, false);
            for (pugi::xml_node child : j.child("Geometries").children("Geometry"))
                geometry(child, jframe, depth + 1);
        }
    }

    void emitter(const pugi::xml_node& leo, const std::string& part, const glm::dmat4& parent) {
        L3dEmitter e;
        e.name = attribute(leo, "partName");
        e.part = part;
        std::string owner = "light-emitting object " + inQuotes(e.name);
        if (e.name.empty()) defect("a <LightEmittingObject> without its partName");
        if (!mNames.insert(e.name).second) defect("two parts named " + inQuotes(e.name));
        if (pugi::xml_node r = leo.child("Rectangle")) {
            e.sizeX = number(r, "sizeX", owner, 0.0, kMaxL3dLength);
            e.sizeY = number(r, "sizeY", owner, 0.0, kMaxL3dLength);
        } else if (pugi::xml_node c = leo.child("Circle")) {
            e.shape = L3dEmitter::Shape::Circle;
            e.sizeX = e.sizeY = number(c, "diameter", owner, 0.0, kMaxL3dLength);
        } else {
            defect(owner + ": neither <Rectangle> nor <Circle>");
        }
        glm::dmat4 m = parent * local(leo, owner);
        e.centre = glm::dvec3(m[3]);
        e.x = glm::normalize(glm::dvec3(m[0]));
        e.y = glm::normalize(glm::dvec3(m[1]));
        e.normal = -glm::normalize(glm::dvec3(m[2]));
        mOut.emitters.push_back(std::move(e));
    }

    void surface(const PendingSurface& s) {
        std::string name = attribute(s.node, "partName");
        std::string owner = "light-emitting surface " + inQuotes(name);
        const L3dPart& part = mOut.parts[s.part];
        for (pugi::xml_node ref : s.node.children("LightEmittingObjectReference")) {
            std::string target = attribute(ref, "lightEmittingPartName");
            auto it = std::find_if(mOut.emitters.begin(), mOut.emitters.end(),
                                   [&](const L3dEmitter& e) { return e.name == target; });
            if (it == mOut.emitters.end())
                defect(owner + " refers to light-emitting object " + inQuotes(target) +
                       ", which no part defines");
            pugi::xml_node assignments = s.node.child("FaceAssignments");
            for (pugi::xml_node a : assignments.children()) {
                std::string kind = a.name();
                bool single = kind == "FaceAssignment";
                if (!single && kind != "FaceRangeAssignment") continue;
                double limit =
                    double(part.triangleFileFace.empty() ? 0 : part.triangleFileFace.back());
                double begin =
                    number(a, single ? "faceIndex" : "faceIndexBegin", owner, 0.0, limit);
                double end = single ? begin : number(a, "faceIndexEnd", owner, begin, limit);
                bool grouped = a.attribute("groupIndex");
                double group = grouped ? number(a, "groupIndex", owner, 0.0, 1e9) : 0.0;
                for (size_t t = 0; t < part.triangleCount(); ++t) {
                    double face = grouped ? part.triangleFace[t] : part.triangleFileFace[t];
                    if ((!grouped || part.triangleGroup[t] == group) && face >= begin &&
                        face <= end)
                        it->triangles.emplace_back(s.part, t);
                }
            }
        }
    }

    L3dPart part(const std::string& name, const std::string& gid, Definition& def,
                 const glm::dmat4& frame) {
        std::string member = gid + "/" + def.file;
        if (!def.obj) {
            std::optional<std::string> text = mRead(member);
            if (!text)
                fail(mOut.path + ": " + member + ": missing (geometry " + inQuotes(gid) + ")");
            // The material library, when the folder holds the one the OBJ names.
            std::string mtl;
            std::istringstream lines(*text);
            for (std::string line; std::getline(lines, line);)
                if (line.rfind("mtllib ", 0) == 0) {
                    std::string lib = line.substr(7);
                    while (!lib.empty() && std::isspace(static_cast<unsigned char>(lib.back())))
                        lib.pop_back();
                    if (std::optional<std::string> m = mRead(gid + "/" + lib)) mtl = *m;
                    break;
                }
            // Every face makes a triangle at least: count them before the OBJ is parsed.
            size_t faces = 0;
            for (size_t at = 0; at < text->size();) {
                if (text->compare(at, 2, "f ") == 0 || text->compare(at, 2, "f\t") == 0) ++faces;
                size_t end = text->find('\n', at);
                if (end == std::string::npos) break;
                at = end + 1;
            }
            if (faces + mTriangles > kMaxL3dTriangles)
                fail(mOut.path + ": " + member + ": more than the " +
                     std::to_string(kMaxL3dTriangles) +
                     " triangles an L3D may hold here (all its parts together): " +
                     std::to_string(faces) + " faces");
            tinyobj::ObjReaderConfig config;
            config.triangulate = false;  // Fans below keep each triangle's face index.
            config.vertex_color = false;
            def.obj.emplace();
            if (!def.obj->ParseFromString(*text, mtl, config))
                fail(mOut.path + ": " + member + ": not a Wavefront OBJ file (" +
                     oneLine(def.obj->Error()) + ")");
        }
        const tinyobj::attrib_t& attrib = def.obj->GetAttrib();
        if (attrib.vertices.size() / 3 + mVertices > kMaxL3dVertices)
            fail(mOut.path + ": " + member + ": more than the " + std::to_string(kMaxL3dVertices) +
                 " vertices an L3D may hold here");
        mVertices += attrib.vertices.size() / 3;
        size_t triangles = 0;
        for (const tinyobj::shape_t& shape : def.obj->GetShapes())
            for (unsigned char n : shape.mesh.num_face_vertices) triangles += n > 2 ? n - 2 : 0;
        if (triangles + mTriangles > kMaxL3dTriangles)
            fail(mOut.path + ": " + member + ": more than the " + std::to_string(kMaxL3dTriangles) +
                 " triangles an L3D may hold here (all its parts together; part " + inQuotes(name) +
                 " would bring them to " + std::to_string(triangles + mTriangles) + ")");
        mTriangles += triangles;
        L3dPart p;
        p.name = name;
        p.geometryId = gid;
        p.toLuminaire = frame * glm::scale(glm::dmat4(1.0), glm::dvec3(def.scale));
        for (size_t i = 0; i + 2 < attrib.vertices.size(); i += 3) {
            glm::dvec3 v(attrib.vertices[i], attrib.vertices[i + 1], attrib.vertices[i + 2]);
            for (int k = 0; k < 3; ++k)
                if (!(std::abs(v[k]) <= kMaxObjCoordinate))
                    fail(mOut.path + ": " + member + ": vertex " + std::to_string(i / 3 + 1) +
                         " is not a finite coordinate within " +
                         photometry_detail::formatNumber(kMaxObjCoordinate));
            p.positions.push_back(glm::dvec3(p.toLuminaire * glm::dvec4(v, 1.0)));
        }
        uint32_t fileFace = 0;
        const auto& shapes = def.obj->GetShapes();
        for (size_t s = 0; s < shapes.size(); ++s) {
            const tinyobj::mesh_t& mesh = shapes[s].mesh;
            size_t offset = 0;
            for (size_t f = 0; f < mesh.num_face_vertices.size(); ++f, ++fileFace) {
                size_t n = mesh.num_face_vertices[f];
                if (offset + n > mesh.indices.size())
                    fail(mOut.path + ": " + member + ": face " + std::to_string(fileFace) +
                         " runs past the indices");
                for (size_t k = 1; k + 1 < n; ++k) {
                    for (size_t c : {size_t(0), k, k + 1}) {
                        int vi = mesh.indices[offset + c].vertex_index;
                        if (vi < 0 || size_t(vi) >= p.positions.size())
                            fail(mOut.path + ": " + member + ": face " + std::to_string(fileFace) +
                                 " names vertex " + std::to_string(vi + 1) + " of " +
                                 std::to_string(p.positions.size()));
                        p.indices.push_back(uint32_t(vi));
                    }
                    p.triangleFace.push_back(uint32_t(f));
                    p.triangleGroup.push_back(uint32_t(s));
                    p.triangleFileFace.push_back(fileFace);
                }
                offset += n;
            }
        }
        return p;
    }

    L3dLuminaire& mOut;
    MemberReader mRead;
    std::map<std::string, Definition> mDefinitions;
    std::set<std::string> mNames;
    std::vector<PendingSurface> mSurfaces;
    size_t mVertices = 0;
    size_t mTriangles = 0;  ///< Made so far, all parts together (kMaxL3dTriangles).
};

}  // namespace

L3dLuminaire l3d_detail::readMembers(const std::string& path, const MemberReader& read) {
    L3dLuminaire out;
    out.path = path;
    std::optional<std::string> xml = read("structure.xml");
    if (!xml) fail(path + ": structure.xml: missing");
    StructureReader(out, read).read(*xml);
    return out;
}

double L3dEmitter::area() const {
    return shape == Shape::Circle ? 0.25 * M_PI * sizeX * sizeX : sizeX * sizeY;
}

const L3dEmitter* L3dLuminaire::emitter(const std::string& n) const {
    for (const L3dEmitter& e : emitters)
        if (e.name == n) return &e;
    return nullptr;
}

size_t L3dLuminaire::triangleCount() const {
    size_t n = 0;
    for (const L3dPart& p : parts) n += p.triangleCount();
    return n;
}

void L3dLuminaire::bounds(glm::dvec3& lo, glm::dvec3& hi) const {
    lo = glm::dvec3(INFINITY);
    hi = glm::dvec3(-INFINITY);
    for (const L3dPart& p : parts)
        for (const glm::dvec3& v : p.positions) {
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
    if (lo.x > hi.x) lo = hi = glm::dvec3(0.0);
}

L3dLuminaire parseL3d(const std::string& bytes, const std::string& path) {
    ZipArchive archive(bytes, path, "an L3D archive");
    return l3d_detail::readMembers(path,
                                   [&](const std::string& member) -> std::optional<std::string> {
                                       int64_t index = archive.find(member);
                                       if (index < 0) return std::nullopt;
                                       return archive.read(index, member);
                                   });
}

L3dLuminaire loadL3d(const std::string& path) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) {
        return l3d_detail::readMembers(
            path, [&](const std::string& member) -> std::optional<std::string> {
                // Members are inside the folder, as inside an archive: a file name that climbs
                // out of it ("../x.obj", "/etc/x") names no member.
                fs::path relative(member);
                if (relative.is_absolute() ||
                    std::any_of(relative.begin(), relative.end(),
                                [](const fs::path& part) { return part == ".."; }))
                    return std::nullopt;
                fs::path file = fs::path(path) / relative;
                if (!fs::exists(file, ec)) return std::nullopt;
                return readInputFile(file.string(), "L3D member", kMaxZipMember);
            });
    }
    return parseL3d(readInputFile(path, "L3D", kMaxL3dContainer), path);
}

}  // namespace candela
