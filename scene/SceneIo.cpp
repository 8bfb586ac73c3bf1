#include "scene/SceneIo.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <vector>

#include "luminaires/Registry.h"
#include "luminaires/environment/Environment.h"
#include "scene/GltfLoader.h"
#include "scene/LayoutGrid.h"
#include "scene/Procedural.h"
#include "scene/RoomIo.h"
#include "shaders/shared/Constants.h"
#include "util/Activity.h"
#include "util/Error.h"
#include "util/FileInput.h"
#include "util/FileOutput.h"

namespace candela {

namespace fs = std::filesystem;

namespace {

/// A rotation about the vertical, degrees, within ten turns (json::kMaxAngleDeg).
const auto kAngle = json::range(-json::kMaxAngleDeg, json::kMaxAngleDeg, "an angle in degrees");

/// A maintenance factor (EN 12464-1): maintained over initial output, in (0, 1].
double maintenanceFactorValue(const nlohmann::json& v, const json::Where& where) {
    double x = json::number(v, where);
    if (!(x > 0.0 && x <= 1.0))
        json::fail(where, "a maintenance factor in (0, 1] (maintained over initial output), got " +
                              v.dump());
    return x;
}

nlohmann::json toJson(const glm::dvec3& v) {
    return nlohmann::json::array({v.x, v.y, v.z});
}
nlohmann::json toJson(const glm::dvec2& v) {
    return nlohmann::json::array({v.x, v.y});
}

std::string lowerExtension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

/// Whole file as bytes (util/FileInput.h: a regular file of at most kMaxSceneBytes); throws
/// InputError "PATH: cannot open scene file (reason)" and the like.
std::string readFile(const std::string& path) {
    return readInputFile(path, "scene", kMaxSceneBytes);
}

/// nlohmann reports a parse error at a 1-based byte count (the last byte it read). Converts it
/// to a 1-based line and column (in bytes) of that byte.
void lineAndColumn(const std::string& text, size_t byte, size_t& line, size_t& column) {
    size_t at = std::min(byte == 0 ? 0 : byte - 1, text.size());
    line = 1;
    size_t lineStart = 0;
    for (size_t i = 0; i < at; ++i) {
        if (text[i] == '\n') {
            ++line;
            lineStart = i + 1;
        }
    }
    column = at - lineStart + 1;
}

/// The reason part of a nlohmann parse error, without its "[json.exception...] parse error at
/// line L, column C: " prefix (we compute the position ourselves).
std::string parseErrorReason(const std::string& what) {
    size_t at = what.find("parse error");
    if (at != std::string::npos) {
        size_t colon = what.find(": ", at);
        if (colon != std::string::npos) return what.substr(colon + 2);
    }
    size_t bracket = what.find("] ");
    return bracket == std::string::npos ? what : what.substr(bracket + 2);
}

glm::dvec3 unitRgb(const nlohmann::json& v, const json::Where& where) {
    glm::dvec3 c = json::vec3(v, where);
    for (int i = 0; i < 3; ++i)
        if (c[i] < 0.0 || c[i] > 1.0) json::fail(where[i], "a value in [0, 1], got " + v.dump());
    return c;
}

double unitNumber(const nlohmann::json& v, const json::Where& where) {
    double x = json::number(v, where);
    if (x < 0.0 || x > 1.0) json::fail(where, "a value in [0, 1], got " + v.dump());
    return x;
}

glm::dvec2 positive2(const nlohmann::json& v, const json::Where& where) {
    glm::dvec2 s = json::vec2(v, where);
    for (int i = 0; i < 2; ++i)
        if (!(s[i] > 0.0 && s[i] <= json::kMaxMetres))
            json::fail(where[i], "a positive size in metres of at most " + json::maxMetresText() +
                                     ", got " + v.dump());
    return s;
}

glm::dvec3 positive3(const nlohmann::json& v, const json::Where& where) {
    glm::dvec3 s = json::vec3(v, where);
    for (int i = 0; i < 3; ++i)
        if (!(s[i] > 0.0 && s[i] <= json::kMaxMetres))
            json::fail(where[i], "a positive size in metres of at most " + json::maxMetresText() +
                                     ", got " + v.dump());
    return s;
}

/// Material of a procedural geometry entry (plane, disc, box); its name is the entry's "name" or
/// `fallbackName`.
uint32_t addItemMaterial(const nlohmann::json& item, const json::Where& where,
                         const std::string& fallbackName, Scene& scene) {
    Material material;
    material.name = json::optional(item, "name", where, fallbackName, json::string);
    material.albedo = glm::vec3(json::optional(item, "albedo", where, glm::dvec3(0.5), unitRgb));
    material.specular =
        glm::vec3(json::optional(item, "specular", where, glm::dvec3(0.0), unitRgb));
    material.roughness = float(json::optional(item, "roughness", where, 1.0, unitNumber));
    scene.materials.push_back(material);
    return uint32_t(scene.materials.size() - 1);
}

/// Plane tangents (see the convention in SceneIo.h); n must be unit length.
void planeTangents(const glm::dvec3& n, glm::dvec3& u, glm::dvec3& v) {
    glm::dvec3 c = glm::cross(glm::dvec3(0.0, 1.0, 0.0), n);
    u = glm::length(c) > 1e-3 ? glm::normalize(c) : glm::dvec3(1.0, 0.0, 0.0);
    u = glm::normalize(u - glm::dot(u, n) * n);
    v = glm::cross(n, u);
}

/// A mesh for a procedural geometry item: its material (from the item's fields), name and shape.
Mesh itemMesh(const nlohmann::json& item, const json::Where& where, const std::string& label,
              MeshShape shape, Scene& scene) {
    Mesh mesh;
    mesh.material = addItemMaterial(item, where, label, scene);
    mesh.name = scene.materials[mesh.material].name;
    mesh.shape = shape;
    return mesh;
}

void parsePlane(const nlohmann::json& item, const json::Where& where, size_t index, Scene& scene) {
    json::checkKeys(item, {"plane", "name", "albedo", "specular", "roughness"}, where);
    const json::Where at = where / "plane";
    const nlohmann::json& spec = item["plane"];
    json::checkKeys(spec, {"center", "normal", "size"}, at);
    glm::dvec3 center = json::optional(spec, "center", at, glm::dvec3(0.0), json::point);
    glm::dvec3 n = glm::normalize(
        json::optional(spec, "normal", at, glm::dvec3(0.0, 1.0, 0.0), json::direction));
    if (!spec.contains("size")) json::fail(at / "size", "[width, height] in metres (missing)");
    glm::dvec2 size = positive2(spec["size"], at / "size");

    Mesh mesh = itemMesh(item, where, "plane " + std::to_string(index), MeshShape::Plane, scene);
    glm::dvec3 u, v;
    planeTangents(n, u, v);
    glm::dvec3 hu = u * (0.5 * size.x), hv = v * (0.5 * size.y);
    // Counter-clockwise seen from the normal's side: (p1 - p0) x (p2 - p0) is along u x v = n.
    for (glm::dvec3 corner :
         {center - hu - hv, center + hu - hv, center + hu + hv, center - hu + hv}) {
        mesh.positions.push_back(glm::vec3(corner));
        mesh.normals.push_back(glm::vec3(n));
    }
    mesh.indices = {0, 1, 2, 0, 2, 3};
    mesh.computeBounds();
    scene.meshes.push_back(std::move(mesh));
}

/// {"disc": {"center", "normal", "radius", "segments"}}: a flat, two-sided disc as a regular
/// polygon (a fan of `segments` triangles, default 256) inscribed in the circle; its area is
/// (segments / 2) sin(2 pi / segments) r^2, 1e-4 below pi r^2 at the default.
void parseDisc(const nlohmann::json& item, const json::Where& where, size_t index, Scene& scene) {
    json::checkKeys(item, {"disc", "name", "albedo", "specular", "roughness"}, where);
    const json::Where at = where / "disc";
    const nlohmann::json& spec = item["disc"];
    json::checkKeys(spec, {"center", "normal", "radius", "segments"}, at);
    glm::dvec3 center = json::optional(spec, "center", at, glm::dvec3(0.0), json::point);
    glm::dvec3 n = glm::normalize(
        json::optional(spec, "normal", at, glm::dvec3(0.0, 1.0, 0.0), json::direction));
    if (!spec.contains("radius")) json::fail(at / "radius", "a radius in metres (missing)");
    double radius = json::length(spec["radius"], at / "radius");
    double segmentsValue = json::optional(spec, "segments", at, 256.0, json::positive);
    if (segmentsValue != std::floor(segmentsValue) || segmentsValue < 3 || segmentsValue > 65536)
        json::fail(at / "segments", "a whole number of segments from 3 to 65536");
    int segments = int(segmentsValue);

    Mesh mesh = itemMesh(item, where, "disc " + std::to_string(index), MeshShape::Plane, scene);
    glm::dvec3 u, v;
    planeTangents(n, u, v);
    mesh.positions.push_back(glm::vec3(center));
    mesh.normals.push_back(glm::vec3(n));
    for (int k = 0; k < segments; ++k) {
        double a = 2.0 * gpu::kPi * double(k) / double(segments);
        mesh.positions.push_back(glm::vec3(center + radius * (std::cos(a) * u + std::sin(a) * v)));
        mesh.normals.push_back(glm::vec3(n));
    }
    // Counter-clockwise seen from the normal's side (u x v = n).
    for (uint32_t k = 0; k < uint32_t(segments); ++k)
        for (uint32_t i : {0u, 1u + k, 1u + (k + 1) % uint32_t(segments)})
            mesh.indices.push_back(i);
    mesh.computeBounds();
    scene.meshes.push_back(std::move(mesh));
}

void parseBox(const nlohmann::json& item, const json::Where& where, size_t index, Scene& scene) {
    json::checkKeys(item, {"box", "name", "albedo", "specular", "roughness"}, where);
    const json::Where at = where / "box";
    const nlohmann::json& spec = item["box"];
    json::checkKeys(spec, {"center", "size", "rotate_y_deg", "inside"}, at);
    glm::dvec3 center = json::optional(spec, "center", at, glm::dvec3(0.0), json::point);
    if (!spec.contains("size"))
        json::fail(at / "size", "[x, y, z] edge lengths in metres (missing)");
    glm::dvec3 half = 0.5 * positive3(spec["size"], at / "size");
    double angle = json::optional(spec, "rotate_y_deg", at, 0.0, kAngle);
    glm::dmat3 rotation(glm::rotate(glm::dmat4(1.0), glm::radians(angle), glm::dvec3(0, 1, 0)));
    // "inside": a room seen from within: the faces look inwards (they reflect light inside).
    bool inside = json::optional(spec, "inside", at, false, json::boolean);

    Mesh mesh = itemMesh(item, where, "box " + std::to_string(index),
                         inside ? MeshShape::General : MeshShape::Convex, scene);
    appendBox(mesh, center, half, rotation, inside);
    mesh.computeBounds();
    scene.meshes.push_back(std::move(mesh));
}

/// {"sphere": {"center", "radius", "subdivisions", "inside"}}: a geodesic polyhedron (an
/// icosahedron whose faces are split in four `subdivisions` times, default 3: 1280 nearly equal
/// triangles, vertices on the sphere), facing out, or in ("inside": true, a spherical room).
void parseSphere(const nlohmann::json& item, const json::Where& where, size_t index, Scene& scene) {
    json::checkKeys(item, {"sphere", "name", "albedo", "specular", "roughness"}, where);
    const json::Where at = where / "sphere";
    const nlohmann::json& spec = item["sphere"];
    json::checkKeys(spec, {"center", "radius", "subdivisions", "inside"}, at);
    glm::dvec3 center = json::optional(spec, "center", at, glm::dvec3(0.0), json::point);
    if (!spec.contains("radius")) json::fail(at / "radius", "a radius in metres (missing)");
    double radius = json::length(spec["radius"], at / "radius");
    double levels = json::optional(spec, "subdivisions", at, 3.0, json::number);
    if (levels != std::floor(levels) || levels < 0 || levels > 7)
        json::fail(at / "subdivisions", "a whole number from 0 to 7 (20 x 4^n triangles)");
    bool inside = json::optional(spec, "inside", at, false, json::boolean);
    Mesh mesh = itemMesh(item, where, "sphere " + std::to_string(index),
                         inside ? MeshShape::General : MeshShape::Convex, scene);
    // The icosahedron: (0, +-1, +-t) and its cyclic permutations, t the golden ratio.
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<glm::dvec3> dirs = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                    {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                    {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (glm::dvec3& d : dirs) d = glm::normalize(d);
    std::vector<std::array<uint32_t, 3>> faces = {
        {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
        {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int level = 0; level < int(levels); ++level) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
        auto middle = [&](uint32_t a, uint32_t b) {
            auto key = std::minmax(a, b);
            auto it = midpoints.find(key);
            if (it != midpoints.end()) return it->second;
            dirs.push_back(glm::normalize(dirs[a] + dirs[b]));
            return midpoints[key] = uint32_t(dirs.size() - 1);
        };
        std::vector<std::array<uint32_t, 3>> finer;
        for (const auto& f : faces) {
            uint32_t ab = middle(f[0], f[1]), bc = middle(f[1], f[2]), ca = middle(f[2], f[0]);
            finer.insert(finer.end(),
                         {{f[0], ab, ca}, {f[1], bc, ab}, {f[2], ca, bc}, {ab, bc, ca}});
        }
        faces = std::move(finer);
    }
    for (const glm::dvec3& d : dirs) {
        mesh.positions.push_back(glm::vec3(center + radius * d));
        mesh.normals.push_back(glm::vec3(inside ? -d : d));
    }
    // The faces are counter-clockwise seen from outside; a room turns them round.
    for (const auto& f : faces)
        mesh.indices.insert(mesh.indices.end(), {f[0], inside ? f[2] : f[1], inside ? f[1] : f[2]});
    mesh.computeBounds();
    scene.meshes.push_back(std::move(mesh));
}

/// Returns the files read (loadGltf).
std::vector<std::string> parseGltfItem(const nlohmann::json& item, const json::Where& where,
                                       Scene& scene) {
    json::checkKeys(item, {"gltf", "transform"}, where);
    std::string file = json::string(item["gltf"], where / "gltf");
    fs::path resolved(file);
    if (resolved.is_relative()) resolved = fs::path(scene.path).parent_path() / resolved;

    glm::dmat4 transform(1.0);
    if (item.contains("transform")) {
        const json::Where at = where / "transform";
        const nlohmann::json& t = item["transform"];
        json::checkKeys(t, {"translate", "rotate_y_deg", "scale"}, at);
        glm::dvec3 translate = json::optional(t, "translate", at, glm::dvec3(0.0), json::point);
        double angle = json::optional(t, "rotate_y_deg", at, 0.0, kAngle);
        // A model in micrometres to one in kilometres, in metres.
        double scale =
            json::optional(t, "scale", at, 1.0, json::range(1e-6, 1e6, "a scale factor"));
        transform = glm::translate(glm::dmat4(1.0), translate) *
                    glm::rotate(glm::dmat4(1.0), glm::radians(angle), glm::dvec3(0, 1, 0)) *
                    glm::scale(glm::dmat4(1.0), glm::dvec3(scale));
    }
    return loadGltf(resolved.string(), transform, scene, where / "gltf");
}

/// Parses one "geometry" entry, appending its meshes and materials and its GeometryItem.
void parseGeometryItem(const nlohmann::json& item, const json::Where& where, size_t index,
                       Scene& scene) {
    if (!item.is_object()) json::fail(where, "an object, got " + std::string(item.type_name()));
    int kinds = 0;
    for (const char* key : {"gltf", "plane", "disc", "box", "sphere", "room", "furniture"})
        kinds += int(item.contains(key));
    if (kinds != 1)
        json::fail(where,
                   "exactly one of \"room\", \"furniture\", \"gltf\", \"plane\", \"disc\", "
                   "\"box\" or \"sphere\"");

    GeometryItem geometry;
    geometry.source = item;
    size_t firstMesh = scene.meshes.size();
    if (item.contains("gltf"))
        geometry.files = parseGltfItem(item, where, scene);
    else if (item.contains("plane"))
        parsePlane(item, where, index, scene);
    else if (item.contains("disc"))
        parseDisc(item, where, index, scene);
    else if (item.contains("sphere"))
        parseSphere(item, where, index, scene);
    else if (item.contains("room"))
        parseRoom(item, where, scene);
    else if (item.contains("furniture"))
        parseFurniture(item, where, index, scene);
    else
        parseBox(item, where, index, scene);
    for (size_t m = firstMesh; m < scene.meshes.size(); ++m) {
        // Finite doubles can still leave float's range (a plane 6e73 m wide, found by fuzzing:
        // its vertices were -inf): refuse what the renderer cannot hold.
        for (const glm::vec3& v : scene.meshes[m].positions)
            if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
                json::fail(where,
                           "geometry within single precision's range (about 3e38 m): "
                           "its vertices overflow float; check its center and size");
        geometry.meshes.push_back(uint32_t(m));
    }
    scene.geometry.push_back(std::move(geometry));
}

Camera parseCamera(const nlohmann::json& v, const json::Where& where) {
    json::checkKeys(v, {"position", "target", "fov_deg", "exposure"}, where);
    Camera camera;
    camera.position = json::optional(v, "position", where, camera.position, json::point);
    camera.target = json::optional(v, "target", where, camera.target, json::point);
    camera.fovDeg = json::optional(v, "fov_deg", where, camera.fovDeg, json::number);
    if (!(camera.fovDeg > 0.0 && camera.fovDeg < 180.0))
        json::fail(where / "fov_deg",
                   "a field of view in (0, 180) degrees, got " + v["fov_deg"].dump());
    if (glm::length(camera.target - camera.position) < 1e-9)
        json::fail(where / "target", "a target different from the camera position");
    if (v.contains("exposure")) {
        camera.exposure = json::number(v["exposure"], where / "exposure");
        // The editor's slider's range, widened as RenderPanels clamps it.
        if (!(camera.exposure >= 1e-4 && camera.exposure <= 1e4))
            json::fail(where / "exposure",
                       "a tone-mapping exposure k in [1e-4, 1e4], got " + v["exposure"].dump());
    }
    return camera;
}

std::string kindNames() {
    std::string names;
    for (const LuminaireKindInfo& kind : luminaireKinds())
        names += (names.empty() ? "" : ", ") + std::string(kind.name);
    for (const LuminaireFormatInfo& format : luminaireFormats())
        names += ", " + std::string(format.type);
    return names;
}

/// Geometry item of a plane or box built in code: validated by the same parser as the file.
size_t addGeneratedItem(Scene& scene, nlohmann::json item, const Material& material) {
    if (!material.name.empty()) item["name"] = material.name;
    item["albedo"] = toJson(glm::dvec3(material.albedo));
    item["specular"] = toJson(glm::dvec3(material.specular));
    item["roughness"] = double(material.roughness);
    size_t index = scene.geometry.size();
    json::Where where{scene.path.empty() ? "<scene>" : scene.path, ""};
    parseGeometryItem(item, (where / "geometry")[index], index, scene);
    return index;
}

/// Rewrites relative glTF, luminaire and environment paths of `doc` written for a scene in the
/// folder of `fromPath` so they resolve from the folder of `toPath`. Paths stay as written when the
/// folder does not change.
void rebaseGltfPaths(nlohmann::json& doc, const std::string& fromPath, const std::string& toPath) {
    // The folder of a file named without one ("room.json") is the current folder.
    auto folderOf = [](const std::string& file) {
        return (file.empty() ? fs::current_path() : fs::absolute(file).parent_path())
            .lexically_normal();
    };
    fs::path fromDir = folderOf(fromPath), toDir = folderOf(toPath);
    if (fromDir == toDir) return;
    // The relative path `object[key]` (if it is one) rewritten to name the same file from toDir.
    auto rebase = [&](nlohmann::json& object, const char* key) {
        if (!object.is_object()) return;
        auto it = object.find(key);
        if (it == object.end() || !it->is_string()) return;
        fs::path file(it->get<std::string>());
        if (file.is_absolute()) return;
        fs::path target = (fromDir / file).lexically_normal();
        fs::path relative = target.lexically_relative(toDir);
        *it = (relative.empty() ? target : relative).generic_string();
    };
    for (nlohmann::json& item : doc["geometry"]) rebase(item, "gltf");
    // Luminaire files (photometry, light fields), a layout's luminaire's, and the environment's
    // "file" or "sequence" pattern, relative to the scene file, likewise.
    for (nlohmann::json& entry : doc["luminaires"]) rebase(entry, "file");
    if (doc.contains("layouts"))
        for (nlohmann::json& layout : doc["layouts"])
            if (layout.is_object() && layout.contains("luminaire"))
                rebase(layout["luminaire"], "file");
    for (const char* key : {"file", "sequence"}) rebase(doc["environment"], key);
}

}  // namespace

Scene loadScene(const std::string& path) {
    ScopedActivity activity("loading the scene " + path);
    std::string ext = lowerExtension(path);
    if (ext != ".json") {
        throw InputError(path + ": unsupported scene file type \"" + ext +
                         "\" (scene files are .json)");
    }
    std::string text = readFile(path);
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        size_t line = 0, column = 0;
        lineAndColumn(text, e.byte, line, column);
        throw InputError(path + ":" + std::to_string(line) + ":" + std::to_string(column) +
                         ": invalid JSON (" + parseErrorReason(e.what()) + ")");
    } catch (const nlohmann::json::exception& e) {
        // A number beyond double's range ("1e400") is an out_of_range error, not a parse_error,
        // and has no position (fuzzing found it escaping as a non-InputError).
        throw InputError(path + ": invalid JSON (" + parseErrorReason(e.what()) + ")");
    }
    return parseScene(doc, path);
}

namespace {

/// The list `key` of the scene document: an array of at most `limit` entries (`what`), else
/// InputError naming the field and the limit.
const nlohmann::json& boundedList(const nlohmann::json& doc, const char* key,
                                  const json::Where& root, size_t limit, const char* what) {
    const nlohmann::json& items = doc[key];
    if (!items.is_array()) json::fail(root / key, std::string("an array of ") + what);
    if (items.size() > limit)
        json::fail(root / key, "at most " + std::to_string(limit) + " " + what + ", found " +
                                   std::to_string(items.size()));
    return items;
}

}  // namespace

Scene parseScene(const nlohmann::json& doc, const std::string& path, const SceneLimits& limits) {
    const json::Where root{path, ""};
    json::checkKeys(doc,
                    {"project", "geometry", "luminaires", "layouts", "environment", "camera",
                     "maintenance_factor", "task_areas", "calculation_points", "glare_observers"},
                    root);
    Scene scene;
    scene.path = path;
    scene.maintenanceFactor =
        json::optional(doc, "maintenance_factor", root, 1.0, maintenanceFactorValue);

    if (doc.contains("geometry")) {
        const nlohmann::json& items =
            boundedList(doc, "geometry", root, limits.geometryEntries, "geometry entries");
        size_t triangles = 0;  // a running total: recounting every mesh per entry is quadratic
        for (size_t i = 0; i < items.size(); ++i) {
            size_t counted = scene.meshes.size();
            parseGeometryItem(items[i], (root / "geometry")[i], i, scene);
            for (size_t m = counted; m < scene.meshes.size(); ++m)
                triangles += scene.meshes[m].triangleCount();
            if (triangles > limits.triangles)
                json::fail((root / "geometry")[i],
                           "geometry of at most " + std::to_string(limits.triangles) +
                               " triangles in all, reached " + std::to_string(triangles));
        }
    }
    // One scene-file luminaire entry: its luminaire and its product's other emitters.
    auto addLuminaire = [&](const nlohmann::json& entry, const json::Where& where, size_t i) {
        {
            std::unique_ptr<Luminaire> first = parseLuminaire(entry, where, i);
            std::vector<std::unique_ptr<Luminaire>> more = companions(*first);
            std::string name = first->name;
            for (size_t k = 0; k < more.size(); ++k) {
                if (k == 0) first->name = name + " #0";
                more[k]->name = name + " #" + std::to_string(k + 1);
                more[k]->pose = first->pose;
                more[k]->technique = first->technique;
                more[k]->maintenanceFactor = first->maintenanceFactor;
            }
            scene.luminaires.push_back(std::move(first));
            for (auto& m : more) scene.luminaires.push_back(std::move(m));
            if (scene.luminaires.size() > limits.luminaires)
                json::fail(where, "at most " + std::to_string(limits.luminaires) +
                                      " luminaires, their products' emitters counted, reached " +
                                      std::to_string(scene.luminaires.size()));
        }
    };
    if (doc.contains("luminaires")) {
        const nlohmann::json& items =
            boundedList(doc, "luminaires", root, limits.luminaires, "luminaires");
        for (size_t i = 0; i < items.size(); ++i)
            addLuminaire(items[i], (root / "luminaires")[i], i);
    }
    scene.environment = nullptr;
    if (doc.contains("environment") && !doc["environment"].is_null()) {
        EnvironmentSource env = parseEnvironment(doc["environment"], root / "environment",
                                                 fs::path(path).parent_path().string());
        scene.environment = doc["environment"];
        scene.environmentMap = std::move(env.map);
        scene.environmentSequence = std::move(env.sequence);
    }
    if (doc.contains("camera")) scene.camera = parseCamera(doc["camera"], root / "camera");
    if (doc.contains("project")) {
        const json::Where at = root / "project";
        const nlohmann::json& p = doc["project"];
        json::checkKeys(p, {"name", "client", "designer", "date", "description"}, at);
        ProjectInfo& info = scene.project;
        for (auto [key, field] : {std::pair{"name", &info.name},
                                  {"client", &info.client},
                                  {"designer", &info.designer},
                                  {"date", &info.date},
                                  {"description", &info.description}})
            *field = json::optional(p, key, at, std::string(), json::string);
    }
    if (doc.contains("task_areas")) {
        const nlohmann::json& items =
            boundedList(doc, "task_areas", root, limits.taskAreas, "task areas");
        for (size_t i = 0; i < items.size(); ++i)
            scene.taskAreas.push_back(parseTaskArea(items[i], (root / "task_areas")[i]));
    }
    if (doc.contains("calculation_points")) {
        const nlohmann::json& items =
            boundedList(doc, "calculation_points", root, limits.calculationPoints, "points");
        for (size_t i = 0; i < items.size(); ++i)
            scene.calcPoints.push_back(parseCalcPoint(items[i], (root / "calculation_points")[i]));
    }
    if (doc.contains("glare_observers")) {
        const nlohmann::json& items =
            boundedList(doc, "glare_observers", root, limits.glareObservers, "observers");
        for (size_t i = 0; i < items.size(); ++i)
            scene.glareObservers.push_back(
                parseGlareObserver(items[i], (root / "glare_observers")[i]));
    }
    if (doc.contains("layouts")) {
        const nlohmann::json& items =
            boundedList(doc, "layouts", root, limits.luminaires, "layouts");
        for (size_t i = 0; i < items.size(); ++i) {
            const json::Where where = (root / "layouts")[i];
            LayoutItem layout;
            layout.source = items[i];
            const size_t first = scene.luminaires.size();
            for (const nlohmann::json& entry :
                 parseLayout(items[i], where, scene, limits.luminaires))
                addLuminaire(entry, where / "luminaire", scene.luminaires.size());
            for (size_t k = first; k < scene.luminaires.size(); ++k)
                layout.placed.push_back(luminaireToJson(*scene.luminaires[k]));
            scene.layouts.push_back(std::move(layout));
        }
    }
    scene.updateBodies(limits.triangles);
    return scene;
}

nlohmann::json sceneToJson(const Scene& scene) {
    nlohmann::json doc = nlohmann::json::object();
    doc["geometry"] = nlohmann::json::array();
    for (const GeometryItem& item : scene.geometry) doc["geometry"].push_back(item.source);
    std::vector<nlohmann::json> entries;
    for (const auto& luminaire : scene.luminaires) entries.push_back(luminaireToJson(*luminaire));
    // A layout is written back while its luminaires are still a run of the list exactly as it
    // placed them; else they are written one by one.
    std::vector<bool> inLayout(entries.size(), false);
    for (const LayoutItem& layout : scene.layouts) {
        const size_t n = layout.placed.size();
        for (size_t start = 0; n > 0 && start + n <= entries.size(); ++start) {
            bool same = true;
            for (size_t k = 0; k < n && same; ++k)
                same = !inLayout[start + k] && entries[start + k] == layout.placed[k];
            if (!same) continue;
            std::fill(inLayout.begin() + std::ptrdiff_t(start),
                      inLayout.begin() + std::ptrdiff_t(start + n), true);
            doc["layouts"].push_back(layout.source);
            break;
        }
    }
    doc["luminaires"] = nlohmann::json::array();
    for (size_t i = 0; i < entries.size(); ++i)
        if (!inLayout[i]) doc["luminaires"].push_back(entries[i]);
    doc["environment"] = scene.environment;
    doc["camera"] = {{"position", toJson(scene.camera.position)},
                     {"target", toJson(scene.camera.target)},
                     {"fov_deg", scene.camera.fovDeg}};
    if (scene.camera.exposure > 0.0) doc["camera"]["exposure"] = scene.camera.exposure;
    if (scene.maintenanceFactor != 1.0) doc["maintenance_factor"] = scene.maintenanceFactor;
    if (!scene.project.empty()) {
        const ProjectInfo& info = scene.project;
        nlohmann::json& p = doc["project"];
        p = nlohmann::json::object();
        for (auto [key, field] : {std::pair{"name", &info.name},
                                  {"client", &info.client},
                                  {"designer", &info.designer},
                                  {"date", &info.date},
                                  {"description", &info.description}})
            if (!field->empty()) p[key] = *field;
    }
    for (const TaskArea& a : scene.taskAreas) doc["task_areas"].push_back(toJson(a));
    for (const CalcPoint& p : scene.calcPoints) doc["calculation_points"].push_back(toJson(p));
    for (const GlareObserver& o : scene.glareObservers) doc["glare_observers"].push_back(toJson(o));
    return doc;
}

namespace {

/// A value on one line, with ", " between items and ": " after keys, as people write JSON.
std::string oneLine(const nlohmann::json& v) {
    if (v.is_object() || v.is_array()) {
        const bool object = v.is_object();
        std::string s = object ? "{" : "[";
        bool first = true;
        for (const auto& [key, item] : v.items()) {
            if (!first) s += ", ";
            first = false;
            if (object) s += nlohmann::json(key).dump() + ": ";
            s += oneLine(item);
        }
        return s + (object ? "}" : "]");
    }
    return v.dump();
}

/// The scene file's text: each top-level field on its own line, and each entry of a list (a
/// geometry entry, a luminaire) on one line of its own, so that a room of twenty luminaires reads
/// as about thirty lines and a change shows as a changed line.
std::string sceneText(const nlohmann::json& doc) {
    std::string s = "{\n";
    size_t field = 0;
    for (const auto& [key, value] : doc.items()) {
        s += "  " + nlohmann::json(key).dump() + ": ";
        if (value.is_array() && !value.empty()) {
            s += "[\n";
            for (size_t i = 0; i < value.size(); ++i)
                s += "    " + oneLine(value[i]) + (i + 1 < value.size() ? ",\n" : "\n");
            s += "  ]";
        } else {
            s += oneLine(value);
        }
        s += ++field < doc.size() ? ",\n" : "\n";
    }
    return s + "}\n";
}

}  // namespace

void saveScene(const Scene& scene, const std::string& path) {
    nlohmann::json doc = sceneToJson(scene);
    rebaseGltfPaths(doc, scene.path, path);
    std::string text;
    try {
        text = sceneText(doc);
    } catch (const nlohmann::json::exception& e) {
        // E.g. a name that is not valid UTF-8: nothing has been written yet.
        throw InputError(path + ": cannot save scene (" + e.what() + ")");
    }
    writeFileAtomically(path, text, "cannot save scene");
}

std::unique_ptr<Luminaire> parseLuminaire(const nlohmann::json& entry, const json::Where& where,
                                          size_t index) {
    if (!entry.is_object()) json::fail(where, "an object, got " + std::string(entry.type_name()));
    if (!entry.contains("type"))
        json::fail(where / "type", "a luminaire type (one of " + kindNames() + "); it is missing");
    std::string type = json::string(entry["type"], where / "type");
    // A kind, or a format that builds a luminaire of a kind (a GLDF variant: photometric).
    const LuminaireKindInfo* kind = findKind(type);
    LuminaireParser parse = kind ? kind->adapter().parse : nullptr;
    if (const LuminaireFormatInfo* format = findFormat(type)) {
        kind = &findKind(format->kind);
        parse = format->parse;
    }
    if (!kind || !parse) {
        throw InputError((where / "type").str() + ": unknown luminaire type \"" + type +
                         "\" (expected one of " + kindNames() + ")");
    }
    std::unique_ptr<Luminaire> luminaire = parse(entry, where);
    if (!luminaire) throw InputError(where.str() + ": luminaire could not be built");

    luminaire->name =
        json::optional(entry, "name", where, type + " " + std::to_string(index), json::string);
    Pose& pose = luminaire->pose;
    pose.position = json::optional(entry, "position", where, Pose{}.position, json::point);
    pose.aim = json::optional(entry, "aim", where, Pose{}.aim, json::direction);
    pose.c0 = json::optional(entry, "c0", where, Pose{}.c0, json::direction);
    luminaire->technique = json::optional(entry, "technique", where,
                                          std::string(kind->defaultTechnique), json::string);
    if (entry.contains("maintenance_factor"))
        luminaire->maintenanceFactor =
            maintenanceFactorValue(entry["maintenance_factor"], where / "maintenance_factor");
    if (!findTechnique(kind->kind, luminaire->technique)) {
        throw InputError((where / "technique").str() + ": unknown technique \"" +
                         luminaire->technique + "\" for " + type + " (expected one of " +
                         techniqueNames(kind->kind) + ")");
    }
    return luminaire;
}

nlohmann::json luminaireToJson(const Luminaire& luminaire) {
    nlohmann::json out = nlohmann::json::object();
    out["type"] = std::string(kindName(luminaire.kind()));
    out["name"] = luminaire.name;
    out["position"] = toJson(luminaire.pose.position);
    out["aim"] = toJson(luminaire.pose.aim);
    out["c0"] = toJson(luminaire.pose.c0);
    out["technique"] = luminaire.technique;
    if (luminaire.maintenanceFactor) out["maintenance_factor"] = *luminaire.maintenanceFactor;
    writeJson(luminaire, out);
    return out;
}

size_t addPlane(Scene& scene, const glm::dvec3& center, const glm::dvec3& normal,
                const glm::dvec2& size, const Material& material) {
    nlohmann::json item;
    item["plane"] = {
        {"center", toJson(center)}, {"normal", toJson(normal)}, {"size", toJson(size)}};
    return addGeneratedItem(scene, std::move(item), material);
}

size_t addBox(Scene& scene, const glm::dvec3& center, const glm::dvec3& size, double rotateYDeg,
              const Material& material) {
    nlohmann::json item;
    item["box"] = {
        {"center", toJson(center)}, {"size", toJson(size)}, {"rotate_y_deg", rotateYDeg}};
    return addGeneratedItem(scene, std::move(item), material);
}

}  // namespace candela
