// Tests of environment maps (luminaires/Environment*.h): the lat-long convention of the scene
// contract, loading and its errors, the sky, sequences, the cube-map and global CDFs (chi-square
// against their pdfs, inversion), the balanced estimator of Lu et al. 2013 against the exact
// reference and hard cases. Havran et al.'s lights, the sky, sequences and scene parsing are in
// environment_sky_test.cpp.
#include "luminaires/environment/Environment.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "luminaires/Random.h"
#include "luminaires/environment/EnvironmentSampling.h"
#include "renderer/passes/EnvironmentPass.h"
#include "scene/Bvh.h"
#include "scene/SceneIo.h"
#include "tests/EnvironmentTestUtil.h"
#include "tests/TestUtil.h"
#include "util/Error.h"

namespace candela {
namespace {

namespace fs = std::filesystem;
using namespace envtest;

// ---------------------------------------------------------------------------------------------
// Conventions

TEST(Environment, BrightTexelLightsTheContractDirection) {
    const int w = 64, h = 32;
    // Texel (16, 8): u = 16.5 / 64, v = 8.5 / 32: theta = pi v, phi = 2 pi u.
    for (double rotation : {0.0, 90.0, -30.0}) {
        auto map = makeMap(
            w, h, [](int x, int y) { return glm::vec3(x == 16 && y == 8 ? 100.f : 0.f); },
            rotation);
        double u = 16.5 / w, v = 8.5 / h;
        double theta = kPi * v, phi = 2.0 * kPi * u + rotation * kPi / 180.0;
        glm::dvec3 d(std::sin(theta) * std::cos(phi), std::cos(theta),
                     std::sin(theta) * std::sin(phi));
        EXPECT_EQ(map->radiance(d), glm::dvec3(100.0)) << "rotation " << rotation;
        EXPECT_LT(glm::length(map->direction(u, v) - d), 1e-12);
        EXPECT_EQ(map->radiance(-d), glm::dvec3(0.0));
        // The reference irradiance is largest for the normal facing that direction.
        EnvironmentLighting lighting(map, 8, 4);
        double facing = lum(environmentReference(lighting, {}, d, {}).irradiance);
        double away = lum(environmentReference(lighting, {}, -d, {}).irradiance);
        EXPECT_GT(facing, 0.0);
        EXPECT_EQ(away, 0.0);
        for (const glm::dvec3& n : test::cubeNormals26())
            EXPECT_LE(lum(environmentReference(lighting, {}, n, {}).irradiance),
                      facing * (1 + 1e-12));
    }
    // Known directions: the top row is +Y, u = 0 is +X, u = 1/4 is +Z; rotation 90 turns +X to +Z.
    auto map = makeMap(4, 2, [](int x, int y) { return glm::vec3(float(1 + x + 4 * y)); });
    EXPECT_EQ(map->radiance({0, 1, 0}), glm::dvec3(1 + 0));    // zenith: row 0
    EXPECT_EQ(map->radiance({0, -1, 0}), glm::dvec3(1 + 4));   // nadir: row 1
    EXPECT_EQ(map->radiance({1, 0.1, 0.01}), glm::dvec3(1));   // phi just above 0: column 0
    EXPECT_EQ(map->radiance({-0.01, 0.1, 1}), glm::dvec3(2));  // phi just above pi/2: column 1
    auto turned = makeMap(
        4, 2, [](int x, int y) { return glm::vec3(float(1 + x + 4 * y)); }, 90.0);
    EXPECT_EQ(turned->radiance({-0.01, 0.1, 1}), glm::dvec3(1));  // column 0 now starts at +Z
}

TEST(Environment, SeamLookupAndSamplingAgree) {
    // Column 0 bright, column W-1 dim: just either side of phi = 0 the lookup switches, and
    // samples drawn from column 0 land on the phi >= 0 side.
    const int w = 32, h = 16;
    auto map = makeMap(
        w, h, [&](int x, int) { return glm::vec3(x == 0 ? 50.f : (x == w - 1 ? 5.f : 0.f)); });
    double eps = 1e-9;
    EXPECT_EQ(map->radiance({1, 0, eps}), glm::dvec3(50.0));
    EXPECT_EQ(map->radiance({1, 0, -eps}), glm::dvec3(5.0));
    EnvironmentLighting lighting(map, 8, 4);
    Random rng(7);
    for (int k = 0; k < 20000; ++k) {
        DirectionSample s = lighting.global().sample({rng.uniform(), rng.uniform()});
        ASSERT_GT(s.pdf, 0.0);
        double L = map->radiance(s.w).x;
        ASSERT_TRUE(L == 50.0 || L == 5.0) << L;
        // pdf(w) evaluated at the sample is the density it was drawn with.
        ASSERT_NEAR(lighting.global().pdf(s.w), s.pdf, 1e-9 * s.pdf);
        std::array<double, 6> mu;
        mu.fill(1.0 / 6.0);
        DirectionSample c =
            lighting.cube().sample(mu, {rng.uniform(), rng.uniform(), rng.uniform()});
        if (c.pdf > 0.0) {
            ASSERT_NEAR(lighting.cube().pdf(mu, c.w), c.pdf, 1e-9 * c.pdf);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Loading and its errors

TEST(Environment, LoadsRealMapsAndRejectsBadFiles) {
    std::string data = test::dataDir() + "/hdr/";
    auto map = EnvironmentMap::load(data + "noon_grass_256.hdr", 2.0, 10.0);
    EXPECT_EQ(map->width(), 256);
    EXPECT_EQ(map->height(), 128);
    EXPECT_GT(map->totalLuminancePower(), 0.0);
    EXPECT_DOUBLE_EQ(map->intensity(), 2.0);

    EXPECT_CONTAINS(inputError([&] { EnvironmentMap::load(data + "nowhere.hdr"); }), "nowhere.hdr");
    EXPECT_CONTAINS(inputError([&] { EnvironmentMap::load(data + "nowhere.hdr"); }),
                    "No such file");
    EXPECT_CONTAINS(inputError([&] { EnvironmentMap::load(data + "LICENSE.md"); }),
                    "LICENSE.md: unsupported environment map type \".md\"");
    std::string dir = tempDir("load");
    writeImage(dir + "/square.exr", 16, 16, std::vector<float>(16 * 16 * 3, 1.f));
    EXPECT_CONTAINS(inputError([&] { EnvironmentMap::load(dir + "/square.exr"); }),
                    "square.exr: 16x16 is not a lat-long map (expected width = 2 x height)");
    writeImage(dir + "/cube.exr", 8, 48, std::vector<float>(8 * 48 * 3, 1.f));
    EXPECT_CONTAINS(inputError([&] { EnvironmentMap::load(dir + "/cube.exr"); }), "cube map");
    for (float bad : {std::nanf(""), -1.f, INFINITY}) {
        std::vector<float> px(16 * 8 * 3, 1.f);
        px[(3 * 16 + 5) * 3 + 1] = bad;
        writeImage(dir + "/bad.exr", 16, 8, px);
        std::string m = inputError([&] { EnvironmentMap::load(dir + "/bad.exr"); });
        EXPECT_CONTAINS(m, "bad.exr: ");
        EXPECT_CONTAINS(m, "texel value at (5, 3) channel G");
        EXPECT_CONTAINS(m, std::isnan(bad) ? "NaN" : (bad < 0 ? "negative" : "infinite"));
    }
    std::ofstream(dir + "/garbage.hdr") << "not an image";
    EXPECT_CONTAINS(inputError([&] { EnvironmentMap::load(dir + "/garbage.hdr"); }), "garbage.hdr");
    EXPECT_CONTAINS(inputError([] { EnvironmentMap(0, 0, {}, 1.0, 0.0, "empty.exr"); }),
                    "empty.exr: empty image (0x0)");
    fs::remove_all(dir);
}

// A caller's smaller limit (the fuzzing target's 2048) refuses a wider map before its pixels are
// read, naming the limit; the default is the product's 16384.
TEST(Environment, LoadRefusesMapsWiderThanTheCallersLimit) {
    std::string file = test::dataDir() + "/hdr/noon_grass_256.hdr";
    EXPECT_EQ(EnvironmentMap::load(file, 1.0, 0.0, 256)->width(), 256);
    std::string m = inputError([&] { EnvironmentMap::load(file, 1.0, 0.0, 128); });
    EXPECT_CONTAINS(m, "noon_grass_256.hdr");
    EXPECT_CONTAINS(m, "out of range (1..128 per side)");
    EXPECT_EQ(EnvironmentMap::kMaxSide, 16384);
}

// ---------------------------------------------------------------------------------------------
// Exact reference and every sampler on a constant map

TEST(Environment, ConstantMapGivesPiL) {
    const double L = 2.5;
    auto map = makeMap(64, 32, [&](int, int) { return glm::vec3(float(L)); });
    EnvironmentLighting lighting(map, 16, 1024);
    EstimateOptions o;
    o.spp = 1 << 18;
    for (const glm::dvec3& n : test::cubeNormals26()) {
        // The reference is exact up to the 8-point Gauss-Legendre rule on the horizon band.
        EXPECT_NEAR(lum(environmentReference(lighting, {}, n, o).irradiance), kPi * L,
                    1e-3 * kPi * L);
        for (const auto& t : techniquesOf(LuminaireKind::Environment)) {
            if (t.name == "reference" || t.irradiance == &onEnvironmentLight<&environmentHavran>)
                continue;  // both havran2005s
            Estimate e = t.irradiance(test::lightOf(lighting), {}, n, o);
            double se = lum(e.stdError);
            // 2^18 samples: the standard error must be below 3e-3 pi L (global-cdf's is
            // sqrt(16/6 - 1) / sqrt(spp) = 2.5e-3 pi L for a constant map, the face-balanced
            // ones lower), and the estimate within 1e-3 pi L plus 4 standard errors.
            EXPECT_LT(se, 3e-3 * kPi * L) << t.name;
            EXPECT_NEAR(lum(e.irradiance), kPi * L, 1e-3 * kPi * L + 4.0 * se)
                << t.name << " n " << n.x << "," << n.y << "," << n.z;
        }
        // 1024 lights carrying their Voronoi cells' energy: the cosine varies over a cell of
        // ~0.0123 sr (about 3.6 deg across), so the deterministic error stays below 0.5 %.
        EXPECT_NEAR(lum(environmentHavran(lighting, {}, n, o).irradiance), kPi * L, 5e-3 * kPi * L);
    }
}

// ---------------------------------------------------------------------------------------------
// Chi-square tests of the samplers against their pdfs

/// A 32 x 16 map with luminance spanning 3 decades and 10 % black texels.
std::shared_ptr<EnvironmentMap> bumpyMap() {
    Random rng(99);
    return makeMap(32, 16, [&](int, int) {
        double u = rng.uniform();
        if (u < 0.1) return glm::vec3(0.f);
        return glm::vec3(float(std::pow(10.0, 3.0 * rng.uniform())), float(rng.uniform() * 100),
                         float(rng.uniform() * 100));
    });
}

/// Cells: every cube texel split 2 x 2 in face coordinates. Expected counts integrate pdf over a
/// cell with a 2 x 2 Gauss rule in (a, b) and dw = da db / (1 + a^2 + b^2)^(3/2) (exact here:
/// pdf q^(3/2) is constant in a texel, so pdf dw is constant in da db).
test::ChiSquareResult cubeChiSquare(const CubeMapDistribution& cube,
                                    const std::function<DirectionSample(Random&)>& draw,
                                    const std::function<double(const glm::dvec3&)>& pdf,
                                    int samples) {
    const int n = cube.faceSize(), m = 2 * n;
    std::vector<double> observed(size_t(6 * m * m) + 1, 0.0), expected(observed.size(), 0.0);
    Random rng(12345);
    for (int k = 0; k < samples; ++k) {
        DirectionSample s = draw(rng);
        if (!(s.pdf > 0.0)) {
            observed.back() += 1.0;
            continue;
        }
        glm::dvec2 ab;
        int f = cubeFaceOf(s.w, ab);
        int c = std::clamp(int((ab.x + 1) * 0.5 * m), 0, m - 1),
            r = std::clamp(int((ab.y + 1) * 0.5 * m), 0, m - 1);
        observed[size_t((f * m + r) * m + c)] += 1.0;
    }
    const double g = 0.5 / std::sqrt(3.0);
    double mass = 0.0;
    for (int f = 0; f < 6; ++f)
        for (int r = 0; r < m; ++r)
            for (int c = 0; c < m; ++c) {
                double h = 2.0 / m, sum = 0.0;
                for (double gy : {0.5 - g, 0.5 + g})
                    for (double gx : {0.5 - g, 0.5 + g}) {
                        double a = -1 + (c + gx) * h, b = -1 + (r + gy) * h, q = 1 + a * a + b * b;
                        const CubeFaceFrame& fr = cubeFaceFrame(f);
                        sum += pdf(glm::normalize(fr.centre + a * fr.right + b * fr.down)) /
                               (q * std::sqrt(q));
                    }
                double p = sum * 0.25 * h * h;
                expected[size_t((f * m + r) * m + c)] = p * samples;
                mass += p;
            }
    expected.back() = std::max(0.0, 1.0 - mass) * samples;
    return test::chiSquare(observed, expected);
}

// Six chi-square tests in this file (Bonferroni): each at 0.01 / 6.
constexpr double kAlpha = 0.01 / 6.0;

TEST(Environment, CubeSamplersPassChiSquare) {
    auto map = bumpyMap();
    EnvironmentLighting lighting(map, 8, 16);
    const CubeMapDistribution& cube = lighting.cube();
    const int samples = 400000;
    glm::dvec3 n = glm::normalize(glm::dvec3(0.3, 0.8, -0.5));
    std::array<double, 6> balanced = cube.balance(n), uniform;
    uniform.fill(1.0 / 6.0);
    for (auto [name, mu] : {std::pair{"balanced", balanced}, std::pair{"uniform-faces", uniform}}) {
        auto r = cubeChiSquare(
            cube,
            [&](Random& rng) {
                return cube.sample(mu, {rng.uniform(), rng.uniform(), rng.uniform()});
            },
            [&](const glm::dvec3& w) { return cube.pdf(mu, w); }, samples);
        EXPECT_GT(r.pValue, kAlpha)
            << name << ": chi2 " << r.statistic << " dof " << r.degreesOfFreedom;
        EXPECT_GT(r.degreesOfFreedom, 500) << name;  // the cells are really tested, not pooled away
    }
    // Balanced: a face wholly behind n gets no samples (mu_f = 0).
    EXPECT_EQ(balanced[3], 0.0);  // -Y: every corner has n . c < 0 for n.y = 0.8
}

// environment_global_cdf.frag's search, in the shader's float arithmetic: the last entry of an
// n-entry CDF (entry 0 is 0, entries 1..n in cdf) not above u, searched in [lo, hi).
static int searchCdf(const std::vector<float>& cdf, float u, int lo, int hi) {
    while (hi - lo > 1) {
        int mid = (lo + hi) >> 1;
        if ((mid == 0 ? 0.f : cdf[size_t(mid - 1)]) <= u)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

TEST(Environment, CdfSearchGuideFindsTheSameBinInOneOrTwoSteps) {
    Random rng(99);
    for (int n : {1, 2, 3, 7, 256, 1000, 16384}) {
        for (int shape = 0; shape < 3; ++shape) {
            // Uniform bins; random bins with runs of empty ones; all mass in one bin.
            std::vector<double> weight(static_cast<size_t>(n), 1.0);
            if (shape == 1)
                for (double& w : weight) w = rng.uniform() < 0.3 ? 0.0 : rng.uniform();
            if (shape == 2) std::fill(weight.begin(), weight.end(), 0.0), weight[size_t(n / 2)] = 1;
            double total = 0.0;
            for (double w : weight) total += w;
            if (!(total > 0)) weight[0] = total = 1.0;
            std::vector<float> cdf(static_cast<size_t>(n));
            double sum = 0.0;
            for (int i = 0; i < n; ++i) cdf[size_t(i)] = float((sum += weight[size_t(i)]) / total);
            cdf.back() = 1.f;
            std::vector<float> guide = cdfSearchGuide(cdf.data(), n);
            ASSERT_EQ(guide.size(), size_t(n));
            std::vector<float> us;
            for (int k = 0; k < 20000; ++k) us.push_back(float(rng.uniform()));
            for (int j = 0; j <= n; ++j) {  // the buckets' edges, a few ulps either side
                float e = float(j) / float(n);
                for (int step = 0; step < 3; ++step) {
                    us.push_back(e);
                    e = std::nextafter(e, 0.f);
                }
                e = float(j) / float(n);
                for (int step = 0; step < 3; ++step) us.push_back(e = std::nextafter(e, 2.f));
            }
            double width = 0.0;
            int counted = 0, widest = 0;
            for (float u : us) {
                if (!(u >= 0.f && u < 1.f)) continue;
                int j = std::min(int(u * float(n)), n - 1);
                int lo = int(guide[size_t(j)]);
                int hi = j + 1 < n ? int(guide[size_t(j + 1)]) + 1 : n;
                ASSERT_EQ(searchCdf(cdf, u, lo, hi), searchCdf(cdf, u, 0, n))
                    << "n " << n << " shape " << shape << " u " << u;
                width += hi - lo;
                widest = std::max(widest, hi - lo);
                ++counted;
            }
            // Uniform bins: a bracket holds one or two entries, three where float rounding moves
            // an entry across a bucket's edge, so at most two search steps. Otherwise the mean
            // bracket is still a few entries (a heavy bin spans many buckets sharing one entry).
            if (shape == 0) {
                EXPECT_LE(widest, 3) << n;
                EXPECT_LE(width / counted, 2.1) << n;
            } else {
                EXPECT_LE(width / counted, 4.0) << n << " shape " << shape;
            }
        }
    }
}

TEST(Environment, GlobalCdfPassesChiSquare) {
    auto map = bumpyMap();
    EnvironmentLighting lighting(map, 8, 16);
    const LatLongDistribution& global = lighting.global();
    const int w = map->width(), h = map->height(), samples = 400000;
    // Cells: every texel split 2 x 2 in (phi, cos(theta)); pdf is constant on a texel, so the
    // midpoint rule is exact.
    std::vector<double> observed(size_t(4 * w * h) + 1, 0.0), expected(observed.size(), 0.0);
    Random rng(4321);
    for (int k = 0; k < samples; ++k) {
        DirectionSample s = global.sample({rng.uniform(), rng.uniform()});
        if (!(s.pdf > 0.0)) {
            observed.back() += 1;
            continue;
        }
        glm::dvec2 uv = map->uvOf(s.w);
        int x = std::clamp(int(uv.x * 2 * w), 0, 2 * w - 1);
        double cosT = glm::normalize(s.w).y;
        int ty = std::clamp(int(std::acos(std::clamp(cosT, -1.0, 1.0)) / kPi * h), 0, h - 1);
        double c0 = std::cos(kPi * ty / h), c1 = std::cos(kPi * (ty + 1) / h);
        int half = (c0 - cosT) / (c0 - c1) < 0.5 ? 0 : 1;
        observed[size_t((2 * ty + half) * 2 * w + x)] += 1;
    }
    double mass = 0.0;
    for (int ty = 0; ty < h; ++ty) {
        double c0 = std::cos(kPi * ty / h), c1 = std::cos(kPi * (ty + 1) / h);
        for (int half = 0; half < 2; ++half) {
            double ca = c0 - half * 0.5 * (c0 - c1), cb = ca - 0.5 * (c0 - c1),
                   cm = 0.5 * (ca + cb);
            for (int x = 0; x < 2 * w; ++x) {
                double phi = 2 * kPi * (x + 0.5) / (2 * w), s = std::sqrt(1 - cm * cm);
                double p =
                    global.pdf({s * std::cos(phi), cm, s * std::sin(phi)}) * (ca - cb) * (kPi / w);
                expected[size_t((2 * ty + half) * 2 * w + x)] = p * samples;
                mass += p;
            }
        }
    }
    expected.back() = std::max(0.0, 1.0 - mass) * samples;
    auto r = test::chiSquare(observed, expected);
    EXPECT_GT(r.pValue, kAlpha) << "chi2 " << r.statistic << " dof " << r.degreesOfFreedom;
    EXPECT_NEAR(mass, 1.0, 1e-9);
}

TEST(Environment, HavranLightChoicePassesChiSquare) {
    auto map = bumpyMap();
    EnvironmentLighting lighting(map, 8, 64);
    const HavranLights& lights = lighting.havran();
    const int samples = 200000;
    std::vector<double> observed(lights.lights().size(), 0.0), expected(observed.size());
    Random rng(77);
    for (int k = 0; k < samples; ++k) observed[size_t(lights.sample(rng.uniform()))] += 1;
    for (size_t i = 0; i < expected.size(); ++i) expected[i] = lights.probability(int(i)) * samples;
    auto r = test::chiSquare(observed, expected);
    EXPECT_GT(r.pValue, kAlpha) << "chi2 " << r.statistic;
}

TEST(Environment, SamplersInvert) {
    auto map = bumpyMap();
    EnvironmentLighting lighting(map, 8, 16);
    Random rng(5);
    std::array<double, 6> mu = lighting.cube().balance(glm::normalize(glm::dvec3(1, 1, 0)));
    for (int k = 0; k < 5000; ++k) {
        glm::dvec2 u(rng.uniform(), rng.uniform());
        DirectionSample s = lighting.global().sample(u);
        if (s.pdf > 0.0) {
            glm::dvec2 back = lighting.global().invert(s.w);
            // Inversion recomputes cos(theta) and phi from the direction: ~1e-12 after rounding.
            EXPECT_NEAR(back.x, u.x, 1e-9);
            EXPECT_NEAR(back.y, u.y, 1e-9);
        }
        for (int f = 0; f < 6; ++f) {
            DirectionSample c = lighting.cube().sampleFace(f, u);
            if (!(c.pdf > 0.0)) continue;
            glm::dvec2 back = lighting.cube().invertFace(f, c.w);
            EXPECT_NEAR(back.x, u.x, 1e-9) << f;
            EXPECT_NEAR(back.y, u.y, 1e-9) << f;
        }
        glm::dvec3 u3(rng.uniform(), u.x, u.y);
        DirectionSample c = lighting.cube().sample(mu, u3);
        if (c.pdf > 0.0) {
            glm::dvec3 back = lighting.cube().invert(mu, c.w);
            EXPECT_NEAR(back.y, u3.y, 1e-9);
            EXPECT_NEAR(back.z, u3.z, 1e-9);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Real maps

TEST(Environment, BalancedAgreesWithReferenceOnRealMaps) {
    for (const char* file : {"noon_grass_256.hdr", "hilly_terrain_01_256.hdr"}) {
        auto map = EnvironmentMap::load(test::dataDir() + "/hdr/" + file);
        EnvironmentLighting lighting(map, 0, 16);
        EstimateOptions o;
        o.spp = 1 << 18;
        double worst = 0.0, worstSe = 0.0;
        for (const glm::dvec3& n : test::cubeNormals26()) {
            double ref = lum(environmentReference(lighting, {}, n, o).irradiance);
            Estimate e = environmentBalanced(lighting, {}, n, o);
            double err = std::abs(lum(e.irradiance) - ref) / ref;
            worst = std::max(worst, err);
            worstSe = std::max(worstSe, lum(e.stdError) / ref);
            // 1 % of the exact irradiance (the issue's figure). The estimator's own standard
            // error is checked to stay below that 1 % (measured worst: 0.33 % on noon_grass,
            // 0.66 % on hilly_terrain for a normal facing away from its low sun).
            EXPECT_LT(err, 0.01) << file << " n " << n.x << "," << n.y << "," << n.z;
            EXPECT_LT(lum(e.stdError), 0.01 * ref) << file;
            Estimate mis = environmentBalancedMis(lighting, {}, n, o);
            EXPECT_LT(std::abs(lum(mis.irradiance) - ref), 0.01 * ref + 4 * lum(mis.stdError))
                << file;
        }
        std::printf(
            "[ info ] %s: balanced at 2^18 spp, worst relative error %.2e, worst relative "
            "standard error %.2e\n",
            file, worst, worstSe);
    }
}

// ---------------------------------------------------------------------------------------------
// Hard cases

TEST(Environment, SunBehindTheSurfaceWastesNoSample) {
    // A sun (one texel near the nadir, 1e6 x the sky) behind a surface facing up.
    const int w = 64, h = 32;
    auto map =
        makeMap(w, h, [&](int x, int y) { return glm::vec3(x == 10 && y == h - 2 ? 1e6f : 1.f); });
    EnvironmentLighting lighting(map, 16, 16);
    EstimateOptions o;
    o.spp = 4096;
    glm::dvec3 n(0, 1, 0);
    SampleCounts balanced, uniform;
    Estimate eb =
        environmentFaceEstimate(lighting, {}, n, o, lighting.cube().balance(n), &balanced);
    std::array<double, 6> mu;
    mu.fill(1.0 / 6.0);
    Estimate eu = environmentFaceEstimate(lighting, {}, n, o, mu, &uniform);
    std::printf("[ info ] sun behind: balanced %d/%d effective, uniform-faces %d/%d effective\n",
                balanced.effective, balanced.drawn, uniform.effective, uniform.drawn);
    // Balanced: the -Y face (the sun's) gets mu = 0; the side faces get 2/3 of the samples
    // (F_f = 2 corners against 4 for +Y), half of them below the horizon: 2/3 effective.
    // Uniform: 1/6 on +Y, 4/6 x 1/2 on the sides, none of the -Y face's: 1/2 effective.
    EXPECT_GT(balanced.effective, 0.62 * balanced.drawn);
    EXPECT_LT(uniform.effective, 0.55 * uniform.drawn);
    // No balanced sample lands on the sun; uniform-faces puts most of its -Y share there.
    int onSunBalanced = 0, onSunUniform = 0, onFaceBalanced = 0, onFaceUniform = 0;
    Random rng(3);
    std::array<double, 6> muB = lighting.cube().balance(n);
    for (int k = 0; k < 6000; ++k) {
        glm::dvec3 u(rng.uniform(), rng.uniform(), rng.uniform());
        DirectionSample sb = lighting.cube().sample(muB, u), su = lighting.cube().sample(mu, u);
        onSunBalanced += sb.pdf > 0.0 && map->texelOf(sb.w) == glm::ivec2(10, h - 2);
        onSunUniform += su.pdf > 0.0 && map->texelOf(su.w) == glm::ivec2(10, h - 2);
        glm::dvec2 ab;
        onFaceBalanced += sb.pdf > 0.0 && cubeFaceOf(sb.w, ab) == 3;
        onFaceUniform += su.pdf > 0.0 && cubeFaceOf(su.w, ab) == 3;
    }
    std::printf(
        "[ info ] of 6000 samples, on the sun's texel / on its face: balanced %d / %d, "
        "uniform-faces %d / %d\n",
        onSunBalanced, onFaceBalanced, onSunUniform, onFaceUniform);
    EXPECT_EQ(onSunBalanced, 0);
    EXPECT_EQ(onFaceBalanced, 0);
    EXPECT_GT(onSunUniform, 0);
    // 1/6 of 6000 = 1000 expected on the face; 4 binomial sigma (~115) below.
    EXPECT_GT(onFaceUniform, 880);
    double ref = lum(environmentReference(lighting, {}, n, o).irradiance);
    EXPECT_NEAR(ref, kPi, 1e-3 * kPi);  // the upper hemisphere is the unit sky
    EXPECT_NEAR(lum(eb.irradiance), ref, 4 * lum(eb.stdError) + 1e-3 * ref);
    EXPECT_NEAR(lum(eu.irradiance), ref, 4 * lum(eu.stdError) + 1e-3 * ref);
}

TEST(Environment, ARoofShadowsTheSky) {
    // A thin box floating 1 m above the receiver: its silhouette from the origin is its bottom
    // face, [-0.3, 0.7] x [-0.4, 0.2] at y = 1, so a unit sky gives pi (1 - F) with F the closed-
    // form rectangle form factor. (Shadow rays once ran as 1e6 m segments whose end bias, 1e-4 of
    // their length, skipped the first 100 m: this roof cast no shadow at all.)
    Scene scene = parseScene(nlohmann::json::parse(R"({"geometry": [
        {"box": {"center": [0.2, 1.025, -0.1], "size": [1.0, 0.05, 0.6]}}]})"),
                             "roof.json");
    Bvh bvh = Bvh::build(scene);
    BvhVisibility visibility(bvh);
    auto map = makeMap(64, 32, [](int, int) { return glm::vec3(1.f); });
    EnvironmentLighting lighting(map, 16, 16);
    EstimateOptions o;
    o.spp = 1 << 16;
    o.visibility = &visibility;
    double F = test::rectangleFormFactor(-0.3, 0.7, -0.4, 0.2, 1.0);
    double expected = kPi * (1.0 - F);
    ASSERT_GT(F, 0.1);  // the test means something: the roof blocks a tenth of the sky or more
    for (const std::string& name : test::unbiasedGpuTechniques(LuminaireKind::Environment)) {
        Estimate e = findTechnique(LuminaireKind::Environment, name)
                         ->irradiance(test::lightOf(lighting), {}, glm::dvec3(0, 1, 0), o);
        // 4 standard errors at 2^16 spp, plus 1e-3 for the float vertices of the box.
        EXPECT_NEAR(lum(e.irradiance), expected, 4.0 * lum(e.stdError) + 1e-3 * expected) << name;
    }
    // Out from under it (5 m to the side) the roof blocks less than 1 % of the sky.
    Estimate beside = environmentFaceEstimate(lighting, {5, 0, 0}, {0, 1, 0}, o,
                                              lighting.cube().balance({0, 1, 0}), nullptr);
    EXPECT_GT(lum(beside.irradiance), 0.99 * kPi - 4.0 * lum(beside.stdError));
}

TEST(Environment, SampleChartShowsSelectedAndEffectiveSamples) {
    // Fig. 1-2 of the paper for a receiver facing up under a map whose sun is below the horizon.
    const int w = 64, h = 32;
    auto map =
        makeMap(w, h, [&](int x, int y) { return glm::vec3(x == 10 && y == h - 2 ? 1e6f : 1.f); });
    CubeMapDistribution cube(*map, 16);
    const int spp = 120;
    auto colourAt = [](const SampleChart& c, int face, int x, int y) {
        glm::ivec2 cell = SampleChart::faceCell(face);
        const unsigned char* p = &c.rgb[(size_t(cell.y * c.facePixels + y) * size_t(c.width) +
                                         size_t(cell.x * c.facePixels + x)) *
                                        3];
        return glm::ivec3(p[0], p[1], p[2]);
    };
    auto marks = [&](const SampleChart& c, int face, bool green) {
        int count = 0;
        for (int y = 0; y < c.facePixels; ++y)
            for (int x = 0; x < c.facePixels; ++x) {
                glm::ivec3 v = colourAt(c, face, x, y);
                count += green ? (v.y > 200 && v.x < 100) : (v.x > 200 && v.y < 100);
            }
        return count;
    };
    for (bool balanced : {true, false}) {
        SampleChart c = sampleChart(*map, cube, {0, 1, 0}, spp, balanced, 5, 48);
        EXPECT_EQ(c.width, 4 * 48);
        EXPECT_EQ(c.height, 3 * 48);
        int drawn = 0;
        for (int f = 0; f < 6; ++f) {
            // As the estimators draw them: ceil(N_f) per face.
            EXPECT_EQ(c.drawn[size_t(f)], int(std::ceil(c.mu[size_t(f)] * spp))) << f;
            EXPECT_LE(c.effective[size_t(f)], c.drawn[size_t(f)]);
            drawn += c.drawn[size_t(f)];
        }
        EXPECT_GE(drawn, spp);
        EXPECT_EQ(c.effective[2], c.drawn[2]);  // every +Y sample faces the receiver
        EXPECT_EQ(c.effective[3], 0);           // no -Y sample does
        EXPECT_EQ(marks(c, 3, true), 0);        // nothing green below
        if (balanced) {
            EXPECT_EQ(c.drawn[3], 0);  // the sun's face gets no sample (mu = 0)
            EXPECT_EQ(marks(c, 3, false), 0);
        } else {
            EXPECT_EQ(c.drawn[3], spp / 6);
            EXPECT_GT(marks(c, 3, false), 0);  // the wasted samples show in red
        }
        EXPECT_GT(marks(c, 2, true), 0);
    }
}

TEST(Environment, SunPositionFollowsTheClock) {
    // Day 81 has declination 0 in Cooper's formula (the equinox): the sun rises due east (+X) at
    // 6 h, culminates due south (+Z) at 90 - latitude, sets due west (-X) at 18 h.
    SunPosition noon = sunPosition(48.0, 81, 12.0);
    EXPECT_NEAR(noon.elevationDeg, 42.0, 1e-6);
    EXPECT_NEAR(noon.azimuthDeg, 90.0, 1e-6);
    SunPosition rise = sunPosition(48.0, 81, 6.0), set = sunPosition(48.0, 81, 18.0);
    EXPECT_NEAR(rise.elevationDeg, 0.0, 1e-6);
    EXPECT_NEAR(rise.azimuthDeg, 0.0, 1e-6);
    EXPECT_NEAR(set.elevationDeg, 0.0, 1e-6);
    EXPECT_NEAR(std::abs(set.azimuthDeg), 180.0, 1e-6);
    // The June solstice (declination 23.45): noon at 90 - 48 + 23.45; midnight below the horizon
    // by 90 - 48 - 23.45 (the sun due north).
    EXPECT_NEAR(sunPosition(48.0, 172, 12.0).elevationDeg, 65.45, 0.01);
    EXPECT_NEAR(sunPosition(48.0, 172, 0.0).elevationDeg, -(90.0 - 48.0 - 23.45), 0.01);
    // Southern hemisphere: the noon sun is due north (-Z).
    EXPECT_NEAR(sunPosition(-33.9, 81, 12.0).azimuthDeg, -90.0, 1e-6);
}

TEST(Environment, BlackFaceAndBlackMap) {
    // Everything above 22.5 degrees of elevation black: the +Y face (down to 35.3 degrees at its
    // corners, one more texel of margin in the conservative max) is entirely black.
    const int w = 64, h = 32;
    auto map = makeMap(w, h, [&](int, int y) { return glm::vec3(y < 3 * h / 8 ? 0.f : 3.f); });
    EnvironmentLighting lighting(map, 16, 16);
    EXPECT_EQ(lighting.cube().faceImportance(2), 0.0);
    EXPECT_EQ(lighting.cube().balance({0, 1, 0})[2], 0.0);
    EXPECT_EQ(lighting.cube().pdf(lighting.cube().balance({0, 1, 0}), {0, 1, 0}), 0.0);
    EstimateOptions o;
    o.spp = 1 << 16;
    for (glm::dvec3 n :
         {glm::dvec3(0, 1, 0), glm::dvec3(1, 0, 0), glm::normalize(glm::dvec3(1, 1, 1))}) {
        double ref = lum(environmentReference(lighting, {}, n, o).irradiance);
        Estimate e = environmentBalanced(lighting, {}, n, o);
        EXPECT_NEAR(lum(e.irradiance), ref, 4 * lum(e.stdError) + 1e-3 * ref);
    }
    auto black = makeMap(w, h, [](int, int) { return glm::vec3(0.f); });
    EnvironmentLighting dark(black, 16, 16);
    for (const auto& t : techniquesOf(LuminaireKind::Environment))
        for (const glm::dvec3& n : test::cubeNormals26()) {
            Estimate e = t.irradiance(test::lightOf(dark), {}, n, o);
            EXPECT_EQ(e.irradiance, glm::dvec3(0.0)) << t.name;  // exactly 0, not NaN
            EXPECT_EQ(e.stdError, glm::dvec3(0.0)) << t.name;
        }
}

TEST(Environment, SingleTexelSunAndPoles) {
    // A sun one texel wide, 1e6 x the sky, and bright texels in the top and bottom rows.
    const int w = 128, h = 64;
    auto map = makeMap(w, h, [&](int x, int y) {
        if (x == 37 && y == 20) return glm::vec3(1e6f);
        if ((y == 0 && x == 5) || (y == h - 1 && x == 90)) return glm::vec3(5e4f);
        return glm::vec3(0.5f, 0.7f, 1.f);
    });
    EnvironmentLighting lighting(map, 0, 16);
    EstimateOptions o;
    o.spp = 1 << 16;
    double worst = 0.0;
    for (const glm::dvec3& n : test::cubeNormals26()) {
        double ref = lum(environmentReference(lighting, {}, n, o).irradiance);
        Estimate e = environmentBalanced(lighting, {}, n, o);
        double err = std::abs(lum(e.irradiance) - ref);
        worst = std::max(worst, err / ref);
        // 1 % of the exact value plus 4 standard errors.
        EXPECT_LT(err, 0.01 * ref + 4 * lum(e.stdError)) << n.x << "," << n.y << "," << n.z;
        Estimate g = environmentGlobalCdf(lighting, {}, n, o);
        EXPECT_LT(std::abs(lum(g.irradiance) - ref), 0.01 * ref + 4 * lum(g.stdError));
    }
    std::printf("[ info ] single-texel sun and poles: balanced worst relative error %.2e\n", worst);
    // The pole texels are found by lookup and by both samplers' pdfs.
    glm::dvec3 northPole = map->direction(5.5 / w, 0.5 / h),
               southPole = map->direction(90.5 / w, (h - 0.5) / h);
    EXPECT_EQ(lum(map->radiance(northPole)), 5e4 * 1.0);
    EXPECT_EQ(lum(map->radiance(southPole)), 5e4 * 1.0);
    EXPECT_GT(lighting.global().pdf(northPole), lighting.global().pdf(map->direction(0.5, 0.5)));
    std::array<double, 6> mu;
    mu.fill(1.0 / 6.0);
    EXPECT_GT(lighting.cube().pdf(mu, northPole), 0.0);
    EXPECT_GT(lighting.cube().pdf(mu, southPole), 0.0);
}

TEST(Environment, HugeSunOnAFaceHalfBehindIsUnbiasedButHeavyTailed) {
    // A one-texel sun 1e8 times the sky. For normals facing away from it, its cube face is partly
    // in front: the face's mu_f is not 0, but its CDF sends all but ~1e-5 of that face's samples
    // to the sun behind the surface, and the sky in front on the same face is sampled so rarely
    // that one run's standard error misses it (this is the GPU test's 4-17 % in
    // BlackMapsAndHugeSunsStayFinite). The estimator is still unbiased: the mean of independent
    // runs converges. BRDF sampling covers that sky, so balanced-mis is accurate in one run.
    auto map =
        makeMap(64, 32, [](int x, int y) { return glm::vec3(x == 20 && y == 10 ? 1e6f : 0.01f); });
    EnvironmentLighting lighting(map);
    for (const glm::dvec3& n : {glm::dvec3(0, -1, 0), glm::dvec3(1, 0, 0)}) {
        EstimateOptions o;
        o.spp = 1 << 16;
        double ref = lum(environmentReference(lighting, {}, n, o).irradiance);
        Estimate mis = environmentBalancedMis(lighting, {}, n, o);
        // 1 % plus 4 standard errors: balanced-mis's weights are bounded here.
        EXPECT_NEAR(lum(mis.irradiance), ref, 0.01 * ref + 4 * lum(mis.stdError))
            << n.x << "," << n.y << "," << n.z;
        const int kRuns = 32;
        double sum = 0.0, sumSq = 0.0, reported = 0.0;
        o.spp = 4096;
        for (int k = 0; k < kRuns; ++k) {
            o.seed = uint64_t(1000 + k);
            Estimate e = environmentBalanced(lighting, {}, n, o);
            sum += lum(e.irradiance);
            sumSq += lum(e.irradiance) * lum(e.irradiance);
            reported += lum(e.stdError) / kRuns;
        }
        double mean = sum / kRuns, spread = std::sqrt(std::max(0.0, sumSq / kRuns - mean * mean));
        // Unbiased: the mean of 32 runs within 4 of its standard errors (from the runs' spread).
        EXPECT_NEAR(mean, ref, 4.0 * spread / std::sqrt(double(kRuns - 1)))
            << n.x << "," << n.y << "," << n.z;
        std::printf(
            "[ info ] 1e8 sun behind n = (%g, %g, %g): balanced mean of %d runs %.5f (exact %.5f), "
            "spread of one run %.2g against its reported standard error %.2g; balanced-mis %.5f\n",
            n.x, n.y, n.z, kRuns, mean, ref, spread, reported, lum(mis.irradiance));
    }
}

}  // namespace
}  // namespace candela
