// The per-cell shadow-map layout of a light field (Lu et al. 2015, Sec. 6.2), against geometry:
// which cells of U each basis function's support covers, found by interval overlap rather than
// by the layout's index arithmetic.
#include <gtest/gtest.h>

#include <random>

#include "luminaires/lightfield/ShadowCells.h"

namespace candela {
namespace {

/// A light field with random images; image `dark` (if >= 0) is all zero.
std::shared_ptr<LightFieldData> field(glm::ivec2 count, int dark, uint32_t seed) {
    auto lf = std::make_shared<LightFieldData>();
    lf->count = count;
    lf->spacing = {0.02, 0.025};
    lf->origin = {-0.03, 0.01};
    lf->delta = 0.04;
    lf->imageMin = {-0.08, -0.07};
    lf->imageMax = {0.09, 0.1};
    lf->width = lf->height = 12;
    lf->images.resize(size_t(count.x * count.y));
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    for (int m = 0; m < count.x * count.y; ++m) {
        lf->images[size_t(m)].luminance.resize(144);
        for (float& v : lf->images[size_t(m)].luminance)
            v = m == dark ? 0.f : (u(rng) < 0.7f ? 0.f : u(rng) * u(rng));
    }
    lf->validate("test");
    lf->precompute();
    return lf;
}

/// Does Phi_m's support overlap cell (cx, cy) of U in an interval of positive length?
bool overlaps(const LightFieldData& lf, int m, int cx, int cy) {
    glm::dvec2 lo, hi;
    lf.support(m, lo, hi);
    glm::dvec2 cellLo = lf.origin + (glm::dvec2(cx, cy) - 1.5) * lf.spacing;
    glm::dvec2 cellHi = cellLo + lf.spacing;
    double eps = 1e-9;
    return std::min(hi.x, cellHi.x) - std::max(lo.x, cellLo.x) > eps &&
           std::min(hi.y, cellHi.y) - std::max(lo.y, cellLo.y) > eps;
}

void checkLayout(const LightFieldData& lf, glm::ivec2 maps) {
    ShadowMapLayout layout = shadowMapLayout(lf, maps);
    glm::ivec2 cells = lf.count + 2;
    ASSERT_EQ(layout.cells, cells);
    glm::ivec2 expectMaps = glm::ivec2(maps.x <= 0 ? cells.x : std::min(maps.x, cells.x),
                                       maps.y <= 0 ? cells.y : std::min(maps.y, cells.y));
    ASSERT_EQ(layout.maps, expectMaps);
    ASSERT_EQ(int(layout.mapList.size()), expectMaps.x * expectMaps.y);
    ASSERT_EQ(int(layout.perImage.size()), lf.imageCount());
    auto mapOf = [&](int cx, int cy) {
        return (cy * expectMaps.y / cells.y) * expectMaps.x + cx * expectMaps.x / cells.x;
    };
    // Cells of U run beyond the supports' union by nothing: every cell meets some support.
    std::vector<glm::dvec2> sum(layout.mapList.size(), glm::dvec2(0.0));
    std::vector<std::vector<bool>> member(layout.mapList.size(),
                                          std::vector<bool>(size_t(lf.imageCount()), false));
    for (int m = 0; m < lf.imageCount(); ++m) {
        std::vector<double> weight(layout.mapList.size(), 0.0);
        int covered = 0;
        for (int cy = 0; cy < cells.y; ++cy)
            for (int cx = 0; cx < cells.x; ++cx)
                if (overlaps(lf, m, cx, cy)) {
                    ++covered;
                    weight[size_t(mapOf(cx, cy))] += 1.0 / 9.0;
                    member[size_t(mapOf(cx, cy))][size_t(m)] = true;
                }
        EXPECT_EQ(covered, 9) << "image " << m << ": a quadratic B-spline covers 3 x 3 cells";
        double total = 0.0;
        for (const ShadowMapLayout::Share& s : layout.perImage[size_t(m)]) {
            EXPECT_NEAR(s.weight, weight[size_t(s.map)], 1e-12)
                << "image " << m << " map " << s.map;
            total += s.weight;
            weight[size_t(s.map)] = 0.0;
        }
        EXPECT_NEAR(total, 1.0, 1e-12);
        for (double w : weight) EXPECT_EQ(w, 0.0) << "image " << m << " misses a map it covers";
    }
    for (size_t k = 0; k < layout.mapList.size(); ++k) {
        glm::dvec2 mean(0.0);
        int lit = 0;
        for (int m = 0; m < lf.imageCount(); ++m)
            if (member[k][size_t(m)] && lf.tables[size_t(m)].total > 0.0)
                mean += lf.tables[size_t(m)].median, ++lit;
        EXPECT_EQ(layout.mapList[k].lit, lit > 0) << "map " << k;
        if (lit == 0) continue;
        mean /= double(lit);
        EXPECT_NEAR(layout.mapList[k].light.x, mean.x, 1e-12) << "map " << k;
        EXPECT_NEAR(layout.mapList[k].light.y, mean.y, 1e-12) << "map " << k;
        EXPECT_EQ(layout.mapList[k].light.z, lf.delta) << "the light sits on S";
    }
}

TEST(ShadowCells, OneMapPerCellAsInThePaper) {
    // 5 x 5 images: 49 maps, the paper's first configuration; 6 x 8: its 80.
    EXPECT_EQ(shadowMapLayout(*field({5, 5}, -1, 1)).mapCount(), 49);
    EXPECT_EQ(shadowMapLayout(*field({6, 8}, -1, 2)).mapCount(), 80);
    checkLayout(*field({5, 4}, -1, 3), {0, 0});
    // With one map per cell every image averages 9 maps of 1/9 each.
    ShadowMapLayout layout = shadowMapLayout(*field({5, 4}, -1, 3));
    for (const auto& shares : layout.perImage) {
        ASSERT_EQ(shares.size(), 9u);
        for (const auto& s : shares) EXPECT_DOUBLE_EQ(s.weight, 1.0 / 9.0);
    }
}

TEST(ShadowCells, FewerMapsGroupCells) {
    auto lf = field({11, 9}, -1, 4);  // the car headlight's grid: 13 x 11 cells
    checkLayout(*lf, {7, 7});
    checkLayout(*lf, {4, 3});
    checkLayout(*lf, {1, 1});  // one map: every weight collapses onto it
    ShadowMapLayout one = shadowMapLayout(*lf, {1, 1});
    for (const auto& shares : one.perImage) {
        ASSERT_EQ(shares.size(), 1u);
        EXPECT_NEAR(shares[0].weight, 1.0, 1e-12);
    }
    checkLayout(*lf, {100, 2});  // more than the cells along x: one per cell there
}

TEST(ShadowCells, DarkImagesDoNotPullTheLight) {
    // Image 0 (a corner) is black: the corner cell that only it covers has no light, and the
    // maps it shares with others take the mean of the others' medians (checkLayout).
    auto lf = field({4, 4}, 0, 5);
    checkLayout(*lf, {0, 0});
    ShadowMapLayout layout = shadowMapLayout(*lf);
    EXPECT_FALSE(layout.mapList[0].lit) << "cell (0, 0) lies only under image 0's support";
    EXPECT_TRUE(layout.mapList[1].lit);
}

}  // namespace
}  // namespace candela
