#include "ui/RoomEditing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "scene/Procedural.h"
#include "scene/SceneIo.h"
#include "ui/EditorState.h"
#include "ui/Project.h"
#include "util/Error.h"
#include "util/Polygon.h"

namespace candela::ui {

namespace {

/// A length rounded to a millimetre for the scene file (what a designer types).
double mm(double metres) {
    return std::round(metres * 1000.0) / 1000.0;
}

std::string formatted(const char* format, double value) {
    char text[64];
    std::snprintf(text, sizeof text, format, value);
    return text;
}

/// The scene's geometry entries as written.
std::vector<nlohmann::json> entriesOf(const Scene& scene) {
    std::vector<nlohmann::json> entries;
    for (const GeometryItem& item : scene.geometry) entries.push_back(item.source);
    return entries;
}

/// Builds `entries` into a scene's meshes by the scene file's parser: what the scene's geometry
/// becomes. InputError (naming the entry and field) for anything it refuses.
Scene builtGeometry(const std::vector<nlohmann::json>& entries, const std::string& scenePath) {
    nlohmann::json doc = {{"geometry", entries}};
    return parseScene(doc, scenePath);
}

/// Puts the geometry of `built` in place of the scene's (luminaire bodies follow in applyEdit).
void takeGeometry(Scene& scene, Scene& built) {
    scene.geometry = std::move(built.geometry);
    scene.meshes = std::move(built.meshes);
    scene.materials = std::move(built.materials);
}

}  // namespace

std::vector<glm::dvec2> floorOutline(const RoomDraft& draft) {
    auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
    double w = draft.width, d = draft.depth;
    switch (draft.shape) {
        case RoomShape::Rectangle:
            if (!positive(w) || !positive(d))
                throw InputError("the room's width and depth must be more than 0 m");
            return {{-w / 2, -d / 2}, {w / 2, -d / 2}, {w / 2, d / 2}, {-w / 2, d / 2}};
        case RoomShape::LShape: {
            double nw = draft.notchWidth, nd = draft.notchDepth;
            if (!positive(w) || !positive(d))
                throw InputError("the room's width and depth must be more than 0 m");
            if (!positive(nw) || !positive(nd) || !(nw < w) || !(nd < d))
                throw InputError(
                    "the corner cut from the L must be more than 0 m and less than the room's "
                    "width and depth");
            return {{-w / 2, -d / 2},         {w / 2, -d / 2},     {w / 2, d / 2 - nd},
                    {w / 2 - nw, d / 2 - nd}, {w / 2 - nw, d / 2}, {-w / 2, d / 2}};
        }
        case RoomShape::Polygon: {
            std::string text = draft.polygon;
            std::replace(text.begin(), text.end(), ';', ',');
            std::vector<glm::dvec2> corners;
            std::stringstream all(text);
            std::string corner;
            while (std::getline(all, corner, ',')) {
                if (corner.find_first_not_of(" \t") == std::string::npos) continue;
                std::istringstream in(corner);
                glm::dvec2 p;
                std::string rest;
                if (!(in >> p.x >> p.y) || (in >> rest) || !std::isfinite(p.x) ||
                    !std::isfinite(p.y))
                    throw InputError("corner " + std::to_string(corners.size() + 1) +
                                     " of the floor: two numbers, x and z in metres (got \"" +
                                     corner + "\")");
                corners.push_back(p);
            }
            if (corners.size() < 3)
                throw InputError("the floor needs at least 3 corners, \"x z, x z, x z\" in metres");
            return corners;
        }
    }
    return {};
}

nlohmann::json roomEntry(const RoomDraft& draft) {
    nlohmann::json floor = nlohmann::json::array();
    for (const glm::dvec2& p : floorOutline(draft)) floor.push_back({mm(p.x), mm(p.y)});
    nlohmann::json room = {{"name", draft.name.empty() ? std::string("Room") : draft.name},
                           {"floor", floor},
                           {"height", mm(draft.height)},
                           {"reflectance",
                            {{"floor", draft.floorReflectance},
                             {"walls", draft.wallReflectance},
                             {"ceiling", draft.ceilingReflectance}}}};
    nlohmann::json openings = nlohmann::json::array();
    for (const OpeningDraft& o : draft.openings) {
        if (o.type == "skylight") {
            openings.push_back({{"type", "skylight"},
                                {"center", {mm(o.center.x), mm(o.center.y)}},
                                {"size", {mm(o.size.x), mm(o.size.y)}}});
            continue;
        }
        nlohmann::json e = {{"type", o.type},
                            {"wall", o.wall},
                            {"offset", mm(o.offset)},
                            {"width", mm(o.width)},
                            {"height", mm(o.height)}};
        if (o.type == "window") {
            e["sill"] = mm(o.sill);
            e["glazing"] = o.glazing;
        }
        openings.push_back(e);
    }
    if (!openings.empty()) room["openings"] = openings;
    return {{"room", room}};
}

std::vector<nlohmann::json> furnitureEntries(const RoomDraft& draft) {
    std::vector<nlohmann::json> out;
    for (const FurnitureDraft& f : draft.furniture) {
        nlohmann::json e = {{"type", f.type},
                            {"position", {mm(f.position.x), 0.0, mm(f.position.y)}}};
        if (f.rotateYDeg != 0.0) e["rotate_y_deg"] = f.rotateYDeg;
        out.push_back({{"furniture", e}});
    }
    return out;
}

nlohmann::json taskAreaEntry(const RoomDraft& draft) {
    if (!draft.taskArea || draft.shape == RoomShape::Polygon) return nullptr;
    std::vector<glm::dvec2> outline = floorOutline(draft);
    // The rectangle, or the L's part that spans its whole width.
    glm::dvec2 lo(-draft.width / 2, -draft.depth / 2), hi(draft.width / 2, draft.depth / 2);
    if (draft.shape == RoomShape::LShape) hi.y -= draft.notchDepth;
    double band = std::max(0.0, draft.wallBand);
    lo += band;
    hi -= band;
    if (!(hi.x > lo.x) || !(hi.y > lo.y))
        throw InputError("the band along the walls leaves no task area");
    nlohmann::json area = {{"name", draft.name.empty() ? std::string("Room") : draft.name},
                           {"plane", "y=" + formatted("%g", mm(draft.workPlane))},
                           {"extent", {mm(lo.x), mm(lo.y), mm(hi.x), mm(hi.y)}}};
    nlohmann::json required = nlohmann::json::object();
    if (draft.requiredEm > 0.0) required["em_lx"] = draft.requiredEm;
    if (draft.requiredU0 > 0.0) required["u0"] = draft.requiredU0;
    if (!required.empty()) area["required"] = required;
    return area;
}

nlohmann::json newSceneDocument(const RoomDraft& draft) {
    nlohmann::json doc = nlohmann::json::object();
    nlohmann::json project = nlohmann::json::object();
    const ProjectInfo& p = draft.project;
    for (auto [key, value] : {std::pair<const char*, const std::string*>{"name", &p.name},
                              {"client", &p.client},
                              {"designer", &p.designer},
                              {"date", &p.date},
                              {"description", &p.description}})
        if (!value->empty()) project[key] = *value;
    if (!project.empty()) doc["project"] = project;
    nlohmann::json geometry = nlohmann::json::array({roomEntry(draft)});
    for (nlohmann::json& f : furnitureEntries(draft)) geometry.push_back(std::move(f));
    doc["geometry"] = geometry;
    doc["maintenance_factor"] = draft.maintenanceFactor;
    // In the corner nearest -x, +z at eye height, looking across to the opposite corner.
    std::vector<glm::dvec2> outline = floorOutline(draft);
    glm::dvec2 lo(1e300), hi(-1e300);
    for (const glm::dvec2& q : outline) lo = glm::min(lo, q), hi = glm::max(hi, q);
    glm::dvec2 corner(lo.x, hi.y), across(hi.x, lo.y);
    glm::dvec2 inward = glm::normalize(across - corner);
    glm::dvec2 eye = corner + inward * std::min(0.6, 0.2 * glm::length(across - corner));
    double eyeHeight = std::min(1.7, 0.6 * draft.height);
    doc["camera"] = {{"position", {mm(eye.x), mm(eyeHeight), mm(eye.y)}},
                     {"target", {mm(across.x), mm(0.35 * draft.height), mm(across.y)}},
                     {"fov_deg", 70}};
    nlohmann::json area = taskAreaEntry(draft);
    if (!area.is_null()) doc["task_areas"] = nlohmann::json::array({area});
    return doc;
}

std::string roomDraftSummary(const RoomDraft& draft, bool& valid) {
    valid = false;
    try {
        nlohmann::json doc = newSceneDocument(draft);
        Scene scene = parseScene(doc, "room");
        std::vector<glm::dvec2> outline = floorOutline(draft);
        double area = std::abs(signedArea(outline));
        valid = true;
        std::string out = formatted("%.1f m² floor, ", area) + std::to_string(outline.size()) +
                          " walls, " + formatted("%.2f m high, ", draft.height) +
                          formatted("%.0f m³", area * draft.height);
        if (!draft.openings.empty())
            out += "; " + std::to_string(draft.openings.size()) +
                   (draft.openings.size() == 1 ? " opening" : " openings");
        if (!draft.furniture.empty())
            out += "; " + std::to_string(draft.furniture.size()) + " furniture";
        return out;
    } catch (const std::exception& e) {
        std::string what = e.what();
        // "room: geometry[0].room.floor: ..." reads better without the made-up file name.
        if (what.rfind("room: ", 0) == 0) what = what.substr(6);
        return what;
    }
}

bool newSceneFromRoom(EditorState& state, const RoomDraft& draft) {
    try {
        Scene scene = parseScene(newSceneDocument(draft), "");
        takeScene(state, std::move(scene));
        state.scene.path.clear();
        state.dirty = true;  // nothing of it is on disk yet
        ++state.edits;
        state.project.onDisk.clear();
        state.project.conflict = false;
        state.project.offers.clear();
        setStatus(state, "New scene: " + draft.name + " (untitled until saved)");
        return true;
    } catch (const std::exception& e) {
        reportError(state, std::string("Cannot make the room: ") + e.what());
        return false;
    }
}

bool addRoom(EditorState& state, const RoomDraft& draft) {
    try {
        std::vector<nlohmann::json> entries = entriesOf(state.scene);
        entries.push_back(roomEntry(draft));
        for (nlohmann::json& f : furnitureEntries(draft)) entries.push_back(std::move(f));
        Scene built = builtGeometry(entries, state.scene.path);
        std::vector<TaskArea> areas;
        nlohmann::json area = taskAreaEntry(draft);
        if (!area.is_null()) {
            // Parsed by the scene file's parser too, through a one-area document.
            Scene withArea = parseScene({{"task_areas", nlohmann::json::array({area})}}, "room");
            areas = withArea.taskAreas;
        }
        applyEdit(state, "Add room " + draft.name, kChangeGeometry, [&](Scene& s) {
            takeGeometry(s, built);
            for (TaskArea& a : areas) s.taskAreas.push_back(a);
        });
        state.selectedGeometry = -1;
        setStatus(state, "Added room " + draft.name);
        return true;
    } catch (const std::exception& e) {
        reportError(state, std::string("Cannot add the room: ") + e.what());
        return false;
    }
}

int addFurniture(EditorState& state, const std::string& type, glm::dvec2 at, double floorY) {
    const FurnitureType* known = nullptr;
    for (const FurnitureType& t : furnitureTypes())
        if (type == t.name) known = &t;
    if (!known) {
        reportError(state, "Unknown furniture \"" + type + "\"");
        return -1;
    }
    try {
        std::vector<nlohmann::json> entries = entriesOf(state.scene);
        entries.push_back(
            {{"furniture", {{"type", type}, {"position", {mm(at.x), mm(floorY), mm(at.y)}}}}});
        Scene built = builtGeometry(entries, state.scene.path);
        applyEdit(state, std::string("Add ") + known->label, kChangeGeometry,
                  [&](Scene& s) { takeGeometry(s, built); });
        state.selectedLuminaire = -1;
        state.alsoSelected.clear();
        state.selectedGeometry = int(state.scene.geometry.size()) - 1;
        return state.selectedGeometry;
    } catch (const std::exception& e) {
        reportError(state, e.what());
        return -1;
    }
}

bool addOpening(EditorState& state, int geometryIndex, const OpeningDraft& opening) {
    if (geometryIndex < 0 || geometryIndex >= int(state.scene.geometry.size())) return false;
    nlohmann::json entry = state.scene.geometry[size_t(geometryIndex)].source;
    if (!entry.is_object() || !entry.contains("room") || !entry["room"].is_object()) {
        reportError(state, "Openings go into a room: select a room in the outline");
        return false;
    }
    RoomDraft one;
    one.openings = {opening};
    // The draft's room entry writes the opening as the scene file does.
    nlohmann::json written = roomEntry(one)["room"]["openings"][0];
    nlohmann::json& openings = entry["room"]["openings"];
    if (!openings.is_array()) openings = nlohmann::json::array();
    openings.push_back(written);
    std::string label = "Add " + opening.type;
    if (!replaceGeometryEntry(state, geometryIndex, entry, label)) {
        reportError(state, "Cannot add the " + opening.type + ": " + state.inspectorError);
        return false;
    }
    return true;
}

bool replaceGeometryEntry(EditorState& state, int index, const nlohmann::json& entry,
                          const std::string& label) {
    if (index < 0 || index >= int(state.scene.geometry.size())) return false;
    if (entry == state.scene.geometry[size_t(index)].source) return false;
    try {
        std::vector<nlohmann::json> entries = entriesOf(state.scene);
        entries[size_t(index)] = entry;
        Scene built = builtGeometry(entries, state.scene.path);
        applyEdit(state, label, kChangeGeometry, [&](Scene& s) { takeGeometry(s, built); });
        state.inspectorError.clear();
        return true;
    } catch (const std::exception& e) {
        state.inspectorError = e.what();
        return false;
    }
}

bool removeGeometryEntry(EditorState& state, int index) {
    if (index < 0 || index >= int(state.scene.geometry.size())) return false;
    try {
        std::vector<nlohmann::json> entries = entriesOf(state.scene);
        entries.erase(entries.begin() + index);
        Scene built = builtGeometry(entries, state.scene.path);
        applyEdit(state, "Delete geometry", kChangeGeometry,
                  [&](Scene& s) { takeGeometry(s, built); });
        state.selectedGeometry = -1;
        return true;
    } catch (const std::exception& e) {
        reportError(state, e.what());
        return false;
    }
}

std::optional<double> roomFloorAt(const Scene& scene, glm::dvec2 xz) {
    for (const GeometryItem& item : scene.geometry) {
        const nlohmann::json& src = item.source;
        if (!src.is_object() || !src.contains("room")) continue;
        const nlohmann::json& room = src["room"];
        std::vector<glm::dvec2> outline;
        for (const nlohmann::json& c : room["floor"])
            outline.push_back({c[0].get<double>(), c[1].get<double>()});
        if (!insidePolygon(outline, xz)) continue;
        return room.contains("elevation") ? room["elevation"].get<double>() : 0.0;
    }
    return std::nullopt;
}

namespace {

/// The BVH of the scene's own surfaces, without the luminaires' bodies (a luminaire's distance to
/// the walls must not stop at its own housing), cached until the geometry changes.
const Bvh& wallsBvh(EditorState& state) {
    PlacementUi& p = state.placement;
    if (!p.walls || p.wallsVersion != state.geometryVersion) {
        Scene surfaces;
        surfaces.materials = state.scene.materials;
        for (const Mesh& m : state.scene.meshes)
            if (!m.luminaireBody) surfaces.meshes.push_back(m);
        p.walls = std::make_shared<const Bvh>(Bvh::build(surfaces));
        p.wallsVersion = state.geometryVersion;
    }
    return *p.walls;
}

}  // namespace

std::optional<double> floorBelow(EditorState& state, const glm::dvec3& point) {
    if (std::optional<double> floor = roomFloorAt(state.scene, {point.x, point.z})) return floor;
    std::optional<BvhHit> hit = wallsBvh(state).closestHit(point, {0.0, -1.0, 0.0});
    if (!hit) return std::nullopt;
    return hit->point.y;
}

std::optional<double> clearDistance(EditorState& state, const glm::dvec3& point,
                                    const glm::dvec3& dir) {
    std::optional<BvhHit> hit = wallsBvh(state).closestHit(point, dir);
    if (!hit) return std::nullopt;
    return hit->t;
}

}  // namespace candela::ui
