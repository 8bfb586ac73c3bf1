#include "luminaires/lightfield/ShadowCells.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace candela {

glm::ivec2 shadowMapGrid(glm::ivec2 cells, int count) {
    if (count <= 0 || count >= cells.x * cells.y) return cells;
    glm::ivec2 best = cells;
    int bestMiss = 1 << 30;
    double bestAspect = 1e300;
    double aspect = double(cells.x) / double(cells.y);
    for (int gx = 1; gx <= cells.x; ++gx) {
        int gy = std::clamp(int(std::lround(double(count) / gx)), 1, cells.y);
        int miss = std::abs(gx * gy - count);
        double skew = std::abs(std::log(double(gx) / gy / aspect));
        if (miss < bestMiss || (miss == bestMiss && skew < bestAspect)) {
            best = {gx, gy};
            bestMiss = miss;
            bestAspect = skew;
        }
    }
    return best;
}

ShadowMapLayout shadowMapLayout(const LightFieldData& lf, glm::ivec2 maps) {
    ShadowMapLayout layout;
    const int n = 3;  // cells per axis under one quadratic B-spline
    layout.cells = lf.count + (n - 1);
    for (int k = 0; k < 2; ++k)
        layout.maps[k] = maps[k] <= 0 ? layout.cells[k] : std::min(maps[k], layout.cells[k]);
    auto mapOf = [&](int cx, int cy) {
        int a = cx * layout.maps.x / layout.cells.x, b = cy * layout.maps.y / layout.cells.y;
        return b * layout.maps.x + a;
    };

    std::vector<glm::dvec2> sum(size_t(layout.mapCount()), glm::dvec2(0.0));
    std::vector<int> images(size_t(layout.mapCount()), 0);
    layout.perImage.resize(size_t(lf.imageCount()));
    for (int m = 0; m < lf.imageCount(); ++m) {
        int i = m % lf.count.x, j = m / lf.count.x;
        const LightFieldTables& t = lf.tables.at(size_t(m));
        bool energy = t.total > 0.0;
        std::vector<ShadowMapLayout::Share>& shares = layout.perImage[size_t(m)];
        std::vector<int> seen;  // maps this image already added its median to
        // Node i's support covers cells i, i + 1, i + 2 (see the header).
        for (int b = 0; b < n; ++b)
            for (int a = 0; a < n; ++a) {
                int map = mapOf(i + a, j + b);
                auto it = std::find_if(shares.begin(), shares.end(),
                                       [&](const auto& s) { return s.map == map; });
                if (it == shares.end()) shares.push_back({map, 0.0}), it = shares.end() - 1;
                it->weight += 1.0 / double(n * n);
                if (energy && std::find(seen.begin(), seen.end(), map) == seen.end()) {
                    seen.push_back(map);
                    sum[size_t(map)] += t.median;
                    ++images[size_t(map)];
                }
            }
    }
    layout.mapList.resize(size_t(layout.mapCount()));
    for (int k = 0; k < layout.mapCount(); ++k) {
        ShadowMapLayout::Map& map = layout.mapList[size_t(k)];
        map.lit = images[size_t(k)] > 0;
        glm::dvec2 s = map.lit ? sum[size_t(k)] / double(images[size_t(k)])
                               : 0.5 * (lf.imageMin + lf.imageMax);
        map.light = glm::dvec3(s, lf.delta);
    }
    return layout;
}

}  // namespace candela
