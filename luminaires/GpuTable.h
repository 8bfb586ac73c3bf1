#pragma once
// Tables a luminaire's shaders read from textures (issue 20, part 2), apart from its std430
// record: large, and unchanged while the luminaire moves, so the renderer uploads them once per
// model (LuminairePass keeps them while the same GpuTables object comes back). No GL here.

#include <memory>
#include <vector>

namespace candela {

/// One 2D array texture: `layers` images of width x height texels of `channels` floats (1, 2 or
/// 4), layer-major, then rows, then texels. Bound at texture unit `unit` (shaders/shared/
/// GpuTypes.h kUnit*) and read with texelFetch, never filtered: the models interpolate in their
/// own coordinates, and GL's filtering weights carry 8 bits at most.
struct GpuTable {
    int unit = 0, channels = 1, width = 0, height = 0, layers = 1;
    bool half = false;  ///< stored as 16-bit floats (values exact in half already)
    std::vector<float> texels;
};

using GpuTables = std::vector<GpuTable>;

}  // namespace candela
