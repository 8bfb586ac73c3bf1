// The hard-case grid on the CPU estimators (issue 18, part 1).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "luminaires/Registry.h"
#include "tests/hardcases/HardCases.h"

namespace candela {
namespace {

TEST(HardCases, PrintMatrix) {
    for (const hard::Case& c : hard::cases()) {
        for (const TechniqueInfo& t : techniques()) {
            if (t.kind != c.kind || !t.irradiance) continue;
            EstimateOptions o;
            o.spp = 4096;
            Estimate e = t.irradiance(*c.light, c.p, c.n, o);
            double got = 0.2126 * e.irradiance.x + 0.7152 * e.irradiance.y + 0.0722 * e.irradiance.z;
            double se = 0.2126 * e.stdError.x + 0.7152 * e.stdError.y + 0.0722 * e.stdError.z;
            double rel = c.expected != 0.0 ? got / c.expected : (got == 0.0 ? 1.0 : INFINITY);
            std::printf("%-46s %-20s expected %-12.5g got %-12.5g (x%-10.4g) se %.3g\n", c.name.c_str(),
                        std::string(t.name).c_str(), c.expected, got, rel, se);
        }
    }
}

}  // namespace
}  // namespace candela
