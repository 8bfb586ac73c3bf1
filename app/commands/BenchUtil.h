#pragma once
// Image metrics and small helpers shared by the benches (app/commands/Bench*.cpp), and each
// bench's options and entry point (app/commands/Bench.cpp reads them from the command line).

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "app/commands/Commands.h"
#include "renderer/ImageMetrics.h"
#include "renderer/LivePreview.h"

namespace candela {

/// The largest sample count of a list (parseList).
constexpr int kMaxSampleCount = 1 << 20;
/// "4,8,16" as integers (each a sample count in 1..kMaxSampleCount); throws InputError naming
/// `flag`.
std::vector<int> parseList(const std::string& text, const std::string& flag = "--spp");
/// "Intel(R) Xeon(R) ... , 2 cores": the CPU the bench ran on (from /proc/cpuinfo), for its
/// summary.
std::string machineDescription();
/// "2.3x", or "n/a" for a ratio that could not be measured (NaN or infinite).
std::string formatRatio(double ratio);
/// One image of a bench's sweep, compared with the reference.
struct BenchRow {
    std::string technique;
    int spp = 0;
    double shadeMs = 0.0;  ///< GPU time of the shading passes, ms
    double rmse = 0.0;     ///< Against the truth: the raw error with the reference's noise removed.
    double deltaE = 0.0;   ///< Mean CIE76 Delta E of the tone-mapped images
    double rawRmse = 0.0;  ///< Against the reference image as it is.
    int repeats = 1;       ///< Images (independent seeds) the row averages.
    double rmseSpread = 0.0;  ///< Standard deviation of one image's rmse over those repeats.
};
/// The mean of independent repeats of one (technique, spp): mean squared errors (so rmse is the
/// root of the expected squared error, as one image's rmse is of its own), mean Delta E and time,
/// and the spread of single images' rmse.
BenchRow meanRow(const std::vector<BenchRow>& repeats);
/// The row of an image (RGB float `linear`, sRGB8 `display`) against a reference whose own noise
/// (relative RMSE against the truth) is refNoise. The two are independent, so
/// E|x - r|^2 = |x - truth|^2 + |r - truth|^2: the reference's noise is removed in quadrature.
BenchRow benchRow(std::string technique, int spp, double shadeMs, const std::vector<float>& linear,
                  const std::vector<unsigned char>& display, const std::vector<float>& refLinear,
                  const std::vector<unsigned char>& refDisplay, double refNoise);
/// The row of `technique` at `spp`; one with NaN error and time when the sweep has none.
BenchRow rowAt(const std::vector<BenchRow>& rows, const std::string& technique, int spp);
/// Samples (time: GPU ms) a technique needs to reach `error`: log-log interpolation along its
/// rows; NaN when its sweep never gets there.
double atError(const std::vector<BenchRow>& rows, const std::string& technique, double error,
               bool time);
/// bench.csv: technique,spp,gpu_ms,rel_rmse,mean_delta_e,rel_rmse_raw,repeats,rel_rmse_spread
/// (written through a temporary file and a rename, as every bench output: util/FileOutput.h).
void writeBenchCsv(const std::string& path, const std::vector<BenchRow>& rows);
/// A gnuplot `plot for` line drawing bench.csv's column yColumn against xColumn, one line per
/// technique of the space-separated list.
std::string sweepPlot(const std::string& techniques, int xColumn, int yColumn);
/// Runs gnuplot on DIR/plot.gp writing DIR/OUTPUT; false (and a note on stdout) without gnuplot
/// or when gnuplot fails. A failure to write DIR/OUTPUT is an InputError.
bool runGnuplot(const std::string& dir, const std::string& output);

// ---- The benches of `candela bench` (app/commands/Bench.cpp reads their command line) --------

/// `candela bench --environment`: the environment techniques (app/commands/BenchEnvironment.cpp).
struct EnvironmentOptions {
    std::string source;  ///< "sky" (the bench's procedural sky) or an .hdr or .exr map.
    std::string out = "bench-environment";
    std::vector<int> spp = {4, 8, 16, 32, 64, 128, 256, 512};
    int referenceSpp = 16384;
    int width = 480, height = 270;  ///< Image size, pixels.
    int temporalFrames = 24, temporalSpp = 16;
    int repeats = 4;
};
int benchEnvironment(const EnvironmentOptions& options);

/// `candela bench --prost`: the photometric-light evaluation of Prost (2019), Sec. 6.2
/// (app/commands/BenchProst.cpp).
struct ProstOptions {
    std::vector<std::string> files;  ///< As given: a folder stands for its .ies and .ldt files.
    std::string out = "bench-prost";
    int size = 128;  ///< Receivers along each side of the ground region.
    int referenceSpp = 2048;
};
int benchProst(const ProstOptions& options);

/// `candela bench --shadows`: shadow maps against ray-traced visibility
/// (app/commands/BenchShadows.cpp).
struct ShadowOptions {
    std::string scenePath =
        std::string(CANDELA_SOURCE_DIR) + "/resources/scenes/headlight-room.json";
    std::string out = "bench-shadows";
    std::vector<int> counts = {1,  4,  9, 16,
                               25, 49, 0};  ///< Maps per luminaire swept (0: one per cell).
    std::vector<int> sizes = {32,  64,  128,
                              192, 256, 512};  ///< Cube-face resolutions swept, texels.
    int spp = 256;
    int width = 480, height = 270;  ///< Image size, pixels.
    int fixedCount = 49;            ///< Maps while the resolution is swept.
    int fixedSize = 192;            ///< Resolution while the count is swept, texels.
};
int benchShadows(const ShadowOptions& options);

/// `candela bench --indirect`: interreflected light from scratch and after a move, against time
/// (app/commands/BenchIndirect.cpp).
struct IndirectOptions {
    std::string scenePath = std::string(CANDELA_SOURCE_DIR) + "/resources/scenes/office.json";
    std::string out = "bench-indirect";
    std::string moved = "Downlight 2";  ///< The luminaire moved 1 m.
    int patches = 2500;                 ///< Asked of the mesher.
    double spacing = 0.25;              ///< Between work-plane points, m.
    double height = 0.8;                ///< Of the work plane, m.
};
int benchIndirect(const IndirectOptions& options);

/// `candela bench --drag`: the editor's frame rate while dragging and refinement after release
/// (app/commands/BenchDrag.cpp).
struct DragOptions {
    std::string scenePath = std::string(CANDELA_SOURCE_DIR) + "/resources/scenes/editor-room.json";
    std::string out = "bench-drag";
    int width = 960, height = 540;  ///< Full image size, pixels.
    int frames = 60;                ///< Frames of each drag.
    int referenceSpp = 1024;
    double timeout = 60.0;  ///< Longest refinement after a release, seconds of rendering.
    PreviewPolicy policy;
    int samplesPerFrame = 16;  // as the editor (ui/Editor.cpp)
};
int benchDrag(const DragOptions& options);

/// `candela bench --design`: the designer's calculations' time and accuracy
/// (app/commands/BenchDesign.cpp).
struct DesignOptions {
    std::string out = "bench-design";
    /// Folder of office.json, classroom.json and office-gldf.json.
    std::string scenes = std::string(CANDELA_SOURCE_DIR) + "/resources/scenes";
    int referenceSpp = 4096;
};
int benchDesign(const DesignOptions& options);

}  // namespace candela
