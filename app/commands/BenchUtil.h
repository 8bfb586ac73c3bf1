#pragma once
// Image metrics and small helpers shared by the benches (app/commands/Bench*.cpp).

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "app/commands/Commands.h"
#include "renderer/ImageMetrics.h"

namespace candela {

/// "4,8,16" as integers (each checked as a sample count); throws InputError.
std::vector<int> parseList(const std::string& text);
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

/// `candela bench --prost`: the photometric-light evaluation of Prost (2019), Sec. 6.2.
int benchProst(const Args& args);
/// `candela bench --environment`: the environment techniques (app/commands/BenchEnvironment.cpp).
int benchEnvironment(const Args& args);
/// `candela bench --drag`: the editor's frame rate while dragging and refinement after release
/// (app/commands/BenchDrag.cpp).
int benchDrag(const Args& args);
/// `candela bench --shadows`: shadow maps against ray-traced visibility
/// (app/commands/BenchShadows.cpp).
int benchShadows(const Args& args);
/// `candela bench --indirect`: interreflected light from scratch and after a move, against time
/// (app/commands/BenchIndirect.cpp).
int benchIndirect(const Args& args);
/// `candela bench --design`: the designer's calculations' time and accuracy
/// (app/commands/BenchDesign.cpp).
int benchDesign(const Args& args);

}  // namespace candela
