#pragma once
// The comparison sheet: every pane of a Comparison and its reference as labelled tiles
// (technique, samples, GPU time, Delta E and relative RMSE under each), written by
// report/ComparisonSheet.h as PNG, EXR and a JSON sidecar holding what reproduces it (the scene as
// it was, the camera, each pane's technique list, sample budget, seed and settings). The editor's
// Export sheet and `candela render --compare` both write it.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "renderer/Comparison.h"
#include "report/ComparisonSheet.h"
#include "scene/Scene.h"

namespace candela {

/// A GPU time for labels: "850.0 ms" (msDecimals after the point) below a second, "2.31 s" above.
std::string formatMs(double ms, int msDecimals = 1);

/// The sidecar's description of the comparison: panes (name, technique list, techniques used,
/// budget, results and measured series), the reference, the shared settings.
nlohmann::json comparisonJson(const Comparison& comparison,
                              const std::vector<std::string>& paneNames);

/// Measures the panes as they are (Comparison::measureNow), then writes DIR/sheet-NNN.{png,exr,
/// json}: the panes (their signed error maps instead of the images when errorMaps; the EXR keeps
/// the linear images) in two columns, then the reference, each image the one its label's
/// samples, time and errors were measured on, tone-mapped as the Delta E saw it. paneNames
/// labels the panes ("A", "B"). Throws InputError naming the file on failure.
SheetFiles exportComparisonSheet(const std::filesystem::path& dir, Comparison& comparison,
                                 const Scene& scene, const std::vector<std::string>& paneNames,
                                 bool errorMaps);

}  // namespace candela
