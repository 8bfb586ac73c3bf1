// `candela layout`: the count and regular arrangement of a luminaire that lights a task area to
// its target (calculation/Layout.h): the lumen method's guess, each arrangement computed, the
// smallest that meets the target, and the scene with it written to a new file.
#include "calculation/Layout.h"

#include <cstdio>
#include <filesystem>

#include "app/commands/Commands.h"
#include "scene/SceneIo.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

namespace fs = std::filesystem;

namespace {

void printLayout(const LayoutResult& r) {
    std::printf("task area \"%s\": target Em %g lx", r.area.c_str(), r.targetEm);
    if (r.targetU0 > 0.0) std::printf(", U0 %.2f", r.targetU0);
    std::printf(" (maintained)\n");
    std::printf("luminaires spread over x %.3f..%.3f m, z %.3f..%.3f m (%.4g m2)\n", r.lo.x, r.hi.x,
                r.lo.y, r.hi.y, (r.hi.x - r.lo.x) * (r.hi.y - r.lo.y));
    std::printf(
        "lumen method: one luminaire %.5g lm, maintenance factor %.3g, %.1f %% of its flux "
        "downwards; room index k %.2f, utilisation guessed %.2f: N = %d\n",
        r.flux, r.maintenanceFactor, 100.0 * r.downwardShare, r.roomIndex, r.utilisationGuess,
        r.lumenMethodCount);
    std::printf("light: %s\n", r.light.c_str());
    std::printf("%-10s %6s %17s %10s %7s %10s  %s\n", "grid", "count", "spacing [m]", "Em [lx]",
                "U0", "Emin [lx]", "target");
    for (size_t i = 0; i < r.tried.size(); ++i) {
        const LayoutCandidate& c = r.tried[i];
        char grid[32], spacing[40];
        std::snprintf(grid, sizeof grid, "%d x %d", c.columns, c.rows);
        std::snprintf(spacing, sizeof spacing, "%.3f x %.3f", c.spacing.x, c.spacing.y);
        std::printf("%-10s %6d %17s %10.4g %7.3f %10.4g  %s%s\n", grid, c.count(), spacing, c.em,
                    c.u0, c.eMin, c.meets ? "met" : "not met",
                    int(i) == r.chosen ? "  <- chosen" : "");
    }
    if (const LayoutCandidate* best = r.best())
        std::printf("layout: %d luminaires, %d x %d, %.3f m apart along x and %.3f m along z\n",
                    best->count(), best->columns, best->rows, best->spacing.x, best->spacing.y);
    else
        std::printf("layout: no arrangement tried met the target\n");
}

}  // namespace

int cmdLayout(const Args& args) {
    std::string scenePath, luminaireFile, variant, outPath;
    LayoutRequest request;
    CommandLine cli("layout");
    cli.argument("scene.json", scenePath, "the scene file (its rooms and task areas)");
    cli.text("--area", request.area, "NAME",
             "the task area to light (default: the scene's only one)");
    cli.text("--luminaire", luminaireFile, "FILE",
             "the luminaire: a photometry (.ies, .ldt, TM-33 .xml) or a GLDF container");
    cli.text("--variant", variant, "ID", "the GLDF variant (default: the first)");
    cli.number("--height", request.mountingHeight, 0.0, 1e4, "M",
               "the luminaires' mounting height above the room's floor, m");
    cli.number("--em", request.targetEm, 0.0, 1e6, "LX",
               "the target maintained illuminance, lx (default: the task area's requirement)");
    cli.number("--u0", request.targetU0, 0.0, 1.0, "U",
               "the target uniformity Emin / Em (default: the task area's requirement)");
    cli.integer("--max", request.maxLuminaires, 1, 10000, "N",
                "look at most this many luminaires (400)");
    cli.output("--out", outPath, "F.json", "write the scene with the layout applied");
    cli.strictPhotometry();
    if (!cli.parse(args)) return 0;
    if (luminaireFile.empty())
        throw CommandUsageError("--luminaire: give the luminaire to lay out", cli.shortHelp());
    if (!(request.mountingHeight > 0.0))
        throw CommandUsageError("--height: give the mounting height in metres", cli.shortHelp());
    Scene scene = loadScene(scenePath);
    ProtectedInputs inputs(scene.inputFiles());
    checkNotAnInput(outPath, "--out");
    if (!fs::exists(luminaireFile)) throw InputError(luminaireFile + ": no such luminaire file");
    // The entry names the file as the scene's own entries do: relative to the scene's folder.
    fs::path sceneDir = fs::absolute(fs::path(scenePath)).parent_path();
    fs::path relative = fs::absolute(luminaireFile).lexically_normal().lexically_relative(sceneDir);
    std::string ext = fs::path(luminaireFile).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    request.luminaire = {{"type", ext == ".gldf" ? "gldf" : "photometric"},
                         {"file", relative.empty() ? fs::absolute(luminaireFile).string()
                                                   : relative.generic_string()}};
    request.name = fs::path(luminaireFile).stem().string();
    if (!variant.empty()) request.luminaire["variant"] = variant;
    LayoutResult result = proposeLayout(scene, request, [](const std::string& s) {
        std::fprintf(stderr, "layout: %s\n", s.c_str());
    });
    printLayout(result);
    if (!outPath.empty()) {
        if (!result.best())
            throw InputError(scenePath + ": no layout met the target, so " + outPath +
                             " was not written (raise --max, or lower the target)");
        Scene laidOut = parseScene(applyLayout(scene, request, result), scenePath);
        saveScene(laidOut, outPath);
        std::printf("wrote %s\n", outPath.c_str());
    }
    return result.best() ? 0 : 1;
}

}  // namespace candela
