// The benches' shared harness (app/commands/BenchHarness.h) without a GL context: the CSV and
// summary text, and the row arithmetic every sweep relies on.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "app/commands/BenchHarness.h"
#include "app/commands/BenchUtil.h"
#include "tests/TestUtil.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {
namespace {

TEST(BenchFiles, CsvRowsPrintAsAnOstreamDoes) {
    CsvFile csv("name,count,value");
    csv.row("\"A, B\"", 3, 0.125);
    csv.row(std::string("c"), size_t(7), 1.0 / 3.0);
    csv.line("d,1,2");
    EXPECT_EQ(csv.text(), "name,count,value\n\"A, B\",3,0.125\nc,7,0.333333\nd,1,2\n");
}

TEST(BenchFiles, FormatTextHasNoLengthLimit) {
    std::string long1000(1000, 'x');
    EXPECT_EQ(formatText("%s|%d|%.2f", long1000.c_str(), 42, 0.5), long1000 + "|42|0.50");
}

TEST(BenchFiles, TheSummaryOpensWithTheMachine) {
    BenchSummary summary;
    summary.add("spp %d\n", 16);
    summary.addText("end\n");
    std::string text = summary.text();
    EXPECT_EQ(text.rfind("machine: ", 0), 0u);
    EXPECT_NE(text.find(machineDescription() + "\nspp 16\nend\n"), std::string::npos);
}

std::string readText(const std::filesystem::path& p) {
    std::ifstream in(p);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// A bench's folder is whole or untouched: what a failed bench wrote is taken away, what a
// finished one wrote (subfolders too) lands in --out, and nothing lands on an input.
TEST(BenchFiles, AFolderIsWholeOrUntouched) {
    namespace fs = std::filesystem;
    fs::path dir = fs::path(::testing::TempDir()) / "bench_folder_test";
    fs::remove_all(dir);
    fs::create_directories(dir);
    writeFileAtomically((dir / "bench.csv").string(), "old\n");
    {
        BenchFolder folder(dir.string());
        EXPECT_NE(folder.path(), dir);
        writeFileAtomically((folder.path() / "bench.csv").string(), "half\n");
        writeFileAtomically((folder.path() / "a.png").string(), "png");
        // destroyed without commit(): the bench failed
    }
    EXPECT_EQ(readText(dir / "bench.csv"), "old\n");
    EXPECT_FALSE(fs::exists(dir / "a.png"));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
    {
        BenchFolder folder(dir.string());
        writeFileAtomically((folder.path() / "bench.csv").string(), "new\n");
        fs::create_directories(folder.path() / "fig11");
        writeFileAtomically((folder.path() / "fig11" / "b.png").string(), "png");
        folder.commit();
    }
    EXPECT_EQ(readText(dir / "bench.csv"), "new\n");
    EXPECT_EQ(readText(dir / "fig11" / "b.png"), "png");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);
    {
        ProtectedInputs inputs;
        inputs.add((dir / "bench.csv").string());
        BenchFolder folder(dir.string());
        writeFileAtomically((folder.path() / "c.png").string(), "png");
        writeFileAtomically((folder.path() / "bench.csv").string(), "onto the input\n");
        EXPECT_THROW(folder.commit(), InputError);
    }
    EXPECT_EQ(readText(dir / "bench.csv"), "new\n");
    EXPECT_FALSE(fs::exists(dir / "c.png"));  // refused before anything moved
    fs::remove_all(dir);
}

TEST(BenchRows, OneRepeatsMeanIsTheRowItself) {
    // A sweep of one image per point goes through meanRow too: its figures must stay the image's
    // own to the last bit (sqrt(x * x) == x in IEEE double for finite, non-tiny x).
    for (double rmse : {0.0, 1e-7, 0.0972531, 0.977696, 2.91558, 1234.5}) {
        BenchRow one{"t", 8, 12.5, rmse, 1.5 * rmse + 0.25, rmse * 1.01};
        BenchRow mean = meanRow({one});
        EXPECT_EQ(mean.rmse, one.rmse);
        EXPECT_EQ(mean.rawRmse, one.rawRmse);
        EXPECT_EQ(mean.deltaE, one.deltaE);
        EXPECT_EQ(mean.shadeMs, one.shadeMs);
        EXPECT_EQ(mean.repeats, 1);
        EXPECT_EQ(mean.rmseSpread, 0.0);
    }
}

TEST(BenchRows, RowAtFindsATechniquesCountOrSaysNaN) {
    std::vector<BenchRow> rows = {{"a", 4, 1.0, 0.5}, {"a", 8, 2.0, 0.25}, {"b", 4, 3.0, 0.75}};
    EXPECT_EQ(rowAt(rows, "a", 8).rmse, 0.25);
    EXPECT_EQ(rowAt(rows, "b", 4).shadeMs, 3.0);
    EXPECT_TRUE(std::isnan(rowAt(rows, "b", 8).rmse));
    EXPECT_TRUE(std::isnan(rowAt(rows, "c", 4).shadeMs));
}

}  // namespace
}  // namespace candela
