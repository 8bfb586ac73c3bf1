// The editor's settings and scene while dragging (renderer/LivePreview.h).
#include <gtest/gtest.h>

#include "luminaires/lightfield/FarField.h"
#include "renderer/FramePlan.h"
#include "renderer/LivePreview.h"
#include "scene/SceneIo.h"

namespace candela {
namespace {

TEST(LivePreview, SettingsAreCheaperAndKeepTheLook) {
    RenderSettings full;
    full.width = 960;
    full.height = 540;
    full.samplesPerFrame = 4;
    full.maxSamples = 256;
    full.techniqueOverride = "reference";
    full.toneMap = ToneMapOperator::Reinhard;
    full.exposure = 2.f;
    PreviewPolicy policy;
    policy.scale = 0.5f;
    RenderSettings p = previewSettings(full, policy);
    EXPECT_EQ(p.width, 480);
    EXPECT_EQ(p.height, 270);
    EXPECT_EQ(p.samplesPerFrame, 1);
    EXPECT_LE(p.maxSamples, 16);
    EXPECT_EQ(p.shadowMaps.count, 1);
    EXPECT_LE(p.shadowMaps.resolution, 64);
    // Every kind's cheap technique, the full override dropped; the tone mapping kept.
    EXPECT_EQ(overrideFor(p.techniqueOverride, LuminaireKind::LambertianRect), "analytic");
    EXPECT_EQ(overrideFor(p.techniqueOverride, LuminaireKind::Photometric), "scattered");
    EXPECT_EQ(p.toneMap, ToneMapOperator::Reinhard);
    EXPECT_EQ(p.exposure, 2.f);
    policy.scale = 0.001f;
    EXPECT_EQ(previewSettings(full, policy).width, 1);  // never 0 pixels
}

TEST(LivePreview, LightFieldsBecomeTheirFarFieldAndFollowTheirPose) {
    Scene scene = loadScene(CANDELA_SOURCE_DIR "/resources/scenes/editor-room.json");
    ASSERT_EQ(scene.luminaires.size(), 3u);
    ASSERT_EQ(scene.luminaires[1]->kind(), LuminaireKind::LightField);
    Scene preview = previewScene(scene);
    ASSERT_EQ(preview.luminaires.size(), 3u);
    EXPECT_EQ(preview.luminaires[0]->kind(), LuminaireKind::LambertianRect);
    EXPECT_EQ(preview.luminaires[1]->kind(), LuminaireKind::Photometric);
    EXPECT_EQ(preview.luminaires[1]->name, scene.luminaires[1]->name);
    EXPECT_EQ(preview.meshes.size(), scene.meshes.size());
    const Luminaire* kept = preview.luminaires[1].get();

    scene.luminaires[1]->pose.position += glm::dvec3(0.5, 0.0, -0.25);
    scene.luminaires[0]->pose.aim = glm::dvec3(0.0, -1.0, 0.3);
    scene.camera.fovDeg = 30.0;
    ASSERT_TRUE(syncPreviewScene(preview, scene));
    EXPECT_EQ(preview.luminaires[1].get(),
              kept);  // moved in place: its shadow maps are kept by address
    EXPECT_EQ(preview.luminaires[0]->pose.aim, scene.luminaires[0]->pose.aim);
    EXPECT_EQ(preview.camera.fovDeg, 30.0);
    // The twin sits on S's image centre, delta along the aim from the light field's origin.
    auto twin = farFieldTwin(*scene.luminaires[1]);
    ASSERT_NE(twin, nullptr);
    EXPECT_EQ(preview.luminaires[1]->pose.position, twin->pose.position);

    scene.luminaires.pop_back();
    EXPECT_FALSE(syncPreviewScene(preview, scene));  // a removed luminaire: make a new one
}

}  // namespace
}  // namespace candela
