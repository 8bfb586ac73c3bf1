#pragma once
// What a render is asked for: size, samples, techniques, tone mapping, shadow maps, bands.
// Plain data, no GL; the passes that read it include this and not the renderer.

#include <cstdint>
#include <string>

#include "renderer/FramePlan.h"
#include "renderer/passes/ShadowMapPass.h"
#include "renderer/passes/TonemapPass.h"

namespace candela {

/// Which light the image shows: all of it, the direct light alone, or the interreflected light
/// alone (what a designer's false colour compares).
enum class LightParts { Total = 0, Direct = 1, Interreflected = 2 };

/// FalseColour maps the values (lux in illuminance mode) through `RenderSettings::legend`.
enum class ToneMapOperator { Exponential = 0, Reinhard = 1, FalseColour = 2 };

struct RenderSettings {
    int width = 512;
    int height = 512;
    int samplesPerFrame = 4;  ///< Light samples per pixel per luminaire each frame.
    int maxSamples = 0;       ///< Stop refining at this many samples per pixel; 0 = never.
    /// Empty: each luminaire's own technique. Else names separated by commas; each luminaire
    /// uses the first its kind has (see planFrame).
    std::string techniqueOverride;
    ToneMapOperator toneMap = ToneMapOperator::Exponential;
    float exposure = 1.0f;      ///< k of the operators in shaders/tonemap.frag.
    float fixedAverage = 0.0f;  ///< > 0: tone-map against this luminance, not the frame mean.
    /// Radiance: what the camera sees. Illuminance: every surface but the luminaires is a white
    /// Lambertian receiver of albedo pi (no glossy lobe), so each pixel holds the irradiance E on
    /// the surface, W/m2 (lux for photometric luminaires); luminaires show no value.
    Quantity quantity = Quantity::Radiance;
    FalseColourLegend legend;              ///< Used by ToneMapOperator::FalseColour.
    LightParts parts = LightParts::Total;  ///< Display only: changing it re-renders nothing.
    uint32_t seed = 0;  ///< Seeds the random numbers (independent renders differ).
    /// The environment's technique; empty: techniqueOverride if it names one, else its own
    /// ("balanced"). Shorthand for "environment=NAME" in front of techniqueOverride.
    std::string environmentTechnique;
    int environmentFaceSize = 0;   ///< Cube faces of N^2 texels; 0: EnvironmentPass's default.
    ShadowMapSettings shadowMaps;  ///< For techniques that read shadow maps.
    /// > 0: renderFrame() shades only a band of rows that takes about this long (ms), so an
    /// interactive caller gets control back in time whatever one pass over the image costs; the
    /// image shown is updated when a pass is complete (band by band during the first pass).
    /// 0: every call shades the whole image (headless rendering, benches, tests).
    double bandBudgetMs = 0.0;
    /// > 0: bands of exactly this many rows instead (tests of the banding itself).
    int bandRows = 0;
    /// A luminaire behind the others (one that moved) takes up to this many passes' samples in
    /// one pass: a pass has a fixed cost per pixel that more samples share (the light field's
    /// restricted-cdf at 960x540 on llvmpipe: 2.5 s for 16 spp, 4.4 s for 48). 1: every pass
    /// takes samplesPerFrame (the live preview, where a frame's time counts).
    int catchUpPasses = 3;
};

/// The technique list a frame is planned with (planFrame): techniqueOverride, preceded by
/// "environment=NAME" when environmentTechnique is set.
std::string techniqueList(const RenderSettings& settings);

}  // namespace candela
