// The scene file's measurement entries (scene/Measurements.h): planes, task areas, calculation
// points and glare observers, read with every field checked and written back.
#include "scene/Measurements.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "util/Error.h"

namespace candela {

namespace {

const char* const kAxisNames[] = {"x", "y", "z"};

int uAxis(int axis) {
    return axis == 0 ? 1 : 0;
}
int vAxis(int axis) {
    return axis == 2 ? 1 : 2;
}

/// A background luminance's bounds, cd/m2: darker than any lit interior's (UGR divides by it, and
/// 5e-324 made it infinite) and brighter than the sun's disc.
constexpr double kMinBackground = 1e-3, kMaxBackground = 1e9;

Requirement parseRequirement(const nlohmann::json& v, const json::Where& where) {
    json::checkKeys(v, {"em_lx", "u0"}, where);
    Requirement r;
    r.em = json::optional(v, "em_lx", where, 0.0, json::positive);
    r.u0 = json::optional(v, "u0", where, 0.0, json::positive);
    if (r.u0 > 1.0) json::fail(where / "u0", "a uniformity Emin / Em in (0, 1]");
    return r;
}

glm::dvec3 unit(const glm::dvec3& v) {
    return v / glm::length(v);
}

/// The line of sight made horizontal and unit; fails when it points straight up or down.
glm::dvec3 horizontalView(const glm::dvec3& v, const json::Where& where) {
    glm::dvec3 h(v.x, 0.0, v.z);
    double l = glm::length(h);
    if (!(l > 1e-9 * glm::length(v)))
        json::fail(where,
                   "a line of sight with a horizontal part (UGR's observer looks ahead, "
                   "not straight up or down)");
    return h / l;
}

}  // namespace

glm::dvec3 CalcPlane::normal() const {
    glm::dvec3 n(0.0);
    n[axis] = sign;
    return n;
}

glm::dvec3 CalcPlane::point(double u, double v) const {
    glm::dvec3 p(0.0);
    p[axis] = offset;
    p[uAxis(axis)] = u;
    p[vAxis(axis)] = v;
    return p;
}

glm::dvec2 CalcPlane::inPlane(const glm::dvec3& p) const {
    return {p[uAxis(axis)], p[vAxis(axis)]};
}

std::string CalcPlane::axisName() const {
    return kAxisNames[axis];
}
std::string CalcPlane::uName() const {
    return kAxisNames[uAxis(axis)];
}
std::string CalcPlane::vName() const {
    return kAxisNames[vAxis(axis)];
}

CalcPlane parsePlane(const std::string& text, const std::string& what) {
    CalcPlane plane;
    std::string t = text;
    if (!t.empty() && (t[0] == '+' || t[0] == '-')) {
        plane.sign = t[0] == '-' ? -1.0 : 1.0;
        t = t.substr(1);
    }
    size_t eq = t.find('=');
    std::string axis = t.substr(0, eq);
    auto bad = [&] {
        return InputError(what + ": expected [+|-]x|y|z=VALUE in metres (e.g. y=0.8), got \"" +
                          text + "\"");
    };
    if (eq == std::string::npos || (axis != "x" && axis != "y" && axis != "z")) throw bad();
    plane.axis = axis[0] - 'x';
    std::string value = t.substr(eq + 1);
    auto notFinite = [&] {
        return InputError(what + ": expected a finite number, got \"" + value + "\"");
    };
    try {
        size_t used = 0;
        plane.offset = std::stod(value, &used);
        if (used != value.size() || !std::isfinite(plane.offset)) throw notFinite();
    } catch (const std::logic_error&) {
        throw notFinite();
    }
    return plane;
}

std::string planeText(const CalcPlane& plane) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s%s=%.17g", plane.sign < 0 ? "-" : "", kAxisNames[plane.axis],
                  plane.offset);
    return buf;
}

TaskArea parseTaskArea(const nlohmann::json& entry, const json::Where& where) {
    json::checkKeys(
        entry, {"name", "plane", "extent", "required", "spacing", "surroundings", "illuminance"},
        where);
    TaskArea a;
    a.name = json::optional(entry, "name", where, std::string("task area"), json::string);
    if (!entry.contains("plane"))
        json::fail(where / "plane", "the work plane, e.g. \"y=0.75\"; it is missing");
    a.plane = parsePlane(json::string(entry["plane"], where / "plane"), (where / "plane").str());
    const nlohmann::json* extent = entry.contains("extent") ? &entry["extent"] : nullptr;
    if (!extent || !extent->is_array() || extent->size() != 4)
        json::fail(where / "extent", "[u0, v0, u1, v1] in metres on the plane");
    double e[4];
    for (size_t k = 0; k < 4; ++k)
        e[k] = json::inRange((*extent)[k], (where / "extent")[k], -json::kMaxMetres,
                             json::kMaxMetres, "a coordinate in metres");
    a.lo = {std::min(e[0], e[2]), std::min(e[1], e[3])};
    a.hi = {std::max(e[0], e[2]), std::max(e[1], e[3])};
    if (!(a.hi.x > a.lo.x) || !(a.hi.y > a.lo.y))
        json::fail(where / "extent", "an area (u1 != u0 and v1 != v0), not a line");
    if (entry.contains("required"))
        a.required = parseRequirement(entry["required"], where / "required");
    a.spacing = json::optional(entry, "spacing", where, 0.0, json::length);
    std::string quantity =
        json::optional(entry, "illuminance", where, std::string("planar"), json::string);
    if (quantity != "planar" && quantity != "cylindrical")
        json::fail(where / "illuminance",
                   "\"planar\" (on the plane) or \"cylindrical\", got \"" + quantity + "\"");
    a.cylindrical = quantity == "cylindrical";
    if (a.cylindrical && a.plane.axis != 1)
        json::fail(where / "plane", "a horizontal plane (y=...) for cylindrical illuminance");
    if (a.cylindrical && json::optional(entry, "surroundings", where, false, json::boolean))
        json::fail(where / "surroundings",
                   "none for cylindrical illuminance (Table 1 is for a task's own illuminance)");
    a.surroundings = json::optional(entry, "surroundings", where, !a.cylindrical, json::boolean);
    return a;
}

CalcPoint parseCalcPoint(const nlohmann::json& entry, const json::Where& where) {
    json::checkKeys(entry, {"name", "position", "normal", "type", "required_lx"}, where);
    CalcPoint p;
    p.name = json::optional(entry, "name", where, std::string("point"), json::string);
    if (!entry.contains("position")) json::fail(where / "position", "[x, y, z] in metres");
    p.position = json::point(entry["position"], where / "position");
    std::string type = json::optional(entry, "type", where, std::string("planar"), json::string);
    if (type != "planar" && type != "cylindrical")
        json::fail(where / "type",
                   "\"planar\" (with a normal) or \"cylindrical\", got \"" + type + "\"");
    p.cylindrical = type == "cylindrical";
    if (p.cylindrical && entry.contains("normal"))
        json::fail(where / "normal",
                   "no normal: cylindrical illuminance faces every horizontal way");
    p.normal = unit(json::optional(entry, "normal", where, glm::dvec3(0, 1, 0), json::direction));
    p.requiredLux = json::optional(entry, "required_lx", where, 0.0, json::positive);
    return p;
}

nlohmann::json toJson(const TaskArea& a) {
    nlohmann::json out = {{"name", a.name},
                          {"plane", planeText(a.plane)},
                          {"extent", {a.lo.x, a.lo.y, a.hi.x, a.hi.y}}};
    if (a.required.any()) {
        out["required"] = nlohmann::json::object();
        if (a.required.em > 0.0) out["required"]["em_lx"] = a.required.em;
        if (a.required.u0 > 0.0) out["required"]["u0"] = a.required.u0;
    }
    if (a.spacing > 0.0) out["spacing"] = a.spacing;
    if (a.cylindrical)
        out["illuminance"] = "cylindrical";
    else if (!a.surroundings)
        out["surroundings"] = false;
    return out;
}

nlohmann::json toJson(const CalcPoint& p) {
    nlohmann::json out = {{"name", p.name},
                          {"position", {p.position.x, p.position.y, p.position.z}}};
    if (p.cylindrical)
        out["type"] = "cylindrical";
    else
        out["normal"] = {p.normal.x, p.normal.y, p.normal.z};
    if (p.requiredLux > 0.0) out["required_lx"] = p.requiredLux;
    return out;
}

GlareObserver parseGlareObserver(const nlohmann::json& entry, const json::Where& where) {
    json::checkKeys(entry, {"name", "position", "view", "limit", "background_cd_m2"}, where);
    GlareObserver o;
    o.name = json::optional(entry, "name", where, std::string("observer"), json::string);
    if (!entry.contains("position"))
        json::fail(where / "position", "the eye's [x, y, z] in metres");
    o.position = json::point(entry["position"], where / "position");
    if (!entry.contains("view"))
        json::fail(where / "view", "the line of sight [x, y, z] (horizontal)");
    o.view = horizontalView(json::direction(entry["view"], where / "view"), where / "view");
    o.limit = json::optional(entry, "limit", where, 0.0, json::positive);
    o.background =
        json::optional(entry, "background_cd_m2", where, 0.0,
                       json::range(kMinBackground, kMaxBackground, "a luminance in cd/m2"));
    return o;
}

nlohmann::json toJson(const GlareObserver& o) {
    nlohmann::json out = {{"name", o.name},
                          {"position", {o.position.x, o.position.y, o.position.z}},
                          {"view", {o.view.x, o.view.y, o.view.z}}};
    if (o.limit > 0.0) out["limit"] = o.limit;
    if (o.background > 0.0) out["background_cd_m2"] = o.background;
    return out;
}

}  // namespace candela
