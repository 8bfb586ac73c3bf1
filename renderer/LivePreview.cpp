#include "renderer/LivePreview.h"

#include <algorithm>
#include <cmath>

#include "luminaires/Registry.h"
#include "luminaires/lightfield/FarField.h"

namespace candela {

RenderSettings previewSettings(const RenderSettings& full, const PreviewPolicy& policy) {
    RenderSettings s = full;
    s.width = std::max(1, int(std::lround(full.width * policy.scale)));
    s.height = std::max(1, int(std::lround(full.height * policy.scale)));
    s.samplesPerFrame = policy.samplesPerFrame;
    s.catchUpPasses = 1;  // a drag frame's time counts: the moved luminaire takes the usual samples
    s.maxSamples =
        full.maxSamples > 0 ? std::min(full.maxSamples, policy.maxSamples) : policy.maxSamples;
    std::string list = policy.techniques;
    for (const LuminaireKindInfo& kind : luminaireKinds()) {
        if (!list.empty()) list.push_back(',');
        list.append(kind.previewTechnique);
    }
    s.techniqueOverride = list;
    s.shadowMaps.count = policy.shadowMaps;
    s.shadowMaps.resolution = std::min(full.shadowMaps.resolution, policy.shadowMapSize);
    s.shadowMaps.directionalResolution =
        std::min(full.shadowMaps.directionalResolution, 4 * policy.shadowMapSize);
    return s;
}

Scene previewScene(const Scene& scene) {
    Scene preview = scene.clone();
    for (auto& lum : preview.luminaires)
        if (std::unique_ptr<Luminaire> twin = farFieldTwin(*lum)) lum = std::move(twin);
    return preview;
}

bool syncPreviewScene(Scene& preview, const Scene& scene) {
    if (preview.luminaires.size() != scene.luminaires.size()) return false;
    for (size_t i = 0; i < scene.luminaires.size(); ++i) {
        const Luminaire& source = *scene.luminaires[i];
        Luminaire& shown = *preview.luminaires[i];
        if (shown.name != source.name) return false;
        if (source.kind() == LuminaireKind::LightField) {
            // Its stand-in (farFieldTwin) follows its pose; another model needs a new stand-in.
            if (shown.kind() != LuminaireKind::Photometric) return false;
            placeFarFieldTwin(shown, source);
        } else {
            if (shown.sharedModel() != source.sharedModel()) return false;
            shown.pose = source.pose;
        }
    }
    preview.camera = scene.camera;
    preview.environmentMap = scene.environmentMap;
    return true;
}

}  // namespace candela
