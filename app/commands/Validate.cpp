// `candela validate`: the validation suite (calculation/Validation.h) as a table: case, expected,
// measured, deviation, tolerance, result; exit code 1 when a case fails.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "app/commands/Commands.h"
#include "calculation/Validation.h"
#include "scene/SceneIo.h"
#include "util/Error.h"

namespace candela {

int cmdValidate(const Args& args) {
    std::vector<std::string> names;
    std::string closed;
    bool list = false;
    CommandLine cli("validate");
    cli.group("the suite (candela validate [--case NAME]... [--list])");
    cli.option("--case", "NAME", "run this case (again for more; default: every case)",
               [&names](const std::string& v) {
                   std::vector<std::string> known = validationCases();
                   if (std::find(known.begin(), known.end(), v) == known.end()) {
                       std::string all;
                       for (const std::string& n : known) all += (all.empty() ? "" : ", ") + n;
                       throw InputError("--case: unknown case \"" + v + "\" (known: " + all + ")");
                   }
                   names.push_back(v);
               });
    cli.flag("--list", list, "list the cases' names instead of running them");
    cli.group("a closed room (candela validate --closed ROOM.json)");
    cli.option("--closed", "ROOM.json",
               "check this closed room's energy balance instead of running the suite",
               [&closed](const std::string& v) {
                   if (v.empty())
                       throw InputError("--closed: expected a scene file, got an empty name");
                   closed = v;
               });
    if (!cli.parse(args)) return 0;
    if (!closed.empty() && (list || !names.empty()))
        throw CommandUsageError(std::string("--closed checks one room: ") +
                                    (list ? "--list" : "--case") + " belongs to the suite's form",
                                cli.shortHelp());
    if (list) {
        for (const std::string& n : validationCases()) std::printf("%s\n", n.c_str());
        return 0;
    }
    if (names.empty()) names = validationCases();
    std::vector<ValidationResult> results;
    int failed = 0;
    std::unique_ptr<Scene> room;
    if (!closed.empty()) {
        room = std::make_unique<Scene>(loadScene(closed));
        names = {"closed-room"};
    }
    for (const std::string& name : names) {
        ValidationResult r = room ? validateClosedRoom(*room) : runValidationCase(name);
        if (results.empty())
            std::printf("%-27s %12s %12s %10s %9s  %-6s %7s\n", "case", "expected", "measured",
                        "deviation", "tolerance", "result", "time");
        failed += !r.pass;
        std::printf("%-27s %9.5g %s %9.5g %s %+9.3f%% %8.2f%%  %-6s %6.1fs\n", r.name.c_str(),
                    r.expected, r.unit.c_str(), r.measured, r.unit.c_str(),
                    std::abs(r.deviation) < 5e-6 ? 0.0 : 100.0 * r.deviation, 100.0 * r.tolerance,
                    r.pass ? "pass" : "FAIL", r.seconds);
        std::fflush(stdout);
        results.push_back(r);
    }
    std::printf("\n");
    for (const ValidationResult& r : results)
        std::printf("%s: %s\n    %s\n", r.name.c_str(), r.description.c_str(), r.detail.c_str());
    std::printf("\n%zu cases, %d failed\n", results.size(), failed);
    return failed ? 1 : 0;
}

}  // namespace candela
