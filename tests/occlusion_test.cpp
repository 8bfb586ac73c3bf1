// Which luminaires need shadow rays: "no" for rooms of planes and objects behind the light,
// "yes" whenever something can stand between the light and a visible surface.
#include "scene/Occlusion.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/SceneIo.h"

namespace candela {
namespace {

const std::string kCornell =
    std::string(CANDELA_SOURCE_DIR) + "/resources/gltf/cornellBox/cornellBox-2.80-Eevee-gltf.gltf";

const std::string kFloor = R"({"plane": {"center": [0,0,0], "normal": [0,1,0], "size": [6,6]}})";
const std::string kRoom = kFloor + R"(,
    {"plane": {"center": [0,3,0], "normal": [0,-1,0], "size": [6,6]}},
    {"plane": {"center": [0,1.5,-3], "normal": [0,0,1], "size": [6,3]}},
    {"plane": {"center": [0,1.5,3], "normal": [0,0,-1], "size": [6,3]}},
    {"plane": {"center": [-3,1.5,0], "normal": [1,0,0], "size": [6,3]}},
    {"plane": {"center": [3,1.5,0], "normal": [-1,0,0], "size": [6,3]}})";
const std::string kCeilingLight =
    R"({"type": "lambertian-rect", "size": [1, 0.5], "position": [0, 2.5, 0], "aim": [0, -1, 0]})";

Scene sceneOf(const std::string& geometry, const std::string& luminaires) {
    return parseScene(nlohmann::json::parse(R"({"geometry": [)" + geometry +
                                            R"(], "luminaires": [)" + luminaires + "]}"),
                      "t.json");
}

/// Camera inside the room near the front wall, looking at its middle; 16:9, 60 degrees.
glm::mat4 viewProj(glm::vec3 eye = {0, 1.6f, 2.5f}, glm::vec3 target = {0, 1, 0}) {
    return glm::perspective(glm::radians(60.f), 16.f / 9.f, 0.05f, 100.f) *
           glm::lookAt(eye, target, glm::vec3(0, 1, 0));
}

TEST(Occlusion, GroundPlaneAloneNeedsNoShadows) {  // (a)
    Scene scene = sceneOf(kFloor, kCeilingLight);
    EXPECT_EQ(luminairesNeedingShadows(scene, viewProj()), std::vector<bool>{false});
}

TEST(Occlusion, ConvexRoomOfPlanesNeedsNoShadows) {  // (a)
    Scene scene = sceneOf(kRoom, kCeilingLight);
    EXPECT_EQ(luminairesNeedingShadows(scene, viewProj()), std::vector<bool>{false});
    // Also for a tilted light near a corner and from a camera outside the room.
    Scene tilted = sceneOf(kRoom, R"({"type": "lambertian-rect", "position": [2, 2.5, -2],
                                       "size": [0.5, 0.5], "aim": [-1, -1, 1], "c0": [0, 0, 1]})");
    EXPECT_EQ(luminairesNeedingShadows(tilted, viewProj({0, 5, 9})), std::vector<bool>{false});
}

TEST(Occlusion, BoxBetweenLightAndFloorNeedsShadows) {  // (b)
    Scene scene = sceneOf(kRoom + R"(, {"box": {"center": [0, 0.4, 0], "size": [1, 0.8, 1]}})",
                          kCeilingLight);
    EXPECT_EQ(luminairesNeedingShadows(scene, viewProj()), std::vector<bool>{true});
}

TEST(Occlusion, BoxBehindTheLightNeedsNoShadows) {  // (c)
    // The box sits above the downward-facing light (between it and the ceiling): it receives
    // no light and blocks none.
    const std::string box = R"(, {"box": {"center": [0, 2.75, 0], "size": [0.6, 0.3, 0.6]}})";
    Scene scene = sceneOf(kRoom + box, kCeilingLight);
    EXPECT_EQ(luminairesNeedingShadows(scene, viewProj()), std::vector<bool>{false});
    // The same box moved just below the light does block it.
    const std::string below = R"(, {"box": {"center": [0, 2.2, 0], "size": [0.6, 0.3, 0.6]}})";
    Scene blocked = sceneOf(kRoom + below, kCeilingLight);
    EXPECT_EQ(luminairesNeedingShadows(blocked, viewProj()), std::vector<bool>{true});
}

TEST(Occlusion, PlaneBetweenLightAndFloorNeedsShadows) {
    // A horizontal plane (a shelf) under the light splits it from the floor.
    Scene scene = sceneOf(
        kRoom + R"(, {"plane": {"center": [0, 1, 0], "normal": [0, 1, 0], "size": [1, 1]}})",
        kCeilingLight);
    EXPECT_EQ(luminairesNeedingShadows(scene, viewProj()), std::vector<bool>{true});
    // A plane far off to the side cannot: the light and the floor are on the same side of it.
    Scene aside = sceneOf(
        kFloor + R"(, {"plane": {"center": [20, 1, 0], "normal": [1, 0, 0], "size": [1, 1]}})",
        kCeilingLight);
    EXPECT_EQ(luminairesNeedingShadows(aside, viewProj()), std::vector<bool>{false});
}

TEST(Occlusion, OnlyVisibleReceiversCount) {
    // Box on the floor under the light, but the camera looks away, at the front wall's outside.
    Scene scene = sceneOf(kFloor + R"(, {"box": {"center": [0, 0.4, 0], "size": [1, 0.8, 1]}})",
                          kCeilingLight);
    EXPECT_EQ(luminairesNeedingShadows(scene, viewProj({0, 1, 10}, {0, 1, 20})),
              std::vector<bool>{false});
    EXPECT_EQ(luminairesNeedingShadows(scene, viewProj({0, 1, 10}, {0, 1, 0})),
              std::vector<bool>{true});
}

TEST(Occlusion, PerLuminaireAnswers) {
    // A box under light 0; light 1 is above the box's top face level and far to the side,
    // aimed away from it (up): nothing can block light 1.
    Scene scene = sceneOf(kRoom + R"(, {"box": {"center": [-1.5, 0.4, 0], "size": [1, 0.8, 1]}})",
                          kCeilingLight + R"(, {"type": "lambertian-rect",
                              "position": [2, 1.5, 0], "aim": [0, 1, 0]})");
    EXPECT_EQ(luminairesNeedingShadows(scene, viewProj()), (std::vector<bool>{true, false}));
}

TEST(Occlusion, GltfMeshesMayShadowThemselves) {
    Scene scene =
        parseScene(nlohmann::json::parse(R"({"geometry": [{"gltf": ")" + kCornell +
                                         R"("}], "luminaires": [)" + kCeilingLight + "]}"),
                   "t.json");
    EXPECT_EQ(luminairesNeedingShadows(scene, viewProj({0, 1.5, 6}, {0, 1.5, 0})),
              std::vector<bool>{true});
}

TEST(Occlusion, NoLuminairesNoFlags) {
    Scene scene = sceneOf(kRoom, "");
    EXPECT_TRUE(luminairesNeedingShadows(scene, viewProj()).empty());
}

}  // namespace
}  // namespace candela
