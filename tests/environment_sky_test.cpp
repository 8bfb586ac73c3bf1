// Tests of Havran et al.'s environment lights and their temporal filter, the procedural sky,
// HDR sequences, and the scene file's three forms of environment (split from environment_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "luminaires/environment/Environment.h"
#include "luminaires/environment/EnvironmentSampling.h"
#include "scene/SceneIo.h"
#include "tests/EnvironmentTestUtil.h"
#include "tests/TestUtil.h"
#include "util/Error.h"

namespace candela {
namespace {

namespace fs = std::filesystem;
using namespace envtest;

// ---------------------------------------------------------------------------------------------
// Havran et al.'s lights

TEST(Environment, HavranTemporalFilter) {
    auto a =
        makeMap(64, 32, [](int x, int y) { return glm::vec3(float(1 + (x * 7 + y * 3) % 5)); });
    auto b = makeMap(64, 32,
                     [](int x, int y) { return glm::vec3(float(2 * (1 + (x * 7 + y * 3) % 5))); });
    HavranLights lights(32);
    lights.update(*a);
    std::vector<HavranLights::Light> first = lights.lights();
    // The lights carry all the energy: their powers sum to the map's.
    double total = 0.0;
    for (const auto& l : first) total += lum(l.power);
    EXPECT_NEAR(total, a->totalLuminancePower(), 1e-9 * total);
    // b is a x 2: the same CDF, so the same directions, and the filter's step response after
    // one new frame is (0.4 x 2 + 0.3 x 1) / 0.7 of the old power, after four frames 2 x.
    lights.update(*b);
    for (size_t k = 0; k < first.size(); ++k) {
        EXPECT_LT(glm::length(lights.lights()[k].direction - first[k].direction), 1e-12);
        EXPECT_NEAR(lum(lights.lights()[k].power), lum(first[k].power) * (0.8 + 0.3) / 0.7,
                    1e-9 * lum(first[k].power));
    }
    for (int i = 0; i < 3; ++i) lights.update(*b);
    for (size_t k = 0; k < first.size(); ++k)
        EXPECT_NEAR(lum(lights.lights()[k].power), 2 * lum(first[k].power),
                    1e-9 * lum(first[k].power));
    // Relaxation spreads the points: the smallest distance between two grows.
    auto minDistance = [](const std::vector<glm::dvec2>& p) {
        double d = 1e9;
        for (size_t i = 0; i < p.size(); ++i)
            for (size_t j = i + 1; j < p.size(); ++j) d = std::min(d, glm::length(p[i] - p[j]));
        return d;
    };
    EXPECT_GT(minDistance(relaxedHalton(64, 16)), 1.2 * minDistance(relaxedHalton(64, 0)));
}

// ---------------------------------------------------------------------------------------------
// Sky and sequences

TEST(Environment, SkyPutsTheSunWhereAsked) {
    SkyParams sky;
    sky.sunElevationDeg = 30;
    sky.sunAzimuthDeg = 120;
    sky.turbidity = 3;
    sky.width = 256;
    auto map = makeSkyMap(sky);
    // The brightest texel contains the sun's direction.
    double el = 30 * kPi / 180, az = 120 * kPi / 180;
    glm::dvec3 sun(std::cos(el) * std::cos(az), std::sin(el), std::cos(el) * std::sin(az));
    int bx = 0, by = 0;
    for (int y = 0; y < map->height(); ++y)
        for (int x = 0; x < map->width(); ++x)
            if (map->texelLuminance(x, y) > map->texelLuminance(bx, by)) bx = x, by = y;
    glm::ivec2 t = map->texelOf(sun);
    EXPECT_LE(std::abs(t.x - bx), 1);
    EXPECT_LE(std::abs(t.y - by), 1);
    // Horizontal illuminance of a clear sky with the sun at 30 degrees: the sun's beam gives
    // ~40-60 klx horizontally, the sky 10-20 klx; accept 40-110 klx.
    EnvironmentLighting lighting(map, 0, 16);
    double eh = lum(environmentReference(lighting, {}, {0, 1, 0}, {}).irradiance);
    std::printf("[ info ] sky T=3, sun at 30 deg: horizontal illuminance %.0f lux\n", eh);
    EXPECT_GT(eh, 40000.0);
    EXPECT_LT(eh, 110000.0);
    // Rotating by 90 degrees moves the sun to azimuth 210.
    auto turned = makeSkyMap(sky, 1.0, 90.0);
    double az2 = 210 * kPi / 180;
    glm::dvec3 sun2(std::cos(el) * std::cos(az2), std::sin(el), std::cos(el) * std::sin(az2));
    EXPECT_GT(lum(turned->radiance(sun2)), 1e6);  // a sun texel is far above any sky texel
    EXPECT_CONTAINS(inputError([&] {
                        SkyParams s;
                        s.turbidity = 20;
                        makeSkyMap(s);
                    }),
                    "turbidity");
}

TEST(Environment, SequenceFramesAtTime) {
    std::string dir = tempDir("seq");
    fs::create_directories(dir + "/frames");
    for (int i = 0; i < 3; ++i)
        writeImage(dir + "/frames/f" + std::to_string(i) + ".exr", 8, 4,
                   std::vector<float>(8 * 4 * 3, float(i + 1)));
    auto seq = EnvironmentSequence::open(dir + "/frames/*.exr", 10.0, 1.0, 0.0);
    EXPECT_EQ(seq->frameCount(), 3u);
    EXPECT_EQ(seq->frameIndex(0.0), 0u);
    EXPECT_EQ(seq->frameIndex(0.15), 1u);
    EXPECT_EQ(seq->frameIndex(0.25), 2u);
    EXPECT_EQ(seq->frameIndex(0.35), 0u);  // loops
    EXPECT_EQ(seq->frameAt(0.25)->texel(0, 0), glm::dvec3(3.0));
    EXPECT_CONTAINS(inputError([&] { EnvironmentSequence::open(dir + "/none/*.exr", 10, 1, 0); }),
                    "none/*.exr: no file matches the sequence pattern");
    fs::remove_all(dir);
}

// ---------------------------------------------------------------------------------------------
// Scene files

TEST(Environment, SceneParsesTheThreeFormsAndTheirErrors) {
    std::string dir = tempDir("scene");
    fs::copy_file(test::dataDir() + "/hdr/hilly_terrain_01_256.hdr", dir + "/sky.hdr");
    fs::create_directories(dir + "/frames");
    for (int i = 0; i < 2; ++i)
        writeImage(dir + "/frames/" + std::to_string(i) + ".exr", 8, 4,
                   std::vector<float>(96, 1.f));
    auto load = [&](const std::string& env) {
        std::ofstream(dir + "/s.json") << R"({"geometry": [], "environment": )" + env + "}";
        return loadScene(dir + "/s.json");
    };
    Scene a = load(R"({"file": "sky.hdr", "intensity": 2.0, "rotation_deg": 45})");
    ASSERT_TRUE(a.environmentMap);
    EXPECT_EQ(a.environmentMap->width(), 256);
    EXPECT_DOUBLE_EQ(a.environmentMap->intensity(), 2.0);
    EXPECT_NEAR(a.environmentMap->rotation(), kPi / 4, 1e-15);
    EXPECT_EQ(a.environment["file"], "sky.hdr");  // kept as written, for saving
    Scene b = load(R"({"sky": {"sun_elevation_deg": 30, "sun_azimuth_deg": 120, "turbidity": 3}})");
    ASSERT_TRUE(b.environmentMap);
    EXPECT_EQ(b.environmentMap->width(), 512);
    Scene c = load(R"({"sequence": "frames/*.exr", "fps": 10})");
    ASSERT_TRUE(c.environmentSequence);
    EXPECT_EQ(c.environmentSequence->frameCount(), 2u);
    EXPECT_TRUE(c.environmentMap);
    Scene none = load("null");
    EXPECT_FALSE(none.environmentMap);
    // Saving keeps the field as given.
    saveScene(a, dir + "/saved.json");
    Scene again = loadScene(dir + "/saved.json");
    EXPECT_EQ(again.environment, a.environment);

    EXPECT_CONTAINS(inputError([&] { load(R"({"file": "nowhere.hdr"})"); }),
                    "s.json: environment.file: ");
    EXPECT_CONTAINS(inputError([&] { load(R"({"file": "nowhere.hdr"})"); }), "nowhere.hdr");
    EXPECT_CONTAINS(inputError([&] { load(R"({"file": "sky.hdr", "intensty": 1})"); }), "intensty");
    EXPECT_CONTAINS(inputError([&] { load(R"({"file": "sky.hdr", "intensity": -1})"); }),
                    "environment.intensity: expected a scale factor");
    EXPECT_CONTAINS(inputError([&] { load(R"({"file": "sky.hdr", "sky": {}})"); }),
                    "environment: expected exactly one of \"file\", \"sky\" or \"sequence\"");
    EXPECT_CONTAINS(inputError([&] { load(R"({"sky": {"turbidity": 40}})"); }),
                    "environment.sky.turbidity: expected a turbidity in [1.7, 10]");
    EXPECT_CONTAINS(inputError([&] { load(R"({"sky": {"sun_elevation_deg": -5}})"); }),
                    "environment.sky.sun_elevation_deg");
    EXPECT_CONTAINS(inputError([&] { load(R"({"sequence": "frames/*.exr", "fps": 0})"); }),
                    "environment.fps: expected a positive number");
    EXPECT_CONTAINS(inputError([&] { load(R"({"sequence": "nothing/*.exr"})"); }),
                    "no file matches the sequence pattern");
    EXPECT_CONTAINS(inputError([&] { load(R"("sky.hdr")"); }),
                    "environment: expected null or an object");
    fs::remove_all(dir);
}

}  // namespace
}  // namespace candela
