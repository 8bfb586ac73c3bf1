// EN 12464-1 calculation surfaces (scene/CalculationSurfaces.h): the grid rule, the immediate
// surroundings and backgrounds laid out around each task area, and their evaluation through
// computeReceivers with one interreflection solution for all of them.
#include "scene/CalculationSurfaces.h"

#include <algorithm>
#include <cmath>

#include "luminaires/Units.h"
#include "scene/Scene.h"
#include "shaders/shared/Constants.h"
#include "util/Error.h"

namespace candela {

double standardGridCell(double a, double b) {
    double longer = std::max(a, b), shorter = std::min(a, b);
    double d = longer >= 2.0 * shorter ? shorter : longer;
    return std::min(10.0, 0.2 * std::pow(5.0, std::log10(d)));
}

int standardPointCount(double length, double p) {
    // 1e-9 keeps an exact multiple (1.6 m at 0.2 m: 8 cells) from becoming one more.
    return std::max(1, int(std::ceil(length / p - 1e-9)));
}

double surroundingIlluminance(double taskLux) {
    if (taskLux >= 750.0) return 500.0;
    if (taskLux >= 500.0) return 300.0;
    if (taskLux >= 300.0) return 200.0;
    if (taskLux >= 200.0) return 150.0;
    return taskLux;
}

namespace {

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

/// The scene's bounds on the plane (u, v), or an unbounded rectangle without geometry.
void roomExtent(const Scene& scene, const CalcPlane& plane, glm::dvec2& lo, glm::dvec2& hi) {
    GridSpec spec;
    spec.plane = plane;
    try {
        defaultGridExtent(scene, spec);
        lo = spec.lo;
        hi = spec.hi;
    } catch (const InputError&) {
        lo = glm::dvec2(-1e30);
        hi = glm::dvec2(1e30);
    }
}

/// A surface gridded over lo..hi with cells of at most `cell` (0: the standard's rule), less the
/// points inside the hole.
SurfaceResult gridded(std::string name, std::string role, const CalcPlane& plane, glm::dvec2 lo,
                      glm::dvec2 hi, glm::dvec2 holeLo, glm::dvec2 holeHi, double cell) {
    SurfaceResult s;
    s.name = std::move(name);
    s.role = std::move(role);
    s.plane = plane;
    s.lo = lo, s.hi = hi, s.holeLo = holeLo, s.holeHi = holeHi;
    glm::dvec2 size = hi - lo;
    if (!(size.x > 0.0) || !(size.y > 0.0)) return s;
    double p = cell > 0.0 ? cell : standardGridCell(size.x, size.y);
    s.cells = glm::ivec2(standardPointCount(size.x, p), standardPointCount(size.y, p));
    s.spacing = size / glm::dvec2(s.cells);
    bool hole = holeHi.x > holeLo.x && holeHi.y > holeLo.y;
    for (int j = 0; j < s.cells.y; ++j)
        for (int i = 0; i < s.cells.x; ++i) {
            glm::dvec2 q = lo + (glm::dvec2(i, j) + 0.5) * s.spacing;
            bool inside = q.x > holeLo.x && q.x < holeHi.x && q.y > holeLo.y && q.y < holeHi.y;
            if (!(hole && inside)) s.points.push_back(q);
        }
    return s;
}

}  // namespace

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

std::vector<SurfaceResult> layoutSurfaces(const Scene& scene) {
    std::vector<SurfaceResult> out;
    for (const TaskArea& a : scene.taskAreas) {
        SurfaceResult task = gridded(a.name, "task area", a.plane, a.lo, a.hi, {}, {}, a.spacing);
        task.required = a.required;
        task.cylindrical = a.cylindrical;
        if (a.cylindrical) task.role = "cylindrical task area";
        out.push_back(std::move(task));
        if (!a.surroundings) continue;
        glm::dvec2 roomLo, roomHi;
        roomExtent(scene, a.plane, roomLo, roomHi);
        // The immediate surrounding stays inside the room; the background also keeps out of
        // the band along the walls (the standard excludes it unless a task area reaches it).
        glm::dvec2 sLo = glm::max(a.lo - kSurroundingBand, roomLo);
        glm::dvec2 sHi = glm::min(a.hi + kSurroundingBand, roomHi);
        SurfaceResult surrounding =
            gridded(a.name + ": immediate surrounding", "immediate surrounding", a.plane, sLo, sHi,
                    a.lo, a.hi, 0.0);
        if (a.required.em > 0.0) surrounding.required.em = surroundingIlluminance(a.required.em);
        surrounding.required.u0 = kSurroundingU0;
        glm::dvec2 bLo = glm::max(sLo - kBackgroundBand, roomLo + kWallBand);
        glm::dvec2 bHi = glm::min(sHi + kBackgroundBand, roomHi - kWallBand);
        SurfaceResult background =
            gridded(a.name + ": background", "background", a.plane, bLo, bHi, sLo, sHi, 0.0);
        if (surrounding.required.em > 0.0)
            background.required.em = kBackgroundShare * surrounding.required.em;
        background.required.u0 = kBackgroundU0;
        out.push_back(std::move(surrounding));
        out.push_back(std::move(background));
    }
    return out;
}

SurfaceReport computeSurfaces(const Scene& scene, const GridSpec& how,
                              const std::function<void(const std::string&)>& status) {
    SurfaceReport report;
    report.surfaces = layoutSurfaces(scene);
    if (report.surfaces.empty() && scene.calcPoints.empty())
        throw InputError((scene.path.empty() ? std::string("the scene") : scene.path) +
                         ": no task_areas or calculation_points to evaluate");
    std::vector<Receiver> receivers;
    auto add = [&](const glm::dvec3& position, const glm::dvec3& normal, bool cylindrical) {
        if (!cylindrical) {
            receivers.push_back({position, normal});
            return;
        }
        for (int k = 0; k < kCylinderAzimuths; ++k) {
            double phi = 2.0 * gpu::kPi * (k + 0.5) / kCylinderAzimuths;
            receivers.push_back({position, {std::cos(phi), 0.0, std::sin(phi)}});
        }
    };
    for (const SurfaceResult& s : report.surfaces)
        for (const glm::dvec2& q : s.points)
            add(s.plane.point(q.x, q.y), s.plane.normal(), s.cylindrical);
    for (const CalcPoint& p : scene.calcPoints) add(p.position, p.normal, p.cylindrical);
    ReceiverResult e = computeReceivers(scene, how, receivers, status);
    report.units = e.units;
    report.maintenance = e.maintenance;
    report.bodies = e.bodies;
    report.light = e.light;
    report.projectFactor = e.projectFactor;
    report.hasIndirect = e.hasIndirect;
    report.indirectNote = e.indirectNote;
    report.patches = e.patches;
    bool anyLux = false;
    size_t next = 0;
    // A point's value and standard error: one receiver's, or the mean of its azimuths'.
    auto take = [&](bool cylindrical, double& value, double& stdError, double& initial) {
        int n = cylindrical ? kCylinderAzimuths : 1;
        double variance = 0.0;
        value = initial = 0.0;
        for (int k = 0; k < n; ++k, ++next) {
            value += e.E[next] / n;
            initial += e.initial[next] / n;
            variance += e.stdError[next] * e.stdError[next] / (double(n) * n);
        }
        stdError = std::sqrt(variance);
    };
    for (SurfaceResult& s : report.surfaces) {
        s.E.resize(s.points.size());
        s.stdError.resize(s.points.size());
        s.initial.resize(s.points.size());
        for (size_t k = 0; k < s.points.size(); ++k)
            take(s.cylindrical, s.E[k], s.stdError[k], s.initial[k]);
        s.summary = summariseGrid(s.E);
        // A surface the room leaves no points of (a task area over the whole floor has no
        // surroundings) has nothing to fail: every output counts it as met, as none.
        s.passes = s.summary.count == 0 ||
                   (s.summary.eAvg >= s.required.em && s.summary.u0 >= s.required.u0);
        anyLux = anyLux || s.required.em > 0.0;
    }
    for (const CalcPoint& p : scene.calcPoints) {
        PointResult r;
        r.point = p;
        take(p.cylindrical, r.E, r.stdError, r.initial);
        r.passes = r.E >= p.requiredLux;
        anyLux = anyLux || p.requiredLux > 0.0;
        report.points.push_back(r);
    }
    if (anyLux && !report.units.photometric)
        throw InputError((scene.path.empty() ? std::string("the scene") : scene.path) +
                         ": requirements are in lx, but this scene's sources are radiometric "
                         "(results in W/m2)");
    return report;
}

}  // namespace candela
