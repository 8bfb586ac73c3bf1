#pragma once
// Per-cell shadow maps of a light-field luminaire (Lu et al. 2015, Sec. 6.2): which maps there
// are, where each one's light sits, and which maps each image C_m averages its visibility over.
// CPU layout only; the GPU pass renders one depth map per entry of `maps`.
//
// Cells: the quadratic B-spline knots cut U into cells of one node spacing, and the support of
// Phi_m (node +- 1.5 spacing) covers n = 3 of them per axis, so W x H images span
// (W + 2) x (H + 2) cells; cell (c, r) is [origin + (c - 1.5) h, origin + (c - 0.5) h] along x
// (h the spacing) and likewise along y. The paper renders one map per cell. A coarser grid of
// maps (the user's count) groups neighbouring cells: map (a, b) of G_x x G_y takes the cells
// c with floor(c G_x / (W + 2)) = a (and likewise rows).
//
// Reference position of a map: the mean of the CDF-median points s_m (on S) of the images whose
// support overlaps one of its cells, over images that carry energy (a dark image's median is
// meaningless and would pull the light towards the image's centre). A map whose images are all
// dark has no light and is skipped (`lit` false).
//
// Per image: each of its n^2 = 9 cells contributes 1/9 of its visibility, through the map that
// holds the cell, so v_m(p) = sum over its maps of weight * visibility of that map (weights sum
// to one; with one map per cell, 9 maps of 1/9 each, the paper's average).

#include <glm/glm.hpp>
#include <vector>

#include "luminaires/lightfield/LightField.h"

namespace candela {

struct ShadowMapLayout {
    glm::ivec2 cells{0};  ///< Cells of U per axis: (W + 2, H + 2).
    glm::ivec2 maps{0};   ///< Maps per axis (G_x, G_y), each at most `cells`.
    struct Map {
        glm::dvec3 light{0.0};  ///< Reference position, luminaire-local metres (on S: z = delta).
        bool lit = false;       ///< Some image with energy overlaps it.
    };
    std::vector<Map> mapList;  ///< G_x * G_y, index b * G_x + a.
    struct Share {
        int map = 0;
        double weight = 0.0;  ///< Cells of the image in that map / 9.
    };
    std::vector<std::vector<Share>> perImage;  ///< One list per image, weights summing to 1.

    int mapCount() const { return maps.x * maps.y; }
};

/// The grid of maps for about `count` maps over `cells` (count <= 0 or at least the cells: one
/// map per cell): G_x G_y as close to count as the grid allows, then G_x / G_y closest to the
/// cells' aspect, each axis at most its cells.
glm::ivec2 shadowMapGrid(glm::ivec2 cells, int count);

/// The layout for `lf` with `maps` maps per axis (0 or more than the cells: one per cell).
/// Needs lf's tables (precompute()) for the medians.
ShadowMapLayout shadowMapLayout(const LightFieldData& lf, glm::ivec2 maps = glm::ivec2(0));

}  // namespace candela
