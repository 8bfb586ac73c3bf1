#pragma once
// The harness every `candela bench` shares (app/commands/Bench*.cpp; the command line is read in
// app/commands/Bench.cpp), so that a bench is the description of its sweep plus what is genuinely
// its own:
//  - BenchFolder, CsvFile, BenchSummary, writePlot: the output folder, CSV files, summary.txt
//    (opening with the machine) and the gnuplot script and image;
//  - BenchGpu, renderShot: an image rendered from scratch until converged at a sample budget,
//    with the GPU time of each pass;
//  - Sweep, renderReference, runSweep: techniques at increasing sample counts against a
//    converged reference whose own noise is measured, as bench.csv rows (BenchUtil.h).
// Every file goes through util/FileOutput.h (a temporary file and a rename).

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "app/commands/BenchUtil.h"
#include "app/commands/Commands.h"
#include "renderer/FrameStats.h"
#include "renderer/Renderer.h"
#include "renderer/ShaderLibrary.h"
#include "renderer/context/GlContext.h"

namespace candela {

struct Scene;

// ---- Output files ------------------------------------------------------------------------------

/// A bench's output folder, whole or not at all: the bench writes into path(), a staging folder
/// DIR/.partial-PID inside DIR (created with DIR and its parents; InputError naming DIR when
/// that fails), and commit() moves what it wrote into DIR, refusing before it moves anything
/// when a file would land on a protected input. Destroyed without commit() (the bench failed),
/// the staging folder is removed and DIR keeps what it held before.
class BenchFolder {
  public:
    explicit BenchFolder(const std::string& dir);
    ~BenchFolder();
    BenchFolder(const BenchFolder&) = delete;
    BenchFolder& operator=(const BenchFolder&) = delete;

    /// Where the bench writes.
    const std::filesystem::path& path() const { return mStaging; }
    /// Moves every file written into the folder (renames within one file system).
    void commit();

  private:
    std::filesystem::path mDir, mStaging;
};

/// printf into a string.
std::string formatText(const char* format, ...) __attribute__((format(printf, 1, 2)));

/// A CSV file built row by row: values joined by commas as an ostream prints them.
class CsvFile {
  public:
    explicit CsvFile(std::string_view header);
    template <class... Values>
    void row(const Values&... values) {
        const char* separator = "";
        ((mText << separator << values, separator = ","), ...);
        mText << "\n";
    }
    /// A row formatted by the caller, without its newline.
    void line(std::string_view text) { mText << text << "\n"; }
    std::string text() const { return mText.str(); }
    /// Writes it whole (again, for a file rewritten as rows arrive).
    void write(const std::filesystem::path& path) const;

  private:
    std::ostringstream mText;
};

/// summary.txt: the machine first (the CPU: on a software rasterizer GPU times are CPU times),
/// then the bench's lines.
class BenchSummary {
  public:
    BenchSummary();
    /// Appends printf-formatted text (with its own newlines).
    void add(const char* format, ...) __attribute__((format(printf, 2, 3)));
    void addText(std::string_view text) { mText << text; }
    /// "light: WHAT": which light the bench's figures include (every bench says so).
    void light(std::string_view what) { mText << "light: " << what << "\n"; }
    std::string text() const { return mText.str(); }
    /// Writes DIR/summary.txt, and prints it on stdout when `echo`.
    void write(const std::filesystem::path& dir, bool echo = true) const;

  private:
    std::ostringstream mText;
};

/// DIR/plot.gp (a pngcairo terminal of width x height pixels, comma-separated data, then `body`)
/// and DIR/OUTPUT drawn from it by gnuplot when installed (runGnuplot).
void writePlot(const std::filesystem::path& dir, int width, int height, const std::string& body,
               const std::string& output);

// ---- Rendering ---------------------------------------------------------------------------------

/// The offscreen GL context, shader library and renderer of a bench, made in that order.
struct BenchGpu {
    BenchGpu();
    std::unique_ptr<GlContext> context;
    ShaderLibrary shaders;
    Renderer renderer;
};

/// GPU time of the passes whose names begin with `prefix` ("shade:", "shadow:", "env:cdf"), ms.
double gpuMs(const std::vector<PassTiming>& passes, std::string_view prefix);

/// One image rendered until converged, and what it cost.
struct Shot {
    std::vector<float> linear;           ///< RGB radiance in the scene's unit.
    std::vector<unsigned char> display;  ///< Tone-mapped sRGB8.
    std::vector<PassTiming> passes;      ///< GPU ms of each pass, summed over the frames.
    int frames = 0;
    double gpuMs(std::string_view prefix) const { return candela::gpuMs(passes, prefix); }
};

/// Where a technique's name goes in RenderSettings: the luminaires' override or the environment's.
enum class TechniqueSlot { Luminaires, Environment };
RenderSettings withTechnique(RenderSettings settings, TechniqueSlot slot,
                             const std::string& technique);
/// `settings` with a budget of `spp` samples per pixel, at most `maxPerFrame` a frame, and `seed`.
RenderSettings withBudget(RenderSettings settings, int spp, uint32_t seed, int maxPerFrame);
/// Renders `scene` from scratch (kChangeAll) with `settings` until converged; reads the image
/// back when `read`.
Shot renderShot(Renderer& renderer, const Scene& scene, const RenderSettings& settings,
                bool read = true);

// ---- Sweeps against a reference ----------------------------------------------------------------

/// Techniques at increasing sample counts against a converged reference (bench.csv).
struct Sweep {
    TechniqueSlot slot = TechniqueSlot::Luminaires;
    std::string reference;  ///< Unbiased technique, converged at referenceSpp.
    int referenceSpp = 0;
    std::vector<std::string> progressive;    ///< Each rendered at every count of spp.
    std::vector<std::string> deterministic;  ///< One frame each: their error is their bias.
    std::vector<int> spp;
    int repeats = 1;          ///< Images of independent seeds per (technique, spp), averaged.
    std::string timedPasses;  ///< Prefix of the passes whose GPU time a row reports.
    int maxPerFrame = 64;     ///< Samples per pixel per frame.
};

/// The converged reference of a sweep.
struct Reference {
    std::vector<float> linear;           ///< RGB, the mean of the two halves.
    std::vector<unsigned char> display;  ///< Tone-mapped against its own mean luminance.
    double noise = 0.0;  ///< Its relative RMSE against the truth, from its two halves.
};

/// Renders the reference as two halves of independent seeds, whose difference measures its own
/// noise (the floor under which no error can be resolved); sets settings.fixedAverage to its
/// mean luminance, so every image is tone-mapped alike; writes DIR/reference.png and .exr.
Reference renderReference(Renderer& renderer, const Scene& scene, RenderSettings& settings,
                          const Sweep& sweep, const std::filesystem::path& dir);
/// Compiles every technique, then renders the sweep (seeds 7, 8, ... in order): a row per
/// (technique, spp) and per deterministic technique, and images at the first, 64 and last
/// sample counts (DIR/TECHNIQUE_SPP.png) and of each deterministic one (DIR/TECHNIQUE.png).
std::vector<BenchRow> runSweep(Renderer& renderer, const Scene& scene,
                               const RenderSettings& settings, const Sweep& sweep,
                               const Reference& reference, const std::filesystem::path& dir);

}  // namespace candela
