#include "scene/RoomIo.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/Procedural.h"

namespace candela {

namespace {

/// A reflectance: a number in [0, 1] (grey) or [r, g, b], each in [0, 1].
glm::dvec3 reflectanceValue(const nlohmann::json& v, const json::Where& where) {
    if (v.is_number()) {
        double x = json::number(v, where);
        if (!(x >= 0.0 && x <= 1.0)) json::fail(where, "a reflectance in [0, 1], got " + v.dump());
        return glm::dvec3(x);
    }
    glm::dvec3 c = json::vec3(v, where);
    for (int i = 0; i < 3; ++i)
        if (!(c[i] >= 0.0 && c[i] <= 1.0))
            json::fail(where[i], "a reflectance in [0, 1], got " + v.dump());
    return c;
}

/// A distance or height that may be zero (an opening's offset or sill), m.
double nonNegative(const nlohmann::json& v, const json::Where& where) {
    return json::inRange(v, where, 0.0, json::kMaxMetres, "a distance in metres");
}

/// A mesh of one material, `reflectance` grey or coloured, named `name`.
Mesh surfaceMesh(const std::string& name, const glm::dvec3& reflectance, MeshShape shape,
                 Scene& scene) {
    Material material;
    material.name = name;
    material.albedo = glm::vec3(reflectance);
    scene.materials.push_back(material);
    Mesh mesh;
    mesh.name = name;
    mesh.material = uint32_t(scene.materials.size() - 1);
    mesh.shape = shape;
    return mesh;
}

void keepMesh(Mesh&& mesh, Scene& scene) {
    if (mesh.indices.empty()) return;  // a wall that is all opening
    mesh.computeBounds();
    scene.meshes.push_back(std::move(mesh));
}

struct RoomReflectances {
    glm::dvec3 floor{kDefaultFloorReflectance}, ceiling{kDefaultCeilingReflectance};
    std::vector<glm::dvec3> walls;
};

RoomReflectances readReflectances(const nlohmann::json& spec, const json::Where& at, size_t walls) {
    RoomReflectances r;
    r.walls.assign(walls, glm::dvec3(kDefaultWallReflectance));
    auto it = spec.find("reflectance");
    if (it == spec.end()) return r;
    const json::Where where = at / "reflectance";
    if (!it->is_object())
        json::fail(where,
                   "{\"floor\": 0.2, \"walls\": 0.5, \"ceiling\": 0.7} (each a number or "
                   "[r, g, b] in [0, 1], and \"wall N\" for one wall)");
    // "walls" first, so that "wall N" overrides it whatever the order written.
    if (it->contains("walls"))
        r.walls.assign(walls, reflectanceValue((*it)["walls"], where / "walls"));
    for (const auto& [key, value] : it->items()) {
        if (key == "floor")
            r.floor = reflectanceValue(value, where / key);
        else if (key == "ceiling")
            r.ceiling = reflectanceValue(value, where / key);
        else if (key == "walls")
            continue;
        else if (key.rfind("wall ", 0) == 0) {
            const std::string number = key.substr(5);
            size_t wall = 0;
            bool digits = !number.empty() && number.size() < 8 &&
                          std::all_of(number.begin(), number.end(), ::isdigit);
            if (digits) wall = std::stoul(number);
            if (wall < 1 || wall > walls)
                json::fail(where / key, "\"wall N\" with N from 1 to " + std::to_string(walls) +
                                            " (the room has " + std::to_string(walls) + " walls)");
            r.walls[wall - 1] = reflectanceValue(value, where / key);
        } else {
            json::fail(where / key,
                       "one of \"floor\", \"walls\", \"ceiling\" or \"wall N\" (unknown key)");
        }
    }
    return r;
}

std::vector<RoomOpening> readOpenings(const nlohmann::json& spec, const json::Where& at,
                                      const std::vector<glm::dvec2>& floor, double height) {
    std::vector<RoomOpening> o;
    auto it = spec.find("openings");
    if (it == spec.end()) return o;
    const json::Where list = at / "openings";
    if (!it->is_array()) json::fail(list, "an array of openings (windows, doors, skylights)");
    if (it->size() > kMaxRoomOpenings)
        json::fail(list, "at most " + std::to_string(kMaxRoomOpenings) + " openings, found " +
                             std::to_string(it->size()));
    for (size_t i = 0; i < it->size(); ++i) {
        const nlohmann::json& e = (*it)[i];
        const json::Where where = list[i];
        json::checkKeys(e,
                        {"type", "name", "wall", "offset", "width", "sill", "height", "glazing",
                         "center", "size"},
                        where);
        if (!e.contains("type"))
            json::fail(where / "type", "\"window\", \"door\" or \"skylight\" (missing)");
        RoomOpening opening;
        opening.type = json::string(e["type"], where / "type");
        const std::string& type = opening.type;
        if (e.contains("name")) opening.name = json::string(e["name"], where / "name");
        if (e.contains("glazing")) {
            if (type == "door") json::fail(where / "glazing", "no glazing on a door");
            json::inRange(e["glazing"], where / "glazing", 0.0, 1.0, "a transmittance");
        }
        if (type == "skylight") {
            for (const char* key : {"wall", "offset", "width", "sill", "height"})
                if (e.contains(key))
                    json::fail(where / key, "no \"" + std::string(key) +
                                                "\" on a skylight (it takes \"center\" [x, z] and "
                                                "\"size\" [along x, along z])");
            for (const char* key : {"center", "size"})
                if (!e.contains(key))
                    json::fail(where / key, "a skylight's " + std::string(key) + " (missing)");
            glm::dvec2 c = json::vec2(e["center"], where / "center");
            glm::dvec2 s = json::vec2(e["size"], where / "size");
            for (int k = 0; k < 2; ++k)
                if (!(s[k] > 0.0 && s[k] <= json::kMaxMetres))
                    json::fail((where / "size")[k], "a positive size in metres");
            const glm::dvec2 lo = c - 0.5 * s, hi = c + 0.5 * s;
            for (glm::dvec2 corner : {lo, hi, glm::dvec2(lo.x, hi.y), glm::dvec2(hi.x, lo.y)})
                if (!insidePolygon(floor, corner))
                    json::fail(where,
                               "a skylight within the room's outline (a corner of it is "
                               "outside)");
            opening.center = c;
            opening.size = s;
            o.push_back(std::move(opening));
            continue;
        }
        if (type != "window" && type != "door")
            json::fail(where / "type",
                       "\"window\", \"door\" or \"skylight\", got \"" + type + "\"");
        for (const char* key : {"center", "size"})
            if (e.contains(key))
                json::fail(where / key, "no \"" + std::string(key) + "\" on a " + type +
                                            " (it takes \"wall\", \"offset\", \"width\", \"sill\" "
                                            "and \"height\")");
        for (const char* key : {"wall", "width", "height"})
            if (!e.contains(key)) json::fail(where / key, "a " + type + "'s " + key + " (missing)");
        const double wallNumber = json::number(e["wall"], where / "wall");
        if (wallNumber != std::floor(wallNumber) || wallNumber < 1 ||
            wallNumber > double(floor.size()))
            json::fail(where / "wall", "a wall from 1 to " + std::to_string(floor.size()) +
                                           " (wall N runs from corner N to the next)");
        const size_t wall = size_t(wallNumber) - 1;
        const double length = glm::length(floor[(wall + 1) % floor.size()] - floor[wall]);
        const double offset = json::optional(e, "offset", where, 0.0, nonNegative);
        const double width = json::length(e["width"], where / "width");
        // A window's sill is 0.9 m unless given; a door starts at the floor.
        const double sill =
            json::optional(e, "sill", where, type == "door" ? 0.0 : 0.9, nonNegative);
        const double tall = json::length(e["height"], where / "height");
        // A micrometre of slack for decimals written in the file.
        constexpr double kSlack = 1e-6;
        if (offset + width > length + kSlack)
            json::fail(where, "a " + type + " within its wall: offset + width is " +
                                  std::to_string(offset + width) + " m, wall " +
                                  std::to_string(wall + 1) + " is " + std::to_string(length) +
                                  " m long");
        if (sill + tall > height + kSlack)
            json::fail(where, "a " + type + " below the ceiling: sill + height is " +
                                  std::to_string(sill + tall) + " m, the room is " +
                                  std::to_string(height) + " m high");
        opening.wall = wall;
        opening.offset = offset;
        opening.width = width;
        opening.sill = sill;
        opening.height = tall;
        o.push_back(std::move(opening));
    }
    return o;
}

/// The holes the openings cut: per wall in the wall's (along, up) coordinates, and the ceiling's
/// skylights in (x, z).
struct RoomHoles {
    std::vector<std::vector<Rect2>> walls;
    std::vector<Rect2> ceiling;
};

RoomHoles holesOf(const RoomSpec& room) {
    RoomHoles h;
    h.walls.resize(room.floor.size());
    for (const RoomOpening& o : room.openings) {
        if (o.type == "skylight") {
            h.ceiling.push_back({o.center - 0.5 * o.size, o.center + 0.5 * o.size});
            continue;
        }
        // Within the wall's slack (readOpenings allows a micrometre for written decimals).
        h.walls[o.wall].push_back({{o.offset, o.sill},
                                   {std::min(o.offset + o.width, room.wallLength(o.wall)),
                                    std::min(o.sill + o.height, room.height)}});
    }
    return h;
}

}  // namespace

double RoomSpec::area() const {
    return std::abs(signedArea(floor));
}

double RoomSpec::wallLength(size_t i) const {
    return glm::length(floor[(i + 1) % floor.size()] - floor[i]);
}

RoomSpec readRoom(const nlohmann::json& item, const json::Where& where) {
    json::checkKeys(item, {"room"}, where);
    const json::Where at = where / "room";
    const nlohmann::json& spec = item["room"];
    json::checkKeys(spec, {"name", "floor", "height", "elevation", "reflectance", "openings"}, at);
    RoomSpec room;
    room.name = json::optional(spec, "name", at, std::string("Room"), json::string);
    if (!spec.contains("floor"))
        json::fail(at / "floor", "the floor's outline, [[x, z], ...] in metres (missing)");
    const nlohmann::json& corners = spec["floor"];
    if (!corners.is_array() || corners.size() < 3 || corners.size() > kMaxRoomCorners)
        json::fail(at / "floor", "the floor's outline: from 3 to " +
                                     std::to_string(kMaxRoomCorners) + " corners [x, z] in metres");
    std::vector<glm::dvec2>& floor = room.floor;
    for (size_t i = 0; i < corners.size(); ++i) {
        glm::dvec2 p = json::vec2(corners[i], (at / "floor")[i]);
        if (std::abs(p.x) > json::kMaxMetres || std::abs(p.y) > json::kMaxMetres)
            json::fail((at / "floor")[i], "coordinates within " + json::maxMetresText() + " m");
        floor.push_back(p);
    }
    if (std::string defect = polygonDefect(floor); !defect.empty())
        json::fail(at / "floor", "an outline that does not cross itself: " + defect);
    if (!spec.contains("height"))
        json::fail(at / "height", "the room's height in metres (missing)");
    room.height = json::length(spec["height"], at / "height");
    room.elevation = json::optional(
        spec, "elevation", at, 0.0,
        json::range(-json::kMaxMetres, json::kMaxMetres, "the floor's height in metres"));
    const RoomReflectances reflectance = readReflectances(spec, at, floor.size());
    room.floorReflectance = reflectance.floor;
    room.ceilingReflectance = reflectance.ceiling;
    room.wallReflectances = reflectance.walls;
    room.openings = readOpenings(spec, at, floor, room.height);
    size_t skylights = 0;
    for (const RoomOpening& o : room.openings) skylights += o.type == "skylight" ? 1 : 0;
    // The ceiling's strips grow with corners x skylights, and each strip looks at every edge.
    if (floor.size() * (skylights + 1) > kMaxCornersTimesSkylights)
        json::fail(at / "openings", "at most " + std::to_string(kMaxCornersTimesSkylights) +
                                        " for the floor's corners times (skylights + 1), got " +
                                        std::to_string(floor.size()) + " x " +
                                        std::to_string(skylights + 1) +
                                        " (split a large room into several)");
    return room;
}

void parseRoom(const nlohmann::json& item, const json::Where& where, Scene& scene) {
    const RoomSpec room = readRoom(item, where);
    const RoomHoles holes = holesOf(room);
    const std::string& name = room.name;
    const std::vector<glm::dvec2>& floor = room.floor;
    const double height = room.height, elevation = room.elevation;
    const glm::dvec3 x(1.0, 0.0, 0.0), up(0.0, 1.0, 0.0), z(0.0, 0.0, 1.0);
    Mesh floorMesh = surfaceMesh(name + ": floor", room.floorReflectance, MeshShape::Plane, scene);
    appendFlat(floorMesh, tessellate(floor, {}), elevation * up, x, z, up);
    keepMesh(std::move(floorMesh), scene);
    Mesh ceiling =
        surfaceMesh(name + ": ceiling", room.ceilingReflectance, MeshShape::Plane, scene);
    appendFlat(ceiling, tessellate(floor, holes.ceiling), (elevation + height) * up, x, z, -up);
    keepMesh(std::move(ceiling), scene);
    // The inside lies left of each edge when the corners run counter-clockwise (x right, z up).
    const double turn = signedArea(floor) > 0.0 ? 1.0 : -1.0;
    for (size_t i = 0; i < floor.size(); ++i) {
        const glm::dvec2 a = floor[i], b = floor[(i + 1) % floor.size()];
        const double length = glm::length(b - a);
        const glm::dvec2 d = (b - a) / length;
        const glm::dvec3 along(d.x, 0.0, d.y), inward(-turn * d.y, 0.0, turn * d.x);
        Mesh wall = surfaceMesh(name + ": wall " + std::to_string(i + 1), room.wallReflectances[i],
                                MeshShape::Plane, scene);
        std::vector<glm::dvec2> outline = {
            {0.0, 0.0}, {length, 0.0}, {length, height}, {0.0, height}};
        appendFlat(wall, tessellate(outline, holes.walls[i]), glm::dvec3(a.x, elevation, a.y),
                   along, up, inward);
        keepMesh(std::move(wall), scene);
    }
}

const std::vector<FurnitureType>& furnitureTypes() {
    // Sizes of common office and school furniture; reflectances of light wood and laminate
    // (the desk's within EN 12464-1's advice of 0.2 to 0.6 for work surfaces).
    static const std::vector<FurnitureType> types = {
        {"desk", "Desk", {1.6, 0.75, 0.8}, 0.5},
        {"table", "Table", {1.8, 0.75, 0.9}, 0.5},
        {"chair", "Chair", {0.45, 0.85, 0.5}, 0.3},
        {"cabinet", "Cabinet", {0.8, 1.2, 0.45}, 0.5},
        {"shelf", "Shelf", {0.9, 2.0, 0.35}, 0.5},
        {"partition", "Partition", {1.6, 1.5, 0.05}, 0.6},
    };
    return types;
}

namespace {

/// A furniture part: a box's centre and half sizes in the piece's own frame (origin at the middle
/// of its footprint on the floor), m.
struct Part {
    glm::dvec3 center, half;
};

std::vector<Part> furnitureParts(const std::string& type, const glm::dvec3& s) {
    const double w = s.x, h = s.y, d = s.z;
    std::vector<Part> parts;
    auto box = [&parts](glm::dvec3 lo, glm::dvec3 hi) {
        parts.push_back({0.5 * (lo + hi), 0.5 * (hi - lo)});
    };
    auto legs = [&](double leg, double top) {
        for (double sx : {-1.0, 1.0})
            for (double sz : {-1.0, 1.0}) {
                glm::dvec3 c(sx * (0.5 * w - 0.5 * leg), 0.0, sz * (0.5 * d - 0.5 * leg));
                box({c.x - 0.5 * leg, 0.0, c.z - 0.5 * leg},
                    {c.x + 0.5 * leg, top, c.z + 0.5 * leg});
            }
    };
    if (type == "desk" || type == "table") {
        const double t = std::min(0.03, 0.2 * h), leg = std::min(0.05, 0.2 * std::min(w, d));
        box({-0.5 * w, h - t, -0.5 * d}, {0.5 * w, h, 0.5 * d});
        legs(leg, h - t);
    } else if (type == "chair") {
        // The seat at 0.53 of the height (0.45 m of 0.85 m), the back along +z.
        const double seat = 0.53 * h, t = std::min(0.04, 0.1 * h);
        const double leg = std::min(0.04, 0.15 * std::min(w, d)), back = std::min(0.03, 0.1 * d);
        box({-0.5 * w, seat - t, -0.5 * d}, {0.5 * w, seat, 0.5 * d});
        legs(leg, seat - t);
        box({-0.5 * w, seat, 0.5 * d - back}, {0.5 * w, h, 0.5 * d});
    } else if (type == "shelf") {
        const double b = std::min(0.02, 0.05 * std::min(w, h));
        box({-0.5 * w, 0.0, -0.5 * d}, {-0.5 * w + b, h, 0.5 * d});
        box({0.5 * w - b, 0.0, -0.5 * d}, {0.5 * w, h, 0.5 * d});
        box({-0.5 * w + b, 0.0, 0.5 * d - b}, {0.5 * w - b, h, 0.5 * d});
        // A board every 0.4 m or so, the lowest on the floor and the highest on top.
        const int boards = std::max(2, int(std::lround(h / 0.4))) + 1;
        for (int k = 0; k < boards; ++k) {
            double y = (h - b) * double(k) / double(boards - 1);
            box({-0.5 * w + b, y, -0.5 * d}, {0.5 * w - b, y + b, 0.5 * d - b});
        }
    } else {  // cabinet, partition: one solid block
        box({-0.5 * w, 0.0, -0.5 * d}, {0.5 * w, h, 0.5 * d});
    }
    return parts;
}

}  // namespace

FurnitureSpec readFurniture(const nlohmann::json& item, const json::Where& where, size_t index) {
    json::checkKeys(item, {"furniture"}, where);
    const json::Where at = where / "furniture";
    const nlohmann::json& spec = item["furniture"];
    json::checkKeys(spec, {"type", "name", "position", "rotate_y_deg", "size", "reflectance"}, at);
    std::string names;
    for (const FurnitureType& t : furnitureTypes())
        names += (names.empty() ? "\"" : ", \"") + std::string(t.name) + "\"";
    if (!spec.contains("type")) json::fail(at / "type", "one of " + names + " (missing)");
    FurnitureSpec f;
    f.type = json::string(spec["type"], at / "type");
    auto known = std::find_if(furnitureTypes().begin(), furnitureTypes().end(),
                              [&f](const FurnitureType& t) { return f.type == t.name; });
    if (known == furnitureTypes().end())
        json::fail(at / "type", "one of " + names + ", got \"" + f.type + "\"");
    f.name = json::optional(spec, "name", at,
                            std::string(known->label) + " " + std::to_string(index), json::string);
    f.position = json::optional(spec, "position", at, glm::dvec3(0.0), json::point);
    f.rotateYDeg =
        json::optional(spec, "rotate_y_deg", at, 0.0,
                       json::range(-json::kMaxAngleDeg, json::kMaxAngleDeg, "an angle in degrees"));
    f.size = known->size;
    if (spec.contains("size")) {
        f.size = json::vec3(spec["size"], at / "size");
        for (int k = 0; k < 3; ++k)
            if (!(f.size[k] > 0.0 && f.size[k] <= json::kMaxMetres))
                json::fail((at / "size")[k], "a positive size in metres (width, height, depth)");
    }
    f.reflectance =
        json::optional(spec, "reflectance", at, glm::dvec3(known->reflectance), reflectanceValue);
    return f;
}

namespace {

glm::dmat3 furnitureRotation(const FurnitureSpec& f) {
    return glm::dmat3(
        glm::rotate(glm::dmat4(1.0), glm::radians(f.rotateYDeg), glm::dvec3(0.0, 1.0, 0.0)));
}

}  // namespace

std::vector<glm::dvec2> FurnitureSpec::footprint() const {
    const glm::dmat3 rotation = furnitureRotation(*this);
    std::vector<glm::dvec2> corners;
    for (glm::dvec2 c :
         {glm::dvec2(-1, -1), glm::dvec2(1, -1), glm::dvec2(1, 1), glm::dvec2(-1, 1)}) {
        const glm::dvec3 p =
            position + rotation * glm::dvec3(0.5 * c.x * size.x, 0.0, 0.5 * c.y * size.z);
        corners.push_back({p.x, p.z});
    }
    return corners;
}

void parseFurniture(const nlohmann::json& item, const json::Where& where, size_t index,
                    Scene& scene) {
    const FurnitureSpec f = readFurniture(item, where, index);
    const std::vector<Part> parts = furnitureParts(f.type, f.size);
    Mesh mesh = surfaceMesh(f.name, f.reflectance,
                            parts.size() == 1 ? MeshShape::Convex : MeshShape::General, scene);
    const glm::dmat3 rotation = furnitureRotation(f);
    for (const Part& p : parts) appendBox(mesh, f.position + rotation * p.center, p.half, rotation);
    keepMesh(std::move(mesh), scene);
}

std::optional<RoomSpec> roomSpec(const Scene& scene, size_t index) {
    const nlohmann::json& source = scene.geometry.at(index).source;
    if (!source.contains("room")) return std::nullopt;
    return readRoom(source, json::Where{scene.path, "geometry"}[index]);
}

std::optional<FurnitureSpec> furnitureSpec(const Scene& scene, size_t index) {
    const nlohmann::json& source = scene.geometry.at(index).source;
    if (!source.contains("furniture")) return std::nullopt;
    return readFurniture(source, json::Where{scene.path, "geometry"}[index], index);
}

}  // namespace candela
