// Tests of the Lambertian rectangle's geometry and record: its frame, outline and one-sided
// radiance, the GPU record, its description and its JSON fields (the estimators, power and
// sampler are tested in lambertian_rect_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "luminaires/lambertian/LambertianRect.h"
#include "shaders/shared/GpuTypes.h"
#include "tests/LambertianRectFixture.h"
#include "util/Error.h"

namespace candela {
namespace {

using test::Frame;
using test::frameOf;
using test::makeLight;
using test::toWorld;

// ---------------------------------------------------------------------------------------------
// Frame, outline, radiance, serialisation.

void expectFrame(const Pose& pose) {
    glm::dvec3 x, y, z;
    pose.frame(x, y, z);
    SCOPED_TRACE(testing::Message()
                 << "aim " << pose.aim.x << "," << pose.aim.y << "," << pose.aim.z << " c0 "
                 << pose.c0.x << "," << pose.c0.y << "," << pose.c0.z);
    // Orthonormal and right-handed to a few roundings.
    const double tol = 1e-14;
    EXPECT_NEAR(glm::length(x), 1.0, tol);
    EXPECT_NEAR(glm::length(y), 1.0, tol);
    EXPECT_NEAR(glm::length(z), 1.0, tol);
    EXPECT_NEAR(glm::dot(x, y), 0.0, tol);
    EXPECT_NEAR(glm::dot(y, z), 0.0, tol);
    EXPECT_NEAR(glm::dot(z, x), 0.0, tol);
    EXPECT_NEAR(glm::length(glm::cross(x, y) - z), 0.0, tol);
    double la = glm::length(pose.aim);
    if (la > 0.0 && std::isfinite(la)) {
        EXPECT_NEAR(glm::length(z - pose.aim / la), 0.0, tol);
    }
    // When c0 is clearly not parallel to aim, x is c0's part orthogonal to aim.
    double lc = glm::length(pose.c0);
    if (la > 0.0 && lc > 0.0 && std::isfinite(la * lc) &&
        glm::length(glm::cross(pose.aim / la, pose.c0 / lc)) > 1e-6) {
        glm::dvec3 c = pose.c0 - glm::dot(pose.c0, z) * z;
        EXPECT_NEAR(glm::length(x - c / glm::length(c)), 0.0, 1e-9);
    }
}

TEST(Pose, FrameIsOrthonormalAndRightHanded) {
    std::mt19937_64 rng(17);
    std::normal_distribution<double> normal(0.0, 1.0);
    for (int k = 0; k < 1000; ++k) {
        Pose pose;
        pose.aim = {normal(rng), normal(rng), normal(rng)};
        pose.c0 = {normal(rng), normal(rng), normal(rng)};
        expectFrame(pose);
        double scale = normal(rng);
        pose.c0 = scale * pose.aim;  // parallel or antiparallel
        expectFrame(pose);
        pose.c0 = pose.aim + glm::dvec3(1e-12, -1e-12, 0.0);  // nearly parallel
        expectFrame(pose);
    }
    for (glm::dvec3 aim :
         {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, -1), glm::dvec3(1e-200, 0, 0),
          glm::dvec3(1e200, 1e200, 0), glm::dvec3(0.0), glm::dvec3(std::nan(""), 0, 0)}) {
        Pose pose;
        pose.aim = aim;
        for (glm::dvec3 c0 : {aim, glm::dvec3(1, 0, 0), glm::dvec3(0, 0, 1), glm::dvec3(0.0),
                              glm::dvec3(1e300, 0, 0)}) {
            pose.c0 = c0;
            expectFrame(pose);
        }
    }
    // The default pose: aim down, c0 along +x, so y = aim x c0 = +z.
    glm::dvec3 x, y, z;
    Pose().frame(x, y, z);
    EXPECT_EQ(x, glm::dvec3(1.0, 0.0, 0.0));
    EXPECT_EQ(y, glm::dvec3(0.0, 0.0, 1.0));
    EXPECT_EQ(z, glm::dvec3(0.0, -1.0, 0.0));
}

TEST(LambertianRect, OutlineIsCounterClockwiseFromTheEmittingSide) {
    Luminaire light = makeLight();
    std::vector<glm::dvec3> c = light.outline();
    ASSERT_EQ(c.size(), 4u);
    Frame f = frameOf(light.pose);
    for (int i = 0; i < 4; ++i) {
        glm::dvec3 e0 = c[size_t((i + 1) % 4)] - c[size_t(i)];
        glm::dvec3 e1 = c[size_t((i + 2) % 4)] - c[size_t((i + 1) % 4)];
        EXPECT_NEAR(glm::dot(glm::cross(e0, e1), f.z), 1.2 * 0.6, 1e-12);
    }
    EXPECT_NEAR(glm::length(c[1] - c[0]), 1.2, 1e-12);
    EXPECT_NEAR(glm::length(c[3] - c[0]), 0.6, 1e-12);
    EXPECT_NEAR(glm::length(0.25 * (c[0] + c[1] + c[2] + c[3]) - light.pose.position), 0.0, 1e-12);
    EXPECT_GT(glm::dot(c[1] - c[0], f.x), 0.0);
}

TEST(LambertianRect, RadianceIsEmittedOnlyFromTheFrontOfTheSurface) {
    Luminaire light = makeLight();
    const LambertianRect& model = *lambertianRectModel(light);
    Frame f = frameOf(light.pose);
    glm::dvec3 x = toWorld(light, {0.5, -0.25, 0.0});
    EXPECT_EQ(light.radiance(x, f.z), model.emitted);
    EXPECT_EQ(light.radiance(x, glm::normalize(f.z + 10.0 * f.x)), model.emitted);
    EXPECT_EQ(light.radiance(x, -f.z), glm::dvec3(0.0));
    EXPECT_EQ(light.radiance(x, glm::normalize(f.x - 1e-9 * f.z)), glm::dvec3(0.0));
    EXPECT_EQ(light.radiance(toWorld(light, {0.7, 0.0, 0.0}), f.z), glm::dvec3(0.0));
    EXPECT_EQ(light.radiance(toWorld(light, {0.0, 0.0, 0.01}), f.z), glm::dvec3(0.0));
}

TEST(LambertianRect, GpuRecordMatchesTheGeometry) {
    Luminaire light = makeLight();
    std::vector<std::byte> bytes = gpuData(light);
    ASSERT_EQ(bytes.size(), sizeof(gpu::LambertianRectGpu));
    ASSERT_EQ(bytes.size(), 80u);  // five vec4, std430
    gpu::LambertianRectGpu g;
    std::memcpy(&g, bytes.data(), sizeof(g));
    std::vector<glm::dvec3> c = light.outline();
    Frame f = frameOf(light.pose);
    // Float storage: 1e-6 of the coordinates.
    const float tol = 1e-6f;
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(g.corner[i], float(c[0][i]), tol * 4);
        EXPECT_NEAR(g.edgeX[i], float(c[1][i] - c[0][i]), tol);
        EXPECT_NEAR(g.edgeY[i], float(c[3][i] - c[0][i]), tol);
        EXPECT_NEAR(g.normal[i], float(f.z[i]), tol);
        EXPECT_EQ(g.radiance[i], float(lambertianRectModel(light)->emitted[i]));
    }
    EXPECT_NEAR(g.corner.w, 1.2f * 0.6f, tol);
    EXPECT_EQ(g.edgeX.w, 1.2f);
    EXPECT_EQ(g.edgeY.w, 0.6f);
}

TEST(LambertianRect, DescribesItself) {
    const LuminaireAdapter& adapter = adapterOf(LuminaireKind::LambertianRect);
    EXPECT_EQ(describe(*adapter.create()),
              "lambertian-rect 1.00 x 0.50 m, L = (10, 10, 10) W/(m2 sr), power 15.7 W");
    EXPECT_EQ(adapter.create()->kind(), LuminaireKind::LambertianRect);
}

std::string parseError(const std::string& text) {
    try {
        adapterOf(LuminaireKind::LambertianRect)
            .parse(nlohmann::json::parse(text), {"t.json", "luminaires[0]"});
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

TEST(LambertianRect, ParsesAndWritesItsFields) {
    const LuminaireAdapter& adapter = adapterOf(LuminaireKind::LambertianRect);
    auto parsed =
        adapter.parse(nlohmann::json::parse(R"({"type": "lambertian-rect", "size": [2, 0.25],
                                                "radiance": [1, 2, 0]})"),
                      {"t.json", "luminaires[0]"});
    ASSERT_TRUE(lambertianRectModel(*parsed));
    const LambertianRect& light = *lambertianRectModel(*parsed);
    EXPECT_EQ(light.size, glm::dvec2(2.0, 0.25));
    EXPECT_EQ(light.emitted, glm::dvec3(1.0, 2.0, 0.0));
    nlohmann::json out;
    writeJson(*parsed, out);
    EXPECT_EQ(out, nlohmann::json::parse(R"({"size": [2.0, 0.25], "radiance": [1.0, 2.0, 0.0]})"));
    auto defaults = adapter.parse(nlohmann::json::parse(R"({"name": "a"})"), {"t.json", ""});
    ASSERT_TRUE(lambertianRectModel(*defaults));
    EXPECT_EQ(lambertianRectModel(*defaults)->size, glm::dvec2(1.0, 0.5));
    EXPECT_EQ(lambertianRectModel(*defaults)->emitted, glm::dvec3(10.0));
    auto copy = parsed->clone();
    ASSERT_TRUE(lambertianRectModel(*copy));
    EXPECT_EQ(lambertianRectModel(*copy)->size, light.size);

    EXPECT_EQ(parseError(R"({"size": [-1, 0.5]})"),
              "t.json: luminaires[0].size[0]: expected a positive number, got -1");
    EXPECT_NE(parseError(R"({"size": [1, "NaN"]})").find("size[1]"), std::string::npos);
    EXPECT_NE(parseError(R"({"size": [1, "NaN"]})").find("NaN"), std::string::npos);
    EXPECT_NE(parseError(R"({"size": [1, 2, 3]})").find("luminaires[0].size: expected"),
              std::string::npos);
    EXPECT_NE(parseError(R"({"size": [1, 1e7]})").find("size[1]"), std::string::npos);
    EXPECT_NE(parseError(R"({"radiance": [1, -2, 3]})").find("radiance[1]: expected a non-neg"),
              std::string::npos);
    EXPECT_NE(parseError(R"({"radiance": [1, 2]})").find("radiance"), std::string::npos);
    EXPECT_NE(parseError(R"({"sise": [1, 2]})").find("unknown field \"sise\""), std::string::npos);
    EXPECT_NE(parseError(R"([1, 2])").find("expected an object"), std::string::npos);
}

}  // namespace
}  // namespace candela
