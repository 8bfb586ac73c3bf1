// Maintenance factors on the GPU (issue 21, part 4): the production shading pass scales each
// luminaire's light by its factor (FramePlan's per-step scale), as the CPU estimators do.
#include <gtest/gtest.h>

#include <string>

#include "renderer/Renderer.h"
#include "renderer/ShaderLibrary.h"
#include "scene/SceneIo.h"
#include "tests/TestUtil.h"

namespace candela {
namespace {

std::vector<glm::vec3> probeFloor(const std::string& factors, const std::string& ownFactor) {
    test::glContext();
    static ShaderLibrary shaders;
    Renderer renderer(shaders);
    std::string text =
        R"({"geometry": [{"plane": {"center": [0,0,0], "normal": [0,1,0], "size": [6,6]}}],)"
        R"( "luminaires": [{"type": "lambertian-rect", "name": "A", "size": [0.2, 0.2],)"
        R"( "radiance": [1000, 1000, 1000], "position": [0.3,3,-0.2], "technique": "analytic")" +
        ownFactor + "}]" + factors + "}";
    Scene scene = parseScene(nlohmann::json::parse(text), "maintenance.json");
    std::vector<glm::vec3> points, normals;
    for (int k = 0; k < 8; ++k) {
        points.push_back(glm::vec3(-1.f + 0.3f * float(k), 0.75f, 0.2f * float(k) - 0.5f));
        normals.push_back(glm::vec3(0.f, 1.f, 0.f));
    }
    return renderer.probe(scene, points, normals, 1);
}

TEST(MaintenanceGl, TheShadingPassScalesEachLuminaireByItsFactor) {
    std::vector<glm::vec3> initial = probeFloor("", "");
    std::vector<glm::vec3> project = probeFloor(R"(, "maintenance_factor": 0.8)", "");
    std::vector<glm::vec3> own =
        probeFloor(R"(, "maintenance_factor": 0.8)", R"(, "maintenance_factor": 0.5)");
    for (size_t k = 0; k < initial.size(); ++k) {
        ASSERT_GT(initial[k].y, 0.f) << k;
        // The analytic technique is deterministic; the same float pass scaled once: 1e-6.
        EXPECT_NEAR(project[k].y, 0.8f * initial[k].y, 1e-6f * initial[k].y) << k;
        EXPECT_NEAR(own[k].y, 0.5f * initial[k].y, 1e-6f * initial[k].y) << k;
    }
}

}  // namespace
}  // namespace candela
