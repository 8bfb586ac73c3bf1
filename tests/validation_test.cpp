// The validation suite (calculation/Validation.h), one ctest per case: each compares Candela's CPU
// path with a closed form within the tolerance the case states (integrating cube 1 %, sphere
// 2 %, direct light 0.5 %, obstruction 1 %, the CIE 171:2006 cases 1 %: what a design calculation
// promises; stochastic estimates beyond three standard errors).
#include "calculation/Validation.h"

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <glm/glm.hpp>

#include "util/Error.h"

namespace candela {
namespace {

class Validation : public testing::TestWithParam<std::string> {};

TEST_P(Validation, MatchesItsClosedForm) {
    ValidationResult r = runValidationCase(GetParam());
    EXPECT_TRUE(r.pass) << r.description << ": expected " << r.expected << " " << r.unit
                        << ", measured " << r.measured << " (" << 100.0 * r.deviation
                        << " %, tolerance " << 100.0 * r.tolerance << " %); " << r.detail;
    EXPECT_LE(std::abs(r.deviation), r.tolerance);
    EXPECT_GT(r.expected, 0.0);
}

INSTANTIATE_TEST_SUITE_P(Cases, Validation, testing::ValuesIn(validationCases()),
                         [](const testing::TestParamInfo<std::string>& info) {
                             std::string name = info.param;
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });

TEST(ValidationSuite, ClosedFormsAgreeWithQuadrature) {
    // The closed forms are the suite's yardstick, so they are checked on their own against a
    // 200 x 200 midpoint quadrature of cos cos / (pi r^2) (its error is below 1e-5 here).
    auto quadrature = [](auto point, double u0, double u1, double v0, double v1, glm::dvec3 n,
                         glm::dvec3 m) {
        const int k = 200;
        double sum = 0.0, du = (u1 - u0) / k, dv = (v1 - v0) / k;
        for (int j = 0; j < k; ++j)
            for (int i = 0; i < k; ++i) {
                glm::dvec3 q = point(u0 + (i + 0.5) * du, v0 + (j + 0.5) * dv);
                double r2 = glm::dot(q, q);
                double c1 = glm::dot(n, q) / std::sqrt(r2), c2 = -glm::dot(m, q) / std::sqrt(r2);
                if (c1 > 0 && c2 > 0) sum += c1 * c2 / (3.14159265358979323846 * r2) * du * dv;
            }
        return sum;
    };
    // Parallel: the element at the origin facing +z, the rectangle at z = 1.3 facing down.
    double parallel = quadrature([](double x, double y) { return glm::dvec3(x, y, 1.3); }, -0.4,
                                 0.9, 0.2, 1.1, {0, 0, 1}, {0, 0, -1});
    EXPECT_NEAR(parallelRectangleFactor(-0.4, 0.9, 0.2, 1.1, 1.3), parallel, 1e-5);
    // Perpendicular: the element facing +z, the rectangle in the plane x = 0.7 facing -x.
    double perpendicular = quadrature([](double y, double z) { return glm::dvec3(0.7, y, z); },
                                      -0.3, 0.5, 0.1, 0.9, {0, 0, 1}, {-1, 0, 0});
    EXPECT_NEAR(perpendicularRectangleFactor(-0.3, 0.5, 0.1, 0.9, 0.7), perpendicular, 1e-5);
}

TEST(ValidationSuite, UnknownCaseIsAClearError) {
    try {
        runValidationCase("cube-laser");
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("cube-laser"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("cube-point-rho0.5"), std::string::npos);
    }
}

}  // namespace
}  // namespace candela
