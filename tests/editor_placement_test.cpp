// Placing luminaires on surfaces (ui/EditorState.h: poseOnSurface, surfaceBvh) and picking the
// surface seen through a pixel of the demo room (renderer/ViewportMath.h).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <set>

#include "formats/Gldf.h"
#include "luminaires/photometric/PhotometricLuminaire.h"
#include "renderer/FramePlan.h"
#include "renderer/ViewportMath.h"
#include "ui/EditorState.h"

namespace candela::ui {
namespace {

TEST(EditorPlacement, OnAWallAlongItsNormalOrDownWithClearanceAndSnap) {
    Pose pose;
    pose.c0 = {0.0, 0.0, 1.0};
    const glm::dvec3 wall(-3.0, 1.234, 0.567), normal(1.0, 0.0, 0.0);
    Pose a = poseOnSurface(pose, wall, normal, true, 0.01, 0.0);
    EXPECT_NEAR(a.position.x, -2.99, 1e-12);
    EXPECT_EQ(a.position.y, 1.234);
    EXPECT_EQ(a.aim, normal);
    EXPECT_EQ(a.c0, pose.c0);  // spin kept
    Pose b = poseOnSurface(pose, wall, normal, false, 0.01, 0.0);
    EXPECT_EQ(b.aim, glm::dvec3(0.0, -1.0, 0.0));
    // Snapping rounds the coordinates along the wall (y, z), never the distance off it (x).
    Pose c = poseOnSurface(pose, wall, normal, true, 0.01, 0.25);
    EXPECT_NEAR(c.position.x, -2.99, 1e-12);
    EXPECT_NEAR(c.position.y, 1.25, 1e-12);
    EXPECT_NEAR(c.position.z, 0.5, 1e-12);
}

// The ray-plane intersection a drawn task area's corners come from, against the closed form
// t = (offset - o[axis]) / d[axis], with the plane's coordinate exact.
TEST(EditorPlacement, RaysMeetCalculationPlanesWhereTheClosedFormSays) {
    Ray ray{{0.5, 2.0, 3.0}, glm::normalize(glm::dvec3(0.2, -0.6, -0.7))};
    auto p = intersectPlane(ray, parsePlane("y=0.75"));
    ASSERT_TRUE(p);
    double t = (0.75 - 2.0) / ray.dir.y;
    EXPECT_EQ(p->y, 0.75);
    EXPECT_NEAR(p->x, 0.5 + t * ray.dir.x, 1e-12);
    EXPECT_NEAR(p->z, 3.0 + t * ray.dir.z, 1e-12);
    // Either facing: a wall plane facing -x is met the same way.
    auto w = intersectPlane(Ray{{0, 1, 0}, {1, 0, 0}}, parsePlane("-x=2.5"));
    ASSERT_TRUE(w);
    EXPECT_EQ(*w, glm::dvec3(2.5, 1.0, 0.0));
    // Behind the ray, and parallel to the plane: no point.
    EXPECT_FALSE(intersectPlane(ray, parsePlane("y=2.5")));
    EXPECT_FALSE(intersectPlane(Ray{{0, 1, 0}, {1, 0, 0}}, parsePlane("y=0.75")));
}

TEST(EditorPlacement, PickingTheDemoRoomsCeilingAimsDownAndTheBvhFollowsTheGeometry) {
    setenv("CANDELA_STATE_DIR",
           (std::filesystem::temp_directory_path() / "candela-placement-test").c_str(), 1);
    EditorState state;
    ASSERT_TRUE(openSceneFile(state, CANDELA_SOURCE_DIR "/resources/scenes/demo.json"));
    // Look straight up from the middle of the room: the centre pixel sees the ceiling (y = 3).
    state.scene.camera = {{0.0, 1.5, 0.0}, {0.0, 3.0, 0.01}, 60.0};
    glm::mat4 viewProj = cameraViewProj(state.scene.camera, 1.0);
    auto hit = pickSurface(surfaceBvh(state), viewProj, 50.0, 50.0, 100, 100);
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(hit->point.y, 3.0, 1e-4);
    Pose pose =
        poseOnSurface(state.scene.luminaires[0]->pose, hit->point, hit->normal, true, 0.02, 0.0);
    EXPECT_NEAR(pose.position.y, 2.98, 1e-4);
    EXPECT_NEAR(pose.aim.y, -1.0, 1e-9);  // the ceiling's normal, turned to the camera: down

    const Bvh* before = &surfaceBvh(state);
    EXPECT_EQ(&surfaceBvh(state), before);  // kept while the geometry stands
    applyEdit(state, "Delete ceiling", kChangeGeometry, [](Scene& s) {
        s.geometry.erase(s.geometry.begin() + 1);
        s.meshes.erase(s.meshes.begin() + 1);
    });
    auto open = pickSurface(surfaceBvh(state), viewProj, 50.0, 50.0, 100, 100);
    EXPECT_FALSE(open.has_value());  // the rebuilt BVH has no ceiling: the sky
}

}  // namespace
}  // namespace candela::ui

namespace candela::ui {
namespace {

TEST(EditorPlacement, SwapKeepsPoseAndNameAndIsOneUndoStep) {
    setenv("CANDELA_STATE_DIR",
           (std::filesystem::temp_directory_path() / "candela-placement-test").c_str(), 1);
    EditorState state;
    ASSERT_TRUE(openSceneFile(state, CANDELA_SOURCE_DIR "/resources/scenes/editor-room.json"));
    const Pose pose = state.scene.luminaires[0]->pose;  // the analytic ceiling panel
    ASSERT_TRUE(swapLuminaireFile(
        state, 0, CANDELA_SOURCE_DIR "/resources/luminaires/photometric/prolicht-e30.ldt"));
    const Luminaire& swapped = *state.scene.luminaires[0];
    EXPECT_EQ(swapped.kind(), LuminaireKind::Photometric);
    EXPECT_EQ(swapped.name, "Ceiling panel");
    EXPECT_EQ(swapped.pose.position, pose.position);
    EXPECT_EQ(swapped.pose.aim, pose.aim);
    EXPECT_EQ(swapped.technique, "adaptive");  // "analytic" is not photometric: the kind's default
    // A light field in place of the pendant keeps nothing of the photometric technique either.
    ASSERT_TRUE(swapLuminaireFile(
        state, 2, CANDELA_SOURCE_DIR "/resources/luminaires/osram-lertduw.lf.json"));
    EXPECT_EQ(state.scene.luminaires[2]->technique, "restricted-cdf");
    // A file that cannot be read changes nothing and says why.
    size_t steps = state.history.undo.size();
    EXPECT_FALSE(swapLuminaireFile(state, 0, "/nonexistent/lamp.ies"));
    EXPECT_EQ(state.history.undo.size(), steps);
    EXPECT_NE(state.modalError.find("lamp.ies"), std::string::npos);
    EXPECT_EQ(state.scene.luminaires[0]->kind(), LuminaireKind::Photometric);
    ASSERT_TRUE(undo(state));
    ASSERT_TRUE(undo(state));
    EXPECT_EQ(state.scene.luminaires[0]->kind(), LuminaireKind::LambertianRect);
}

}  // namespace
}  // namespace candela::ui

namespace candela::ui {
namespace {

TEST(EditorPlacement, ArrayIsAGridOfCopiesAndOneUndoStep) {
    setenv("CANDELA_STATE_DIR",
           (std::filesystem::temp_directory_path() / "candela-placement-test").c_str(), 1);
    EditorState state;
    ASSERT_TRUE(openSceneFile(state, CANDELA_SOURCE_DIR "/resources/scenes/editor-room.json"));
    const Luminaire& source = *state.scene.luminaires[2];
    glm::dvec3 origin = source.pose.position;
    EXPECT_EQ(arrayLuminaire(state, 2, 3, 2, 1.2, 0.8), 5);
    ASSERT_EQ(state.scene.luminaires.size(), 8u);
    std::set<std::string> names;
    for (const auto& lum : state.scene.luminaires) names.insert(lum->name);
    EXPECT_EQ(names.size(), 8u);  // all distinct
    // The last copy sits at (2 dx, 0, 1 dz) from the source, same aim and technique.
    const Luminaire& last = *state.scene.luminaires.back();
    EXPECT_NEAR(glm::length(last.pose.position - (origin + glm::dvec3(2.4, 0.0, 0.8))), 0.0, 1e-12);
    EXPECT_EQ(last.pose.aim, state.scene.luminaires[2]->pose.aim);
    EXPECT_EQ(last.technique, "adaptive");
    EXPECT_EQ(arrayLuminaire(state, 2, 1, 1, 1.0, 1.0), 0);  // 1 x 1: nothing to add
    ASSERT_TRUE(undo(state));
    EXPECT_EQ(state.scene.luminaires.size(), 3u);
}

}  // namespace
}  // namespace candela::ui

namespace candela::ui {
namespace {

TEST(EditorPlacement, DroppedFilesBecomeLuminairesEnvironmentOrGeometry) {
    setenv("CANDELA_STATE_DIR",
           (std::filesystem::temp_directory_path() / "candela-placement-test").c_str(), 1);
    EditorState state;
    ASSERT_TRUE(openSceneFile(state, CANDELA_SOURCE_DIR "/resources/scenes/demo.json"));
    size_t meshes = state.scene.meshes.size(), items = state.scene.geometry.size();

    ASSERT_TRUE(dropFile(state, CANDELA_SOURCE_DIR "/tests/data/hdr/noon_grass_256.hdr"));
    ASSERT_TRUE(state.scene.environmentMap);
    EXPECT_NE(state.pendingChanges & kChangeEnvironment, 0u);

    ASSERT_TRUE(dropFile(
        state, CANDELA_SOURCE_DIR "/resources/gltf/cornellBox/cornellBox-2.80-Eevee-gltf.gltf"));
    EXPECT_GT(state.scene.meshes.size(), meshes);
    EXPECT_EQ(state.scene.geometry.size(), items + 1);
    for (const Mesh& m : state.scene.meshes) EXPECT_LT(m.material, state.scene.materials.size());
    for (uint32_t m : state.scene.geometry.back().meshes) EXPECT_LT(m, state.scene.meshes.size());

    ASSERT_TRUE(dropFile(
        state, CANDELA_SOURCE_DIR "/resources/luminaires/photometric/floor-washlight.ies"));
    EXPECT_EQ(state.scene.luminaires.back()->kind(), LuminaireKind::Photometric);
    EXPECT_TRUE(state.placement.armed);  // the next click on a surface places it

    size_t steps = state.history.undo.size();
    EXPECT_FALSE(dropFile(state, "/tmp/notes.txt"));
    EXPECT_NE(state.modalError.find("notes.txt"), std::string::npos);
    EXPECT_FALSE(dropFile(state, "/nonexistent/sky.hdr"));
    EXPECT_NE(state.modalError.find("sky.hdr"), std::string::npos);
    EXPECT_EQ(state.history.undo.size(), steps);  // nothing changed

    for (int i = 0; i < 3; ++i) ASSERT_TRUE(undo(state));
    EXPECT_EQ(state.scene.meshes.size(), meshes);
    EXPECT_FALSE(state.scene.environmentMap);
}

TEST(EditorPlacement, DroppedGldfBecomesItsFirstVariant) {
    setenv("CANDELA_STATE_DIR",
           (std::filesystem::temp_directory_path() / "candela-placement-test").c_str(), 1);
    EditorState state;
    ASSERT_TRUE(openSceneFile(state, CANDELA_SOURCE_DIR "/resources/scenes/demo.json"));
    size_t count = state.scene.luminaires.size();
    EXPECT_EQ(fileKind("LAMP.GLDF"), FileKind::Gldf);
    ASSERT_TRUE(dropFile(state, CANDELA_SOURCE_DIR "/tests/data/gldf/GldfWithFilesComplete.gldf"));
    ASSERT_EQ(state.scene.luminaires.size(), count + 1);
    const Luminaire& placedLight = *state.scene.luminaires.back();
    const PhotometricLuminaire* light = photometricModel(placedLight);
    ASSERT_NE(light, nullptr);
    ASSERT_NE(light->gldf, nullptr);
    EXPECT_EQ(light->gldf->manufacturer, "DIAL");
    EXPECT_EQ(light->gldfVariant, "variant-1");
    EXPECT_EQ(placedLight.technique, "adaptive");  // the photometric kind's default
    EXPECT_TRUE(state.placement.armed);
    // A container that cannot be placed is reported, naming the member, and changes nothing.
    size_t steps = state.history.undo.size();
    EXPECT_FALSE(dropFile(state, CANDELA_SOURCE_DIR "/tests/data/gldf/GldfWithMissingFiles.gldf"));
    EXPECT_NE(state.modalError.find("ldc/file.ldt"), std::string::npos) << state.modalError;
    EXPECT_EQ(state.history.undo.size(), steps);
}

TEST(EditorPlacement, DroppedGldfWithTwoEmittersAddsBothInOneStepSelectedTogether) {
    setenv("CANDELA_STATE_DIR",
           (std::filesystem::temp_directory_path() / "candela-placement-test").c_str(), 1);
    EditorState state;
    ASSERT_TRUE(openSceneFile(state, CANDELA_SOURCE_DIR "/resources/scenes/demo.json"));
    size_t count = state.scene.luminaires.size(), steps = state.history.undo.size();
    ASSERT_TRUE(dropFile(state, CANDELA_SOURCE_DIR "/tests/data/gldf/PendantTwoEmitters.gldf"));
    ASSERT_EQ(state.scene.luminaires.size(), count + 2);
    EXPECT_EQ(state.history.undo.size(), steps + 1);  // one undo step
    const Luminaire* down = state.scene.luminaires[count].get();
    const Luminaire* up = state.scene.luminaires[count + 1].get();
    ASSERT_TRUE(photometricModel(*down) && photometricModel(*up));
    ASSERT_TRUE(photometricModel(*down)->placement && photometricModel(*up)->placement);
    EXPECT_EQ(photometricModel(*down)->placement->object, "leo_bottom");
    EXPECT_EQ(photometricModel(*up)->placement->object, "leo_top");
    EXPECT_EQ(down->pose.position, up->pose.position);
    // Both selected, so a move or a delete takes both.
    EXPECT_EQ(state.selectedLuminaire, int(count));
    EXPECT_EQ(state.alsoSelected, std::vector<int>{int(count) + 1});
    // Turning or moving one placement, however it is done (here as the inspector and the
    // gizmo do: an edit of that luminaire's pose alone), turns and moves the other with it.
    Pose other = state.scene.luminaires[0]->pose;
    Pose turned = down->pose;
    turned.aim = glm::dvec3(0.3, -1.0, 0.2);
    turned.position += glm::dvec3(0.5, 0.0, -0.25);
    applyEdit(state, "Rotate", kChangeLuminaires,
              [&](Scene& s) { s.luminaires[count]->pose = turned; });
    EXPECT_EQ(up->pose.position, turned.position);
    EXPECT_EQ(up->pose.aim, turned.aim);
    EXPECT_EQ(up->pose.c0, turned.c0);
    // A luminaire that is not one of its placements keeps its pose.
    EXPECT_EQ(state.scene.luminaires[0]->pose.position, other.position);
    EXPECT_EQ(state.scene.luminaires[0]->pose.aim, other.aim);
    ASSERT_TRUE(undo(state));  // the rotation, for both (undo restores copies: look them up again)
    const Pose& downNow = state.scene.luminaires[count]->pose;
    const Pose& upNow = state.scene.luminaires[count + 1]->pose;
    EXPECT_EQ(upNow.position, downNow.position);
    EXPECT_NE(upNow.position, turned.position);
    ASSERT_TRUE(undo(state));
    EXPECT_EQ(state.scene.luminaires.size(), count);
}

}  // namespace
}  // namespace candela::ui
