// IntensitySampler (the photometric reference's third strategy): its directions follow its pdf
// (chi-square), and the pdf is a density over the sphere (integrates to 1).
#include <gtest/gtest.h>

#include <cmath>

#include "formats/Photometry.h"
#include "luminaires/Random.h"
#include "luminaires/photometric/IntensitySampler.h"
#include "shaders/shared/Constants.h"
#include "tests/TestUtil.h"

namespace candela {
namespace {

using gpu::kPi;

/// The files: type C with several C planes, an axial spot, a real asymmetric type C, type B.
const char* const kFiles[] = {
    "/photometric/cplanes.ies",
    "/photometric/spot.ies",
    "/photometry/ies/ies_rescale/Type C - 03.ies",
    "/photometry/ies/ies_rescale/Type B - 01.ies",
};

/// Coordinates in which solid angle is area: (a, phi) with a = -cos(gamma), phi the azimuth
/// about z (type C), or a = sin(V), phi the azimuth about y from +z (type B). Maps a direction
/// to them.
glm::dvec2 coordinates(bool typeC, const glm::dvec3& d) {
    if (typeC) {
        double phi = std::atan2(d.y, d.x);
        return {-d.z, phi < 0.0 ? phi + 2.0 * kPi : phi};
    }
    return {d.y, std::atan2(d.x, d.z) + kPi};  // shifted to [0, 2 pi)
}

glm::dvec3 direction(bool typeC, double a, double phi) {
    double s = std::sqrt(std::max(0.0, 1.0 - a * a));
    if (typeC) return {s * std::cos(phi), s * std::sin(phi), -a};
    phi -= kPi;
    return {s * std::sin(phi), a, s * std::cos(phi)};
}

TEST(IntensitySampler, DirectionsFollowThePdf) {
    for (const char* name : kFiles) {
        std::string path = std::string(CANDELA_TEST_DATA) + name;
        PhotometricData data = loadPhotometry(path);
        IntensitySampler sampler(data);
        ASSERT_TRUE(sampler.valid()) << path;
        const bool typeC = data.goniometer == Goniometer::C;
        // Bins unrelated to the table's cells: 13 in a, 17 in phi over the whole sphere. The pdf
        // is constant on each cell of the table, a rectangle in (a, phi), so a bin's expected
        // share is exact: the sum over cells of the pdf (read at the cell's centre) times the
        // cell's overlap with the bin.
        const int na = 13, np = 17, samples = 200000;
        std::vector<double> expected(size_t(na * np), 0.0), observed(size_t(na * np), 0.0);
        auto cellA = [&](double angleDeg) {
            double r = angleDeg * kPi / 180.0;
            return typeC ? -std::cos(r) : std::sin(r);
        };
        auto cellPhi = [&](double angleDeg) {
            return angleDeg * kPi / 180.0 + (typeC ? 0.0 : kPi);
        };
        double total = 0.0;
        for (size_t h = 0; h + 1 < data.horizontal.size(); ++h)
            for (size_t v = 0; v + 1 < data.vertical.size(); ++v) {
                double a0 = cellA(data.vertical[v]), a1 = cellA(data.vertical[v + 1]);
                double p0 = cellPhi(data.horizontal[h]), p1 = cellPhi(data.horizontal[h + 1]);
                double density = sampler.pdf(direction(typeC, 0.5 * (a0 + a1), 0.5 * (p0 + p1)));
                total += density * (a1 - a0) * (p1 - p0);
                for (int i = 0; i < na; ++i) {
                    double b0 = -1.0 + 2.0 * i / na, b1 = -1.0 + 2.0 * (i + 1) / na;
                    double da = std::min(a1, b1) - std::max(a0, b0);
                    if (!(da > 0.0)) continue;
                    for (int j = 0; j < np; ++j) {
                        double c0 = 2.0 * kPi * j / np, c1 = 2.0 * kPi * (j + 1) / np;
                        double dp = std::min(p1, c1) - std::max(p0, c0);
                        if (dp > 0.0) expected[size_t(i * np + j)] += density * da * dp;
                    }
                }
            }
        // The pdf is a density over the sphere: exactly 1 up to rounding.
        EXPECT_NEAR(total, 1.0, 1e-9) << path;
        for (double& e : expected) e *= samples / total;
        Random rng(7);
        for (int k = 0; k < samples; ++k) {
            double pick = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
            glm::dvec3 d = sampler.sample(pick, glm::dvec2(u1, u2));
            ASSERT_NEAR(glm::length(d), 1.0, 1e-9);
            glm::dvec2 c = coordinates(typeC, d);
            int i = std::clamp(int((c.x + 1.0) / 2.0 * na), 0, na - 1);
            int j = std::clamp(int(c.y / (2.0 * kPi) * np), 0, np - 1);
            observed[size_t(i * np + j)] += 1.0;
            // Where it samples, the pdf is positive (a zero there would bias the reference).
            ASSERT_GT(sampler.pdf(d), 0.0) << path << " sample " << k;
        }
        test::ChiSquareResult chi = test::chiSquare(observed, expected);
        // 1e-3: one chance in a thousand of a false alarm per file at these fixed seeds.
        EXPECT_GT(chi.pValue, 1e-3)
            << path << ": chi2 " << chi.statistic << " dof " << chi.degreesOfFreedom;
    }
}

TEST(IntensitySampler, ATableOfZerosCannotBeSampled) {
    PhotometricData data;
    data.vertical = {0, 90, 180};
    data.horizontal = {0, 360};
    data.candela.assign(6, 0.0);
    EXPECT_FALSE(IntensitySampler(data).valid());
    EXPECT_EQ(IntensitySampler(data).pdf({0, 0, -1}), 0.0);
}

}  // namespace
}  // namespace candela
