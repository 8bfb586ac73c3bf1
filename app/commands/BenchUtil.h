#pragma once
// Image metrics and small helpers shared by the benches (app/commands/Bench*.cpp).

#include <glm/glm.hpp>

#include <string>
#include <vector>

#include "app/commands/Commands.h"

namespace candela {

/// Rec. 709 luminance of an RGB triple.
double luma(const float* c);
/// sqrt(sum (x - r)^2 / sum r^2) over pixel luminances of RGB float images.
double relRmse(const std::vector<float>& x, const std::vector<float>& r);
/// sRGB8 to CIELAB (D65).
glm::dvec3 lab(const unsigned char* c);
/// Mean CIE76 Delta E between two sRGB8 RGB images.
double meanDeltaE(const std::vector<unsigned char>& x, const std::vector<unsigned char>& r);
/// "4,8,16" as integers (each checked as a sample count); throws InputError.
std::vector<int> parseList(const std::string& text);
/// "2.3x", or "n/a" for a ratio that could not be measured (NaN or infinite).
std::string formatRatio(double ratio);
/// Runs gnuplot on DIR/plot.gp writing DIR/OUTPUT; false (and a note on stdout) without gnuplot.
bool runGnuplot(const std::string& dir, const std::string& output);

/// `candela bench --prost`: the photometric-light evaluation of Prost (2019), Sec. 6.2.
int benchProst(const Args& args);
/// `candela bench --environment`: the environment techniques (app/commands/BenchEnvironment.cpp).
int benchEnvironment(const Args& args);

}  // namespace candela
