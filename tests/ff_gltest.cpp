// Float-float arithmetic (shaders/ff.glsl) under the compiler that runs the shaders, against 64-bit
// arithmetic on the CPU. The summed-area tables and environment CDFs depend on it to keep the
// digits that fp64 kept before; a compiler that reassociates or fuses the error-free
// transformations (ignoring `precise`) or lowers fma inexactly fails here first.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tests/TestUtil.h"
#include "util/FloatFloat.h"

namespace candela {
namespace {

struct FfIn {
    glm::vec4 ab, c;
};
struct FfOut {
    glm::vec4 sumDifference, productQuotient, twoProduct;
};

TEST(FloatFloatGl, ArithmeticKeepsAbout47Bits) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    std::vector<FfIn> in;
    std::vector<glm::dvec3> values;  // a, b, c as 64-bit numbers (a and b exactly their pairs)
    for (int k = 0; k < 4096; ++k) {
        // Magnitudes from 1e-12 to 1e12, and b near -a for a quarter of them (cancellation).
        double a = U(rng) * std::pow(10.0, 12.0 * U(rng));
        double b = k % 4 == 0 ? -a * (1.0 + 1e-9 * U(rng)) : U(rng) * std::pow(10.0, 12.0 * U(rng));
        float c = float(U(rng) * std::pow(10.0, 6.0 * U(rng)));
        glm::vec2 pa = toFloatFloat(a), pb = toFloatFloat(b);
        in.push_back({glm::vec4(pa, pb), glm::vec4(c, 0.f, 0.f, 0.f)});
        values.push_back({fromFloatFloat(pa), fromFloatFloat(pb), double(c)});
    }
    std::vector<FfOut> out = test::runComputeTest<FfOut>("../tests/shaders/ff_parity.comp",
                                                         std::vector<std::byte>(16), in);
    // Float-float's unit roundoff is 2^-48; a sum or difference errs by a few of those relative
    // to its operands (the "sloppy" sum), a product or quotient relative to its result: 2^-44
    // leaves a factor 16 for the few roundings each chains.
    const double kEps = std::ldexp(1.0, -44);
    for (size_t k = 0; k < in.size(); ++k) {
        double a = values[k].x, b = values[k].y, c = values[k].z;
        const FfOut& o = out[k];
        double scale = std::abs(a) + std::abs(b);
        EXPECT_NEAR(fromFloatFloat({o.sumDifference.x, o.sumDifference.y}), a + b, kEps * scale)
            << k;
        EXPECT_NEAR(fromFloatFloat({o.sumDifference.z, o.sumDifference.w}), a - b, kEps * scale)
            << k;
        EXPECT_NEAR(fromFloatFloat({o.productQuotient.x, o.productQuotient.y}), a * c,
                    kEps * std::abs(a * c))
            << k;
        EXPECT_NEAR(fromFloatFloat({o.productQuotient.z, o.productQuotient.w}), a / b,
                    kEps * std::abs(a / b))
            << k;
        // The error-free transformations are exact: a float product of two floats fits in 48
        // bits and a float sum's error is a float (for these magnitudes), so a 64-bit number
        // holds both exactly.
        double hiA = double(in[k].ab.x), hiB = double(in[k].ab.z);
        ASSERT_EQ(double(o.twoProduct.x) + double(o.twoProduct.y), hiA * c) << k;
        ASSERT_EQ(double(o.twoProduct.z) + double(o.twoProduct.w), hiA + hiB) << k;
    }
}

}  // namespace
}  // namespace candela
