// The hard-case grid on the CPU estimators (issue 18, part 1): every case of HardCases.cpp times
// every technique the registry lists for its kind, each held to its stated limit
// (TechniqueLimits.cpp, the table in docs/hard-cases.md). Stochastic techniques run at two sample
// counts, so a standard error that hides a miss at few samples fails too.
#include "tests/hardcases/HardCases.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "luminaires/Registry.h"
#include "tests/hardcases/TechniqueLimits.h"

namespace candela {
namespace {

TEST(HardCases, EveryTechniqueHoldsItsStatedLimit) {
    int checked = 0;
    for (const hard::Case& c : hard::cases()) {
        for (const TechniqueInfo& t : techniques()) {
            if (t.kind != c.kind || !t.irradiance) continue;
            hard::Promise p = hard::promise(t, c);
            for (int spp : {256, 4096}) {
                if (!t.progressive && spp != 4096) continue;  // deterministic: one run says all
                EstimateOptions o;
                o.spp = spp;
                o.seed = 17;
                Estimate e = t.irradiance(*c.light, c.p, c.n, o);
                std::string why = hard::judge(c, p, e);
                EXPECT_TRUE(why.empty()) << c.name << " [" << hard::className(c.cls) << "], "
                                         << t.name << " at " << spp << " spp: " << why;
                ++checked;
            }
        }
    }
    // Every kind with a case, and a few hundred checks: the grid did not silently shrink.
    EXPECT_GE(checked, 200);
}

// The grid covers every kind that has techniques with CPU estimators, and every class of trouble.
TEST(HardCases, GridCoversEveryKindAndClass) {
    for (const LuminaireKindInfo& k : luminaireKinds()) {
        bool has = false;
        for (const hard::Case& c : hard::cases()) has = has || c.kind == k.kind;
        EXPECT_TRUE(has) << "no hard case for the kind " << k.name;
    }
    for (int cls = 0; cls <= int(hard::Class::Table); ++cls) {
        bool has = false;
        for (const hard::Case& c : hard::cases()) has = has || int(c.cls) == cls;
        EXPECT_TRUE(has) << "no hard case of class " << hard::className(hard::Class(cls));
    }
}

// The test's own references against each other where two apply: on the 0.6 x 0.3 m Lambertian
// opening, Lambert's polygon formula (the expected values) and the graded area quadrature (the
// spike's expected value) are independent; a slip in either shows here. 1e-6: both are exact to
// far better; the quadrature's graded grid resolves contact down to 1e-12 of the opening.
TEST(HardCases, ReferencesAgree) {
    int compared = 0;
    for (const hard::Case& c : hard::cases()) {
        if (c.name.rfind("photometric/lambert/", 0) != 0 || c.cls == hard::Class::OnPlane ||
            c.expected == 0.0)
            continue;
        double quadrature = hard::areaForm(c.p, c.n, 0.3, 0.15, c.intensity);
        EXPECT_NEAR(quadrature, c.expected, 1e-6 * c.expected) << c.name;
        // And no receiver gets more than the opening at its brightest radiance everywhere.
        EXPECT_LE(c.expected, c.upperBound * (1.0 + 1e-9)) << c.name;
        ++compared;
    }
    EXPECT_GE(compared, 6);
}

}  // namespace
}  // namespace candela
