// `candela bench --indirect [SCENE] --out DIR`: what interreflected light costs in time (issue 17,
// part 6), on the shipped office by default. It runs the pipeline the editor runs on its worker
// thread (calculation/InterreflectionWorker.h), step by step on this thread with the same settings:
// patches and form factors, every source's direct light at 4 samples, then refined at 32, and
// measures after each step the interreflected illuminance on the work plane (0.8 m, from the
// patches: what the editor's grid shows) against the value it converges to (the same pipeline at
// 512 samples). Then one downlight moves 1 m and only its share is updated, timed the same way.
// Also: how the cost grows with the patches and the luminaires, and how far the patches'
// solution is from finer patches and from the final-gather reference (probe/grid --indirect).
// Writes bench.csv, scaling.csv, summary.txt and plot.png.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <thread>

#include "app/commands/BenchHarness.h"
#include "app/commands/BenchUtil.h"
#include "app/commands/Commands.h"
#include "calculation/CalculationGrid.h"
#include "calculation/Interreflection.h"
#include "calculation/InterreflectionWorker.h"
#include "scene/SceneIo.h"
#include "util/Error.h"
#include "util/FileOutput.h"
#include "util/Threads.h"

namespace candela {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}
double lum(const glm::dvec3& c) {
    return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

/// The work plane's interreflected illuminance at `points` (facing up), from the patches.
std::vector<double> workPlane(const Interreflection& ir, const std::vector<glm::dvec3>& points) {
    std::vector<double> out(points.size());
    std::atomic<size_t> next{0};
    auto work = [&] {
        for (size_t i; (i = next.fetch_add(1)) < points.size();)
            out[i] = lum(ir.fromPatches(points[i], {0, 1, 0}));
    };
    runInParallel(workerThreads(0), work);
    return out;
}

double mean(const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v) s += x;
    return v.empty() ? 0.0 : s / double(v.size());
}

/// The largest deviation of any point from the converged values, relative to their mean.
double worstDeviation(const std::vector<double>& v, const std::vector<double>& converged) {
    double worst = 0.0, m = mean(converged);
    for (size_t i = 0; i < v.size(); ++i)
        worst = std::max(worst, std::abs(v[i] - converged[i]) / m);
    return worst;
}

struct Step {
    std::string phase, step;
    double seconds = 0.0;        ///< Since the phase began (wall time, this thread and its pool).
    std::vector<double> values;  ///< Work plane, lx.
};

constexpr int kConvergedSpp = 512;  ///< Every source's direct light for the value it converges to.

/// The worker's steps from scratch and after the move, and what each phase converges to.
struct Timeline {
    std::unique_ptr<Interreflection> ir;  ///< The solution, after the move.
    std::vector<Step> steps;
    size_t coldSteps = 0;  ///< steps before this are from scratch, the rest after the move.
    std::vector<double> coldConverged, moveConverged;  ///< Work plane, lx.
    double transferSeconds = 0.0;                      ///< The form factors.
    const std::vector<double>& convergedFor(size_t step) const {
        return step < coldSteps ? coldConverged : moveConverged;
    }
};

/// From scratch (the patches included), then after `moved` goes 1 m along x, as the editor's
/// worker does: each phase at 4 samples, then refined at 32, timed from its start, then converged.
Timeline runWorkerSteps(Scene& scene, const InterreflectionOptions& options, Luminaire& moved,
                        const std::vector<glm::dvec3>& points) {
    const int quick = InterreflectionWorker::kQuickSpp, fine = InterreflectionWorker::kFineSpp;
    Timeline t;
    auto t0 = Clock::now();
    t.ir = std::make_unique<Interreflection>(scene, options);
    Interreflection& ir = *t.ir;
    auto record = [&](const std::string& phase, const std::string& step, Clock::time_point start) {
        Step s{phase, step, 0.0, workPlane(ir, points)};
        s.seconds = since(start);
        std::printf("  %-6s %-24s %7.2f s  Em %.4g lx\n", phase.c_str(), step.c_str(), s.seconds,
                    mean(s.values));
        std::fflush(stdout);
        t.steps.push_back(std::move(s));
    };
    ir.buildTransfer();
    t.transferSeconds = since(t0);
    ir.sync(scene, quick);
    record("cold", "direct light, 4 spp", t0);
    ir.refine(fine);
    record("cold", "refined, 32 spp", t0);
    ir.refine(kConvergedSpp);
    t.coldConverged = workPlane(ir, points);
    t.coldSteps = t.steps.size();

    moved.pose.position += glm::dvec3(1.0, 0.0, 0.0);
    auto t1 = Clock::now();
    ir.sync(scene, quick);
    record("move", "moved one, 4 spp", t1);
    ir.refine(fine);
    record("move", "refined, 32 spp", t1);
    ir.refine(kConvergedSpp);
    t.moveConverged = workPlane(ir, points);
    return t;
}

/// How far the patches' solution is from finer patches and from the final gather.
struct Accuracy {
    size_t finePatches = 0;
    std::vector<double> fineValues;  ///< Work plane with 4 times the patches, lx.
    double fineSeconds = 0.0;
    int gathered = 0;  ///< Points gathered at.
    double gatherWorst = 0.0, gatherMean = 0.0, patchMean = 0.0, gatherSigma = 0.0;  ///< lx
};

Accuracy measureAccuracy(const Scene& scene, const InterreflectionOptions& options,
                         const Interreflection& ir, const std::vector<glm::dvec3>& points,
                         const std::vector<double>& converged) {
    Accuracy a;
    InterreflectionOptions finer = options;
    finer.mesh.targetPatches = options.mesh.targetPatches * 4;
    finer.directSpp = 128;
    auto t2 = Clock::now();
    Interreflection fineIr(scene, finer);
    fineIr.compute();
    a.fineValues = workPlane(fineIr, points);
    a.fineSeconds = since(t2);
    a.finePatches = fineIr.mesh().patches.size();
    // The gather at every 8th point (its first bounce exact, 4096 rays, a standard error).
    for (size_t i = 0; i < points.size(); i += 8, ++a.gathered) {
        EstimateOptions g;
        g.spp = 4096;
        g.seed = 99 + i;
        Estimate e = ir.gather(points[i], {0, 1, 0}, g);
        a.gatherMean += lum(e.irradiance);
        a.patchMean += converged[i];
        a.gatherSigma = std::max(a.gatherSigma, lum(e.stdError));
        a.gatherWorst = std::max(a.gatherWorst, std::abs(lum(e.irradiance) - converged[i]));
    }
    a.gatherMean /= a.gathered;
    a.patchMean /= a.gathered;
    return a;
}

/// How the cost grows with the patches (form factors ~ N^2) and the luminaires (direct light ~
/// luminaires x N): scaling.csv.
void measureScaling(const Scene& scene, const InterreflectionOptions& options,
                    const fs::path& out) {
    const int fine = InterreflectionWorker::kFineSpp, patches = options.mesh.targetPatches;
    CsvFile scaling("what,patches,luminaires,form_factor_s,direct_s,solve_iterations");
    std::printf("scaling:\n");
    for (int n : {patches / 2, patches, patches * 2}) {
        InterreflectionOptions o = options;
        o.mesh.targetPatches = n;
        auto s0 = Clock::now();
        Interreflection x(scene, o);
        x.buildTransfer();
        double ff = since(s0);
        auto s1 = Clock::now();
        x.sync(scene, fine);
        double direct = since(s1);
        scaling.row("patches", x.mesh().patches.size(), scene.luminaires.size(), ff, direct,
                    x.lastIterations());
        std::printf(
            "  %6zu patches, %zu luminaires: form factors %.2f s, direct light + solve %.2f s\n",
            x.mesh().patches.size(), scene.luminaires.size(), ff, direct);
    }
    for (size_t keep : {size_t(1), size_t(3), scene.luminaires.size()}) {
        Scene some = scene.clone();
        some.luminaires.resize(std::min(keep, some.luminaires.size()));
        Interreflection x(some, options);
        x.buildTransfer();
        auto s1 = Clock::now();
        x.sync(some, fine);
        double direct = since(s1);
        scaling.row("luminaires", x.mesh().patches.size(), some.luminaires.size(), "", direct,
                    x.lastIterations());
        std::printf("  %6zu patches, %zu luminaires: direct light + solve %.2f s\n",
                    x.mesh().patches.size(), some.luminaires.size(), direct);
    }
    scaling.write(out / "scaling.csv");
}

/// bench.csv: each step against what its phase converges to; returns the first time of each
/// phase within 1 % everywhere (-1: never).
std::pair<double, double> writeSteps(const Timeline& t, const fs::path& path) {
    CsvFile csv("phase,step,seconds,em_lx,worst_deviation,em_deviation");
    double coldTime = -1.0, moveTime = -1.0;
    for (size_t k = 0; k < t.steps.size(); ++k) {
        const Step& s = t.steps[k];
        const std::vector<double>& c = t.convergedFor(k);
        double worst = worstDeviation(s.values, c), em = mean(s.values) / mean(c) - 1.0;
        // A step's name ("direct light, 4 spp") holds commas: ';' keeps the columns apart.
        std::string step = s.step;
        std::replace(step.begin(), step.end(), ',', ';');
        csv.line(formatText("%s,%s,%.3f,%.5g,%.5f,%.5f", s.phase.c_str(), step.c_str(), s.seconds,
                            mean(s.values), worst, em));
        double& first = k < t.coldSteps ? coldTime : moveTime;
        if (first < 0.0 && worst <= 0.01) first = s.seconds;
    }
    csv.write(path);
    return {coldTime, moveTime};
}

/// What the summary reports besides the timeline.
struct IndirectReport {
    const IndirectOptions& options;
    const Scene& scene;
    size_t patches = 0, points = 0;
    std::pair<double, double> within1Percent;  ///< From scratch and after the move, s (-1: never).
};

void addSummary(BenchSummary& summary, const IndirectReport& r, const Timeline& t,
                const Accuracy& a) {
    auto time = [](double s) {
        return s < 0 ? std::string("not reached") : formatText("%.2f s", s);
    };
    const IndirectOptions& o = r.options;
    std::string shown = o.scenePath;
    if (shown.rfind(CANDELA_SOURCE_DIR "/", 0) == 0)
        shown = shown.substr(std::string(CANDELA_SOURCE_DIR "/").size());
    std::ostringstream text;
    text << "scene: " << shown << "; " << r.patches << " patches (about " << o.patches
         << " asked), " << r.scene.luminaires.size() << " luminaires, " << workerThreads(0)
         << " threads\n"
         << "work plane: " << r.points << " points at " << o.height << " m, " << o.spacing
         << " m apart; interreflected illuminance from the patches (the editor's grid)\n"
         << "converged value: the same patches with every source's direct light at "
         << kConvergedSpp << " spp: Em " << mean(t.coldConverged) << " lx (after the move "
         << mean(t.moveConverged) << " lx)\n"
         << "form factors: " << t.transferSeconds << " s\n"
         << "from scratch to every point within 1 % of the converged value (relative to Em): "
         << time(r.within1Percent.first) << " (target 10 s)\n"
         << "after moving \"" << o.moved
         << "\" 1 m, within 1 % again: " << time(r.within1Percent.second) << " (target 3 s)\n";
    summary.addText(text.str());
    for (size_t k = 0; k < t.steps.size(); ++k) {
        const Step& s = t.steps[k];
        const std::vector<double>& c = t.convergedFor(k);
        summary.add("  %-5s %-22s %6.2f s: Em %.4g lx, worst point %.2f %%, Em %+.2f %%\n",
                    s.phase.c_str(), s.step.c_str(), s.seconds, mean(s.values),
                    100.0 * worstDeviation(s.values, c), 100.0 * (mean(s.values) / mean(c) - 1.0));
    }
    summary.add(
        "discretisation: %zu patches give Em %.4g lx, %zu patches %.4g lx (%+.2f %%; worst point "
        "%.2f %% of "
        "Em; %.1f s)\n",
        r.patches, mean(t.moveConverged), a.finePatches, mean(a.fineValues),
        100.0 * (mean(t.moveConverged) / mean(a.fineValues) - 1.0),
        100.0 * worstDeviation(t.moveConverged, a.fineValues), a.fineSeconds);
    summary.add(
        "final gather (grid --indirect's reference) at %d points: mean %.4g lx against the "
        "patches' %.4g lx "
        "(%+.2f %%), largest difference %.3g lx, its standard error up to %.2g lx\n",
        a.gathered, a.gatherMean, a.patchMean, 100.0 * (a.patchMean / a.gatherMean - 1.0),
        a.gatherWorst, a.gatherSigma);
}

void plotSteps(const fs::path& out) {
    writePlot(out, 800, 420,
              "set grid\nset logscale y\n"
              "set xlabel 'wall time since the change, s'\nset ylabel 'worst work-plane point, "
              "fraction of Em'\n"
              "set key top right\nplot 'bench.csv' using (strcol(1) eq 'cold' ? $3 : 1/0):5 with "
              "linespoints "
              "pointsize 1.5 title 'from scratch', 'bench.csv' using (strcol(1) eq 'move' ? $3 : "
              "1/0):5 with "
              "linespoints pointsize 1.5 title 'after a move', 0.01 title '1 %' dt 2\n",
              "plot.png");
}

/// The work plane over the scene's bounds, points `spacing` apart at cell centres.
std::vector<glm::dvec3> workPlanePoints(const Scene& scene, double spacing, double height) {
    glm::vec3 lo = scene.boundsMin(), hi = scene.boundsMax();
    std::vector<glm::dvec3> points;
    for (double z : gridCoordinates(lo.z, hi.z, spacing))
        for (double x : gridCoordinates(lo.x, hi.x, spacing)) points.push_back({x, height, z});
    return points;
}

}  // namespace

int benchIndirect(const IndirectOptions& o) {
    Scene scene = loadScene(o.scenePath);
    ProtectedInputs inputs(scene.inputFiles());
    BenchFolder folder(o.out);  // whole or not at all: committed at the end
    const fs::path& out = folder.path();
    auto moved = std::find_if(scene.luminaires.begin(), scene.luminaires.end(),
                              [&](const auto& l) { return l->name == o.moved; });
    if (moved == scene.luminaires.end())
        throw InputError(o.scenePath + ": no luminaire named \"" + o.moved + "\" (--move)");
    if (!scene.hasSurfaces())
        throw InputError(o.scenePath + ": geometry: no surfaces to interreflect light");

    std::vector<glm::dvec3> points = workPlanePoints(scene, o.spacing, o.height);
    InterreflectionOptions options;
    options.mesh.targetPatches = o.patches;
    std::printf("bench --indirect: %s, %zu work-plane points at %.2f m, %d threads\n",
                o.scenePath.c_str(), points.size(), o.height, workerThreads(0));
    Timeline timeline = runWorkerSteps(scene, options, **moved, points);
    Accuracy accuracy =
        measureAccuracy(scene, options, *timeline.ir, points, timeline.moveConverged);
    measureScaling(scene, options, out);

    IndirectReport report{o, scene, timeline.ir->mesh().patches.size(), points.size(),
                          writeSteps(timeline, out / "bench.csv")};
    BenchSummary summary;
    summary.light(
        "interreflected light on the work plane, measured alone (the direct light is the same in "
        "every step)");
    addSummary(summary, report, timeline, accuracy);
    summary.write(out);
    plotSteps(out);
    folder.commit();
    std::printf("wrote %s/bench.csv, scaling.csv, summary.txt\n", o.out.c_str());
    return 0;
}

}  // namespace candela
