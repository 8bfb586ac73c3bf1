#pragma once
// Error metrics between two images of one view (the benches' columns and the editor's comparison
// panes), and the tone mapping they are taken through. CPU only, no GL.

#include <glm/glm.hpp>
#include <vector>

namespace candela {

/// Rec. 709 luminance of an RGB triple.
double luma(const float* c);
/// sqrt(sum (x - r)^2 / sum r^2) over pixel luminances of RGB float images; 0 when r is black.
double relRmse(const std::vector<float>& x, const std::vector<float>& r);
/// The same over the pixels whose skip entry is 0 (skip holds one byte per pixel; empty: none).
double relRmse(const std::vector<float>& x, const std::vector<float>& r,
               const std::vector<unsigned char>& skip);
/// Mean pixel luminance of an RGB float image.
double meanLuminance(const std::vector<float>& rgb);
/// sRGB8 to CIELAB (D65).
glm::dvec3 lab(const unsigned char* c);
/// Mean CIE76 Delta E between two sRGB8 RGB images.
double meanDeltaE(const std::vector<unsigned char>& x, const std::vector<unsigned char>& r);
/// The exponential operator of shaders/tonemap.frag on the CPU: sRGB8 of 1 - exp(-k c / average)
/// per channel (Reinhard's when reinhard is set: m / (1 + m), m = 0.18 k c / average).
std::vector<unsigned char> toneMapSrgb8(const std::vector<float>& rgb, double average,
                                        double exposure, bool reinhard = false);

/// One measurement of an image against a reference: what it cost and how far it is.
struct ErrorPoint {
    double timeMs = 0.0;   ///< GPU time spent on the image so far, ms.
    int spp = 0;           ///< Samples per pixel (0: a deterministic technique).
    double relRmse = 0.0;  ///< Relative RMSE of luminance, the reference's own noise removed.
    double deltaE = 0.0;   ///< Mean CIE76 Delta E of the tone-mapped images.
};

}  // namespace candela
