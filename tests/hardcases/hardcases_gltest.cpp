// The hard-case grid through the GPU passes (issue 18, part 1): every case of HardCases.cpp times
// every technique with a GLSL variant, through Renderer::probe (what `candela probe --device
// gpu` runs), held to the stated limits of TechniqueLimits.cpp in their float form (gpuPromise).
// A stochastic technique's GPU error is judged against the standard error its C++ twin reports
// at the same sample count: the same estimator, so the same spread.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "luminaires/Registry.h"
#include "renderer/Renderer.h"
#include "renderer/ShaderLibrary.h"
#include "scene/Scene.h"
#include "tests/TestUtil.h"
#include "tests/hardcases/HardCases.h"
#include "tests/hardcases/TechniqueLimits.h"

namespace candela {
namespace {

TEST(HardCasesGl, EveryTechniqueHoldsItsStatedLimitOnTheGpu) {
    test::glContext();
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    // The cases grouped by light, so each technique probes all of a light's receivers at once.
    std::map<const Luminaire*, std::vector<const hard::Case*>> byLight;
    for (const hard::Case& c : hard::cases()) byLight[c.light.get()].push_back(&c);
    int checked = 0;
    for (const auto& [light, group] : byLight) {
        Scene scene;
        scene.luminaires.push_back(light->clone());
        std::vector<glm::vec3> points, normals;
        for (const hard::Case* c : group) {
            points.push_back(glm::vec3(c->p));
            normals.push_back(glm::vec3(c->n));
        }
        for (const TechniqueInfo& t : techniques()) {
            if (t.kind != light->kind() || t.shader.empty() || !t.irradiance) continue;
            RenderSettings s;
            s.width = s.height = 16;
            s.techniqueOverride = std::string(t.name);
            renderer.setSettings(s);
            const int spp = t.progressive ? 16384 : 1;
            std::vector<glm::vec3> gpu = renderer.probe(scene, points, normals, spp);
            for (size_t i = 0; i < group.size(); ++i) {
                const hard::Case& c = *group[i];
                Estimate e;
                e.irradiance = glm::dvec3(gpu[i]);
                if (t.progressive) {
                    EstimateOptions o;
                    o.spp = spp;
                    e.stdError = t.irradiance(*c.light, c.p, c.n, o).stdError;
                }
                std::string why = hard::judge(c, hard::gpuPromise(t, c), e);
                EXPECT_TRUE(why.empty()) << c.name << " [" << hard::className(c.cls) << "], "
                                         << t.name << " on the GPU: " << why;
                ++checked;
            }
        }
    }
    EXPECT_GE(checked, 150);  // the grid did not silently shrink
}

}  // namespace
}  // namespace candela
