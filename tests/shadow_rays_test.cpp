// Shadow rays where the light is: a design calculation gives each luminaire's exact technique
// shadow rays in proportion to its unshadowed light at the point (shadowRays), so thousands of
// luminaires cost a few rays each where they add little.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "TestUtil.h"
#include "calculation/CalculationGrid.h"
#include "luminaires/Registry.h"
#include "scene/EmbreeVisibility.h"
#include "scene/SceneIo.h"

namespace candela {
namespace {

TEST(ShadowRays, FollowEachLuminairesShareOfTheLight) {
    EXPECT_EQ(shadowRays(1024, 3.0, 3.0), 1024);  // the brightest: every ray
    EXPECT_EQ(shadowRays(1024, 1.0, 2.0), 512);
    EXPECT_EQ(shadowRays(1024, 1.0, 3.0), 342);  // rounded up
    EXPECT_EQ(shadowRays(1024, 1e-9, 1.0), kMinShadowRays);
    EXPECT_EQ(shadowRays(1024, 0.0, 1.0), kMinShadowRays);
    EXPECT_EQ(shadowRays(1024, 1.0, 0.0), kMinShadowRays);  // nothing lit: a few to be sure
    EXPECT_EQ(shadowRays(1024, 5.0, 1.0), 1024);            // never more than asked for
    EXPECT_EQ(shadowRays(4, 1e-9, 1.0), 4);                 // nor more than spp to the faintest
}

// 60 luminaires over a floor, a thin beam between them and the points: the points under the
// beam's penumbra see each luminaire partly. The sum with rays shared by light must agree with
// every luminaire traced at the full count (each luminaire's technique called alone here, its
// own EmbreeVisibility), within their combined standard errors.
TEST(ShadowRays, ManyLuminairesKeepTheirShadowsWithinTheStandardError) {
    std::string luminaires;
    for (int i = 0; i < 60; ++i) {
        double x = -5.0 + (i % 10), z = -2.5 + (i / 10);
        if (!luminaires.empty()) luminaires += ",";
        luminaires += R"({"type": "photometric", "file": ")" + test::dataDir() +
                      R"(/photometric/lambert.ies", "position": [)" + std::to_string(x) + ", 3, " +
                      std::to_string(z) + "]}";
    }
    std::string text = R"({"geometry": [
        {"plane": {"center": [0,0,0], "normal": [0,1,0], "size": [20,20]}},
        {"box": {"center": [0, 1.5, 0.3], "size": [12, 0.05, 0.08]}}],
        "luminaires": [)" +
                       luminaires + "]}";
    Scene scene = parseScene(nlohmann::json::parse(text), test::dataDir() + "/shadow_rays.json");
    GridSpec how;
    how.visibility = true;
    how.spp = 256;
    std::vector<Receiver> receivers;
    for (int i = 0; i < 7; ++i) receivers.push_back({{0.5, 0.0, 0.1 + 0.05 * i}, {0, 1, 0}});
    ReceiverResult shared = computeReceivers(scene, how, receivers);

    EmbreeVisibility visibility(scene);
    int penumbra = 0;  // points where some luminaire is partly hidden
    for (size_t i = 0; i < receivers.size(); ++i) {
        double full = 0.0, variance = 0.0;
        for (size_t k = 0; k < scene.luminaires.size(); ++k) {
            const Luminaire& l = *scene.luminaires[k];
            EstimateOptions o;
            o.spp = how.spp;
            o.seed = 99991ull * i + k;
            o.visibility = &visibility;
            Estimate e = findTechnique(l.kind(), l.technique)
                             ->irradiance(l, receivers[i].position, receivers[i].normal, o);
            double scale = scene.lightScale(l);
            full += scale * e.irradiance.y;
            variance += scale * scale * e.stdError.y * e.stdError.y;
        }
        double both = std::sqrt(variance + shared.directStdError[i] * shared.directStdError[i]);
        SCOPED_TRACE("point " + std::to_string(i) + ": shared " + std::to_string(shared.direct[i]) +
                     " lx +- " + std::to_string(shared.directStdError[i]) + ", full " +
                     std::to_string(full) + " lx +- " + std::to_string(std::sqrt(variance)));
        if (both > 0.0) ++penumbra;
        // Four combined standard errors: 7 points, a false alarm about once in 2000 runs (the
        // seeds are fixed, so a run that passes always passes); 1e-12 of the light for the
        // rounding of two sums in different orders where nothing is in shadow.
        EXPECT_NEAR(shared.direct[i], full, 4.0 * both + 1e-12 * full);
        // The rays saved cost precision only where the light is small: the shared sum's
        // standard error stays within twice the full count's (measured: 1.19 to 1.22 times).
        EXPECT_LE(shared.directStdError[i], 2.0 * std::sqrt(variance));
    }
    // The beam's penumbra crosses most points: there is a shadow to get wrong.
    EXPECT_GE(penumbra, 4);
}

}  // namespace
}  // namespace candela
