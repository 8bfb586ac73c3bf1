// Accuracy plot: reading bench CSVs, error at a time budget, the winner, and drawing without a
// crash on any data.

#include <gtest/gtest.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <string>

#include "ui/AccuracyPlot.h"
#include "util/Error.h"

namespace {

using candela::ErrorPoint;
using candela::InputError;
using candela::ui::ErrorMetric;
using candela::ui::ErrorSeries;
namespace fs = std::filesystem;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

ErrorPoint point(double timeMs, double relRmse, double deltaE = 1.0, int spp = 1) {
    ErrorPoint p;
    p.timeMs = timeMs;
    p.spp = spp;
    p.relRmse = relRmse;
    p.deltaE = deltaE;
    return p;
}

/// err = c * t^k sampled at the given times, in relRmse.
ErrorSeries powerLaw(const std::string& label, double c, double k,
                     std::initializer_list<double> t) {
    ErrorSeries s{label, {}, false};
    for (double time : t) s.points.push_back(point(time, c * std::pow(time, k)));
    return s;
}

TEST(AccuracyPlot, ReadsBenchCsvOfTheRepo) {
    fs::path file = fs::path(CANDELA_SOURCE_DIR) / "docs/bench/lightfield-car/bench.csv";
    // Count the rows of each technique independently of the parser.
    std::ifstream in(file);
    ASSERT_TRUE(in) << file;
    std::string line;
    std::getline(in, line);  // header
    std::vector<std::string> order;
    std::map<std::string, size_t> rows;
    while (std::getline(in, line)) {
        if (line.empty()) continue;
        std::string name = line.substr(0, line.find(','));
        if (rows[name]++ == 0) order.push_back(name);
    }
    ASSERT_GE(order.size(), 2u);

    std::vector<ErrorSeries> series = candela::ui::readBenchCsv(file);
    ASSERT_EQ(series.size(), order.size());
    for (size_t k = 0; k < order.size(); ++k) {
        EXPECT_EQ(series[k].label, order[k] + " (bench)");
        EXPECT_TRUE(series[k].fromBench);
        EXPECT_EQ(series[k].points.size(), rows[order[k]]) << order[k];
    }
    // The row "precomputed-global,64,1988.73,0.575013,6.00168,0.576326", its 5th: the parsed
    // doubles are the nearest doubles to the text, as the literals below.
    auto it = std::find(order.begin(), order.end(), "precomputed-global");
    ASSERT_NE(it, order.end());
    const ErrorSeries& s = series[size_t(it - order.begin())];
    ASSERT_GE(s.points.size(), 5u);
    EXPECT_EQ(s.points[4].spp, 64);
    EXPECT_EQ(s.points[4].timeMs, 1988.73);
    EXPECT_EQ(s.points[4].relRmse, 0.575013);
    EXPECT_EQ(s.points[4].deltaE, 6.00168);

    // Measured times may step back a little (uniform-restricted: 422 ms at 8 spp, 382 at 16);
    // errorAtTime stays finite from each series' first point on.
    for (const ErrorSeries& t : series)
        for (double ms = t.points.front().timeMs; ms < 3e4; ms *= 1.1)
            ASSERT_TRUE(std::isfinite(candela::ui::errorAtTime(t, ms, ErrorMetric::DeltaE)))
                << t.label << " at " << ms;
}

TEST(AccuracyPlot, ReadsBenchCsvWithExtraColumns) {
    fs::path file = fs::path(CANDELA_SOURCE_DIR) / "docs/bench/environment-sky/bench.csv";
    std::vector<ErrorSeries> series = candela::ui::readBenchCsv(file);
    ASSERT_FALSE(series.empty());
    EXPECT_EQ(series[0].label, "balanced (bench)");
    ASSERT_FALSE(series[0].points.empty());
    EXPECT_EQ(series[0].points[0].spp, 4);
    EXPECT_EQ(series[0].points[0].timeMs, 43.4676);
}

/// A fresh directory under the system's temp directory, removed at the end of the test.
class MalformedCsv : public ::testing::Test {
  protected:
    void SetUp() override {
        std::random_device random;
        mDir = fs::temp_directory_path() / ("candela_accuracy_plot_test_" +
                                            std::to_string(random()) + std::to_string(random()));
        fs::create_directories(mDir);
    }
    void TearDown() override {
        std::error_code ec;
        fs::remove_all(mDir, ec);
    }
    fs::path write(const std::string& name, const std::string& text) {
        fs::path file = mDir / name;
        std::ofstream(file) << text;
        return file;
    }
    /// The message of the InputError readBenchCsv throws on `file` ("" when it does not throw).
    static std::string errorOf(const fs::path& file) {
        try {
            candela::ui::readBenchCsv(file);
        } catch (const InputError& e) {
            return e.what();
        }
        return "";
    }
    fs::path mDir;
};

const char* kHeader = "technique,spp,gpu_ms,rel_rmse,mean_delta_e,rel_rmse_raw\n";

TEST_F(MalformedCsv, MissingFile) {
    std::string message = errorOf(mDir / "absent.csv");
    EXPECT_NE(message.find("absent.csv"), std::string::npos) << message;
}

TEST_F(MalformedCsv, MissingColumn) {
    fs::path file = write("nogpu.csv", "technique,spp,rel_rmse,mean_delta_e\na,4,0.5,3\n");
    std::string message = errorOf(file);
    EXPECT_NE(message.find("nogpu.csv"), std::string::npos) << message;
    EXPECT_NE(message.find("gpu_ms"), std::string::npos) << message;
}

TEST_F(MalformedCsv, NonNumericValue) {
    fs::path file =
        write("text.csv", std::string(kHeader) + "a,4,10,0.5,3,0.5\na,8,abc,0.4,2,0.4\n");
    std::string message = errorOf(file);
    EXPECT_NE(message.find("text.csv"), std::string::npos) << message;
    EXPECT_NE(message.find("line 3"), std::string::npos) << message;
    EXPECT_NE(message.find("gpu_ms"), std::string::npos) << message;
}

TEST_F(MalformedCsv, NanValue) {
    fs::path file = write("nan.csv", std::string(kHeader) + "a,4,10,0.5,3,0.5\na,8,20,nan,2,0.4\n");
    std::string message = errorOf(file);
    EXPECT_NE(message.find("nan.csv"), std::string::npos) << message;
    EXPECT_NE(message.find("line 3"), std::string::npos) << message;
    EXPECT_NE(message.find("finite"), std::string::npos) << message;
}

TEST_F(MalformedCsv, NegativeValue) {
    fs::path file =
        write("neg.csv", std::string(kHeader) + "a,4,10,0.5,3,0.5\n\na,8,20,0.4,-2,0.4\n");
    std::string message = errorOf(file);
    EXPECT_NE(message.find("neg.csv"), std::string::npos) << message;
    EXPECT_NE(message.find("line 4"), std::string::npos) << message;  // blank line 3 counts
    EXPECT_NE(message.find("mean_delta_e"), std::string::npos) << message;
}

TEST_F(MalformedCsv, TooFewFields) {
    fs::path file = write("short.csv", std::string(kHeader) + "a,4,10,0.5,3,0.5\na,8,20\n");
    std::string message = errorOf(file);
    EXPECT_NE(message.find("short.csv"), std::string::npos) << message;
    EXPECT_NE(message.find("line 3"), std::string::npos) << message;
    EXPECT_NE(message.find("fields"), std::string::npos) << message;
}

TEST_F(MalformedCsv, ColumnsFoundByName) {
    fs::path file = write("order.csv",
                          "mean_delta_e,gpu_ms,note,technique,rel_rmse,spp\n"
                          "3.5,12.25,x,b,0.125,16\n2.5,40,y,b,0.0625,32\n");
    std::vector<ErrorSeries> series = candela::ui::readBenchCsv(file);
    ASSERT_EQ(series.size(), 1u);
    ASSERT_EQ(series[0].points.size(), 2u);
    EXPECT_EQ(series[0].label, "b (bench)");
    EXPECT_EQ(series[0].points[0].spp, 16);
    EXPECT_EQ(series[0].points[0].timeMs, 12.25);
    EXPECT_EQ(series[0].points[0].relRmse, 0.125);
    EXPECT_EQ(series[0].points[0].deltaE, 3.5);
}

TEST(AccuracyPlot, MetricOfPicksTheField) {
    ErrorPoint p = point(10.0, 0.25, 4.0);
    EXPECT_EQ(candela::ui::metricOf(p, ErrorMetric::RelRmse), 0.25);
    EXPECT_EQ(candela::ui::metricOf(p, ErrorMetric::DeltaE), 4.0);
}

TEST(AccuracyPlot, ErrorAtTimeIsExactOnAPowerLaw) {
    ErrorSeries s = powerLaw("p", 2.0, -0.5, {10.0, 100.0, 1000.0});
    // Linear in log-log space, so exact on err = 2 t^-0.5 up to rounding (~1e-15).
    for (double t : {31.6, 10.0, 100.0, 555.0, 1000.0}) {
        double expected = 2.0 * std::pow(t, -0.5);
        EXPECT_NEAR(candela::ui::errorAtTime(s, t, ErrorMetric::RelRmse), expected,
                    1e-12 * expected)
            << t;
    }
    EXPECT_TRUE(std::isnan(candela::ui::errorAtTime(s, 9.99, ErrorMetric::RelRmse)));
    EXPECT_TRUE(std::isnan(candela::ui::errorAtTime(s, kNaN, ErrorMetric::RelRmse)));
    EXPECT_EQ(candela::ui::errorAtTime(s, 5000.0, ErrorMetric::RelRmse), s.points.back().relRmse);
    EXPECT_EQ(candela::ui::errorAtTime(s, kInf, ErrorMetric::RelRmse), s.points.back().relRmse);
}

TEST(AccuracyPlot, ErrorAtTimeOfOneOrNoPoint) {
    ErrorSeries one{"one", {point(50.0, 0.3, 2.0)}, false};
    EXPECT_TRUE(std::isnan(candela::ui::errorAtTime(one, 49.0, ErrorMetric::RelRmse)));
    EXPECT_EQ(candela::ui::errorAtTime(one, 50.0, ErrorMetric::RelRmse), 0.3);
    EXPECT_EQ(candela::ui::errorAtTime(one, 1e6, ErrorMetric::DeltaE), 2.0);
    ErrorSeries none{"none", {}, false};
    EXPECT_TRUE(std::isnan(candela::ui::errorAtTime(none, 10.0, ErrorMetric::RelRmse)));
}

TEST(AccuracyPlot, ZeroAndNegativeValuesGiveNoNan) {
    // A series that reaches zero error, one that starts at time zero, and one with a NaN point.
    ErrorSeries zero{"zero", {point(10, 0.5), point(100, 0.0), point(1000, 0.0)}, false};
    ErrorSeries fromZero{"t0", {point(0.0, 1.0), point(10.0, 0.5)}, false};
    ErrorSeries broken{
        "nan", {point(10, 0.5), point(kNaN, 0.3), point(100, kInf), point(1000, 0.1)}, false};
    for (double t : {10.0, 31.6, 100.0, 500.0, 1e5}) {
        double e = candela::ui::errorAtTime(zero, t, ErrorMetric::RelRmse);
        EXPECT_TRUE(std::isfinite(e)) << t;
        EXPECT_GE(e, 0.0) << t;
        EXPECT_LE(e, 0.5) << t;
        EXPECT_TRUE(std::isfinite(candela::ui::errorAtTime(broken, t, ErrorMetric::RelRmse))) << t;
    }
    EXPECT_EQ(candela::ui::errorAtTime(zero, 500.0, ErrorMetric::RelRmse), 0.0);
    EXPECT_DOUBLE_EQ(candela::ui::errorAtTime(fromZero, 5.0, ErrorMetric::RelRmse), 0.75);
    EXPECT_EQ(candela::ui::errorAtTime(fromZero, 0.0, ErrorMetric::RelRmse), 1.0);
}

TEST(AccuracyPlot, WinnerFlipsAtTheCrossing) {
    // Fast but noisy 0.5 t^-0.4 against slow but steep 7 t^-1: equal where t^0.6 = 14.
    std::vector<ErrorSeries> series = {powerLaw("steep", 7.0, -1.0, {1.0, 10.0, 1000.0, 10000.0}),
                                       powerLaw("flat", 0.5, -0.4, {1.0, 10.0, 1000.0, 10000.0})};
    double crossing = std::pow(14.0, 1.0 / 0.6);  // ~81.3 ms, inside the segment 10 .. 1000
    // 1e-6 from the crossing the errors differ by ~0.6e-6 relative, far above rounding.
    candela::ui::Winner before =
        candela::ui::winnerAt(series, crossing * (1 - 1e-6), ErrorMetric::RelRmse);
    candela::ui::Winner after =
        candela::ui::winnerAt(series, crossing * (1 + 1e-6), ErrorMetric::RelRmse);
    EXPECT_EQ(before.series, 1);
    EXPECT_EQ(after.series, 0);
    EXPECT_NEAR(after.error, 7.0 / (crossing * (1 + 1e-6)), 1e-12);
    EXPECT_EQ(candela::ui::winnerAt(series, 5.0, ErrorMetric::RelRmse).series, 1);
    EXPECT_EQ(candela::ui::winnerAt(series, 5000.0, ErrorMetric::RelRmse).series, 0);

    candela::ui::Winner none = candela::ui::winnerAt(series, 0.5, ErrorMetric::RelRmse);
    EXPECT_EQ(none.series, -1);
    EXPECT_TRUE(std::isnan(none.error));
    EXPECT_EQ(candela::ui::winnerAt({}, 10.0, ErrorMetric::RelRmse).series, -1);
}

TEST(AccuracyPlot, TickLabels) {
    EXPECT_EQ(candela::ui::timeTickLabel(0.1), "0.1 ms");
    EXPECT_EQ(candela::ui::timeTickLabel(1.0), "1 ms");
    EXPECT_EQ(candela::ui::timeTickLabel(100.0), "100 ms");
    EXPECT_EQ(candela::ui::timeTickLabel(1000.0), "1 s");
    EXPECT_EQ(candela::ui::timeTickLabel(std::pow(10.0, 4)), "10 s");
    EXPECT_EQ(candela::ui::metricTickLabel(std::pow(10.0, -2), ErrorMetric::RelRmse), "1%");
    EXPECT_EQ(candela::ui::metricTickLabel(1.0, ErrorMetric::RelRmse), "100%");
    EXPECT_EQ(candela::ui::metricTickLabel(std::pow(10.0, -1), ErrorMetric::DeltaE), "0.1");
    EXPECT_EQ(candela::ui::metricTickLabel(10.0, ErrorMetric::DeltaE), "10");
    EXPECT_NE(candela::ui::seriesColour(0), candela::ui::seriesColour(1));
}

TEST(AccuracyPlot, DrawsAnyDataWithoutCrashing) {
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(800.f, 600.f);
    io.IniFilename = nullptr;
    unsigned char* pixels = nullptr;
    int width = 0, height = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);

    std::vector<ErrorSeries> normal = {powerLaw("steep", 7.0, -1.0, {1.0, 10.0, 1000.0}),
                                       powerLaw("flat", 0.5, -0.4, {2.0, 20.0, 2000.0})};
    normal[1].fromBench = true;
    std::vector<ErrorSeries> bad = {
        {"bad",
         {point(kNaN, 0.1), point(-1.0, 0.2), point(0.0, 0.3), point(10.0, -0.1), point(kInf, 0.5),
          point(10.0, kInf), point(20.0, 0.0), point(30.0, 0.05, kNaN)},
         false},
        {"", {}, true}};
    std::vector<ErrorSeries> huge = {powerLaw("wide", 1.0, -1.0, {1e-300, 1e300})};
    // Two frames with the mouse on the plot, so the second one sees it hovered.
    for (int frame = 0; frame < 2; ++frame) {
        io.MousePos = ImVec2(200.f, 200.f);
        ImGui::NewFrame();
        ImGui::SetNextWindowPos(ImVec2(0.f, 0.f));
        ImGui::SetNextWindowSize(ImVec2(800.f, 600.f));
        ImGui::Begin("plots");
        ImDrawList* draw = ImGui::GetWindowDrawList();
        auto plot = [&](const char* id, const std::vector<ErrorSeries>& s, ErrorMetric m,
                        double budget, ImVec2 size) {
            int before = draw->VtxBuffer.Size;
            candela::ui::accuracyPlot(id, s, m, budget, size);
            EXPECT_GT(draw->VtxBuffer.Size, before) << id;
        };
        plot("normal", normal, ErrorMetric::RelRmse, 100.0, ImVec2(400.f, 250.f));
        plot("deltaE", normal, ErrorMetric::DeltaE, 0.0, ImVec2(0.f, 120.f));
        plot("empty", {}, ErrorMetric::RelRmse, 100.0, ImVec2(300.f, 100.f));
        plot("bad", bad, ErrorMetric::RelRmse, kNaN, ImVec2(300.f, 100.f));
        plot("huge", huge, ErrorMetric::DeltaE, -5.0, ImVec2(300.f, 100.f));
        plot("tiny", normal, ErrorMetric::RelRmse, kInf, ImVec2(kNaN, -3.f));
        ImGui::End();
        ImGui::Render();
        EXPECT_GT(ImGui::GetDrawData()->TotalVtxCount, 0);
    }
    ImGui::DestroyContext();
}

}  // namespace
