#pragma once
// L3D luminaire geometry (DIAL and Relux; schema in shared/formats/l3d, version 0.11): a ZIP
// archive (or, unpacked, a folder) holding structure.xml and one folder of Wavefront OBJ parts
// per geometry definition. structure.xml places the parts in a tree: each Geometry and Joint has a
// Position (metres) and a Rotation (degrees about its local axes, order Z, X, Y: R = Rz Rx Ry)
// relative to its parent; a Joint's DefaultRotation is the articulation the luminaire is shown
// in. LightEmittingObjects are the luminous openings a GLDF emitter refers to by name: a
// rectangle (sizeX along its local x, sizeY along y) or a circle in its local z = 0 plane,
// emitting towards its local -z (the example luminaires' bottom faces; the photometry's gamma = 0
// for an emitter not rotated). LightEmittingSurfaces tie OBJ faces (zero-based, in file order,
// within a group when groupIndex is given) to an object.
//
// Everything here is in the luminaire's own frame, the L3D one: right-handed, +z up, metres.
// placeLuminaireFrame() maps it into a photometric pose: x to C0, y to C90, -z to the aim.
//
// The OBJ parts are read with tinyobjloader; their polygons are triangulated as fans, keeping
// which face each triangle came from. Every defect is an InputError of one line naming the
// archive, the member and what is wrong. No GL here.

#include <functional>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

namespace candela {

/// Largest number of vertices read from one L3D (all parts together): the examples hold
/// thousands, manufacturers' models up to about a million.
constexpr size_t kMaxL3dVertices = size_t(4) << 20;
/// Largest number of triangles made from one L3D's faces (all parts together, a part that
/// shares another's OBJ counted again): real models hold up to about a million; 200 parts
/// sharing one OBJ of 7 million faces took 5.6 GB before this was counted.
constexpr size_t kMaxL3dTriangles = size_t(4) << 20;
/// Largest .l3d container read: the archive is read whole before it is unpacked.
constexpr uint64_t kMaxL3dContainer = uint64_t(256) << 20;

/// One Geometry element: its OBJ part placed in the luminaire frame.
struct L3dPart {
    std::string name;        ///< partName.
    std::string geometryId;  ///< The GeometryFileDefinition it shows.
    /// Part frame (the OBJ's coordinates, scaled to metres) to luminaire frame.
    glm::dmat4 toLuminaire{1.0};
    std::vector<glm::dvec3> positions;       ///< Luminaire frame, metres.
    std::vector<uint32_t> indices;           ///< Three per triangle, as the OBJ winds its faces.
    std::vector<uint32_t> triangleFace;      ///< Per triangle: its OBJ face's index in its group.
    std::vector<uint32_t> triangleGroup;     ///< Per triangle: its OBJ group ("g"/"o"), from 0.
    std::vector<uint32_t> triangleFileFace;  ///< Per triangle: its face's index in the file.
    size_t triangleCount() const { return indices.size() / 3; }
};

/// One LightEmittingObject: a luminous opening in the luminaire frame.
struct L3dEmitter {
    enum class Shape { Rectangle, Circle };
    std::string name;  ///< partName, what GLDF's EmitterObjectExternalName refers to.
    std::string part;  ///< The Geometry it belongs to.
    Shape shape = Shape::Rectangle;
    double sizeX = 0.0, sizeY = 0.0;    ///< Metres; a circle's diameter in both.
    glm::dvec3 centre{0.0};             ///< Luminaire frame, metres.
    glm::dvec3 x{1, 0, 0}, y{0, 1, 0};  ///< Unit: its local x (sizeX) and y axes.
    glm::dvec3 normal{0, 0, -1};        ///< Unit: the direction it emits towards (local -z).
    /// Its LightEmittingSurfaces' triangles: (part index, triangle index) pairs.
    std::vector<std::pair<size_t, size_t>> triangles;
    double area() const;  ///< m2.
};

struct L3dLuminaire {
    std::string path;  ///< The archive or folder, for messages.
    std::string name, description, createdWithApplication, formatVersion;
    std::vector<L3dPart> parts;
    std::vector<L3dEmitter> emitters;
    int joints = 0;  ///< Joints read (shown at their DefaultRotation).

    const L3dEmitter* emitter(const std::string& name) const;
    size_t triangleCount() const;
    /// Axis-aligned bounds of every part, luminaire frame, metres (zero for no vertices).
    void bounds(glm::dvec3& lo, glm::dvec3& hi) const;
};

/// Reads an .l3d archive's bytes; `path` names it in messages ("lamp.gldf:geo/a.l3d").
L3dLuminaire parseL3d(const std::string& bytes, const std::string& path);
/// Reads an .l3d archive, or a folder holding structure.xml and the parts' folders.
L3dLuminaire loadL3d(const std::string& path);

namespace l3d_detail {
/// Where an L3D's members come from: the member's bytes ("structure.xml", "ID/FILE.obj"), or
/// nullopt when there is none.
using MemberReader = std::function<std::optional<std::string>(const std::string& member)>;
/// Reads an L3D from its members; for parseL3d, loadL3d and the fuzz target, which serves
/// structure.xml and the OBJ text without a ZIP around them.
L3dLuminaire readMembers(const std::string& path, const MemberReader& read);
}  // namespace l3d_detail

/// The frame a luminous opening gives a photometric emitter, in the luminaire frame: the
/// opening's centre, C0 along its x, the aim along its normal.
struct L3dEmitterFrame {
    glm::dvec3 centre{0.0}, c0{1, 0, 0}, aim{0, 0, -1};
};
inline L3dEmitterFrame emitterFrame(const L3dEmitter& e) {
    return {e.centre, e.x, e.normal};
}

}  // namespace candela
