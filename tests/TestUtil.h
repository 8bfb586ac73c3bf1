#pragma once
// Helpers shared by the tests: statistics for sampler tests and a GL context for *_gltest.cpp.

#include <memory>
#include <string>
#include <vector>

namespace candela {
class GlContext;
}

namespace candela::test {

/// Upper tail of the chi-square distribution with k degrees of freedom: P(X >= x).
double chiSquareSurvival(double x, double k);

struct ChiSquareResult {
    double statistic = 0.0;
    int degreesOfFreedom = 0;
    double pValue = 0.0;
};

/// Pearson's test of observed counts against expected counts. Cells whose expected count is
/// below 5 are pooled into one cell (the usual validity rule). The expected counts should sum
/// to the number of samples; mass outside the cells may be passed as one more cell.
ChiSquareResult chiSquare(const std::vector<double>& observed, const std::vector<double>& expected);

/// One OSMesa context for the whole GL test binary (created on first use).
GlContext& glContext();

/// Folder of the test data (tests/data) and of the repository.
std::string dataDir();
std::string sourceDir();

}  // namespace candela::test
