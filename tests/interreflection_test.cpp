// Interreflected light (issue 17, part 3): radiosity over patches with Embree form factors,
// against energy balance (closed rooms) and the final gather's consistency.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "TestUtil.h"
#include "luminaires/Units.h"
#include "scene/EmbreeVisibility.h"
#include "scene/Interreflection.h"
#include "scene/SceneIo.h"

namespace candela {
namespace {

/// A closed cube room of edge 2 m (six planes facing in) of uniform albedo rho, with `luminaire`.
Scene cube(double rho, const std::string& luminaire) {
    std::string a = std::to_string(rho);
    std::string alb = R"(, "albedo": [)" + a + "," + a + "," + a + "]}";
    std::string text = R"({"geometry": [
      {"plane": {"center": [0, 0, 0], "normal": [0, 1, 0], "size": [2, 2]})" + alb + R"(,
      {"plane": {"center": [0, 2, 0], "normal": [0, -1, 0], "size": [2, 2]})" + alb + R"(,
      {"plane": {"center": [-1, 1, 0], "normal": [1, 0, 0], "size": [2, 2]})" + alb + R"(,
      {"plane": {"center": [1, 1, 0], "normal": [-1, 0, 0], "size": [2, 2]})" + alb + R"(,
      {"plane": {"center": [0, 1, -1], "normal": [0, 0, 1], "size": [2, 2]})" + alb + R"(,
      {"plane": {"center": [0, 1, 1], "normal": [0, 0, -1], "size": [2, 2]})" + alb + R"(],
      "luminaires": [)" + luminaire + "]}";
    return parseScene(nlohmann::json::parse(text), test::dataDir() + "/cube.json");
}

TEST(Interreflection, IntegratingCubeBalancesEnergy) {
    std::string lamp = R"({"type": "photometric", "name": "Lamp", "file": ")" + test::dataDir() +
                       R"(/photometric/lambert.ies", "position": [0.2, 1.6, 0.1], "technique": "point"})";
    for (double rho : {0.0, 0.2, 0.5, 0.8}) {
        Scene s = cube(rho, lamp);
        double phi = s.luminaires[0]->power().y;
        InterreflectionOptions o;
        o.mesh.targetPatches = 1500;
        auto start = std::chrono::steady_clock::now();
        Interreflection ir(s, o);
        ASSERT_TRUE(ir.compute());
        double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        double area = 0.0, flux = 0.0, direct = 0.0;
        const auto& m = ir.mesh();
        for (size_t i = 0; i < m.patches.size(); ++i) {
            area += m.patches[i].area;
            flux += m.patches[i].area * (ir.direct()[i].y + ir.indirect()[i].y);
            direct += m.patches[i].area * ir.direct()[i].y;
        }
        double want = phi / (area * (1.0 - rho));
        std::printf("rho %.1f: %zu patches, %d iterations, %.2f s; direct flux %.5g of %.5g lm; mean E %.5g lx, "
                    "closed form %.5g lx (%.3f %%)\n",
                    rho, m.patches.size(), ir.lastIterations(), seconds, direct, phi, flux / area, want,
                    100.0 * (flux / area - want) / want);
        EXPECT_NEAR(flux / area, want, 0.01 * want) << rho;
    }
}

}  // namespace
}  // namespace candela
