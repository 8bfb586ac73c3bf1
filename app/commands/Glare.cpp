// `candela glare`: the Unified Glare Rating (CIE 117) at the scene's observers, or at one given
// on the command line, computed by calculation/Glare.h: UGR with its limit, the background
// luminance and where it came from, and what each luminaire contributes.
#include "calculation/Glare.h"

#include <cmath>
#include <cstdio>

#include "app/commands/Commands.h"
#include "scene/SceneIo.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

namespace {

glm::dvec3 parseTriple(const std::string& flag, const std::string& text) {
    double x = 0, y = 0, z = 0;
    char extra = 0;
    if (std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &x, &y, &z, &extra) != 3 || !std::isfinite(x) ||
        !std::isfinite(y) || !std::isfinite(z))
        throw InputError(flag + ": expected X,Y,Z (three numbers), got \"" + text + "\"");
    return {x, y, z};
}

void printResult(const GlareResult& r) {
    const GlareObserver& o = r.observer;
    std::printf("\n%s: eye at (%.3f, %.3f, %.3f) m, looking (%.3f, %.3f, %.3f)\n", o.name.c_str(),
                o.position.x, o.position.y, o.position.z, o.view.x, o.view.y, o.view.z);
    if (r.backgroundFromIndirect)
        std::printf(
            "  background luminance Lb %.4g cd/m2 = Eind %.4g lx / pi (interreflected light "
            "at the eye, standard error %.2g lx)\n",
            r.background, r.background * 3.14159265358979323846, r.indirectStdError);
    else
        std::printf("  background luminance Lb %.4g cd/m2 (given)\n", r.background);
    std::printf("  %-24s %10s %8s %10s %12s %10s %7s %12s\n", "luminaire", "I [cd]", "r [m]",
                "Ap [m2]", "L [cd/m2]", "omega [sr]", "p", "L2 w / p2");
    for (const GlareSource& s : r.sources) {
        if (!s.excluded.empty()) {
            std::printf("  %-24s left out: %s\n", s.luminaire.c_str(), s.excluded.c_str());
            continue;
        }
        std::printf("  %-24s %10.4g %8.3f %10.4g %12.4g %10.3g %7.3f %12.4g%s%s\n",
                    s.luminaire.c_str(), s.intensity, s.distance, s.projectedArea, s.luminance,
                    s.solidAngle, s.positionIndex, s.term,
                    s.small ? "  small source (under 0.005 m2): CIE 147's 200 I2 / r2" : "",
                    s.large ? "  larger than CIE 117's 0.1 sr" : "");
    }
    std::printf("  UGR %.1f", r.ugr);
    if (o.limit > 0.0) std::printf(", limit UGR_L %g: %s", o.limit, r.passes ? "PASS" : "FAIL");
    std::printf("\n");
}

std::string reportCsv(const GlareReport& report) {
    std::string out = "observer,x_m,y_m,z_m,view_x,view_y,view_z,Lb_cd_m2,UGR,limit,passes\n";
    char line[256];
    for (const GlareResult& r : report.observers) {
        const GlareObserver& o = r.observer;
        std::string name = "\"";
        for (char c : o.name) name += c == '"' ? std::string("\"\"") : std::string(1, c);
        std::snprintf(line, sizeof line, "\",%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.3f,%g,%s\n",
                      o.position.x, o.position.y, o.position.z, o.view.x, o.view.y, o.view.z,
                      r.background, r.ugr, o.limit, r.passes ? "yes" : "no");
        out += name + line;
    }
    return out;
}

}  // namespace

int cmdGlare(const Args& args) {
    // The table form parses its own options (GlareTable.cpp); they are declared here too so
    // that this help lists both forms', and here they can only be misplaced.
    for (const std::string& a : args)
        if (a == "--table" || a.rfind("--table=", 0) == 0) return cmdGlareTable(args);
    std::string scenePath, csvPath, unused;
    GridSpec how;
    GlareObserver one;
    CommandLine cli("glare");
    cli.argument(
        "scene.json", scenePath,
        "the scene file, whose \"glare_observers\" are rated unless --observer places one");
    cli.output("--out", csvPath, "F.csv",
               "also write each observer's UGR as CSV (observer, position, view, Lb, UGR, limit); "
               "with --table, every cell of the table with its intermediate values");
    cli.renamed("--csv", "--out");
    cli.group("one observer instead of the scene's \"glare_observers\"");
    cli.option("--observer", "X,Y,Z", "the eye's position, metres (with --view)",
               [&one](const std::string& v) { one.position = parseTriple("--observer", v); });
    cli.option("--view", "X,Y,Z", "the line of sight, with a horizontal part (with --observer)",
               [&one](const std::string& v) { one.view = parseTriple("--view", v); });
    cli.number("--limit", one.limit, 1.0, 40.0, "UGR_L",
               "the observer's UGR limit, 1..40, to pass or fail (default: none)");
    cli.number("--background", one.background, 1e-6, 1e9, "CD_M2",
               "the background luminance Lb, cd/m2 (default: from the interreflected light at "
               "the eye)");
    cli.group("the background luminance from the interreflected light");
    cli.integer("--spp", how.spp, 1, 1 << 24, "N",
                "samples per eye of the interreflected light's final gather (1024)");
    cli.integer("--patches", how.patches, 16, 1000000, "N",
                "about this many patches for the interreflection (1500)");
    cli.group("the table form (candela glare --table FILE)");
    cli.text("--table", unused, "FILE",
             "the standard UGR table of this photometry file (.ldt, .ies, .xml or .gldf) instead "
             "of a scene's UGR");
    cli.text("--spacing-ratio", unused, "R", kSpacingRatioHelp);
    if (!cli.parse(args)) return 0;
    if (cli.given("--spacing-ratio"))
        throw CommandUsageError("--spacing-ratio goes with --table (the table form)",
                                cli.shortHelp());
    bool position = cli.given("--observer");
    if (position != cli.given("--view"))
        throw CommandUsageError(
            std::string("missing ") + (position ? "--view" : "--observer") +
                " (--observer X,Y,Z and --view X,Y,Z place one observer together)",
            cli.shortHelp());
    for (const char* option : {"--limit", "--background"})
        if (!position && cli.given(option))
            throw CommandUsageError(std::string(option) +
                                        " goes with --observer and --view (the scene's observers "
                                        "give their own in \"glare_observers\")",
                                    cli.shortHelp());
    std::vector<GlareObserver> observers;
    if (position) {
        // Through the scene file's parser, so the command line gets the same checks.
        nlohmann::json entry = {{"name", "command line"},
                                {"position", {one.position.x, one.position.y, one.position.z}},
                                {"view", {one.view.x, one.view.y, one.view.z}}};
        if (one.limit > 0.0) entry["limit"] = one.limit;
        if (one.background > 0.0) entry["background_cd_m2"] = one.background;
        observers.push_back(parseGlareObserver(entry, json::Where{"--observer", ""}));
    }
    Scene scene = loadScene(scenePath);
    ProtectedInputs inputs(scene.inputFiles());
    checkNotAnInput(csvPath, "--out");
    GlareReport report = computeGlare(scene, how, observers, [](const std::string& s) {
        std::fprintf(stderr, "glare: %s\n", s.c_str());
    });
    std::printf("Unified Glare Rating (CIE 117), UGR = 8 log10(0.25 / Lb x sum L2 omega / p2)\n");
    std::printf("%s\n%s\n", report.maintenance.c_str(), report.bodies.c_str());
    int failed = 0;
    for (const GlareResult& r : report.observers) {
        printResult(r);
        if (!r.passes) ++failed;
    }
    std::printf("\n%d limit%s exceeded\n", failed, failed == 1 ? "" : "s");
    if (!csvPath.empty()) {
        writeFileAtomically(csvPath, reportCsv(report), "cannot write the CSV file");
        std::printf("wrote %s\n", csvPath.c_str());
    }
    return 0;
}

}  // namespace candela
