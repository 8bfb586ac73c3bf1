// Projection of rays onto a light field (luminaires/lightfield/LightFieldRays.h): a Lambertian
// patch of known radiance is reproduced, flux is accounted for to the last ray, the source frame
// options work, and the converted OSRAM LED keeps its 337 lm through LightFieldData::power().
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "luminaires/Random.h"
#include "luminaires/lightfield/LightFieldRays.h"
#include "shaders/shared/Constants.h"
#include "tests/TestUtil.h"
#include "util/Error.h"

namespace candela {
namespace {

namespace fs = std::filesystem;

using gpu::kPi;
constexpr double kPatchHalf = 0.010;  ///< Half-size of the Lambertian patch, metres.
constexpr double kRadiance = 1000.0;  ///< Its luminance, cd/m2.

std::string ledFile() {
    return test::dataDir() + "/nearfield/rayfile_LERTDUW_S2WP_green_100k_20161013_IES_TM25.TM25RAY";
}

/// Rays leaving a uniform Lambertian square (z = 0, facing +z) of radiance kRadiance: flux
/// pi L A in all, uniform start points, cosine-weighted directions.
std::vector<EmittedRay> lambertianPatch(size_t n, uint64_t seed) {
    Random rng(seed);
    double area = 4.0 * kPatchHalf * kPatchHalf;
    std::vector<EmittedRay> rays(n);
    for (EmittedRay& r : rays) {
        r.position = glm::dvec3((2.0 * rng.uniform() - 1.0) * kPatchHalf,
                                (2.0 * rng.uniform() - 1.0) * kPatchHalf, 0.0);
        double r2 = rng.uniform(), phi = 2.0 * kPi * rng.uniform(), s = std::sqrt(r2);
        r.direction = glm::dvec3(s * std::cos(phi), s * std::sin(phi), std::sqrt(1.0 - r2));
        r.flux = kPi * kRadiance * area / double(n);
    }
    return rays;
}

/// 5x5 basis of spacing 2 mm: every support (node +- 3 mm, nodes within +-4 mm) lies inside the
/// +-10 mm patch, so L is constant over each support and every C_m should be kRadiance.
LightFieldLayout patchLayout() {
    LightFieldLayout l;
    l.delta = 0.005;
    l.count = {5, 5};
    l.spacing = {0.002, 0.002};
    l.origin = {-0.004, -0.004};
    l.imageMin = glm::dvec2(-0.015);
    l.imageMax = glm::dvec2(0.015);
    l.resolution = {32, 32};
    return l;
}

struct PixelStats {
    std::vector<double> sum, sumSq;  ///< Per pixel: sum of flux Phi_m(u) and of its square.
};

/// Independent replay of one image's accumulation, for the variance of each pixel's estimate.
PixelStats replay(const std::vector<EmittedRay>& rays, const LightFieldLayout& l, int m,
                  Estimator e) {
    PixelStats st;
    size_t pixels = size_t(l.resolution.x * l.resolution.y);
    st.sum.assign(pixels, 0.0);
    st.sumSq.assign(pixels, 0.0);
    glm::dvec2 node = l.origin + glm::dvec2(m % l.count.x, m / l.count.x) * l.spacing;
    glm::dvec2 px = (l.imageMax - l.imageMin) / glm::dvec2(l.resolution);
    for (const EmittedRay& r : rays) {
        glm::dvec2 u(r.position), s = u + l.delta / r.direction.z * glm::dvec2(r.direction);
        glm::ivec2 p(glm::floor((s - l.imageMin) / px));
        if (p.x < 0 || p.y < 0 || p.x >= l.resolution.x || p.y >= l.resolution.y) continue;
        double w = r.flux * bspline2((u.x - node.x) / l.spacing.x) *
                   bspline2((u.y - node.y) / l.spacing.y);
        if (e == Estimator::PerRay) w /= std::pow(r.direction.z, 4.0);  // the per-ray weight
        size_t k = size_t(p.y * l.resolution.x + p.x);
        st.sum[k] += w;
        st.sumSq[k] += w * w;
    }
    return st;
}

void checkReproducesRadiance(Estimator estimator) {
    std::vector<EmittedRay> rays = lambertianPatch(1000000, 7);
    LightFieldLayout l = patchLayout();
    LightFieldAccumulator acc(l, estimator);
    for (const EmittedRay& r : rays) acc.add(r);
    auto lf = acc.build("cd/m2");
    for (int m : {12, 0, 6, 24}) {  // the centre, a corner and two others
        PixelStats st = replay(rays, l, m, estimator);
        const std::vector<float>& c = lf->images[size_t(m)].luminance;
        double zSum = 0.0, z2Sum = 0.0, zMax = 0.0;
        int cells = 0;
        for (size_t k = 0; k < c.size(); ++k) {
            // The estimate is a fixed multiple of a sum of random weights: its relative standard
            // deviation is sqrt(sum of squares) / sum. With at least 30 effective rays (sum^2 /
            // sum of squares) it is close enough to normal for the bounds below.
            if (st.sum[k] <= 0.0 || st.sum[k] * st.sum[k] / st.sumSq[k] < 30.0) continue;
            double z = (c[k] / kRadiance - 1.0) / (std::sqrt(st.sumSq[k]) / st.sum[k]);
            zSum += z;
            z2Sum += z * z;
            zMax = std::max(zMax, std::abs(z));
            ++cells;
        }
        ASSERT_GT(cells, 150) << "image " << m;
        // Unbiased: the mean z-score is within 4 standard errors (1 / sqrt(cells)) of zero;
        // a 1 % bias of G would show as a shift of ~0.15 here.
        EXPECT_LT(std::abs(zSum / cells), 4.0 / std::sqrt(double(cells))) << "image " << m;
        // The scatter is the ray noise: mean z^2 near 1 (for ~200 cells its standard error is
        // about sqrt(2 / cells) = 0.1; 0.6..1.5 is 4-5 of those), and no cell beyond 6 sigma.
        EXPECT_GT(z2Sum / cells, 0.6) << "image " << m;
        EXPECT_LT(z2Sum / cells, 1.5) << "image " << m;
        EXPECT_LT(zMax, 6.0) << "image " << m;
    }
}

TEST(LightFieldRays, LambertianPatchReproducesRadianceFluxConserving) {
    checkReproducesRadiance(Estimator::FluxConserving);
}

TEST(LightFieldRays, LambertianPatchReproducesRadiancePerRay) {
    checkReproducesRadiance(Estimator::PerRay);
}

// A source lit only on the half x < 0 of the patch: images whose basis support lies wholly in the
// dark (node x = +4 mm, support from +1 mm) are exactly zero, the image of node (-4, 0) mm (support
// wholly lit) holds kRadiance. Catches swapped or mirrored node indices.
TEST(LightFieldRays, HalfLitSourceLightsOnlyItsNodes) {
    std::vector<EmittedRay> rays = lambertianPatch(400000, 5);
    for (EmittedRay& r : rays) {
        r.position.x = 0.5 * (r.position.x - kPatchHalf);
        r.flux *= 0.5;  // half the area, same radiance
    }
    LightFieldLayout l = patchLayout();
    LightFieldAccumulator acc(l);
    for (const EmittedRay& r : rays) acc.add(r);
    auto lf = acc.build("cd/m2");
    for (int m = 0; m < 25; ++m) {
        bool dark = m % 5 == 4;
        float peak = *std::max_element(lf->images[size_t(m)].luminance.begin(),
                                       lf->images[size_t(m)].luminance.end());
        if (dark)
            EXPECT_EQ(peak, 0.0f) << "image " << m;
        else
            EXPECT_GT(peak, 0.0f) << "image " << m;
    }
    // Pixels within 4 mm of (-4, 0) mm on S (rays within ~40 degrees of the axis, ~300 rays
    // each): their mean is kRadiance to the noise of ~50 pixels (about 1 %), so 4 %.
    glm::dvec2 px = lf->pixelSize();
    double sum = 0.0;
    int n = 0;
    for (int j = 0; j < l.resolution.y; ++j)
        for (int i = 0; i < l.resolution.x; ++i) {
            glm::dvec2 s = l.imageMin + (glm::dvec2(i, j) + 0.5) * px;
            if (glm::length(s - glm::dvec2(-0.004, 0.0)) > 0.004) continue;
            sum += lf->images[10].luminance[size_t(j * l.resolution.x + i)];
            ++n;
        }
    ASSERT_GT(n, 50);
    EXPECT_NEAR(sum / n / kRadiance, 1.0, 0.04);
}

TEST(LightFieldRays, FluxIsAccountedForAndConserved) {
    std::vector<EmittedRay> rays = lambertianPatch(100000, 11);
    rays.push_back({{0, 0, 0}, {0, 0, -1}, 0.5});    // backward
    rays.push_back({{0.5, 0, 0}, {0, 0, 1}, 0.25});  // far outside the basis
    rays.push_back({{0, 0, 0}, glm::normalize(glm::dvec3(10, 0, 1)), 0.125});  // beyond the image
    LightFieldLayout l = patchLayout();
    LightFieldAccumulator fc(l, Estimator::FluxConserving), perRay(l, Estimator::PerRay);
    for (const EmittedRay& r : rays) {
        fc.add(r);
        perRay.add(r);
    }
    auto lf = fc.build("cd/m2");
    perRay.build("cd/m2");
    const ProjectionReport& r = fc.report();
    double total = kPi * kRadiance * 4.0 * kPatchHalf * kPatchHalf + 0.875;
    // Sums of 1e5 doubles in another order: rounding ~1e-12 relative.
    EXPECT_NEAR(r.totalFlux, total, total * 1e-9);
    EXPECT_NEAR(r.keptFlux + r.backwardFlux + r.outsideImageFlux + r.outsideBasisFlux, r.totalFlux,
                r.totalFlux * 1e-9);
    EXPECT_EQ(r.backwardRays, 1u);
    EXPECT_DOUBLE_EQ(r.backwardFlux, 0.5);
    EXPECT_GE(r.outsideBasisRays, 1u);
    EXPECT_GE(r.outsideImageRays, 1u);
    // Flux-conserving: the images' own flux is the kept flux, to the float rounding of C (1e-7).
    EXPECT_NEAR(r.modelFlux, r.keptFlux, r.keptFlux * 1e-6);
    // LightFieldData::power() integrates the same model independently: its quadrature and ours
    // agree to their tabulation errors (each ~0.2 %), so 1 %.
    double power = lf->power().x;
    EXPECT_NEAR(power, r.keptFlux, 0.01 * r.keptFlux);
    // Per-ray: unbiased for this constant radiance too, so its model flux is the kept flux up to
    // noise; measured, not asserted.
    const ProjectionReport& p = perRay.report();
    std::printf("patch: kept %.6g lm, model %.6g (flux-conserving), %.6g (per-ray), power() %.6g\n",
                r.keptFlux, r.modelFlux, p.modelFlux, power);
}

TEST(LightFieldRays, MainAxisRotationMatchesRaysGivenAlongZ) {
    std::vector<EmittedRay> rays = lambertianPatch(50000, 3);
    // The same source facing +x: (x, y, z) -> (z, y, -x), a rotation about y.
    std::vector<EmittedRay> sideways = rays;
    for (EmittedRay& r : sideways) {
        r.position = glm::dvec3(r.position.z, r.position.y, -r.position.x);
        r.direction = glm::dvec3(r.direction.z, r.direction.y, -r.direction.x);
    }
    LayoutOptions o;
    o.count = {5, 5};
    o.resolution = {32, 32};
    o.delta = 0.005;
    LayoutChoice straight = chooseLayout(rays, o);
    o.axis = SourceAxis::MainAxis;
    LayoutChoice turned = chooseLayout(sideways, o);
    EXPECT_FALSE(turned.axisFallback);
    // Lambertian: the mean direction is 2/3 along the normal.
    EXPECT_NEAR(turned.meanDirection.x, 2.0 / 3.0, 0.01);
    glm::dvec3 axis = turned.frame.direction(glm::normalize(turned.meanDirection));
    EXPECT_NEAR(axis.z, 1.0, 1e-12);
    ProjectionReport a, b;
    projectRays(rays, straight, "cd/m2", a);
    projectRays(sideways, turned, "cd/m2", b);
    // The main-axis rotation undoes the turn (both are the quarter turn about y), so the layouts
    // agree to the rounding of the rotation: kept flux within 0.1 % (pixel-edge flips at most).
    EXPECT_NEAR(b.keptFlux, a.keptFlux, 1e-3 * a.keptFlux);
    // The main axis is estimated from 50 000 rays: its noise (~0.003 per component) tilts the
    // frame by ~0.3 degrees, which moves the U quantiles by well under 2 %.
    EXPECT_NEAR(turned.layout.spacing.x, straight.layout.spacing.x,
                0.02 * straight.layout.spacing.x);

    // A custom axis does the same; given as is, the sideways source sends half its flux backwards
    // (binomial: 50 % +- 0.25 % at 50 000 rays, so 2 %).
    o.axis = SourceAxis::Custom;
    o.customAxis = {1, 0, 0};
    LayoutChoice custom = chooseLayout(sideways, o);
    EXPECT_NEAR(custom.frame.direction({1, 0, 0}).z, 1.0, 1e-12);
    o.axis = SourceAxis::AsGiven;
    LayoutChoice given = chooseLayout(sideways, o);
    ProjectionReport c;
    projectRays(sideways, given, "cd/m2", c);
    EXPECT_NEAR(c.backwardFlux / c.totalFlux, 0.5, 0.02);
}

TEST(LightFieldRays, LayoutErrorsNameTheInput) {
    std::vector<EmittedRay> back = {{{0, 0, 0}, {0, 0, -1}, 1.0}};
    LayoutOptions o;
    o.what = "backward.TM25RAY";
    try {
        chooseLayout(back, o);
        FAIL() << "no InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("backward.TM25RAY"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("forward"), std::string::npos);
    }
    o.count = {2, 5};
    EXPECT_THROW(chooseLayout(lambertianPatch(10, 1), o), InputError);
    o.count = {5, 5};
    o.axis = SourceAxis::Custom;
    o.customAxis = glm::dvec3(0.0);
    EXPECT_THROW(chooseLayout(lambertianPatch(10, 1), o), InputError);
    EXPECT_THROW(chooseLayout({}, LayoutOptions{}), InputError);
}

TEST(LightFieldRays, CylinderIsScaledToItsHeader) {
    Tm25RayFile file = readTm25(test::dataDir() + "/nearfield/Cyl10k.1.tm25ray");
    Tm25FluxInfo info;
    std::vector<EmittedRay> rays = raysFromTm25(file, true, info);
    EXPECT_TRUE(info.photometric);
    EXPECT_EQ(info.unit, "cd/m2");
    EXPECT_NEAR(info.scale, 1e-4, 1e-7);  // header 1 lm over ~10 000 (mean 1.000, 4 digits)
    double sum = 0.0;
    for (const EmittedRay& r : rays) sum += r.flux;
    EXPECT_NEAR(sum, 1.0, 1e-9);
    raysFromTm25(file, false, info);
    EXPECT_EQ(info.scale, 1.0);
    LayoutOptions o;
    o.what = "Cyl10k.1.tm25ray";
    LayoutChoice c = chooseLayout(rays, o);
    ProjectionReport report;
    projectRays(rays, c, info.unit, report);
    // Half the cylinder's flux goes backwards (TM25.md Sec. 8.2): reported, not an error.
    EXPECT_NEAR(report.backwardFlux, 0.5, 0.01);
    std::printf("cylinder: kept %.4g lm, backward %.4g, outside image %.4g, outside basis %.4g\n",
                report.keptFlux, report.backwardFlux, report.outsideImageFlux,
                report.outsideBasisFlux);
}

// The converted LED (the 5x5 x 64x64 layout of resources/luminaires/) keeps its flux.
TEST(LightFieldRays, OsramLedKeepsItsFlux) {
    auto t0 = std::chrono::steady_clock::now();
    Tm25RayFile file = readTm25(ledFile());
    Tm25FluxInfo info;
    std::vector<EmittedRay> rays = raysFromTm25(file, true, info);
    LayoutOptions o;
    o.count = {5, 5};
    o.resolution = {64, 64};
    o.what = ledFile();
    LayoutChoice c = chooseLayout(rays, o);
    // The node grid is centred on the local origin, U at the top face z = +0.02 mm.
    EXPECT_NEAR(c.layout.origin.x, -2.0 * c.layout.spacing.x, 1e-15);
    EXPECT_NEAR(c.layout.origin.y, -2.0 * c.layout.spacing.y, 1e-15);
    EXPECT_NEAR(c.frame.uPlaneZ, 0.02e-3, 1e-9);
    ProjectionReport r;
    auto lf = projectRays(rays, c, info.unit, r);
    auto t1 = std::chrono::steady_clock::now();
    EXPECT_EQ(lf->imageCount(), 25);
    EXPECT_EQ(lf->width, 64);
    EXPECT_EQ(lf->unit, "cd/m2");
    // The brief's bounds: kept flux within 2 % of the header's 337 lm (the layout keeps 99.5 % of
    // the forward flux in each box, and 0.06 % goes backwards) ...
    EXPECT_NEAR(r.keptFlux, 337.0, 0.02 * 337.0);
    EXPECT_NEAR(r.keptFlux + r.backwardFlux + r.outsideImageFlux + r.outsideBasisFlux, 337.0,
                337.0 * 1e-6);
    // ... and the light field's own power() within 2 % of the kept flux.
    double power = lf->power().x;
    auto t2 = std::chrono::steady_clock::now();
    EXPECT_NEAR(power, r.keptFlux, 0.02 * r.keptFlux);
    std::printf(
        "LED: kept %.6g lm (%.3f %%), backward %.4g, outside image %.4g, outside basis %.4g, "
        "model %.6g, power() %.6g (%.3f %% of kept); read+project %.3f s, power %.3f s\n",
        r.keptFlux, 100.0 * r.keptFlux / 337.0, r.backwardFlux, r.outsideImageFlux,
        r.outsideBasisFlux, r.modelFlux, power, 100.0 * power / r.keptFlux,
        std::chrono::duration<double>(t1 - t0).count(),
        std::chrono::duration<double>(t2 - t1).count());

    ProjectionReport pr;
    auto perRay = projectRays(rays, c, info.unit, pr, Estimator::PerRay);
    std::printf("LED per-ray estimator: model %.6g lm, power() %.6g (%.3f %% of kept)\n",
                pr.modelFlux, perRay->power().x, 100.0 * perRay->power().x / pr.keptFlux);

    // Saved and loaded back, the images are the same floats.
    fs::path dir = fs::temp_directory_path() / "candela_lightfield_rays_test";
    fs::remove_all(dir);
    fs::create_directories(dir);
    lf->save(dir / "led.lf.json");
    auto back = LightFieldData::load(dir / "led.lf.json");
    ASSERT_EQ(back->imageCount(), 25);
    EXPECT_EQ(back->images[12].luminance, lf->images[12].luminance);
    EXPECT_DOUBLE_EQ(back->delta, lf->delta);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace candela
