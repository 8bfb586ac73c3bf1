#pragma once
// Screenshots of the renderer's image: shot-NNN.png (tone-mapped), shot-NNN.exr (linear) and a
// shot-NNN.json sidecar that records how the image was made. Shared by the editor's Screenshot
// button and the headless `candela edit` fallback.

#include <filesystem>
#include <string>
#include <vector>

#include "renderer/FrameStats.h"
#include "renderer/Renderer.h"
#include "scene/Scene.h"

namespace candela {

/// GPU time per pass summed over the frames of the current accumulation, plus the passes of the
/// last frame that ran any (a converged frame runs none, and the statistics should still show
/// what produced the image).
class PassTotals {
  public:
    /// Adds a frame's passes; a frame that ran the G-buffer pass starts a new accumulation.
    void add(const FrameStats& stats);
    /// Milliseconds per pass over the current accumulation, in first-run order.
    const std::vector<PassTiming>& totals() const { return mTotals; }
    /// The last frame that ran at least one pass.
    const std::vector<PassTiming>& lastFrame() const { return mLastFrame; }
    /// Sum of totals(), GPU milliseconds.
    double totalGpuMs() const;

  private:
    std::vector<PassTiming> mTotals;
    std::vector<PassTiming> mLastFrame;
};

struct ScreenshotFiles {
    std::string png;   ///< Tone-mapped 8-bit sRGB.
    std::string exr;   ///< Linear radiance, W/(m2 sr).
    std::string json;  ///< Sidecar, written last (its presence means the other two are complete).
};

/// Writes the next free shot-NNN.{png,exr,json} in dir (created if needed), each through a
/// temporary file and a rename (util/FileOutput.h). Throws InputError naming the file when a
/// write fails.
ScreenshotFiles writeScreenshot(const std::filesystem::path& dir, const Scene& scene,
                                const Renderer& renderer, const PassTotals& passes);

/// First DIR/PREFIX-NNN (NNN = 000, 001, ...) for which none of PREFIX-NNN.{png,exr,json} exists.
/// Throws InputError naming dir when all 100000 are taken.
std::filesystem::path nextFreeStem(const std::filesystem::path& dir, const std::string& prefix);

/// UTC time as ISO 8601, e.g. "2024-05-01T12:34:56Z" (the sidecars' timestamps).
std::string utcTimestamp();

/// The camera as a scene-file JSON object (position, target, fov_deg).
nlohmann::json cameraToJsonObject(const Camera& camera);

}  // namespace candela
