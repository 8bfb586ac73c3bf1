// `candela bench --design --out DIR`: what a designer's calculations cost in time, with their
// default light (direct light with shadows and interreflected light), on the shipped scenes:
// the office's grid at 0.5 m, the classroom's surfaces and report, the office with GLDF
// downlights' report. Each is timed in this process as the command runs it (the scene loaded
// first, not timed), and the grid and the surfaces are compared point by point with the same
// calculation gathering every point's interreflected light at --reference-spp rays: the worst
// deviation relative to the point's light, beside the reference's own standard error.
// Writes bench.csv and summary.txt (the machine first).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/commands/BenchHarness.h"
#include "app/commands/BenchUtil.h"
#include "app/commands/Commands.h"
#include "calculation/CalculationGrid.h"
#include "calculation/CalculationSurfaces.h"
#include "report/Report.h"
#include "scene/SceneIo.h"
#include "util/Error.h"

namespace candela {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Every value of a surfaces report, in order (task areas, their surroundings, points).
std::vector<double> surfaceValues(const SurfaceReport& r, std::vector<double>* errors = nullptr) {
    std::vector<double> out;
    for (const SurfaceResult& s : r.surfaces)
        for (size_t k = 0; k < s.E.size(); ++k) {
            out.push_back(s.E[k]);
            if (errors) errors->push_back(s.stdError[k]);
        }
    for (const PointResult& p : r.points) {
        out.push_back(p.E);
        if (errors) errors->push_back(p.stdError);
    }
    return out;
}

struct Deviation {
    double worst = 0.0;     ///< Largest |E - E_ref| / E_ref over the points.
    double refError = 0.0;  ///< Largest standard error of the reference relative to E_ref.
};

Deviation deviation(const std::vector<double>& e, const std::vector<double>& ref,
                    const std::vector<double>& refStdError) {
    Deviation d;
    for (size_t k = 0; k < e.size() && k < ref.size(); ++k) {
        if (!(ref[k] > 0.0)) continue;
        d.worst = std::max(d.worst, std::abs(e[k] - ref[k]) / ref[k]);
        d.refError = std::max(d.refError, refStdError[k] / ref[k]);
    }
    return d;
}

}  // namespace

int benchDesign(const DesignOptions& o) {
    BenchFolder folder(o.out);  // whole or not at all: committed at the end
    const fs::path& out = folder.path();
    auto scenePath = [&](const char* name) { return (fs::path(o.scenes) / name).string(); };
    Scene office = loadScene(scenePath("office.json"));
    Scene classroom = loadScene(scenePath("classroom.json"));
    Scene gldfOffice = loadScene(scenePath("office-gldf.json"));

    CsvFile csv(
        "calculation,scene,seconds,points,patches,gathered_points,worst_deviation,"
        "reference_stderr,result");
    BenchSummary summary;
    summary.add(
        "calculations with their default light (direct light with shadows and "
        "interreflected light), timed in one process; reference: the same with every "
        "point's interreflected light gathered at %d rays\n\n",
        o.referenceSpp);
    auto row = [&](const char* what, const char* scene, double seconds, size_t points,
                   size_t patches, const std::string& note, const Deviation* d,
                   const std::string& result) {
        // "at N of M points" from the adaptive method's note.
        std::string gathered = "-";
        size_t at = note.find(" at ");
        if (at != std::string::npos)
            gathered = note.substr(at + 4, note.find(" points", at) - at - 4);
        csv.row(what, scene, formatText("%.2f", seconds), points, patches, "\"" + gathered + "\"",
                d ? formatText("%.4f", d->worst) : "-", d ? formatText("%.4f", d->refError) : "-",
                "\"" + result + "\"");
        summary.add("%-22s %-18s %7.2f s  %4zu points, %4zu patches, gathered at %s", what, scene,
                    seconds, points, patches, gathered.c_str());
        if (d)
            summary.add(
                ";  worst point %.2f %% off the reference (its standard error up to "
                "%.2f %%)",
                100.0 * d->worst, 100.0 * d->refError);
        summary.add("\n    %s\n", result.c_str());
        std::fflush(stdout);
    };

    // The office's grid at 0.5 m on the work plane (what `candela grid` runs).
    {
        GridSpec spec;
        spec.plane = parsePlane("y=0.8");
        spec.spacing = 0.5;
        defaultGridExtent(office, spec);
        applyLightChoice(office, LightChoice{}, spec);
        auto t0 = Clock::now();
        GridResult r = computeGrid(office, spec);
        double seconds = since(t0);
        GridSpec reference = spec;
        reference.indirectMethod = GridSpec::Indirect::Gather;
        reference.spp = o.referenceSpp;
        GridResult ref = computeGrid(office, reference);
        Deviation d = deviation(r.E, ref.E, ref.stdError);
        GridSummary s = summariseGrid(r.E);
        row("grid y=0.8, 0.5 m", "office", seconds, r.E.size(), r.patches, r.indirectNote, &d,
            formatText("Em %.4g lx, U0 %.3f", s.eAvg, s.u0));
    }
    // The classroom's surfaces (what `candela surfaces` runs).
    {
        GridSpec how;
        applyLightChoice(classroom, LightChoice{}, how);
        auto t0 = Clock::now();
        SurfaceReport r = computeSurfaces(classroom, how);
        double seconds = since(t0);
        GridSpec reference = how;
        reference.indirectMethod = GridSpec::Indirect::Gather;
        reference.spp = o.referenceSpp;
        SurfaceReport ref = computeSurfaces(classroom, reference);
        std::vector<double> refErrors;
        std::vector<double> refValues = surfaceValues(ref, &refErrors);
        Deviation d = deviation(surfaceValues(r), refValues, refErrors);
        const GridSummary& s = r.surfaces.front().summary;
        row("surfaces", "classroom", seconds, surfaceValues(r).size(), r.patches, r.indirectNote,
            &d,
            formatText("%s: Em %.4g lx, U0 %.3f", r.surfaces.front().name.c_str(), s.eAvg, s.u0));
    }
    // The reports (what `candela report` runs: contents, the view at its default size, the PDF).
    for (auto [scene, name] : {std::pair<const Scene*, const char*>{&classroom, "classroom"},
                               {&gldfOffice, "office-gldf"}}) {
        GridSpec how;
        applyLightChoice(*scene, LightChoice{}, how);
        auto t0 = Clock::now();
        ReportInput in;
        computeReportContents(in, *scene, name, how);
        double contents = since(t0);
        in.view = renderSceneView(*scene, how, 960, 540, 64, in.viewNote);
        in.viewWidth = 960;
        in.viewHeight = 540;
        std::string pdf = reportPdf(in);
        double seconds = since(t0);
        size_t points = surfaceValues(in.surfaces).size();
        row("report", name, seconds, points, in.surfaces.patches, in.surfaces.indirectNote, nullptr,
            formatText("%zu-byte PDF; its calculations %.2f s, the view (960x540, 64 samples "
                       "per pixel) and the PDF the rest",
                       pdf.size(), contents));
    }
    csv.write(out / "bench.csv");
    summary.write(out);
    folder.commit();
    std::printf("wrote %s/bench.csv\n", o.out.c_str());
    return 0;
}

}  // namespace candela
