#pragma once
// The editor's fallback while the user drags something (issue 7, "live while moving"): the same
// scene at a fraction of the resolution, one sample per pixel and frame, every light field
// replaced by its far field (luminaires/lightfield/FarField.h), each luminaire kind's cheap
// technique (LuminaireKindInfo::previewTechnique: the analytic rectangle, Prost's scattered
// sampling of the far field) and a single small shadow map per luminaire. When the drag ends the
// editor renders the real scene with the full settings again, which restarts the progressive
// refinement with the chosen techniques.

#include "renderer/Renderer.h"
#include "scene/Scene.h"

namespace candela {

struct PreviewPolicy {
    float scale = 0.5f;       ///< Render pixels per full-resolution pixel, per axis.
    int samplesPerFrame = 1;  ///< Light samples per pixel per luminaire each frame.
    int maxSamples = 16;      ///< Refines this far while the mouse holds still mid-drag.
    int shadowMaps = 1;       ///< Maps per luminaire (ShadowMapSettings::count).
    int shadowMapSize = 64;   ///< Texels along a cube face (ShadowMapSettings::resolution).
    /// Comma-separated techniques tried first (as RenderSettings::techniqueOverride); each
    /// kind's previewTechnique follows them.
    std::string techniques;
};

/// The settings to render while dragging, derived from the full ones: techniqueOverride lists
/// every kind's preview technique (replacing any override of the full settings: while the user
/// drags, responsiveness comes first), sizes are scaled (at least 1 pixel), the tone mapping and
/// quantity are kept.
RenderSettings previewSettings(const RenderSettings& full, const PreviewPolicy& policy = {});

/// The scene to render while dragging: a copy of `scene` whose light fields are their far-field
/// twins (the tables are computed once per light-field file and kept).
Scene previewScene(const Scene& scene);
/// Brings a preview scene made by previewScene(scene) up to date with the scene's luminaire
/// poses and camera, in place (the renderer keeps each luminaire's shadow maps by its address,
/// so only the ones that moved are rendered again). Returns false when the luminaires were added,
/// removed or replaced since: then make a new preview scene.
bool syncPreviewScene(Scene& preview, const Scene& scene);

}  // namespace candela
