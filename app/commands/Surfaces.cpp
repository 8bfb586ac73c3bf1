// `candela surfaces`: the scene's EN 12464-1 calculation surfaces (task areas, their immediate
// surroundings and backgrounds) and calculation points, computed by
// calculation/CalculationSurfaces.h: a summary per surface checked against its requirement, and
// optionally every point as CSV.
#include <cstdio>

#include "app/commands/Commands.h"
#include "calculation/CalculationSurfaces.h"
#include "scene/SceneIo.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

namespace {

std::string requirementText(const Requirement& r, const char* mean, const char* unit) {
    if (!r.any()) return "-";
    char buf[96];
    if (r.em > 0.0 && r.u0 > 0.0)
        std::snprintf(buf, sizeof buf, "%s >= %g %s, U0 >= %.2f", mean, r.em, unit, r.u0);
    else if (r.em > 0.0)
        std::snprintf(buf, sizeof buf, "%s >= %g %s", mean, r.em, unit);
    else
        std::snprintf(buf, sizeof buf, "U0 >= %.2f", r.u0);
    return buf;
}

void printReport(const SurfaceReport& r) {
    const char* unit = r.units.irradiance();
    std::printf("maintained illuminance E [%s]%s%s\n", unit, r.units.converted ? ", " : "",
                r.units.note().c_str());
    std::printf("%s\n%s\n", r.maintenance.c_str(), r.bodies.c_str());
    std::printf("light: %s\n", r.light.c_str());
    if (r.hasIndirect) std::printf("%s\n", r.indirectNote.c_str());
    int failed = 0;
    for (const SurfaceResult& s : r.surfaces) {
        if (s.cylindrical)
            std::printf("\n%s (%s), cylindrical illuminance at %s m\n", s.name.c_str(),
                        s.role.c_str(), planeText(s.plane).c_str());
        else
            std::printf("\n%s (%s), plane %s (normal %s%s)\n", s.name.c_str(), s.role.c_str(),
                        planeText(s.plane).c_str(), s.plane.sign > 0 ? "+" : "-",
                        s.plane.axisName().c_str());
        std::printf("  area %s %.3f..%.3f m, %s %.3f..%.3f m", s.plane.uName().c_str(), s.lo.x,
                    s.hi.x, s.plane.vName().c_str(), s.lo.y, s.hi.y);
        if (s.holeHi.x > s.holeLo.x)
            std::printf(" less %s %.3f..%.3f m, %s %.3f..%.3f m", s.plane.uName().c_str(),
                        s.holeLo.x, s.holeHi.x, s.plane.vName().c_str(), s.holeLo.y, s.holeHi.y);
        std::printf("\n  grid %d x %d cells of %.3f x %.3f m, %zu points\n", s.cells.x, s.cells.y,
                    s.spacing.x, s.spacing.y, s.points.size());
        if (s.verdict == Verdict::NoPoints) {
            std::printf("  %s (the room leaves no %s)\n", verdictText(s.verdict), s.role.c_str());
            continue;
        }
        const GridSummary& g = s.summary;
        // Cylindrical illuminance is named Ez: Ez,m its mean, as the standard writes it.
        const char* e = s.cylindrical ? "Ez" : "E";
        std::printf("  %sm %.4g %s, U0 %.3f, %smin %.4g %s, %smax %.4g %s\n", e, g.eAvg, unit, g.u0,
                    e, g.eMin, unit, e, g.eMax, unit);
        std::string need = requirementText(s.required, s.cylindrical ? "Ezm" : "Em", unit);
        std::printf("  required: %s: %s\n", need.c_str(), verdictText(s.verdict));
        failed += s.verdict == Verdict::Fail;
    }
    if (!r.points.empty()) std::printf("\ncalculation points\n");
    for (const PointResult& p : r.points) {
        const CalcPoint& c = p.point;
        std::printf("  %s at (%.3f, %.3f, %.3f) m: ", c.name.c_str(), c.position.x, c.position.y,
                    c.position.z);
        if (c.cylindrical)
            std::printf("cylindrical Ez %.4g %s", p.E, unit);
        else
            std::printf("E %.4g %s (normal %.3f, %.3f, %.3f)", p.E, unit, c.normal.x, c.normal.y,
                        c.normal.z);
        if (p.stdError > 0.0) std::printf(", standard error %.2g %s", p.stdError, unit);
        if (c.requiredLux > 0.0) {
            std::printf(", required %g %s: %s", c.requiredLux, unit, verdictText(p.verdict));
            failed += p.verdict == Verdict::Fail;
        }
        std::printf("\n");
    }
    std::printf("\n%d requirement%s not met\n", failed, failed == 1 ? "" : "s");
}

std::string reportCsv(const SurfaceReport& r) {
    std::string unit = r.units.photometric ? "_lx" : "_W_m2";
    // E is maintained; maintenance_factor = E / E_initial, the factor in effect at the point.
    std::string out = "surface,role,x,y,z,E" + unit + ",E_stderr" + unit +
                      ",maintenance_factor,E_initial" + unit + "\n";
    auto quoted = [](const std::string& s) {
        std::string q = "\"";
        for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
        return q + "\"";
    };
    char line[160];
    for (const SurfaceResult& s : r.surfaces)
        for (size_t k = 0; k < s.points.size(); ++k) {
            glm::dvec3 q = s.plane.point(s.points[k].x, s.points[k].y);
            std::snprintf(line, sizeof line, ",%.9g,%.9g,%.9g,%.10g,%.4g,%.6g,%.10g\n", q.x, q.y,
                          q.z, s.E[k], s.stdError[k],
                          effectiveMaintenanceFactor(s.E[k], s.initial[k], r.projectFactor),
                          s.initial[k]);
            out += quoted(s.name) + "," + quoted(s.role) + line;
        }
    for (const PointResult& p : r.points) {
        glm::dvec3 q = p.point.position;
        std::snprintf(line, sizeof line, ",%.9g,%.9g,%.9g,%.10g,%.4g,%.6g,%.10g\n", q.x, q.y, q.z,
                      p.E, p.stdError, effectiveMaintenanceFactor(p.E, p.initial, r.projectFactor),
                      p.initial);
        out += quoted(p.point.name) + "," +
               quoted(p.point.cylindrical ? "cylindrical point" : "point") + line;
    }
    return out;
}

}  // namespace

int cmdSurfaces(const Args& args) {
    std::string scenePath, csvPath;
    GridSpec how;
    LightChoice light;
    CommandLine cli("surfaces");
    cli.argument("scene.json", scenePath, "the scene file (its task areas and calculation points)");
    cli.output("--out", csvPath, "F.csv", "also write every surface's and point's values as CSV");
    cli.renamed("--csv", "--out");
    cli.strictPhotometry();
    declareEvaluation(cli, how, light);
    if (!cli.parse(args)) return 0;
    Scene scene = loadScene(scenePath);
    applyLightChoice(scene, light, how);
    ProtectedInputs inputs(scene.inputFiles());
    checkNotAnInput(csvPath, "--out");
    SurfaceReport report = computeSurfaces(scene, how, [](const std::string& s) {
        std::fprintf(stderr, "surfaces: %s\n", s.c_str());
    });
    printReport(report);
    if (!csvPath.empty()) {
        writeFileAtomically(csvPath, reportCsv(report), "cannot write the CSV file");
        std::printf("wrote %s\n", csvPath.c_str());
    }
    return 0;
}

}  // namespace candela
