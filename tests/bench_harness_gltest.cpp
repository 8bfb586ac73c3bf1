// The benches' shared harness (app/commands/BenchHarness.h) under OSMesa: an image rendered to
// its sample budget, and a sweep against a reference, whose rows must be the same for the same
// seeds (what makes two bench runs comparable) and whose files are where the benches say.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "app/commands/BenchHarness.h"
#include "scene/SceneIo.h"
#include "tests/TestUtil.h"

namespace candela {
namespace {

namespace fs = std::filesystem;

/// A floor lit by a Lambertian panel with no occluder ("analytic" is exact, "reference" is
/// Monte Carlo).
Scene panelScene() {
    std::string text = R"({"geometry": [
        {"plane": {"center": [0,0,0], "normal": [0,1,0], "size": [6,6]}, "albedo": [0.5,0.6,0.7]}],
      "luminaires": [{"type": "lambertian-rect", "name": "Panel", "size": [1, 0.5],
        "radiance": [10, 10, 10], "position": [0.2, 2.5, -0.3], "aim": [0.1, -1, 0], "technique": "analytic"}],
      "camera": {"position": [0, 1.5, 4], "target": [0, 0.5, 0], "fov_deg": 50}})";
    return parseScene(nlohmann::json::parse(text), "test.json");
}

RenderSettings small() {
    RenderSettings s;
    s.width = 32;
    s.height = 24;
    return s;
}

TEST(BenchHarness, AShotRendersItsBudgetInFramesOfAtMostTheCap) {
    test::glContext();
    Scene scene = panelScene();
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    RenderSettings s =
        withBudget(withTechnique(small(), TechniqueSlot::Luminaires, "reference"), 12, 5, 4);
    EXPECT_EQ(s.techniqueOverride, "reference");
    EXPECT_EQ(s.samplesPerFrame, 4);
    EXPECT_EQ(s.maxSamples, 12);
    Shot shot = renderShot(renderer, scene, s);
    EXPECT_EQ(shot.frames, 3);
    EXPECT_EQ(renderer.stats().samplesPerPixel, 12);
    EXPECT_EQ(shot.linear.size(), size_t(32 * 24 * 3));
    EXPECT_EQ(shot.display.size(), size_t(32 * 24 * 3));
    bool shaded = false;
    for (const PassTiming& p : shot.passes) shaded = shaded || p.name.rfind("shade:Panel", 0) == 0;
    EXPECT_TRUE(shaded);
    Shot unread = renderShot(renderer, scene, s, false);
    EXPECT_TRUE(unread.linear.empty());
    EXPECT_EQ(withTechnique(s, TechniqueSlot::Environment, "balanced").environmentTechnique,
              "balanced");
}

TEST(BenchHarness, ASweepGivesTheSameRowsForTheSameSeedsAndWritesItsImages) {
    test::glContext();
    Scene scene = panelScene();
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    fs::path dir = fs::temp_directory_path() / ("candela-sweep-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    Sweep sweep;
    sweep.reference = "reference";
    sweep.referenceSpp = 64;
    sweep.progressive = {"reference"};
    sweep.deterministic = {"analytic"};
    sweep.spp = {2, 16};
    sweep.timedPasses = "shade:";
    std::vector<std::vector<BenchRow>> runs;
    for (int run = 0; run < 2; ++run) {
        RenderSettings settings = small();
        Reference ref = renderReference(renderer, scene, settings, sweep, dir);
        EXPECT_GT(ref.noise, 0.0);
        EXPECT_GT(settings.fixedAverage,
                  0.f);  // every image tone-mapped against the reference's mean
        runs.push_back(runSweep(renderer, scene, settings, sweep, ref, dir));
    }
    ASSERT_EQ(runs[0].size(), 3u);
    EXPECT_EQ(runs[0][0].technique, "reference");
    EXPECT_EQ(runs[0][1].spp, 16);
    EXPECT_EQ(runs[0][2].technique, "analytic");
    EXPECT_EQ(runs[0][2].spp, 1);
    for (size_t i = 0; i < runs[0].size(); ++i) {
        EXPECT_TRUE(std::isfinite(runs[0][i].rmse)) << i;
        EXPECT_EQ(runs[0][i].rmse, runs[1][i].rmse) << i;
        EXPECT_EQ(runs[0][i].deltaE, runs[1][i].deltaE) << i;
        EXPECT_EQ(runs[0][i].rawRmse, runs[1][i].rawRmse) << i;
    }
    for (const char* file :
         {"reference.png", "reference.exr", "reference_2.png", "reference_16.png", "analytic.png"})
        EXPECT_TRUE(fs::is_regular_file(dir / file)) << file;
    fs::remove_all(dir);
}

}  // namespace
}  // namespace candela
