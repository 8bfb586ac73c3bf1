// Lighting-design measurements without a GL context: the false-colour scale (monotone in
// lightness, through its stops), the legend's mapping, ticks and isolux levels, the frame plan of
// illuminance mode (no GLOSSY variant), and the calculation grid (points, summary, parsing).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "app/commands/Commands.h"  // parsePlane
#include "calculation/CalculationGrid.h"
#include "luminaires/lambertian/LambertianRect.h"
#include "renderer/FramePlan.h"
#include "renderer/Renderer.h"
#include "scene/SceneIo.h"
#include "shaders/shared/FalseColour.h"
#include "util/Error.h"

namespace candela {
namespace {

/// CIE L* of an sRGB-encoded colour.
double lightness(const glm::vec3& srgb) {
    auto linear = [](double c) {
        return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
    };
    double y = 0.2126 * linear(srgb.x) + 0.7152 * linear(srgb.y) + 0.0722 * linear(srgb.z);
    return y > 216.0 / 24389.0 ? 116.0 * std::cbrt(y) - 16.0 : 24389.0 / 27.0 * y;
}

TEST(FalseColour, HitsItsStopsAndClamps) {
    int n = gpu::kFalseColourStops;
    for (int i = 0; i < n; ++i) {
        glm::vec3 c = gpu::falseColour(float(i) / float(n - 1)), stop = gpu::falseColourStop(i);
        // i / (n - 1) * (n - 1) in float is i to within one ulp: 1e-6 of a unit colour.
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], stop[k], 1e-6f) << i;
    }
    EXPECT_EQ(gpu::falseColour(-3.f), gpu::falseColourStop(0));
    EXPECT_EQ(gpu::falseColour(7.f), gpu::falseColourStop(n - 1));
    // Midway between two stops is their mean (linear interpolation in the sRGB encoding).
    glm::vec3 mid = gpu::falseColour(0.5f / float(n - 1));
    glm::vec3 mean = 0.5f * (gpu::falseColourStop(0) + gpu::falseColourStop(1));
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(mid[k], mean[k], 1e-6f);
}

TEST(FalseColour, LightnessRisesMonotonically) {
    // Perceptual order: L* strictly increasing along the whole scale (sampled every 0.001) and
    // by at least 8 from stop to stop (the header's promise: 8.6 to 14 per stop).
    double previous = -1.0;
    for (int k = 0; k <= 1000; ++k) {
        double l = lightness(gpu::falseColour(float(k) / 1000.f));
        EXPECT_GT(l, previous) << "t = " << k / 1000.0;
        previous = l;
    }
    for (int i = 0; i + 1 < gpu::kFalseColourStops; ++i)
        EXPECT_GT(lightness(gpu::falseColourStop(i + 1)) - lightness(gpu::falseColourStop(i)), 8.0)
            << i;
    EXPECT_LT(lightness(gpu::falseColourStop(0)), 10.0);
    EXPECT_GT(lightness(gpu::falseColourStop(gpu::kFalseColourStops - 1)), 95.0);
}

TEST(FalseColour, LegendPositionLinearAndLog) {
    // Float arithmetic on values of order 1: 1e-6.
    EXPECT_NEAR(gpu::legendPosition(250.f, 0.f, 500.f, 0), 0.5f, 1e-6f);
    EXPECT_NEAR(gpu::legendPosition(-100.f, 0.f, 500.f, 0), -0.2f, 1e-6f);
    EXPECT_NEAR(gpu::legendPosition(100.f, 10.f, 1000.f, 1), 0.5f, 1e-6f);
    EXPECT_NEAR(gpu::legendPosition(10.f, 10.f, 1000.f, 1), 0.f, 1e-6f);
    // A black pixel on a log scale is far below the scale, not -infinity or NaN.
    float black = gpu::legendPosition(0.f, 10.f, 1000.f, 1);
    EXPECT_TRUE(std::isfinite(black));
    EXPECT_LT(black, -2.f);
}

TEST(FalseColour, LegendTicksAreRound) {
    FalseColourLegend linear;
    linear.min = 0.f;
    linear.max = 500.f;
    EXPECT_EQ(legendTicks(linear), (std::vector<float>{0, 100, 200, 300, 400, 500}));
    linear.min = 0.f;
    linear.max = 750.f;
    EXPECT_EQ(legendTicks(linear), (std::vector<float>{0, 200, 400, 600}));  // 125 rounds up to 200
    FalseColourLegend log;
    log.logScale = true;
    log.min = 10.f;
    log.max = 1000.f;
    EXPECT_EQ(legendTicks(log), (std::vector<float>{10, 20, 50, 100, 200, 500, 1000}));
    log.min = 0.1f;
    log.max = 1e5f;  // six decades: the decades only
    std::vector<float> decades = legendTicks(log);
    ASSERT_EQ(decades.size(), 7u);
    for (size_t i = 0; i < decades.size(); ++i)
        EXPECT_NEAR(decades[i], std::pow(10.f, float(i) - 1.f), 1e-6f * decades[i]);
}

TEST(FalseColour, ContourLevels) {
    FalseColourLegend l;
    l.min = 0.f;
    l.max = 500.f;
    // Automatic: the ticks strictly inside the range (a line at the range's ends says nothing).
    EXPECT_EQ(contourLevels(l), (std::vector<float>{100, 200, 300, 400}));
    l.levels = {300.f, 100.f, NAN, 100.f, -5.f};
    EXPECT_EQ(contourLevels(l), (std::vector<float>{-5, 100, 300}));  // sorted, unique, finite
    l.logScale = true;
    l.min = 1.f;
    EXPECT_EQ(contourLevels(l), (std::vector<float>{100, 300}));  // nothing <= 0 on a log scale
    l.levels.assign(40, 0.f);
    for (size_t i = 0; i < l.levels.size(); ++i) l.levels[i] = float(i + 1);
    EXPECT_EQ(contourLevels(l).size(), size_t(kMaxContourLevels));
    l.contours = false;
    EXPECT_TRUE(contourLevels(l).empty());
}

TEST(FalseColour, SanitizedLegendIsAlwaysUsable) {
    FalseColourLegend l;
    l.min = 5.f;
    l.max = 5.f;
    EXPECT_GT(sanitizedLegend(l).max, 5.f);
    l.logScale = true;
    l.min = 0.f;
    l.max = NAN;
    FalseColourLegend s = sanitizedLegend(l);
    EXPECT_GT(s.min, 0.f);
    EXPECT_GT(s.max, s.min);
    EXPECT_TRUE(std::isfinite(s.max));
}

Scene sceneFrom(const std::string& geometry, const std::string& luminaires) {
    std::string text =
        R"({"geometry": [)" + geometry + R"(], "luminaires": [)" + luminaires +
        R"(], "camera": {"position": [0, 1.5, 4], "target": [0, 0.5, 0], "fov_deg": 50}})";
    return parseScene(nlohmann::json::parse(text), "test.json");
}

const std::string kFloor =
    R"({"plane": {"center": [0,0,0], "normal": [0,1,0], "size": [6,6]}, "albedo": [0.5,0.5,0.5]})";
const std::string kGlossyBox =
    R"({"box": {"center": [2,0.5,0], "size": [0.5,1,0.5]}, "albedo": [0.2,0.2,0.2], "specular": [0.5,0.5,0.5], "roughness": 0.2})";
const std::string kPanel =
    R"({"type": "lambertian-rect", "name": "Panel", "size": [0.2, 0.2], "radiance": [1000, 1000, 1000], "position": [0.3,3,-0.2], "technique": "analytic"})";

TEST(IlluminancePlan, NoGlossyVariantAndOtherwiseTheSamePlan) {
    Scene scene = sceneFrom(kFloor + "," + kGlossyBox, kPanel);
    glm::mat4 view = cameraViewProj(scene.camera, 1.0);
    FramePlan radiance = planFrame(scene, view, "", Quantity::Radiance);
    FramePlan illuminance = planFrame(scene, view, "", Quantity::Illuminance);
    ASSERT_EQ(radiance.shading.size(), 1u);
    ASSERT_EQ(illuminance.shading.size(), 1u);
    auto& r = radiance.shading[0].program.defines;
    auto& e = illuminance.shading[0].program.defines;
    EXPECT_NE(std::find(r.begin(), r.end(), "GLOSSY"), r.end());
    EXPECT_EQ(std::find(e.begin(), e.end(), "GLOSSY"), e.end());
    EXPECT_FALSE(illuminance.glossy);
    // Glossy makes radiance progressive; in illuminance mode only shadows can (the box may
    // shadow the floor), the closed form being exact.
    EXPECT_TRUE(radiance.progressive());
    EXPECT_EQ(illuminance.shading[0].progressive, illuminance.shading[0].shadows);
    EXPECT_EQ(illuminance.passNames(), radiance.passNames());
    EXPECT_EQ(illuminance.needsBvh, radiance.needsBvh);
}

TEST(CalculationGrid, SummaryOfAHandMadeGrid) {
    // Values chosen so each figure is exact in binary: 100, 200, 300, 400 lx.
    GridSummary s = summariseGrid({300.0, 100.0, 400.0, 200.0});
    EXPECT_EQ(s.count, 4u);
    EXPECT_EQ(s.eMin, 100.0);
    EXPECT_EQ(s.eMax, 400.0);
    EXPECT_EQ(s.eAvg, 250.0);
    EXPECT_DOUBLE_EQ(s.u0, 0.4);           // Emin / Eavg
    EXPECT_DOUBLE_EQ(s.minOverMax, 0.25);  // Emin / Emax
    GridSummary dark = summariseGrid({0.0, 0.0, 0.0});
    EXPECT_EQ(dark.u0, 0.0);  // no light: uniformity 0, not NaN
    EXPECT_EQ(dark.minOverMax, 0.0);
    EXPECT_EQ(summariseGrid({}).count, 0u);
}

TEST(CalculationGrid, PointsAtCellCentresCentredInTheExtent) {
    std::vector<double> c = gridCoordinates(0.0, 4.0, 0.25);
    ASSERT_EQ(c.size(), 16u);
    // Sums of binary fractions: exact up to the last bit or two.
    EXPECT_NEAR(c.front(), 0.125, 1e-12);
    EXPECT_NEAR(c.back(), 3.875, 1e-12);
    std::vector<double> odd = gridCoordinates(0.0, 1.0, 0.3);  // 3 points, 0.1 m margins
    ASSERT_EQ(odd.size(), 3u);
    EXPECT_NEAR(odd[0], 0.2, 1e-12);
    EXPECT_NEAR(odd[2], 0.8, 1e-12);
    EXPECT_EQ(gridCoordinates(0.0, 0.1, 1.0), std::vector<double>{0.05});
}

TEST(CalculationGrid, ParsesPlanes) {
    CalcPlane p = parsePlane("y=0.8");
    EXPECT_EQ(p.axis, 1);
    EXPECT_EQ(p.offset, 0.8);
    EXPECT_EQ(p.normal(), glm::dvec3(0, 1, 0));
    EXPECT_EQ(p.point(1.0, 2.0), glm::dvec3(1.0, 0.8, 2.0));
    CalcPlane wall = parsePlane("-x=2.5");
    EXPECT_EQ(wall.normal(), glm::dvec3(-1, 0, 0));
    EXPECT_EQ(wall.point(1.0, 2.0), glm::dvec3(2.5, 1.0, 2.0));                 // (u, v) = (y, z)
    EXPECT_EQ(parsePlane("z=-1").point(3.0, 4.0), glm::dvec3(3.0, 4.0, -1.0));  // (x, y)
    for (const char* bad : {"", "y", "y=", "w=1", "y=abc", "y=nan", "y=inf", "y=1m", "=1"})
        EXPECT_THROW(parsePlane(bad), InputError) << bad;
}

TEST(CalculationGrid, EachPointIsTheRegistrysEstimate) {
    Scene scene = sceneFrom(kFloor, kPanel);
    GridSpec spec;
    spec.plane = parsePlane("y=0.75");
    spec.lo = {-1.0, -1.0};
    spec.hi = {1.0, 0.5};
    spec.spacing = 0.5;
    GridResult r = computeGrid(scene, spec);
    ASSERT_EQ(r.u.size(), 4u);
    ASSERT_EQ(r.v.size(), 3u);
    ASSERT_EQ(r.E.size(), 12u);
    for (size_t j = 0; j < r.v.size(); ++j)
        for (size_t i = 0; i < r.u.size(); ++i) {
            glm::dvec3 p(r.u[i], 0.75, r.v[j]);
            Estimate e = lambertianRectAnalytic(*scene.luminaires[0], p, {0, 1, 0}, {});
            // The same double-precision function: equal but for the luminance weighting's sum.
            EXPECT_NEAR(r.E[j * r.u.size() + i], e.irradiance.y, 1e-12 * e.irradiance.y);
        }
    spec.spacing = 0.0;
    EXPECT_THROW(computeGrid(scene, spec), InputError);
    spec.spacing = NAN;
    EXPECT_THROW(computeGrid(scene, spec), InputError);
    spec.spacing = 0.5;
    spec.hi.x = spec.lo.x;
    EXPECT_THROW(computeGrid(scene, spec), InputError);
}

}  // namespace
}  // namespace candela
