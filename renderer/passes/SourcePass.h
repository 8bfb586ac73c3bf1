#pragma once
// A light source's GPU pass: what the renderer runs for each step of the frame plan, the same
// for every kind. A source's pass keeps what its kind's shading reads besides the G-buffer (a
// luminaire's record and shadow maps; the environment's map, tables and samples), prepares what
// the step's technique needs at the start of each pass (TechniqueInfo::resources) and shades.
// The renderer keeps one pass per source; which class serves a kind is the table in
// SourcePass.cpp, the renderer's one line per kind.

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "renderer/FramePlan.h"
#include "renderer/FrameStats.h"
#include "renderer/PassTimer.h"
#include "renderer/RenderSettings.h"
#include "renderer/ShaderLibrary.h"
#include "renderer/gl/GlObjects.h"

namespace candela {

class GBufferPass;
class ShadowGeometry;

/// What a source's pass may use while the renderer prepares and shades one of its steps.
struct SourceContext {
    ShaderLibrary& shaders;
    FrameStats& stats;  ///< Prepasses record themselves here, timed by `timer`.
    PassTimer& timer;
    const GBufferPass& gbuffer;
    const RenderSettings& settings;
    /// The scene's triangles for shadow maps, made on first use; and their generation.
    std::function<const ShadowGeometry&()> geometry;
    int geometryGeneration = 0;
    bool pointMode = false;  ///< Probing points (Renderer::probe): no background, no shadows.
};

class SourcePass {
  public:
    virtual ~SourcePass() = default;
    /// The source this pass serves now (a new one, or the same with new data) and its record
    /// (gpuData, luminaires/Adapter.h, made once by the renderer): upload what changed.
    virtual void setSource(const Luminaire& source, const std::vector<std::byte>& record) = 0;
    /// At the start of a pass (before its first band): what the step's technique reads (tables,
    /// this pass's samples, shadow maps), each timed under the names of ShadeStep::prepasses or
    /// shadowPassName(step). `frame` counts the source's passes; spp is this pass's samples.
    virtual void prepare(const ShadeStep& step, SourceContext& context, int frame, int spp) = 0;
    /// Shades the G-buffer (within the current scissor) into `target`, additively.
    virtual void shade(const ShadeStep& step, SourceContext& context,
                       const gl::Framebuffer& target) = 0;
};

/// The pass for a source of `kind` (needs a current GL context).
std::unique_ptr<SourcePass> makeSourcePass(LuminaireKind kind);
/// The names of the prepasses a technique's kind runs for it (FramePlan::passNames).
std::vector<std::string> sourcePrepasses(const TechniqueInfo& technique);

}  // namespace candela
