// The OSRAM LERTDUW LED converted from its measured TM-25 ray file (resources/luminaires/):
// the flux that `candela probe`'s estimator integrates over a sphere around it, and its far-field
// intensity against a histogram of the ray file's directions (an independent path: the rays
// themselves, not the light field).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "formats/Tm25RayFile.h"
#include "luminaires/lightfield/LightField.h"
#include "shaders/shared/Constants.h"

namespace candela {
namespace {

using gpu::kPi;
constexpr double kHeaderFlux = 337.0;  ///< lm, the ray file's header.
constexpr int kBands = 6;              ///< Polar-angle bands of 15 degrees over the front.

Luminaire osram() {
    auto model = std::make_shared<LightFieldLuminaire>();
    model->data =
        LightFieldData::load(CANDELA_SOURCE_DIR "/resources/luminaires/osram-lertduw.lf.json");
    Luminaire l(model);
    l.pose.position = glm::dvec3(0.0);
    l.pose.aim = {0.0, 0.0, 1.0};  // world = the light field's local frame = the ray file's frame
    l.pose.c0 = {1.0, 0.0, 0.0};
    return l;
}

/// Flux (lm) through each 15-degree polar band of a sphere of radius R around the LED, integrated
/// from the restricted-CDF estimator with the receiver facing the centre: per band, the midpoint
/// rule in z (equal areas, Archimedes: dA = R dz dphi) and in azimuth, so band edges are exact.
std::vector<double> bandFlux(const Luminaire& l, double R, int nzPerBand, int nphi, double& total) {
    std::vector<double> bands(kBands, 0.0);
    total = 0.0;
    EstimateOptions o;
    o.spp = 256;
    for (int b = 0; b < kBands; ++b) {
        double z0 = R * std::cos((b + 1) * kPi / 2.0 / kBands),
               z1 = R * std::cos(b * kPi / 2.0 / kBands);
        double dA = R * ((z1 - z0) / nzPerBand) * (2.0 * kPi / nphi);
        for (int i = 0; i < nzPerBand; ++i) {
            double z = z0 + (i + 0.5) / nzPerBand * (z1 - z0);
            double rho = std::sqrt(R * R - z * z);
            for (int j = 0; j < nphi; ++j) {
                double phi = (j + 0.5) / nphi * 2.0 * kPi;
                glm::dvec3 p(rho * std::cos(phi), rho * std::sin(phi), z);
                o.seed = uint64_t((b * nzPerBand + i) * nphi + j + 1);
                Estimate e = lightFieldRestrictedCdf(l, p, -p / R, o);
                double lum =
                    0.2126 * e.irradiance.x + 0.7152 * e.irradiance.y + 0.0722 * e.irradiance.z;
                bands[size_t(b)] += lum * dA;
            }
        }
        total += bands[size_t(b)];
    }
    return bands;
}

TEST(LightFieldOsram, SphereFluxIsThe337LumenOfTheRayFile) {
    Luminaire l = osram();
    ASSERT_EQ(lightFieldModel(l)->data->unit, "cd/m2");
    double total = 0.0;
    bandFlux(l, 1.0, 16, 96, total);
    // The bound: 2 % of the header's 337 lm. The conversion keeps 334.8 lm (0.7 % goes
    // backwards or misses the images), and the sphere's midpoint rule with 256-spp estimates at
    // 9216 points adds well under 0.5 %. (The band nearest the plane of S, z < delta, is
    // sampled too and receives nothing, as it should.)
    std::printf("sphere flux %.3f lm, power() %.3f lm\n", total,
                0.2126 * l.power().x + 0.7152 * l.power().y + 0.0722 * l.power().z);
    EXPECT_NEAR(total, kHeaderFlux, 0.02 * kHeaderFlux);
    // And it is the model's own flux: quadrature error of power() and of the sphere, 1 %.
    double power = 0.7152 * l.power().y + 0.2126 * l.power().x + 0.0722 * l.power().z;
    EXPECT_NEAR(total, power, 0.01 * power);
}

TEST(LightFieldOsram, FarFieldIntensityMatchesTheRayHistogram) {
    Tm25RayFile rays = readTm25(CANDELA_SOURCE_DIR
                                "/tests/data/nearfield/"
                                "rayfile_LERTDUW_S2WP_green_100k_20161013_IES_TM25.TM25RAY");
    Luminaire l = osram();
    std::vector<double> histogram(kBands, 0.0);
    double rayTotal = 0.0;
    for (const Tm25Ray& r : rays.rays) rayTotal += r.luminousFlux;
    double scale = kHeaderFlux / rayTotal;
    for (const Tm25Ray& r : rays.rays) {
        if (!(r.direction.z > 0.0)) continue;
        int band = std::min(kBands - 1, int(std::acos(r.direction.z) / (kPi / 2.0) * kBands));
        histogram[size_t(band)] += r.luminousFlux * scale;
    }
    double total = 0.0;
    // 3 m: the source (6 cm) subtends 1 degree, so the sphere sees the far field.
    std::vector<double> bands = bandFlux(l, 3.0, 8, 48, total);
    for (int b = 0; b < kBands; ++b) {
        double c0 = std::cos(b * kPi / 2.0 / kBands), c1 = std::cos((b + 1) * kPi / 2.0 / kBands);
        double omega = 2.0 * kPi * (c0 - c1);
        double iRays = histogram[size_t(b)] / omega, iField = bands[size_t(b)] / omega;  // cd
        // The light field reconstructs directions through B-splines (spacing 3 mm over a delta
        // of 4.7 mm) and pixels on S, which blurs the angular distribution, and it drops 0.7 %
        // of the flux (backward rays, grazing rays that miss S, which shows in the last band).
        // Bound: 4 % of the peak (on-axis) intensity; the 100k rays' own noise is ~1 % per band.
        double peak = histogram[0] / (2.0 * kPi * (1.0 - std::cos(kPi / 2.0 / kBands)));
        EXPECT_NEAR(iField, iRays, 0.04 * peak)
            << "band " << b * 15 << "-" << (b + 1) * 15 << " deg";
        std::printf("band %2d-%2d deg: rays %.3f cd, light field %.3f cd\n", b * 15, (b + 1) * 15,
                    iRays, iField);
    }
}

}  // namespace
}  // namespace candela
