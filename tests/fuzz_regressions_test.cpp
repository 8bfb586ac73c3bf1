// Every input fuzzing found a bug with (fuzz/regressions/TARGET/, each fixed since) replayed in the
// normal build through the same checks as the libFuzzer targets (fuzz/Targets.h): it must load or
// be refused with an InputError, and what loads must be valid. A failed check aborts, which fails
// this test; the fuzzing build (scripts/fuzz.sh) replays the same files under ASan and UBSan.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz/Targets.h"
#include "tests/TestUtil.h"

namespace candela {
namespace {

namespace fs = std::filesystem;

TEST(FuzzRegressions, EveryRegressionInputPassesItsTargetsChecks) {
    int replayed = 0;
    for (const fuzz::Target& target : fuzz::kTargets) {
        fs::path dir = fs::path(test::sourceDir()) / "fuzz" / "regressions" / target.name;
        if (!fs::is_directory(dir)) continue;
        for (const auto& entry : fs::directory_iterator(dir)) {
            std::ifstream in(entry.path(), std::ios::binary);
            std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                       std::istreambuf_iterator<char>());
            SCOPED_TRACE(entry.path().string());
            target.run(bytes.data(), bytes.size());
            ++replayed;
        }
    }
    std::printf("replayed %d regression inputs\n", replayed);
    EXPECT_GT(replayed, 0);
}

}  // namespace
}  // namespace candela
