#include "renderer/Renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>

#include "renderer/ImageFile.h"
#include "renderer/passes/EnvironmentPass.h"
#include "renderer/passes/GBufferPass.h"
#include "renderer/passes/IndirectPass.h"
#include "renderer/passes/ResolvePass.h"
#include "renderer/passes/ShadePass.h"
#include "renderer/passes/TonemapPass.h"
#include "scene/Bvh.h"
#include "shaders/shared/GpuTypes.h"

namespace candela {

namespace {

/// True on Mesa's software rasterizer, whose GL_TIME_ELAPSED queries end before its rasterizer
/// threads have run the pass's fragment shaders whenever those sample textures (measured: the
/// restricted-cdf pass at 960x540 reads 26 ms from its query and takes 1.6 s to glFinish).
bool softwareRasterizer() {
    static const bool software = [] {
        const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
        return renderer && (std::strstr(renderer, "llvmpipe") || std::strstr(renderer, "softpipe"));
    }();
    return software;
}

/// Times a pass and records it in the frame statistics: with a GPU timer query, or on a software
/// rasterizer as the wall time from a glFinish before it to one after it (the CPU is the GPU).
template <class Fn>
void timed(FrameStats& stats, const std::string& name, Fn&& fn) {
    if (softwareRasterizer()) {
        glFinish();
        auto start = std::chrono::steady_clock::now();
        fn();
        glFinish();
        stats.passes.push_back(
            {name, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count()});
        return;
    }
    gl::TimerQuery query;
    query.begin();
    fn();
    query.end();
    stats.passes.push_back({name, query.milliseconds()});
}

}  // namespace

Renderer::Renderer(ShaderLibrary& shaders)
    : mShaders(shaders),
      mGBuffer(std::make_unique<GBufferPass>()),
      mShade(std::make_unique<ShadePass>()),
      mResolve(std::make_unique<ResolvePass>()),
      mTonemap(std::make_unique<TonemapPass>()),
      mEnvironment(std::make_unique<EnvironmentPass>()),
      mIndirect(std::make_unique<IndirectPass>()),
      mFrameUniforms(sizeof(gpu::FrameUniforms), nullptr) {}

Renderer::~Renderer() = default;

void Renderer::update(const Scene& scene, unsigned changes) {
    mScene = &scene;
    mPending |= changes;
}

void Renderer::setSettings(const RenderSettings& s) {
    const RenderSettings& o = mSettings;
    bool restart = s.width != o.width || s.height != o.height ||
                   s.samplesPerFrame != o.samplesPerFrame || s.maxSamples != o.maxSamples ||
                   s.techniqueOverride != o.techniqueOverride || s.quantity != o.quantity ||
                   s.environmentTechnique != o.environmentTechnique ||
                   s.environmentFaceSize != o.environmentFaceSize || !(s.shadowMaps == o.shadowMaps);
    bool display = s.toneMap != o.toneMap || s.exposure != o.exposure ||
                   s.fixedAverage != o.fixedAverage || s.legend != o.legend || s.parts != o.parts;
    mSettings = s;
    mSettings.samplesPerFrame = std::max(1, s.samplesPerFrame);
    if (restart) mPending |= kChangeSettings;
    if (display) mNeedDisplay = true;
}

void Renderer::setIndirect(std::shared_ptr<const RadiosityMesh> mesh, std::vector<glm::vec3> vertexIrradiance) {
    mIndirectMesh = std::move(mesh);
    mIndirectIrradiance = std::move(vertexIrradiance);
    mIndirectUpload = true;
}

bool Renderer::hasIndirect() const { return mIndirectUpload ? mIndirectMesh != nullptr : mIndirect->hasLight(); }

glm::mat4 Renderer::viewProj() const {
    return cameraViewProj(mScene ? mScene->camera : Camera{},
                          double(mSettings.width) / double(std::max(1, mSettings.height)));
}

void Renderer::resize(int width, int height) {
    mGBuffer->resize(width, height);
    mResolve->resize(width, height);
    mTonemap->resize(width, height);
    mIndirect->resize(width, height);
    mIndirectDirty = true;
    mAccum = gl::Texture2D(width, height, GL_RGBA32F);
    mAccumFbo = gl::Framebuffer({&mAccum}, nullptr);
    mAccumulations.clear();  // made again at the new size
    mEnvironmentAccumulation = Accumulation{};
    mPass.clear();
}

std::vector<int> Renderer::planSteps() const {
    std::vector<int> steps;
    if (mPlan.environment) steps.push_back(-1);
    for (size_t i = 0; i < mPlan.shading.size(); ++i) steps.push_back(int(i));
    return steps;
}

const Luminaire* Renderer::luminaireOf(int step) const {
    return step < 0 ? nullptr : mScene->luminaires[size_t(mPlan.shading[size_t(step)].luminaire)].get();
}

bool Renderer::progressiveStep(int step) const {
    return step < 0 ? mPlan.environmentTechnique->progressive : mPlan.shading[size_t(step)].progressive;
}

Renderer::Accumulation& Renderer::accumulationOf(int step) {
    Accumulation& a = step < 0 ? mEnvironmentAccumulation : mAccumulations[luminaireOf(step)];
    if (a.texture.width() != mGBuffer->width() || a.texture.height() != mGBuffer->height()) {
        a.texture = gl::Texture2D(mGBuffer->width(), mGBuffer->height(), GL_RGBA32F);
        a.fbo = gl::Framebuffer({&a.texture}, nullptr);
        a.working = gl::Texture2D(mGBuffer->width(), mGBuffer->height(), GL_RGBA32F);
        a.workingFbo = gl::Framebuffer({&a.working}, nullptr);
        const float zero[4] = {0.f, 0.f, 0.f, 0.f};
        glClearNamedFramebufferfv(a.fbo.id(), GL_COLOR, 0, zero);
        glClearNamedFramebufferfv(a.workingFbo.id(), GL_COLOR, 0, zero);
        a.frames = 0;
        a.samples = 0;
        a.key.clear();
    }
    return a;
}

int Renderer::stepOf(const Luminaire* lum) const {
    if (!lum) return mPlan.environment ? -1 : -2;
    for (size_t i = 0; i < mPlan.shading.size(); ++i)
        if (luminaireOf(int(i)) == lum) return int(i);
    return -2;
}

bool Renderer::refines(int step) {
    const Accumulation& a = accumulationOf(step);
    if (!progressiveStep(step)) return a.frames == 0;
    return mSettings.maxSamples <= 0 || a.samples < mSettings.maxSamples;
}

std::vector<const Luminaire*> Renderer::choosePass() {
    std::vector<int> steps = planSteps();
    // The samples the others have reached: the most of any progressive step not catching up
    // itself; with none, the sample budget.
    int fewest = -1, ahead = 0;
    for (int st : steps) {
        const Accumulation& a = accumulationOf(st);
        if (progressiveStep(st) && !a.catchingUp) ahead = std::max(ahead, a.samples);
        if (refines(st) && (fewest < 0 || a.samples < fewest)) fewest = a.samples;
    }
    if (ahead == 0) ahead = std::max(mSettings.maxSamples, 0);
    std::vector<const Luminaire*> pass;
    bool catchUp = true;
    for (int st : steps) {
        Accumulation& a = accumulationOf(st);
        if (!refines(st) || a.samples != fewest) continue;
        a.catchingUp = a.catchingUp && a.samples < ahead;
        catchUp = catchUp && a.catchingUp;
        pass.push_back(luminaireOf(st));
    }
    // A luminaire that restarted alone (one that moved) catches up with the others in passes
    // of up to catchUpPasses passes' samples (RenderSettings::catchUpPasses).
    int spf = mSettings.samplesPerFrame;
    mPassSpp = spf;
    if (catchUp && !pass.empty())
        mPassSpp = std::clamp(ahead - std::max(fewest, 0), spf, std::max(1, mSettings.catchUpPasses) * spf);
    if (mSettings.maxSamples > 0) mPassSpp = std::max(1, std::min(mPassSpp, mSettings.maxSamples - std::max(fewest, 0)));
    return pass;
}

void Renderer::uploadLuminaires() {
    mLuminaireBuffers.clear();
    mRecords.clear();
    for (const auto& lum : mScene->luminaires) {
        std::vector<std::byte> data = lum->gpuData();
        mLuminaireBuffers.emplace_back(GLsizeiptr(data.size()), data.data());
        mRecords.push_back(std::move(data));
    }
}

void Renderer::rebuildPlan() {
    mPlan = planFrame(*mScene, viewProj(), mSettings.techniqueOverride, mSettings.quantity,
                      mSettings.environmentTechnique);
    mEnvironment->setMap(mPlan.environment ? mScene->environmentMap : nullptr,
                         mSettings.environmentFaceSize);
    if (mPlan.needsBvh && !mBvh) {
        mBvh = std::make_unique<Bvh>(Bvh::build(*mScene));
        auto bytes = [](const auto& v) { return GLsizeiptr(v.size() * sizeof(v[0])); };
        mBvhNodes = gl::Buffer(bytes(mBvh->nodes), mBvh->nodes.data(), 0);
        mBvhTris = gl::Buffer(bytes(mBvh->triangles), mBvh->triangles.data(), 0);
    }
}

void Renderer::setFrameUniforms(int frame, int spp) {
    gpu::FrameUniforms u{};
    u.viewProj = viewProj();
    u.invViewProj = glm::inverse(u.viewProj);
    u.cameraPos = glm::vec4(glm::vec3(mScene->camera.position), 1.f);
    u.frameInfo = glm::ivec4(frame, spp, 0, mPlan.needsBvh ? 1 : 0);
    u.seeds = glm::ivec4(int(mSettings.seed), 0, 0, 0);
    u.viewport = glm::vec4(float(mGBuffer->width()), float(mGBuffer->height()),
                           1.f / float(mGBuffer->width()), 1.f / float(mGBuffer->height()));
    mFrameUniforms.update(0, sizeof(u), &u);
    mFrameUniforms.bindBase(GL_UNIFORM_BUFFER, gpu::kBindingFrame);
}

void Renderer::runShading(int spp, int row0, int rows) {
    if (mBvh) {
        mBvhNodes.bindBase(GL_SHADER_STORAGE_BUFFER, gpu::kBindingBvhNodes);
        mBvhTris.bindBase(GL_SHADER_STORAGE_BUFFER, gpu::kBindingBvhTris);
    }
    glBindVertexArray(mEmptyVao.id());
    int height = mGBuffer->height();
    bool band = row0 > 0 || rows < height;
    auto scissor = [&] {
        // GL counts rows from the bottom; bands go from the top of the image down.
        if (!band) return;
        glEnable(GL_SCISSOR_TEST);
        glScissor(0, height - row0 - rows, mGBuffer->width(), rows);
    };
    // Probe mode: every step into mAccum, pass mFrames. Else the pass's steps, each into its
    // own accumulation with its own pass count (the seeds of its random numbers).
    std::vector<int> steps;
    if (mPointMode) {
        steps = planSteps();
    } else {
        for (const Luminaire* lum : mPass)
            if (int st = stepOf(lum); st >= -1) steps.push_back(st);
    }
    for (int st : steps) {
        Accumulation* acc = mPointMode ? nullptr : &accumulationOf(st);
        int frame = mPointMode ? mFrames : acc->frames;
        const gl::Framebuffer& target = mPointMode ? mAccumFbo : acc->workingFbo;
        setFrameUniforms(frame, spp);
        scissor();
        if (st < 0) {
            runEnvironment(spp, row0 == 0, frame, target);
            continue;
        }
        const ShadeStep& step = mPlan.shading[size_t(st)];
        if (step.shadowMaps) mShadowMaps.at(mScene->luminaires[size_t(step.luminaire)].get())->bind();
        timed(mStats, step.name, [&] {
            mShade->execute(mShaders, step, mLuminaireBuffers[size_t(step.luminaire)], *mGBuffer, target,
                            mGBuffer->width(), mGBuffer->height());
        });
    }
    glDisable(GL_SCISSOR_TEST);
}

const ShadowGeometry& Renderer::shadowGeometry() {
    if (mShadowGeometryGeneration != mGeometryGeneration) {
        mShadowGeometry.set(*mScene);
        mShadowGeometryGeneration = mGeometryGeneration;
    }
    return mShadowGeometry;
}

void Renderer::updateShadowMaps() {
    std::map<const Luminaire*, std::unique_ptr<ShadowMaps>> kept;
    for (const ShadeStep& step : mPlan.shading) {
        if (!step.shadowMaps) continue;
        const Luminaire* lum = mScene->luminaires[size_t(step.luminaire)].get();
        std::unique_ptr<ShadowMaps> maps = std::move(mShadowMaps[lum]);
        if (!maps) maps = std::make_unique<ShadowMaps>();
        ShadowLights lights = lum->shadowLights(mSettings.shadowMaps.count);
        if (maps->stale(lights, mSettings.shadowMaps, mGeometryGeneration)) {
            const ShadowGeometry& geometry = shadowGeometry();
            timed(mStats, shadowPassName(step), [&] {
                maps->render(mShaders, geometry, lights, mSettings.shadowMaps, mGeometryGeneration);
            });
        }
        kept[lum] = std::move(maps);
    }
    mShadowMaps = std::move(kept);
}

void Renderer::runEnvironment(int spp, bool newPass, int frame, const gl::Framebuffer& target) {
    using Tables = EnvironmentTechniqueInfo::Tables;
    Tables tables = mPlan.environmentTechnique->tables;
    if (tables == Tables::Cube) {
        if (!mEnvironment->tablesBuilt())
            timed(mStats, "env:cdf", [&] { mEnvironment->buildTables(mShaders); });
        // Enough samples per face that a pixel whose faces balance to one face still draws
        // distinct ones; a fresh pool every frame (every band of a frame shares it).
        if (newPass) {
            int pool = std::max(256, spp);
            uint32_t seed = uint32_t(mSettings.seed) * 2654435761u ^ uint32_t(frame) * 40503u ^ 0x5bd1e995u;
            timed(mStats, "env:samples", [&] { mEnvironment->drawSamples(mShaders, seed, pool); });
        }
    } else if (tables == Tables::LatLong) {
        mEnvironment->prepareGlobalCdf();
    } else if (tables == Tables::Lights) {
        mEnvironment->prepareHavran();
        if (mPlan.environment->shadowMaps) {
            std::vector<glm::dvec3> directions = mEnvironment->havranDirections();
            if (mEnvironmentShadows.stale(directions, mSettings.shadowMaps, mGeometryGeneration)) {
                const ShadowGeometry& geometry = shadowGeometry();
                timed(mStats, "shadow:environment", [&] {
                    mEnvironmentShadows.render(mShaders, geometry, directions, mSettings.shadowMaps,
                                               mGeometryGeneration);
                });
                glBindVertexArray(mEmptyVao.id());
            }
            mEnvironmentShadows.bind();
        }
    }
    bool background = !mPointMode && mSettings.quantity == Quantity::Radiance;
    timed(mStats, mPlan.environment->name, [&] {
        mEnvironment->shade(mShaders, *mPlan.environment, *mGBuffer, target, mGBuffer->width(),
                            mGBuffer->height(), background);
    });
    // The shading passes bind their own G-buffer units; restore the frame block.
    mFrameUniforms.bindBase(GL_UNIFORM_BUFFER, gpu::kBindingFrame);
}

void Renderer::renderFrame() {
    mStats.passes.clear();
    if (!mScene) return;
    // A new map (a sequence's next frame, a moved sun) restarts the environment's accumulation.
    if (mScene->environmentMap.get() != mEnvironment->map()) mPending |= kChangeEnvironment;
    if (mPending || mPointMode) {
        if (mPointMode || mGBuffer->width() != mSettings.width ||
            mGBuffer->height() != mSettings.height) {
            resize(mSettings.width, mSettings.height);
            mPending = kChangeAll;
            mPointMode = false;
        }
        if (mPending & kChangeGeometry) {
            mGBuffer->setGeometry(*mScene);
            mBvh.reset();
            ++mGeometryGeneration;
        }
        if (mPending & (kChangeGeometry | kChangeLuminaires)) {
            mGBuffer->setLuminaires(*mScene);
            uploadLuminaires();
        }
        // What every accumulation depends on: the view, the geometry (shadows), the settings.
        bool everything = (mPending & (kChangeCamera | kChangeGeometry | kChangeSettings)) != 0;
        mIndirectDirty = mIndirectDirty || everything;  // the interreflected light's image too
        bool environment = everything || (mPending & kChangeEnvironment) != 0;
        rebuildPlan();
        mPending = kChangeNone;

        gpu::FrameUniforms u{};
        u.viewProj = viewProj();
        u.cameraPos = glm::vec4(glm::vec3(mScene->camera.position), 1.f);
        mFrameUniforms.update(0, sizeof(u), &u);
        mFrameUniforms.bindBase(GL_UNIFORM_BUFFER, gpu::kBindingFrame);
        // Luminaires only mark their own pixels in the G-buffer (GBufferPass), so drawing it again
        // for a moved luminaire leaves what the others shade as it was.
        timed(mStats, "gbuffer", [&] { mGBuffer->execute(mShaders, mSettings.quantity); });
        updateShadowMaps();

        // Each accumulation restarts when what it was shaded for changed: everything after a
        // camera, geometry or settings change, else a luminaire whose record, technique or
        // variant differs (a moved one), the environment when its map changed.
        const float zero[4] = {0.f, 0.f, 0.f, 0.f};
        // A pass under way is dropped (what it shaded so far was kept apart, in `working`).
        for (const Luminaire* lum : mPass)
            if (int st = stepOf(lum); st >= -1) glClearNamedFramebufferfv(accumulationOf(st).workingFbo.id(), GL_COLOR, 0, zero);
        mPass.clear();
        mBandRow = 0;
        auto restart = [&](Accumulation& a, std::vector<std::byte> key) {
            glClearNamedFramebufferfv(a.fbo.id(), GL_COLOR, 0, zero);
            glClearNamedFramebufferfv(a.workingFbo.id(), GL_COLOR, 0, zero);
            a.frames = 0;
            a.samples = 0;
            a.key = std::move(key);
        };
        std::map<const Luminaire*, Accumulation> kept;
        std::vector<const Luminaire*> restarted;
        for (size_t i = 0; i < mPlan.shading.size(); ++i) {
            const ShadeStep& step = mPlan.shading[i];
            const Luminaire* lum = mScene->luminaires[size_t(step.luminaire)].get();
            std::vector<std::byte> key = mRecords[size_t(step.luminaire)];
            for (const std::string& part : {step.name, std::string(step.technique->name)})
                for (char c : part) key.push_back(std::byte(c));
            for (const std::string& d : step.program.defines)
                for (char c : d + ";") key.push_back(std::byte(c));
            const auto* scale = reinterpret_cast<const std::byte*>(&step.unitScale);
            key.insert(key.end(), scale, scale + sizeof step.unitScale);
            Accumulation& a = accumulationOf(int(i));
            if (everything || a.key != key) {
                restart(a, std::move(key));
                a.catchingUp = !everything;
                restarted.push_back(lum);
            }
            kept[lum] = std::move(a);
        }
        mAccumulations = std::move(kept);  // luminaires that left the scene are dropped
        if (mPlan.environment) {
            Accumulation& a = accumulationOf(-1);
            // Its key is its unit conversion: adding or removing a luminaire of the other unit
            // system changes it.
            const auto* scale = reinterpret_cast<const std::byte*>(&mPlan.environment->unitScale);
            std::vector<std::byte> key(scale, scale + sizeof(float));
            if (environment || a.key != key) {
                restart(a, std::move(key));
                a.catchingUp = !everything;
                restarted.push_back(nullptr);
            }
        }
        mStats.converged = false;
        mNeedDisplay = true;
    }

    // Interreflected light: its image again only when the solution or the view changed.
    if (mIndirectUpload) {
        mIndirect->set(mIndirectMesh, mIndirectIrradiance);
        mIndirectUpload = false;
        mIndirectDirty = true;
        mNeedDisplay = true;
    }
    if (mIndirectDirty && mIndirect->hasLight() && !mPointMode) {
        mFrameUniforms.bindBase(GL_UNIFORM_BUFFER, gpu::kBindingFrame);
        setFrameUniforms(0, 1);
        timed(mStats, "indirect", [&] { mIndirect->execute(mShaders, *mGBuffer); });
        mNeedDisplay = true;
    }
    mIndirectDirty = false;
    if (mBandRow == 0 && !mStats.converged) {
        mPass = choosePass();
        mStats.converged = mPass.empty();
    }
    int spp = mPassSpp;
    if (!mStats.converged) {
        int height = mGBuffer->height();
        int rows = height - mBandRow;
        int width = mGBuffer->width();
        if (mSettings.bandBudgetMs > 0.0 && mPixelsPerMs > 0.0)
            rows = std::clamp(int(mPixelsPerMs * mSettings.bandBudgetMs / width), 1, height - mBandRow);
        auto start = std::chrono::steady_clock::now();
        runShading(spp, mBandRow, rows);
        if (mSettings.bandBudgetMs > 0.0) {
            glFinish();  // the band's real cost sets the next band's height
            double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
            // Per pixel, so the rate carries over when the size changes (preview <-> full).
            mPixelsPerMs = double(rows) * double(width) / std::max(ms, 1e-3);
        }
        mBandRow += rows;
        // A step's first pass shows band by band (rows not done yet lack its light); later
        // passes show when complete, so the image never mixes sample counts.
        for (const Luminaire* lum : mPass)
            if (int st = stepOf(lum); st >= -1 && accumulationOf(st).frames == 0) mNeedDisplay = true;
        if (mBandRow >= height) {
            // The pass is complete: each step's working image (the pass's estimate) joins its
            // accumulation weighted by the pass's samples.
            mBandRow = 0;
            const float zero[4] = {0.f, 0.f, 0.f, 0.f};
            glBindVertexArray(mEmptyVao.id());
            for (const Luminaire* lum : mPass)
                if (int st = stepOf(lum); st >= -1) {
                    Accumulation& a = accumulationOf(st);
                    addScaled(mShaders, a.fbo, width, height, {{&a.working, float(spp)}});
                    glClearNamedFramebufferfv(a.workingFbo.id(), GL_COLOR, 0, zero);
                    ++a.frames;
                    a.samples += spp;
                }
            mPass.clear();
            mNeedDisplay = true;
            bool more = false;
            for (int st : planSteps()) more = more || refines(st);
            mStats.converged = !more;
        }
    }
    if (mNeedDisplay) {
        std::vector<ResolvePass::Term> terms;
        bool direct = mSettings.parts != LightParts::Interreflected;
        for (int st : direct ? planSteps() : std::vector<int>{}) {
            // A step's first pass shows as it is shaded; later ones when complete.
            Accumulation& a = accumulationOf(st);
            terms.push_back(a.frames == 0 ? ResolvePass::Term{&a.working, 1.f}
                                          : ResolvePass::Term{&a.texture, 1.f / float(a.samples)});
        }
        if (mIndirect->hasLight() && mSettings.parts != LightParts::Direct)
            terms.push_back(ResolvePass::Term{&mIndirect->image(), 1.f});
        glBindVertexArray(mEmptyVao.id());
        timed(mStats, "resolve",
              [&] { mResolve->execute(mShaders, terms, mGBuffer->texture(gpu::kGBufferEmission)); });
        timed(mStats, "tonemap", [&] {
            mTonemap->execute(mShaders, mResolve->linear(), mResolve->luminance(),
                              mGBuffer->texture(gpu::kGBufferPosition),
                              mGBuffer->texture(gpu::kGBufferEmission), mSettings);
        });
        mNeedDisplay = false;
    }
    // Statistics: the least refined progressive step's passes and samples (what every pixel
    // has at least; deterministic steps hold their one pass), or the one pass of a frame of
    // deterministic steps only.
    int fewest = -1, fewestProgressive = -1, fewestSamples = -1;
    for (int st : planSteps()) {
        const Accumulation& a = accumulationOf(st);
        bool progressive = progressiveStep(st);
        if (fewest < 0 || a.frames < fewest) fewest = a.frames;
        if (progressive && (fewestProgressive < 0 || a.frames < fewestProgressive)) fewestProgressive = a.frames;
        if (progressive && (fewestSamples < 0 || a.samples < fewestSamples)) fewestSamples = a.samples;
    }
    mStats.accumulatedFrames = std::max(fewestProgressive >= 0 ? fewestProgressive : fewest, 0);
    mStats.samplesPerPixel = mPlan.progressive() ? std::max(fewestSamples, 0) : 0;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

const gl::Texture2D& Renderer::displayTexture() const { return mTonemap->display(); }

std::vector<float> Renderer::readLinear() const {
    const gl::Texture2D& t = mResolve->linear();
    int w = t.width(), h = t.height();
    std::vector<float> rgba(size_t(w) * size_t(h) * 4);
    glGetTextureImage(t.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(rgba.size() * sizeof(float)), rgba.data());
    return rgbTopDown(rgba, w, h);
}

std::vector<unsigned char> Renderer::readDisplay() const {
    const gl::Texture2D& t = mTonemap->display();
    int w = t.width(), h = t.height();
    std::vector<unsigned char> rgba(size_t(w) * size_t(h) * 4);
    glGetTextureImage(t.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(rgba.size()), rgba.data());
    return rgbTopDown(rgba, w, h);
}

std::vector<unsigned char> Renderer::readEmitterMask() const {
    const gl::Texture2D& t = mGBuffer->texture(gpu::kGBufferEmission);
    int w = t.width(), h = t.height();
    std::vector<float> rgba(size_t(w) * size_t(h) * 4);
    glGetTextureImage(t.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(rgba.size() * sizeof(float)), rgba.data());
    // Alpha marks a luminaire's pixel from either side (shaders/gbuffer.frag); rows bottom-up.
    std::vector<unsigned char> mask(size_t(w) * size_t(h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            mask[size_t(y) * size_t(w) + size_t(x)] = rgba[(size_t(h - 1 - y) * size_t(w) + size_t(x)) * 4 + 3] > 0.5f;
    return mask;
}

std::vector<glm::vec3> Renderer::probe(const Scene& scene, const std::vector<glm::vec3>& points,
                                       const std::vector<glm::vec3>& normals, int spp, int width) {
    mScene = &scene;
    int n = std::max<int>(1, int(points.size()));
    int w = width > 0 ? width : n;
    int h = (n + w - 1) / w;
    resize(w, h);
    mPointMode = true;
    mStats = FrameStats{};
    mGBuffer->uploadPoints(points, normals, w);
    uploadLuminaires();
    mPlan = planFrame(scene, viewProj(), mSettings.techniqueOverride, Quantity::Radiance,
                      mSettings.environmentTechnique);
    // Probes measure unshadowed irradiance on a Lambertian receiver: no shadow or glossy variant.
    auto unshadowed = [](ShadeStep& s) {
        std::erase_if(s.program.defines, [](const std::string& d) {
            return d == "SHADOWS" || d == "SHADOW_MAPS" || d == "GLOSSY";
        });
        s.shadows = false;
        s.shadowMaps = false;
    };
    for (ShadeStep& s : mPlan.shading) {
        unshadowed(s);
        s.progressive = s.technique->progressive;
    }
    if (mPlan.environment) unshadowed(*mPlan.environment);
    mEnvironment->setMap(mPlan.environment ? scene.environmentMap : nullptr,
                         mSettings.environmentFaceSize);
    mPlan.needsBvh = false;
    const float zero[4] = {0.f, 0.f, 0.f, 0.f};
    glClearNamedFramebufferfv(mAccumFbo.id(), GL_COLOR, 0, zero);
    int perFrame = std::max(1, std::min(spp, 256));
    int frames = mPlan.progressive() ? std::max(1, (spp + perFrame - 1) / perFrame) : 1;
    for (mFrames = 0; mFrames < frames; ++mFrames) runShading(perFrame, 0, h);
    std::vector<glm::vec4> accum(static_cast<size_t>(w) * size_t(h), glm::vec4(0.f));
    glGetTextureImage(mAccum.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(accum.size() * sizeof(glm::vec4)),
                      accum.data());
    std::vector<glm::vec3> out(points.size());
    for (size_t i = 0; i < points.size(); ++i) out[i] = glm::vec3(accum[i]) / float(frames);
    mPending = kChangeAll;
    return out;
}

int Renderer::pickLuminaire(const Scene& scene, double x, double y) const {
    glm::dmat4 inv = glm::inverse(glm::dmat4(viewProj()));
    double ndcX = 2.0 * x / mSettings.width - 1.0;
    double ndcY = 1.0 - 2.0 * y / mSettings.height;
    glm::dvec4 a = inv * glm::dvec4(ndcX, ndcY, -1.0, 1.0);
    glm::dvec4 b = inv * glm::dvec4(ndcX, ndcY, 1.0, 1.0);
    glm::dvec3 origin = glm::dvec3(a) / a.w;
    glm::dvec3 dir = glm::normalize(glm::dvec3(b) / b.w - origin);
    int best = -1;
    double bestT = 1e300;
    for (size_t i = 0; i < scene.luminaires.size(); ++i) {
        std::vector<glm::dvec3> poly = scene.luminaires[i]->outline();
        for (size_t k = 1; k + 1 < poly.size(); ++k) {
            // Moller-Trumbore against the fan triangle (poly[0], poly[k], poly[k+1]).
            glm::dvec3 e1 = poly[k] - poly[0], e2 = poly[k + 1] - poly[0];
            glm::dvec3 pv = glm::cross(dir, e2);
            double det = glm::dot(e1, pv);
            if (std::abs(det) < 1e-18) continue;
            glm::dvec3 tv = origin - poly[0];
            double u = glm::dot(tv, pv) / det;
            glm::dvec3 qv = glm::cross(tv, e1);
            double v = glm::dot(dir, qv) / det;
            double t = glm::dot(e2, qv) / det;
            if (u >= 0 && v >= 0 && u + v <= 1 && t > 0 && t < bestT) {
                bestT = t;
                best = int(i);
            }
        }
    }
    return best;
}

}  // namespace candela
