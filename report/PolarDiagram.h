#pragma once
// The polar candela diagram of a far-field photometry, as lighting reports draw it: intensity in
// the C0-C180 and C90-C270 planes as two curves, gamma 0 (the aim, nadir for a downlight) at the
// bottom, C0 and C90 on the right half, C180 and C270 on the left, rings of round candela values.
// The curves and the rings are plain data (also used by `candela polar`); drawPolarDiagram draws
// them with Dear ImGui's draw list.

#include <vector>

namespace candela {
struct PhotometricData;
}

namespace candela {

/// Intensity along the two vertical planes at the angles gamma, from PhotometricData::intensity
/// towards (cos C sin gamma, sin C sin gamma, cos gamma) in the luminaire's local frame.
struct PolarCurves {
    std::vector<double> gamma;                ///< Angle from the aim, degrees, 0 .. 180.
    std::vector<double> c0, c180, c90, c270;  ///< Luminous intensity in each half plane, cd.
    double peak = 0.0;                        ///< Largest value of the four curves, cd.
};

/// Samples the curves at every `stepDeg` degrees from 0 to 180 (180 included).
PolarCurves polarCurves(const PhotometricData& data, double stepDeg = 1.0);
/// Samples them at the given angles (degrees, each in [0, 180]).
PolarCurves polarCurves(const PhotometricData& data, const std::vector<double>& gammaDeg);

/// Ring values of the radial axis, cd: steps of 1, 2 or 5 times a power of ten, 2 to 5 rings, the
/// last at or above peak (one ring at 1 cd if peak <= 0).
std::vector<double> polarRings(double peak);

/// Draws the diagram of `data` at the ImGui cursor in a square of sizePx pixels (the caller's
/// window must be open; the cursor advances past it): both curves (C0-C180 solid orange, C90-C270
/// blue), the rings labelled in cd, spokes every 30 degrees labelled in degrees, and a legend
/// with the peak intensity. Call it from any panel, e.g. the inspector of a photometric luminaire:
///     drawPolarDiagram(luminaire.photometry(), ImGui::GetContentRegionAvail().x);
void drawPolarDiagram(const PhotometricData& data, float sizePx);

}  // namespace candela
