// The far field of a light field (luminaires/lightfield/FarField.h), the editor's stand-in while
// dragging: against the light field's own flux (its U x S quadrature) and against the exact model's
// irradiance far away (lightFieldReference, Gauss-Legendre over U: another code path), where
// E R^2 -> I(w), in directions that tell the photometric frame's y from the light field's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "luminaires/lightfield/FarField.h"
#include "luminaires/lightfield/LightField.h"
#include "shaders/shared/Constants.h"

namespace candela {
namespace {

using gpu::kPi;

double luminance(const glm::dvec3& c) {
    return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

/// A placed light field of the given data.
Luminaire placedLightField(std::shared_ptr<const LightFieldData> data) {
    auto model = std::make_shared<LightFieldLuminaire>();
    model->data = std::move(data);
    return Luminaire(model);
}

Luminaire osram(const glm::dvec3& aim, const glm::dvec3& c0) {
    Luminaire l = placedLightField(
        LightFieldData::load(CANDELA_SOURCE_DIR "/resources/luminaires/osram-lertduw.lf.json"));
    l.name = "LED";
    l.pose.position = glm::dvec3(0.3, 2.0, -0.4);
    l.pose.aim = aim;
    l.pose.c0 = c0;
    return l;
}

/// The LED with only the +x +y quadrant of S left lit in every image: its beam leans towards
/// +x +y, so a flipped frame shows.
Luminaire quadrantLed(const glm::dvec3& aim, const glm::dvec3& c0) {
    Luminaire l = osram(aim, c0);
    const LightFieldData& src = *lightFieldModel(l)->data;
    auto data = std::make_shared<LightFieldData>();
    data->model = src.model;
    data->delta = src.delta;
    data->count = src.count;
    data->spacing = src.spacing;
    data->origin = src.origin;
    data->imageMin = src.imageMin;
    data->imageMax = src.imageMax;
    data->width = src.width;
    data->height = src.height;
    data->rgb = src.rgb;
    data->unit = src.unit;
    data->images = src.images;
    glm::dvec2 pixel = data->pixelSize();
    for (auto& image : data->images)
        for (int j = 0; j < data->height; ++j)
            for (int i = 0; i < data->width; ++i) {
                glm::dvec2 s = data->imageMin + (glm::dvec2(i, j) + 0.5) * pixel;
                if (s.x < 0.0 || s.y < 0.0) image.luminance[size_t(j * data->width + i)] = 0.f;
            }
    data->precompute();
    Luminaire out = placedLightField(data);
    out.name = l.name;
    out.pose = l.pose;
    return out;
}

TEST(FarField, FluxIsTheLightFieldsFlux) {
    Luminaire l = osram({0.0, -1.0, 0.0}, {1.0, 0.0, 0.0});
    auto twin = farFieldTwin(l);
    ASSERT_NE(twin, nullptr);
    double lf = luminance(lightFieldModel(l)->data->cachedPower());
    double ff = luminance(twin->power());
    // The table sums pixel centres over S (every pixel of the 64 x 64 images), interpolated
    // bilinearly between
    // directions 2.5 x 5 degrees apart; the light field's flux is its own U x S quadrature.
    // Measured 0.3 %; 2 % leaves room for the interpolation over the beam's edge.
    EXPECT_NEAR(ff / lf, 1.0, 0.02) << "far field " << ff << " lm, light field " << lf << " lm";
}

TEST(FarField, IntensityMatchesTheExactModelFarAway) {
    const glm::dvec3 aim = glm::normalize(glm::dvec3(0.3, -1.0, 0.2)), c0(0.0, 0.0, 1.0);
    Luminaire l = quadrantLed(aim, c0);
    auto twin = farFieldTwin(l);
    ASSERT_NE(twin, nullptr);
    ASSERT_NE(photometricModel(*twin), nullptr);
    const PhotometricLuminaire& farField = *photometricModel(*twin);
    glm::dvec3 x, y, z;
    l.pose.frame(x, y, z);
    const double R = 20.0;  // metres: 300 times the image's extent, so E R^2 = I(w) to 1e-5
    EstimateOptions o;
    double peak = 0.0;
    struct Probe {
        double gamma, azimuth, reference, twin;
    };
    std::vector<Probe> probes;
    for (double gamma : {0.0, 20.0, 40.0, 60.0})
        for (double azimuth : {45.0, 135.0, 225.0, 315.0}) {
            double g = gamma * kPi / 180.0, a = azimuth * kPi / 180.0;
            // Azimuth in the light field's own frame (from x towards its y = aim x c0).
            glm::dvec3 w =
                std::sin(g) * std::cos(a) * x + std::sin(g) * std::sin(a) * y + std::cos(g) * z;
            glm::dvec3 p = l.pose.position + R * w;
            double e = luminance(lightFieldReference(l, p, -w, o).irradiance);
            probes.push_back({gamma, azimuth, e * R * R, farField.intensity(twin->pose, w)});
            peak = std::max(peak, e * R * R);
        }
    ASSERT_GT(peak, 0.0);
    double asymmetry = 0.0;
    for (const Probe& p : probes) {
        // Bilinear between table directions 2.5 x 5 degrees apart: within 3 % of the peak
        // intensity (measured under 1 %).
        EXPECT_NEAR(p.twin, p.reference, 0.03 * peak)
            << "gamma " << p.gamma << " azimuth " << p.azimuth << ": far field " << p.twin
            << " cd, exact " << p.reference << " cd";
    }
    // Azimuths 45 and 315, 135 and 225 (probes 0 and 3, 1 and 2 of each gamma) mirror in y.
    for (size_t g = 0; g < probes.size(); g += 4)
        asymmetry = std::max({asymmetry, std::abs(probes[g].reference - probes[g + 3].reference),
                              std::abs(probes[g + 1].reference - probes[g + 2].reference)});
    // The probes must tell the frames apart: the beam differs by far more than the tolerance
    // between azimuths mirrored in the light field's y.
    EXPECT_GT(asymmetry, 0.1 * peak);
}

}  // namespace
}  // namespace candela

namespace candela {
namespace {

TEST(FarField, FootprintIsBrightestUnderADownlightAndFollowsItsC0) {
    // A table lit only around gamma 30 deg in the C0 half-plane (C = 0): the bright spot of the
    // floor image lies towards +x (C0), right of the centre, at tan(30) of the height.
    PhotometricData d;
    d.goniometer = Goniometer::C;
    d.vertical = {0.0, 20.0, 30.0, 40.0, 180.0};
    d.horizontal = {0.0, 20.0, 340.0, 360.0};
    d.candela.assign(d.vertical.size() * d.horizontal.size(), 0.0);
    for (size_t h : {size_t(0), size_t(3)}) d.candela[h * d.vertical.size() + 2] = 1000.0;
    const int n = 101;
    std::vector<unsigned char> img = footprintImage(d, n, 1.0);
    ASSERT_EQ(img.size(), size_t(n * n * 3));
    int best = 0;
    for (int k = 1; k < n * n; ++k)
        if (img[3 * size_t(k)] + img[3 * size_t(k) + 1] + img[3 * size_t(k) + 2] >
            img[3 * size_t(best)] + img[3 * size_t(best) + 1] + img[3 * size_t(best) + 2])
            best = k;
    int row = best / n, col = best % n;
    // Pixel centres span +-2.5 m in 101 pixels: tan(30 deg) = 0.577 m is 11.5 pixels right.
    EXPECT_NEAR(col - n / 2, 11.5, 1.5);
    EXPECT_NEAR(row - n / 2, 0.0, 1.5);
    std::vector<unsigned char> dark = footprintImage(PhotometricData{}, 8);
    for (unsigned char c : dark) EXPECT_EQ(c, 0);  // no light: black, no NaN
}

}  // namespace
}  // namespace candela
