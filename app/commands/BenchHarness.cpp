#include "app/commands/BenchHarness.h"

#include <unistd.h>

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <system_error>

#include "renderer/ImageFile.h"
#include "renderer/ImageMetrics.h"
#include "scene/Scene.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

namespace fs = std::filesystem;

// ---- Output files ------------------------------------------------------------------------------

BenchFolder::BenchFolder(const std::string& dir) : mDir(dir) {
    std::error_code ec;
    fs::create_directories(mDir, ec);
    if (ec) throw InputError(dir + ": cannot create folder (" + ec.message() + ")");
    mStaging = mDir / (".partial-" + std::to_string(::getpid()));
    fs::remove_all(mStaging, ec);  // a crashed run's of the same process id
    fs::create_directory(mStaging, ec);
    if (ec) throw InputError(dir + ": cannot create a folder in it (" + ec.message() + ")");
}

BenchFolder::~BenchFolder() {
    std::error_code ec;
    fs::remove_all(mStaging, ec);
}

void BenchFolder::commit() {
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(mStaging))
        if (!entry.is_directory()) files.push_back(fs::relative(entry.path(), mStaging));
    for (const fs::path& f : files) checkNotAnInput((mDir / f).string(), "--out");
    for (const fs::path& f : files) {
        std::error_code ec;
        fs::create_directories((mDir / f).parent_path(), ec);
        fs::rename(mStaging / f, mDir / f, ec);
        if (ec)
            throw InputError((mDir / f).string() + ": cannot move the bench's result into place (" +
                             ec.message() + ")");
    }
}

namespace {

std::string formatList(const char* format, va_list args) {
    va_list copy;
    va_copy(copy, args);
    int length = std::vsnprintf(nullptr, 0, format, copy);
    va_end(copy);
    std::string text(size_t(std::max(length, 0)), '\0');
    std::vsnprintf(text.data(), text.size() + 1, format, args);
    return text;
}

}  // namespace

std::string formatText(const char* format, ...) {
    va_list args;
    va_start(args, format);
    std::string text = formatList(format, args);
    va_end(args);
    return text;
}

CsvFile::CsvFile(std::string_view header) {
    mText << header << "\n";
}

void CsvFile::write(const fs::path& path) const {
    writeFileAtomically(path.string(), mText.str());
}

BenchSummary::BenchSummary() {
    mText << "machine: " << machineDescription() << "\n";
}

void BenchSummary::add(const char* format, ...) {
    va_list args;
    va_start(args, format);
    mText << formatList(format, args);
    va_end(args);
}

void BenchSummary::write(const fs::path& dir, bool echo) const {
    writeFileAtomically((dir / "summary.txt").string(), mText.str());
    if (echo) std::fputs(mText.str().c_str(), stdout);
}

void writePlot(const fs::path& dir, int width, int height, const std::string& body,
               const std::string& output) {
    std::string script =
        formatText("set terminal pngcairo size %d,%d noenhanced\nset datafile separator ','\n",
                   width, height) +
        body;
    writeFileAtomically((dir / "plot.gp").string(), script);
    runGnuplot(dir.string(), output);
}

// ---- Rendering ---------------------------------------------------------------------------------

BenchGpu::BenchGpu() : context(createOffscreenContext()), shaders(), renderer(shaders) {
    renderer.setExactTimes(true);  // a bench's figures are each frame's own GPU times
}

double gpuMs(const std::vector<PassTiming>& passes, std::string_view prefix) {
    double ms = 0.0;
    for (const PassTiming& p : passes)
        if (std::string_view(p.name).substr(0, prefix.size()) == prefix) ms += p.gpuMs;
    return ms;
}

RenderSettings withTechnique(RenderSettings settings, TechniqueSlot slot,
                             const std::string& technique) {
    (slot == TechniqueSlot::Environment ? settings.environmentTechnique
                                        : settings.techniqueOverride) = technique;
    return settings;
}

RenderSettings withBudget(RenderSettings settings, int spp, uint32_t seed, int maxPerFrame) {
    settings.samplesPerFrame = std::min(spp, maxPerFrame);
    settings.maxSamples = spp;
    settings.seed = seed;
    return settings;
}

Shot renderShot(Renderer& renderer, const Scene& scene, const RenderSettings& settings, bool read) {
    renderer.setSettings(settings);
    renderer.update(scene, kChangeAll);
    Shot shot;
    do {
        renderer.renderFrame();
        ++shot.frames;
        for (const PassTiming& p : renderer.stats().passes) {
            auto same = std::find_if(shot.passes.begin(), shot.passes.end(),
                                     [&](const PassTiming& t) { return t.name == p.name; });
            if (same == shot.passes.end())
                shot.passes.push_back(p);
            else
                same->gpuMs += p.gpuMs;
        }
    } while (!renderer.converged());
    if (read) {
        shot.linear = renderer.readLinear();
        shot.display = renderer.readDisplay();
    }
    return shot;
}

// ---- Sweeps against a reference ----------------------------------------------------------------

namespace {

constexpr uint32_t kFirstHalfSeed = 1000001;  ///< Seeds of the reference's two halves.
constexpr uint32_t kSecondHalfSeed = 2000003;
constexpr uint32_t kFirstSweepSeed = 7;  ///< The sweep's images take 7, 8, ... in order.
constexpr int kImageSpp = 64;  ///< Besides the first and last counts, images kept at this one.

/// One image of the sweep, timed, against the reference.
BenchRow measure(Renderer& renderer, const Scene& scene, const RenderSettings& settings,
                 const Sweep& sweep, const Reference& ref, const std::string& technique, int spp,
                 uint32_t seed, Shot& shot) {
    RenderSettings s =
        withBudget(withTechnique(settings, sweep.slot, technique), spp, seed, sweep.maxPerFrame);
    shot = renderShot(renderer, scene, s);
    // The image and the reference are independent, so E|x - r|^2 = |x - t|^2 + |r - t|^2: the
    // reference's own noise is removed from the error against it.
    return benchRow(technique, spp, shot.gpuMs(sweep.timedPasses), shot.linear, shot.display,
                    ref.linear, ref.display, ref.noise);
}

/// A progressive technique at one sample count: the mean of sweep.repeats images.
BenchRow sweepPoint(Renderer& renderer, const Scene& scene, const RenderSettings& settings,
                    const Sweep& sweep, const Reference& ref, const std::string& technique, int spp,
                    uint32_t& seed, const fs::path& dir) {
    std::vector<BenchRow> images;
    for (int k = 0; k < sweep.repeats; ++k) {
        Shot shot;
        images.push_back(
            measure(renderer, scene, settings, sweep, ref, technique, spp, seed++, shot));
        if (k == 0 && (spp == sweep.spp.front() || spp == kImageSpp || spp == sweep.spp.back()))
            writeImage8((dir / (technique + "_" + std::to_string(spp) + ".png")).string(),
                        settings.width, settings.height, shot.display);
    }
    BenchRow r = meanRow(images);
    if (r.repeats == 1)
        std::fprintf(stderr,
                     "bench: %-20s %6d spp  %9.2f ms  rel. RMSE %.4f (raw %.4f)  Delta E %.3f\n",
                     technique.c_str(), spp, r.shadeMs, r.rmse, r.rawRmse, r.deltaE);
    else
        std::fprintf(
            stderr,
            "bench: %-20s %6d spp  %9.2f ms  rel. RMSE %.4f +- %.4f over %d images  Delta E %.3f\n",
            technique.c_str(), spp, r.shadeMs, r.rmse, r.rmseSpread, r.repeats, r.deltaE);
    return r;
}

}  // namespace

Reference renderReference(Renderer& renderer, const Scene& scene, RenderSettings& settings,
                          const Sweep& sweep, const fs::path& dir) {
    int half = sweep.referenceSpp / 2;
    std::fprintf(stderr, "bench: reference, 2 x %d spp at %dx%d\n", half, settings.width,
                 settings.height);
    auto halfSettings = [&](uint32_t seed) {
        return withBudget(withTechnique(settings, sweep.slot, sweep.reference), half, seed,
                          sweep.maxPerFrame);
    };
    Shot first = renderShot(renderer, scene, halfSettings(kFirstHalfSeed));
    Shot second = renderShot(renderer, scene, halfSettings(kSecondHalfSeed));
    Reference ref;
    ref.linear.resize(first.linear.size());
    for (size_t i = 0; i < ref.linear.size(); ++i)
        ref.linear[i] = 0.5f * (first.linear[i] + second.linear[i]);
    ref.noise = 0.5 * relRmse(first.linear, second.linear);  // of the mean of both halves
    settings.fixedAverage = float(meanLuminance(ref.linear));
    // Tone-mapped with that average: the first half again (cheap next to the sweep, converged).
    ref.display = renderShot(renderer, scene, halfSettings(kFirstHalfSeed)).display;
    writeImage8((dir / "reference.png").string(), settings.width, settings.height, ref.display);
    writeImageFloat((dir / "reference.exr").string(), settings.width, settings.height, ref.linear);
    return ref;
}

std::vector<BenchRow> runSweep(Renderer& renderer, const Scene& scene,
                               const RenderSettings& settings, const Sweep& sweep,
                               const Reference& ref, const fs::path& dir) {
    auto compile = [&](const std::string& technique) {
        renderShot(renderer, scene,
                   withBudget(withTechnique(settings, sweep.slot, technique), 1, 1, 1), false);
    };
    // Every variant compiled before anything is timed.
    for (const std::string& t : sweep.progressive) compile(t);
    std::vector<BenchRow> rows;
    uint32_t seed = kFirstSweepSeed;
    for (const std::string& t : sweep.progressive)
        for (int spp : sweep.spp)
            rows.push_back(sweepPoint(renderer, scene, settings, sweep, ref, t, spp, seed, dir));
    for (const std::string& t : sweep.deterministic) {
        compile(t);
        Shot shot;
        BenchRow r = measure(renderer, scene, settings, sweep, ref, t, 1, seed++, shot);
        rows.push_back(r);
        std::fprintf(stderr, "bench: %-20s  1 frame  %9.2f ms  rel. RMSE %.4f  Delta E %.3f\n",
                     t.c_str(), r.shadeMs, r.rmse, r.deltaE);
        writeImage8((dir / (t + ".png")).string(), settings.width, settings.height, shot.display);
    }
    return rows;
}

}  // namespace candela
