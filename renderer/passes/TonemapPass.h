#pragma once
// Linear HDR to display sRGB with the exponential or Reinhard operator, or to a false-colour
// picture of the values with isolux contour lines (shaders/tonemap.frag).

#include <vector>

#include "renderer/ShaderLibrary.h"
#include "renderer/gl/GlObjects.h"
#include "shaders/shared/FalseColour.h"

namespace candela {

struct RenderSettings;

/// The false-colour operator's legend. Values are in the image's unit: lux in illuminance mode
/// (W/m2 for radiometric luminaires), cd/m2 (W/(m2 sr)) in radiance mode.
struct FalseColourLegend {
    float min = 0.f;            ///< Value at the bottom of the scale, lux (> 0 for a log scale).
    float max = 500.f;          ///< Value at the top of the scale, lux (> min).
    bool logScale = false;      ///< Log scale (decades equally spaced) instead of linear.
    bool contours = true;       ///< Draw isolux lines.
    std::vector<float> levels;  ///< Isolux levels, lux; empty: at the legend's ticks.
    bool operator==(const FalseColourLegend&) const = default;
};

/// Most contour levels the shader takes (shared with shaders/tonemap.frag).
using gpu::kMaxContourLevels;

/// Round tick values of the legend, within [min, max] both included when they are round: steps
/// of 1, 2 or 5 times a power of ten (about `target` of them) for a linear scale; for a log scale
/// the decades, with 2 and 5 times them when at most three and a half decades are shown.
std::vector<float> legendTicks(const FalseColourLegend& legend, int target = 6);
/// Where isolux lines go: the legend's own levels (finite, positive for a log scale, sorted, at
/// most kMaxContourLevels), else its ticks strictly inside (min, max); none if contours are off.
std::vector<float> contourLevels(const FalseColourLegend& legend);
/// Sets the range from the largest value shown (peak, lux): linear from 0 to the first of 1, 2,
/// 2.5, 5 or 10 times a power of ten at or above it; log over the decade above it and 3 below.
void fitLegend(FalseColourLegend& legend, float peak);
/// The legend made valid: finite, max > min, min > 0 for a log scale (then max / min <= 1e9).
FalseColourLegend sanitizedLegend(FalseColourLegend legend);

class TonemapPass {
  public:
    void resize(int width, int height);
    /// position and emission: the G-buffer's (false colour greys out background and luminaires).
    void execute(ShaderLibrary& shaders, const gl::Texture2D& linear,
                 const gl::Texture2D& luminance, const gl::Texture2D& position,
                 const gl::Texture2D& emission, const RenderSettings& settings);
    const gl::Texture2D& display() const { return mDisplay; }

  private:
    gl::Texture2D mDisplay;
    gl::Framebuffer mFbo;
    int mWidth = 0, mHeight = 0;
};

}  // namespace candela
