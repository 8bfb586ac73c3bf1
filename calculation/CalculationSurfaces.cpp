// EN 12464-1 calculation surfaces (calculation/CalculationSurfaces.h): the grid rule, the immediate
// surroundings and backgrounds laid out around each task area, and their evaluation through
// computeReceivers with one interreflection solution for all of them.
#include "calculation/CalculationSurfaces.h"

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

const char* verdictText(Verdict verdict) {
    switch (verdict) {
        case Verdict::Pass:
            return "PASS";
        case Verdict::Fail:
            return "FAIL";
        case Verdict::NoRequirement:
            return "no requirement";
        case Verdict::NoPoints:
            return "no points";
    }
    return "?";
}

namespace {

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

double surroundingCell(const glm::dvec2& size) {
    if (!(size.x > 0.0) || !(size.y > 0.0)) return 0.0;
    return std::min(standardGridCell(size.x, size.y), kSurroundingBand / 3.0);
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
                    a.lo, a.hi, surroundingCell(sHi - sLo));
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

NodeGrid surfaceNodes(const SurfaceResult& s) {
    NodeGrid g;
    if (s.cells.x < 1 || s.cells.y < 1) return g;
    g.nx = s.cells.x, g.ny = s.cells.y;
    g.spacing = s.spacing;
    g.origin = s.lo + 0.5 * s.spacing;
    g.values.assign(size_t(g.nx) * size_t(g.ny), std::nan(""));
    // Each point's cell from its position (points sit at the cells' centres, so rounding finds it
    // whatever the floating-point error of the layout).
    for (size_t k = 0; k < s.points.size() && k < s.E.size(); ++k) {
        glm::dvec2 at = (s.points[k] - g.origin) / s.spacing;
        int i = int(std::lround(at.x)), j = int(std::lround(at.y));
        if (i >= 0 && i < g.nx && j >= 0 && j < g.ny)
            g.values[size_t(j) * size_t(g.nx) + size_t(i)] = s.E[k];
    }
    return g;
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
        // surroundings) has nothing to judge: "no points", neither met nor failed.
        if (s.summary.count == 0)
            s.verdict = Verdict::NoPoints;
        else if (!s.required.any())
            s.verdict = Verdict::NoRequirement;
        else
            s.verdict = s.summary.eAvg >= s.required.em && s.summary.u0 >= s.required.u0
                            ? Verdict::Pass
                            : Verdict::Fail;
        s.passes = s.verdict != Verdict::Fail;
        anyLux = anyLux || s.required.em > 0.0;
    }
    for (const CalcPoint& p : scene.calcPoints) {
        PointResult r;
        r.point = p;
        take(p.cylindrical, r.E, r.stdError, r.initial);
        r.verdict = p.requiredLux <= 0.0   ? Verdict::NoRequirement
                    : r.E >= p.requiredLux ? Verdict::Pass
                                           : Verdict::Fail;
        r.passes = r.verdict != Verdict::Fail;
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
