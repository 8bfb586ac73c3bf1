#pragma once
// Directions drawn in proportion to a photometric table's intensity: the third strategy of the
// photometric reference (PhotometricEstimators.cpp), so that a peak that covers a thousandth of
// the opening seen from the receiver (a 1e9 cd spike 0.5 degrees wide) is sampled as often as
// the light it carries, rather than missed by area and cosine samples whose variance then hides
// the miss.
//
// The density is piecewise constant over the table's own cells (vertical x horizontal angle),
// each weighted by the largest of its four corners times its solid angle, and uniform in solid
// angle within a cell. It only has to be positive wherever the table is and cheap to evaluate;
// the balance heuristic keeps the reference unbiased for any such density.

#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "formats/Photometry.h"

namespace candela {

class IntensitySampler {
  public:
    explicit IntensitySampler(const PhotometricData& data);

    /// The shared sampler of a table (built once per table, kept while the table lives).
    static std::shared_ptr<const IntensitySampler> of(
        const std::shared_ptr<const PhotometricData>& data);

    /// Whether any cell has intensity (a table of zeros cannot be sampled).
    bool valid() const { return mTotal > 0.0; }
    /// A unit direction in the table's local frame for u in [0, 1)^2 (and one more uniform to
    /// pick the cell).
    glm::dvec3 sample(double pick, const glm::dvec2& u) const;
    /// Its density per steradian at the unit local direction d.
    double pdf(const glm::dvec3& d) const;
    /// The cells' cumulative probabilities, from 0 to 1: cell h (nv - 1) + v (v along the
    /// vertical angles) for the GPU twin (shaders/photometric.glsl).
    std::vector<double> normalisedCdf() const;

  private:
    /// The cell (v, h) holding d, or false outside the table's range.
    bool locate(const glm::dvec3& d, size_t& v, size_t& h) const;

    bool mTypeC = true;            ///< Polar axis z (type C), else type B (latitude about y).
    std::vector<double> mV, mH;    ///< Cell edges, radians.
    std::vector<double> mCdf;      ///< Cumulative cell weights, (nv-1)(nh-1) + 1 entries.
    std::vector<double> mDensity;  ///< Weight / (total x solid angle) per cell.
    double mTotal = 0.0;
};

}  // namespace candela
