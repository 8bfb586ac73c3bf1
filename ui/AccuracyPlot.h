#pragma once
// Accuracy against cost: how fast each rendering technique converges to the progressive reference.
// Each technique is a series of measurements (GPU time, samples per pixel, error); the series come
// from the editor's live comparison or from a benchmark's CSV (readBenchCsv). errorAtTime and
// winnerAt answer "which technique is best for a budget of T ms"; accuracyPlot draws the series
// on log-log axes with Dear ImGui's draw list.

#include <imgui.h>

#include <cstddef>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "renderer/ImageMetrics.h"

namespace candela::ui {

/// Which error of an ErrorPoint a plot or a comparison uses.
enum class ErrorMetric { RelRmse, DeltaE };

/// The measurements of one technique.
struct ErrorSeries {
    std::string label;               ///< Technique name (bench series: "NAME (bench)").
    std::vector<ErrorPoint> points;  ///< In increasing timeMs.
    bool fromBench = false;          ///< Read from a benchmark's CSV; drawn dashed.
};

/// Reads a benchmark's CSV (header `technique,spp,gpu_ms,rel_rmse,mean_delta_e,...`; columns found
/// by name, others ignored): one series per technique in order of first appearance, labelled
/// "NAME (bench)" with fromBench set, points in file order. Blank lines are skipped. Throws
/// candela::InputError naming the file and, for a bad row, its line number and what is wrong
/// (missing file, missing column, non-numeric, non-finite or negative value, wrong field count).
std::vector<ErrorSeries> readBenchCsv(const std::filesystem::path& path);

/// The metric's value of a point (relative RMSE as a fraction, or mean Delta E).
double metricOf(const ErrorPoint& p, ErrorMetric metric);

/// The error the series has reached after timeMs (ms) of GPU time: NaN before its first point
/// (or for an empty series); linear in log time vs log error between the two points around
/// timeMs; after the last point, the last point's error (the technique stopped there). Points
/// with non-finite time or error are ignored; segments with a non-positive time or error are
/// interpolated linearly instead, so the result is never NaN or inf once the series has started.
double errorAtTime(const ErrorSeries& series, double timeMs, ErrorMetric metric);

/// The best technique at a time budget.
struct Winner {
    int series = -1;                                          ///< Index, -1 when none.
    double error = std::numeric_limits<double>::quiet_NaN();  ///< Its errorAtTime.
};

/// The series with the lowest errorAtTime at timeMs (ms) among those that have a value there
/// (the first on a tie); series -1 when none has.
Winner winnerAt(const std::vector<ErrorSeries>& series, double timeMs, ErrorMetric metric);

/// Colour of series `index` in plots and legends: a fixed palette of 8, repeating.
ImU32 seriesColour(size_t index);

/// Decade label of a time axis: "0.1 ms", "1 ms", "100 ms", "1 s", "10 s".
std::string timeTickLabel(double ms);
/// Decade label of an error axis: relative RMSE in percent ("1%", "100%"), Delta E as a plain
/// number ("0.1", "10").
std::string metricTickLabel(double value, ErrorMetric metric);

/// Draws the series as a log-log plot (x: GPU time in ms, y: the metric) in a region of `size`
/// pixels at the ImGui cursor, taken as an InvisibleButton `id` (a size <= 0 on an axis takes
/// the available width or height). Decade grid with labels, one coloured polyline with markers per
/// series (dashed when fromBench), a legend, a vertical line at budgetMs (ms, when > 0) with the
/// winner there drawn thicker and its error marked; a tooltip on the point under the mouse.
/// Points with a non-finite or non-positive time or error are skipped.
void accuracyPlot(const char* id, const std::vector<ErrorSeries>& series, ErrorMetric metric,
                  double budgetMs, ImVec2 size);

}  // namespace candela::ui
