// `candela grid`: illuminance on a calculation grid over an axis-aligned plane, with its summary
// (Emin, Eavg, Emax, U0 = Emin / Eavg, Emin / Emax), computed by calculation/CalculationGrid.h,
// printed as a table and optionally written as CSV.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/commands/Commands.h"
#include "calculation/CalculationGrid.h"
#include "scene/SceneIo.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

namespace {

double parseFinite(const std::string& flag, const std::string& text) {
    try {
        size_t used = 0;
        double v = std::stod(text, &used);
        if (used == text.size() && std::isfinite(v)) return v;
    } catch (const std::exception&) {
    }
    throw InputError(flag + ": expected a finite number, got \"" + text + "\"");
}

/// "x0,v0,x1,v1" in metres.
void parseExtent(const std::string& text, GridSpec& spec) {
    std::vector<double> values;
    size_t start = 0;
    while (true) {
        size_t comma = text.find(',', start);
        values.push_back(parseFinite("--extent", text.substr(start, comma - start)));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    if (values.size() != 4)
        throw InputError("--extent: expected u0,v0,u1,v1 (four numbers in metres), got \"" + text +
                         "\"");
    spec.lo = {std::min(values[0], values[2]), std::min(values[1], values[3])};
    spec.hi = {std::max(values[0], values[2]), std::max(values[1], values[3])};
}

void printGrid(const GridResult& r, const GridSummary& s) {
    const GridSpec& g = r.spec;
    const CalcPlane& p = g.plane;
    std::printf(
        "plane %s = %g m (normal %s%s), extent %s %g..%g m, %s %g..%g m, spacing %g m, "
        "%zu x %zu points\n",
        p.axisName().c_str(), p.offset, p.sign > 0 ? "+" : "-", p.axisName().c_str(),
        p.uName().c_str(), g.lo.x, g.hi.x, p.vName().c_str(), g.lo.y, g.hi.y, g.spacing, r.u.size(),
        r.v.size());
    const UnitSystem& units = r.units;
    std::printf("%s E [%s]%s%s; rows %s [m], columns %s [m]\n",
                units.photometric ? "illuminance" : "irradiance", units.irradiance(),
                units.converted ? ", " : "", units.note().c_str(), p.vName().c_str(),
                p.uName().c_str());
    std::printf("%s\n%s\nlight: %s\n", r.maintenance.c_str(), r.bodies.c_str(), r.light.c_str());
    std::printf("%7s\\%s", p.vName().c_str(), p.uName().c_str());
    for (double u : r.u) std::printf(" %9.3f", u);
    std::printf("\n");
    for (size_t j = 0; j < r.v.size(); ++j) {
        std::printf("%9.3f", r.v[j]);
        for (size_t i = 0; i < r.u.size(); ++i) std::printf(" %9.4g", r.E[j * r.u.size() + i]);
        std::printf("\n");
    }
    std::printf("points: %zu\n", s.count);
    const char* unit = units.irradiance();
    std::printf("Emin: %.6g %s\nEavg: %.6g %s\nEmax: %.6g %s\n", s.eMin, unit, s.eAvg, unit, s.eMax,
                unit);
    std::printf("U0 (Emin/Eavg): %.4f\nEmin/Emax: %.4f\n", s.u0, s.minOverMax);
    if (!r.hasIndirect) return;
    // Em (the mean) and U0 of each part, as design tools report them.
    auto part = [&](const char* name, const std::vector<double>& values) {
        GridSummary p = summariseGrid(values);
        std::printf("%-15s Emin %.6g %s, Em %.6g %s, Emax %.6g %s, U0 %.4f\n", name, p.eMin, unit,
                    p.eAvg, unit, p.eMax, unit, p.u0);
    };
    part("direct:", r.direct);
    part("interreflected:", r.indirect);
    part("total:", r.E);
    std::printf("%s\n", r.indirectNote.c_str());
}

std::string gridCsv(const GridResult& r) {
    // The unit is in the column names: _lx, or _W_m2 for a radiometric scene.
    std::string unit = r.units.photometric ? "_lx" : "_W_m2";
    // E is maintained: maintenance_factor is the factor in effect at the point (E over
    // E_initial, which differ between points only where luminaires have their own factors).
    std::string out =
        "x,y,z,E" + unit + ",E_stderr" + unit + ",maintenance_factor,E_initial" + unit;
    if (r.hasIndirect)
        out += ",E_direct" + unit + ",E_direct_stderr" + unit + ",E_indirect" + unit +
               ",E_indirect_stderr" + unit;
    out += "\n";
    char line[160];
    for (size_t j = 0; j < r.v.size(); ++j)
        for (size_t i = 0; i < r.u.size(); ++i) {
            glm::dvec3 q = r.spec.plane.point(r.u[i], r.v[j]);
            size_t k = j * r.u.size() + i;
            std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g,%.10g,%.4g,%.6g,%.10g", q.x, q.y, q.z,
                          r.E[k], r.stdError[k],
                          effectiveMaintenanceFactor(r.E[k], r.initial[k], r.projectFactor),
                          r.initial[k]);
            out += line;
            if (r.hasIndirect) {
                std::snprintf(line, sizeof line, ",%.10g,%.4g,%.10g,%.4g", r.direct[k],
                              r.directStdError[k], r.indirect[k], r.indirectStdError[k]);
                out += line;
            }
            out += "\n";
        }
    return out;
}

}  // namespace

void writeGridCsv(const std::string& path, const GridResult& r) {
    writeFileAtomically(path, gridCsv(r), "cannot write the CSV file");
}

void declareEvaluation(CommandLine& cli, GridSpec& how, LightChoice& light) {
    cli.group("how the light is computed (grid, surfaces and report alike)");
    cli.option("--light", "total|direct",
               "total: direct light with shadows and interreflected light, wherever the scene "
               "calls for them (the default); direct: the direct light alone",
               [&light](const std::string& m) {
                   if (m != "total" && m != "direct")
                       throw InputError(
                           "--light: expected total (direct light with shadows and "
                           "interreflected light, the default) or direct, got \"" +
                           m + "\"");
                   light.interreflection = m == "total";
                   light.insist = false;
               });
    cli.flag("--no-shadows", light.shadows,
             "leave shadows out (every luminaire lights every point; the output says so)", false);
    cli.flag("--visibility", light.shadows, "shadows wherever the scene casts them (the default)");
    cli.flag("--indirect", "interreflected light even where the scene would not call for it",
             [&light] { light.interreflection = light.insist = true; });
    cli.integer("--spp", how.spp, 1, 1 << 24, "N",
                "samples per point and luminaire of the stochastic techniques (1024)");
    cli.text("--technique", how.technique, "T",
             "one technique for every luminaire (default: each luminaire's own)");
    cli.text(
        "--env-technique", how.environmentTechnique, "T",
        "the environment's technique (default: --technique's when it names one, else the exact "
        "reference)");
    cli.integer("--patches", how.patches, 16, 50000, "N",
                "about this many patches for the interreflection (1500)");
    cli.option(
        "--indirect-method", "adaptive|gather|patches",
        "how interreflected light reaches the points (adaptive)", [&how](const std::string& m) {
            if (m == "adaptive")
                how.indirectMethod = GridSpec::Indirect::Adaptive;
            else if (m == "gather")
                how.indirectMethod = GridSpec::Indirect::Gather;
            else if (m == "patches")
                how.indirectMethod = GridSpec::Indirect::Patches;
            else
                throw InputError("--indirect-method: expected adaptive, gather or patches, got \"" +
                                 m + "\"");
        });
}

int cmdGrid(const Args& args) {
    std::string scenePath, csvPath;
    GridSpec spec;
    LightChoice light;
    CommandLine cli("grid");
    cli.argument("scene.json", scenePath, "the scene file");
    cli.option("--plane", "[+|-]x|y|z=VALUE", "the grid's plane, metres (y=0.8 faces up)",
               [&spec](const std::string& v) { spec.plane = parsePlane(v, "--plane"); });
    cli.option("--extent", "U0,V0,U1,V1",
               "the grid's rectangle on the plane, metres (default: the scene's floor)",
               [&spec](const std::string& v) { parseExtent(v, spec); });
    cli.option("--spacing", "METRES", "between adjacent points (0.25)",
               [&spec](const std::string& v) { spec.spacing = parseFinite("--spacing", v); });
    cli.output("--out", csvPath, "F.csv", "also write every point's illuminance as CSV");
    cli.renamed("--csv", "--out");
    cli.strictPhotometry();
    declareEvaluation(cli, spec, light);
    if (!cli.parse(args)) return 0;
    if (!cli.given("--plane"))
        throw CommandUsageError("missing --plane (the grid's plane, e.g. y=0.8)", cli.shortHelp());
    bool haveExtent = cli.given("--extent");
    if (!(spec.spacing > 0.0))
        throw InputError("--spacing: expected a positive number of metres, got " +
                         std::to_string(spec.spacing));
    Scene scene = loadScene(scenePath);
    ProtectedInputs inputs(scene.inputFiles());
    checkNotAnInput(csvPath, "--out");
    if (!haveExtent) defaultGridExtent(scene, spec);
    applyLightChoice(scene, light, spec);
    GridResult result = computeGrid(
        scene, spec, [](const std::string& s) { std::fprintf(stderr, "grid: %s\n", s.c_str()); });
    GridSummary summary = summariseGrid(result.E);
    printGrid(result, summary);
    if (!csvPath.empty()) {
        writeGridCsv(csvPath, result);
        std::printf("wrote %s\n", csvPath.c_str());
    }
    return 0;
}

}  // namespace candela
