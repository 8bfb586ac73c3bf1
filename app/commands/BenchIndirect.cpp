// `candela bench --indirect [SCENE] --out DIR`: what interreflected light costs in time (issue 17,
// part 6), on the shipped office by default. It runs the pipeline the editor runs on its worker
// thread (scene/InterreflectionWorker.h), step by step on this thread with the same settings:
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
#include <sstream>
#include <thread>

#include "app/commands/BenchUtil.h"
#include "app/commands/Commands.h"
#include "scene/CalculationGrid.h"
#include "scene/Interreflection.h"
#include "scene/InterreflectionWorker.h"
#include "scene/SceneIo.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
double lum(const glm::dvec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

/// The work plane's interreflected illuminance at `points` (facing up), from the patches.
std::vector<double> workPlane(const Interreflection& ir, const std::vector<glm::dvec3>& points) {
    std::vector<double> out(points.size());
    std::atomic<size_t> next{0};
    auto work = [&] {
        for (size_t i; (i = next.fetch_add(1)) < points.size();) out[i] = lum(ir.fromPatches(points[i], {0, 1, 0}));
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < workerThreads(0); ++t) pool.emplace_back(work);
    work();
    for (auto& t : pool) t.join();
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
    for (size_t i = 0; i < v.size(); ++i) worst = std::max(worst, std::abs(v[i] - converged[i]) / m);
    return worst;
}

struct Step {
    std::string phase, step;
    double seconds = 0.0;          ///< Since the phase began (wall time, this thread and its pool).
    std::vector<double> values;    ///< Work plane, lx.
};

}  // namespace

int benchIndirect(const Args& args) {
    std::string scenePath = std::string(CANDELA_SOURCE_DIR) + "/resources/scenes/office.json";
    std::string outDir = "bench-indirect", moved = "Downlight 2";
    int patches = 2500;
    double spacing = 0.25, height = 0.8;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--indirect") {
            if (i + 1 < args.size() && args[i + 1].rfind("--", 0) != 0) scenePath = args[++i];
        } else if (a == "--out") outDir = flagValue(args, i);
        else if (a == "--patches") patches = parseInt(a, flagValue(args, i), 16, 50000);
        else if (a == "--move") moved = flagValue(args, i);
        else throw InputError("bench --indirect: unknown option " + a +
                              " (usage: candela bench --indirect [SCENE.json] [--out DIR] [--patches N] [--move NAME])");
    }
    Scene scene = loadScene(scenePath);
    ProtectedInputs inputs(scene.inputFiles());
    fs::path out(outDir);
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec) throw InputError(outDir + ": cannot create folder (" + ec.message() + ")");
    auto movedIt = std::find_if(scene.luminaires.begin(), scene.luminaires.end(),
                                [&](const auto& l) { return l->name == moved; });
    if (movedIt == scene.luminaires.end()) throw InputError(scenePath + ": no luminaire named \"" + moved + "\" (--move)");
    if (scene.meshes.empty()) throw InputError(scenePath + ": geometry: no surfaces to interreflect light");

    // The work plane over the scene's bounds, points spacing apart at cell centres.
    glm::vec3 lo = scene.boundsMin(), hi = scene.boundsMax();
    std::vector<glm::dvec3> points;
    for (double z : gridCoordinates(lo.z, hi.z, spacing))
        for (double x : gridCoordinates(lo.x, hi.x, spacing)) points.push_back({x, height, z});
    InterreflectionOptions options;
    options.mesh.targetPatches = patches;
    const int quick = InterreflectionWorker::kQuickSpp, fine = InterreflectionWorker::kFineSpp, converged = 512;
    std::vector<Step> steps;
    std::printf("bench --indirect: %s, %zu work-plane points at %.2f m, %d threads\n", scenePath.c_str(), points.size(),
                height, workerThreads(0));

    // --- From scratch, then after a move, as the editor's worker does ------------------------------
    auto t0 = Clock::now();
    Interreflection ir(scene, options);
    ir.buildTransfer();
    double transferSeconds = since(t0);
    auto record = [&](const std::string& phase, const std::string& step, Clock::time_point start) {
        Step s{phase, step, 0.0, workPlane(ir, points)};
        s.seconds = since(start);
        std::printf("  %-6s %-24s %7.2f s  Em %.4g lx\n", phase.c_str(), step.c_str(), s.seconds, mean(s.values));
        std::fflush(stdout);
        steps.push_back(std::move(s));
    };
    ir.sync(scene, quick);
    record("cold", "direct light, 4 spp", t0);
    ir.refine(fine);
    record("cold", "refined, 32 spp", t0);
    ir.refine(converged);
    std::vector<double> coldConverged = workPlane(ir, points);
    size_t coldSteps = steps.size();

    (*movedIt)->pose.position += glm::dvec3(1.0, 0.0, 0.0);
    auto t1 = Clock::now();
    ir.sync(scene, quick);
    record("move", "moved one, 4 spp", t1);
    ir.refine(fine);
    record("move", "refined, 32 spp", t1);
    ir.refine(converged);
    std::vector<double> moveConverged = workPlane(ir, points);

    // --- Accuracy: finer patches, and the final gather (the CLI's reference) ------------------------
    InterreflectionOptions finer = options;
    finer.mesh.targetPatches = patches * 4;
    finer.directSpp = 128;
    auto t2 = Clock::now();
    Interreflection fineIr(scene, finer);
    fineIr.compute();
    std::vector<double> fineValues = workPlane(fineIr, points);
    double fineSeconds = since(t2);
    // The gather at every 8th point (its first bounce exact, 4096 rays, a standard error).
    double gatherWorst = 0.0, gatherMean = 0.0, patchMean = 0.0, gatherSigma = 0.0;
    int gathered = 0;
    for (size_t i = 0; i < points.size(); i += 8, ++gathered) {
        EstimateOptions g;
        g.spp = 4096;
        g.seed = 99 + i;
        Estimate e = ir.gather(points[i], {0, 1, 0}, g);
        gatherMean += lum(e.irradiance);
        patchMean += moveConverged[i];
        gatherSigma = std::max(gatherSigma, lum(e.stdError));
        gatherWorst = std::max(gatherWorst, std::abs(lum(e.irradiance) - moveConverged[i]));
    }
    gatherMean /= gathered;
    patchMean /= gathered;

    // --- Scaling: patches (form factors ~ N^2) and luminaires (direct light ~ luminaires x N) -------
    std::ostringstream scaling;
    scaling << "what,patches,luminaires,form_factor_s,direct_s,solve_iterations\n";
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
        scaling << "patches," << x.mesh().patches.size() << "," << scene.luminaires.size() << "," << ff << "," << direct
                << "," << x.lastIterations() << "\n";
        std::printf("  %6zu patches, %zu luminaires: form factors %.2f s, direct light + solve %.2f s\n",
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
        scaling << "luminaires," << x.mesh().patches.size() << "," << some.luminaires.size() << ",," << direct << ","
                << x.lastIterations() << "\n";
        std::printf("  %6zu patches, %zu luminaires: direct light + solve %.2f s\n", x.mesh().patches.size(),
                    some.luminaires.size(), direct);
    }
    writeFileAtomically((out / "scaling.csv").string(), scaling.str());

    // --- Results -------------------------------------------------------------------------------------
    std::ostringstream csv, summary;
    csv << "phase,step,seconds,em_lx,worst_deviation,em_deviation\n";
    char line[256];
    double coldTime = -1.0, moveTime = -1.0;
    for (size_t k = 0; k < steps.size(); ++k) {
        const Step& s = steps[k];
        const std::vector<double>& c = k < coldSteps ? coldConverged : moveConverged;
        double worst = worstDeviation(s.values, c), em = mean(s.values) / mean(c) - 1.0;
        std::snprintf(line, sizeof line, "%s,%s,%.3f,%.5g,%.5f,%.5f\n", s.phase.c_str(), s.step.c_str(), s.seconds,
                      mean(s.values), worst, em);
        csv << line;
        double& first = k < coldSteps ? coldTime : moveTime;
        if (first < 0.0 && worst <= 0.01) first = s.seconds;
    }
    writeFileAtomically((out / "bench.csv").string(), csv.str());
    auto time = [](double t) {
        char text[64];
        std::snprintf(text, sizeof text, t < 0 ? "not reached" : "%.2f s", t);
        return std::string(text);
    };
    std::string shown = scenePath;
    if (shown.rfind(CANDELA_SOURCE_DIR "/", 0) == 0) shown = shown.substr(std::string(CANDELA_SOURCE_DIR "/").size());
    summary << "machine: " << machineDescription() << "\n"
            << "scene: " << shown << "; " << ir.mesh().patches.size() << " patches (about " << patches
            << " asked), " << scene.luminaires.size() << " luminaires, " << workerThreads(0) << " threads\n"
            << "work plane: " << points.size() << " points at " << height << " m, " << spacing
            << " m apart; interreflected illuminance from the patches (the editor's grid)\n"
            << "converged value: the same patches with every source's direct light at " << converged << " spp: Em "
            << mean(coldConverged) << " lx (after the move " << mean(moveConverged) << " lx)\n"
            << "form factors: " << transferSeconds << " s\n"
            << "from scratch to every point within 1 % of the converged value (relative to Em): " << time(coldTime)
            << " (target 10 s)\n"
            << "after moving \"" << moved << "\" 1 m, within 1 % again: " << time(moveTime) << " (target 3 s)\n";
    for (size_t k = 0; k < steps.size(); ++k) {
        const std::vector<double>& c = k < coldSteps ? coldConverged : moveConverged;
        std::snprintf(line, sizeof line, "  %-5s %-22s %6.2f s: Em %.4g lx, worst point %.2f %%, Em %+.2f %%\n",
                      steps[k].phase.c_str(), steps[k].step.c_str(), steps[k].seconds, mean(steps[k].values),
                      100.0 * worstDeviation(steps[k].values, c), 100.0 * (mean(steps[k].values) / mean(c) - 1.0));
        summary << line;
    }
    std::snprintf(line, sizeof line,
                  "discretisation: %zu patches give Em %.4g lx, %zu patches %.4g lx (%+.2f %%; worst point %.2f %% of Em; "
                  "%.1f s)\n",
                  ir.mesh().patches.size(), mean(moveConverged), fineIr.mesh().patches.size(), mean(fineValues),
                  100.0 * (mean(moveConverged) / mean(fineValues) - 1.0), 100.0 * worstDeviation(moveConverged, fineValues),
                  fineSeconds);
    summary << line;
    std::snprintf(line, sizeof line,
                  "final gather (grid --indirect's reference) at %d points: mean %.4g lx against the patches' %.4g lx "
                  "(%+.2f %%), largest difference %.3g lx, its standard error up to %.2g lx\n",
                  gathered, gatherMean, patchMean, 100.0 * (patchMean / gatherMean - 1.0), gatherWorst, gatherSigma);
    summary << line;
    writeFileAtomically((out / "summary.txt").string(), summary.str());
    std::printf("%s", summary.str().c_str());
    std::ostringstream gp;
    gp << "set terminal pngcairo size 800,420 noenhanced\nset datafile separator ','\nset grid\nset logscale y\n"
          "set xlabel 'wall time since the change, s'\nset ylabel 'worst work-plane point, fraction of Em'\n"
          "set key top right\nplot 'bench.csv' using (strcol(1) eq 'cold' ? $3 : 1/0):5 with linespoints pointsize 1.5 "
          "title 'from scratch', 'bench.csv' using (strcol(1) eq 'move' ? $3 : 1/0):5 with linespoints pointsize 1.5 "
          "title 'after a move', 0.01 title '1 %' dt 2\n";
    writeFileAtomically((out / "plot.gp").string(), gp.str());
    runGnuplot(outDir, "plot.png");
    std::printf("wrote %s/bench.csv, scaling.csv, summary.txt\n", outDir.c_str());
    return 0;
}

}  // namespace candela
