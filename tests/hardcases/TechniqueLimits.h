#pragma once
// What each technique promises on each hard case (issue 18, part 1): the limits its registry line
// states (TechniqueInfo::limits, the table in docs/hard-cases.md), applied to a case, in a form
// the suites hold the techniques to. A technique without a statement is held to the strictest
// promise (exact if deterministic, unbiased with an honest standard error if progressive), so
// one added later is covered without editing the suites, and fails until it states its limits.

#include <string>

#include "luminaires/Registry.h"
#include "tests/hardcases/HardCases.h"

namespace candela::hard {

struct Promise {
    enum Kind {
        Exact,     ///< |E - expected| <= rel |expected| (+ abs); expected 0 means exactly 0.
        Unbiased,  ///< |E - expected| <= 4 standard errors + rel |expected|.
        Bounded,   ///< lo <= E <= hi (a stochastic E within 4 standard errors of them).
        PointLaw,  ///< E is the point law at the opening's centre (hard::pointLaw), rel.
        Finite,    ///< Finite and non-negative; any factor off (a documented approximation).
    };
    Kind kind = Exact;
    double rel = 0.0;
    double lo = 0.0, hi = 0.0;
    double abs = 0.0;  ///< An absolute slack added to every tolerance, the case's unit.
    std::string why;   ///< The wording of docs/hard-cases.md, printed with a failure.
};

/// The promise of technique `t` on case `c` (CPU, double precision).
Promise promise(const TechniqueInfo& t, const Case& c);

/// The promise on the GPU (float): the CPU's, with room for float rounding, and on cases whose
/// receiver is within float rounding of the emitter (Case::belowFloat) any value between the
/// limits 0 (behind) and the expected value (in front).
Promise gpuPromise(const TechniqueInfo& t, const Case& c);

/// Checks an estimate against a promise: an empty string when it holds, else what failed.
std::string judge(const Case& c, const Promise& p, const Estimate& e);

/// Distance from the case's receiver to the centre of its photometric opening, in opening
/// diagonals (infinity for segments and points, whose techniques are exact at any distance).
double openingSizesAway(const Case& c);

}  // namespace candela::hard
