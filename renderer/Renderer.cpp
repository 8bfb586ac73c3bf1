#include "renderer/Renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "renderer/ImageFile.h"
#include "renderer/PassTimer.h"
#include "renderer/ProgramVariants.h"
#include "renderer/passes/GBufferPass.h"
#include "renderer/passes/IndirectPass.h"
#include "renderer/passes/ResolvePass.h"
#include "renderer/passes/SourcePass.h"
#include "renderer/passes/TonemapPass.h"
#include "scene/Bvh.h"
#include "shaders/shared/GpuTypes.h"

namespace candela {

namespace {

const float kZero[4] = {0.f, 0.f, 0.f, 0.f};

void append(std::vector<std::byte>& key, const std::string& text) {
    for (char c : text) key.push_back(std::byte(c));
}

}  // namespace

Renderer::Renderer(ShaderLibrary& shaders)
    : mShaders(shaders),
      mGBuffer(std::make_unique<GBufferPass>()),
      mResolve(std::make_unique<ResolvePass>()),
      mTonemap(std::make_unique<TonemapPass>()),
      mIndirect(std::make_unique<IndirectPass>()),
      mFrameUniforms(sizeof(gpu::FrameUniforms), nullptr) {}

Renderer::~Renderer() = default;

void Renderer::update(const Scene& scene, unsigned changes) {
    mScene = &scene;
    mPending |= changes;
}

void Renderer::setSettings(const RenderSettings& s) {
    const RenderSettings& o = mSettings;
    bool restart =
        s.width != o.width || s.height != o.height || s.samplesPerFrame != o.samplesPerFrame ||
        s.maxSamples != o.maxSamples || s.techniqueOverride != o.techniqueOverride ||
        s.quantity != o.quantity || s.environmentTechnique != o.environmentTechnique ||
        s.environmentFaceSize != o.environmentFaceSize || !(s.shadowMaps == o.shadowMaps);
    bool display = s.toneMap != o.toneMap || s.exposure != o.exposure ||
                   s.fixedAverage != o.fixedAverage || s.legend != o.legend || s.parts != o.parts;
    mSettings = s;
    mSettings.samplesPerFrame = std::max(1, s.samplesPerFrame);
    if (restart) mPending |= kChangeSettings;
    if (display) mNeedDisplay = true;
}

void Renderer::setIndirect(std::shared_ptr<const RadiosityMesh> mesh,
                           std::vector<glm::vec3> vertexIrradiance) {
    mIndirectMesh = std::move(mesh);
    mIndirectIrradiance = std::move(vertexIrradiance);
    mIndirectUpload = true;
}

bool Renderer::hasIndirect() const {
    return mIndirectUpload ? mIndirectMesh != nullptr : mIndirect->hasLight();
}

glm::mat4 Renderer::viewProj() const {
    return cameraViewProj(mScene ? mScene->camera : Camera{},
                          double(mSettings.width) / double(std::max(1, mSettings.height)));
}

const SourcePass* Renderer::sourcePass(const Luminaire* source) const {
    auto it = mSourcePasses.find(source);
    return it == mSourcePasses.end() ? nullptr : it->second.pass.get();
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
    mPass.clear();
}

std::vector<int> Renderer::planSteps() const {
    std::vector<int> steps;
    for (size_t i = 0; i < mPlan.shading.size(); ++i) steps.push_back(int(i));
    return steps;
}

Renderer::Accumulation& Renderer::accumulationOf(int step) {
    Accumulation& a = mAccumulations[sourceOf(step)];
    if (a.texture.width() != mGBuffer->width() || a.texture.height() != mGBuffer->height()) {
        a.texture = gl::Texture2D(mGBuffer->width(), mGBuffer->height(), GL_RGBA32F);
        a.fbo = gl::Framebuffer({&a.texture}, nullptr);
        a.working = gl::Texture2D(mGBuffer->width(), mGBuffer->height(), GL_RGBA32F);
        a.workingFbo = gl::Framebuffer({&a.working}, nullptr);
        glClearNamedFramebufferfv(a.fbo.id(), GL_COLOR, 0, kZero);
        glClearNamedFramebufferfv(a.workingFbo.id(), GL_COLOR, 0, kZero);
        a.frames = 0;
        a.samples = 0;
        a.key.clear();
    }
    return a;
}

int Renderer::stepOf(const Luminaire* source) const {
    for (size_t i = 0; i < mPlan.shading.size(); ++i)
        if (sourceOf(int(i)) == source) return int(i);
    return -1;
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
        pass.push_back(sourceOf(st));
    }
    // A source that restarted alone (a luminaire that moved) catches up with the others in
    // passes of up to catchUpPasses passes' samples (RenderSettings::catchUpPasses).
    int spf = mSettings.samplesPerFrame;
    mPassSpp = spf;
    if (catchUp && !pass.empty())
        mPassSpp = std::clamp(ahead - std::max(fewest, 0), spf,
                              std::max(1, mSettings.catchUpPasses) * spf);
    if (mSettings.maxSamples > 0)
        mPassSpp = std::max(1, std::min(mPassSpp, mSettings.maxSamples - std::max(fewest, 0)));
    return pass;
}

bool Renderer::sourcesChanged() const {
    std::vector<const Luminaire*> sources = mScene->sources();
    if (sources.size() != mPlan.shading.size()) return true;
    for (size_t i = 0; i < sources.size(); ++i)
        if (sources[i] != mPlan.shading[i].source) return true;
    return false;
}

void Renderer::syncSources(bool allRecords) {
    // Each source keeps its pass; a new one takes the pass of a source of its kind that left
    // (the environment's next map keeps its tables' buffers and Havran's filter), else a new one.
    std::map<const Luminaire*, KindPass> passes;
    std::map<const Luminaire*, std::vector<std::byte>> records;
    std::vector<const Luminaire*> fresh;
    for (const ShadeStep& step : mPlan.shading) {
        auto it = mSourcePasses.find(step.source);
        if (it == mSourcePasses.end()) {
            fresh.push_back(step.source);
            continue;
        }
        passes[step.source] = std::move(it->second);
        mSourcePasses.erase(it);
        records[step.source] = std::move(mRecords[step.source]);
    }
    for (const Luminaire* source : fresh) {
        KindPass& entry = passes[source];
        entry.kind = source->kind();
        for (auto it = mSourcePasses.begin(); it != mSourcePasses.end(); ++it)
            if (it->second.kind == entry.kind) {
                entry.pass = std::move(it->second.pass);
                mSourcePasses.erase(it);
                break;
            }
        if (!entry.pass) entry.pass = makeSourcePass(source->kind());
    }
    for (const ShadeStep& step : mPlan.shading) {
        bool isNew = std::find(fresh.begin(), fresh.end(), step.source) != fresh.end();
        if (!allRecords && !isNew) continue;
        records[step.source] = gpuData(*step.source);
        passes[step.source].pass->setSource(*step.source, records[step.source]);
    }
    mSourcePasses = std::move(passes);  // the passes of sources that left are dropped
    mRecords = std::move(records);
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

const ShadowGeometry& Renderer::shadowGeometry() {
    if (mShadowGeometryGeneration != mGeometryGeneration) {
        mShadowGeometry.set(*mScene);
        mShadowGeometryGeneration = mGeometryGeneration;
    }
    return mShadowGeometry;
}

void Renderer::runShading(int spp, int row0, int rows) {
    int height = mGBuffer->height();
    bool band = row0 > 0 || rows < height;
    // Probe mode: every step into mAccum, pass mFrames. Else the pass's steps, each into its
    // own accumulation with its own pass count (the seeds of its random numbers).
    std::vector<int> steps;
    if (mPointMode) {
        steps = planSteps();
    } else {
        for (const Luminaire* source : mPass)
            if (int st = stepOf(source); st >= 0) steps.push_back(st);
    }
    SourceContext context{mShaders,
                          mStats,
                          mTimer,
                          *mGBuffer,
                          mSettings,
                          [this]() -> const ShadowGeometry& { return shadowGeometry(); },
                          mGeometryGeneration,
                          mPointMode};
    for (int st : steps) {
        const ShadeStep& step = mPlan.shading[size_t(st)];
        SourcePass& pass = *mSourcePasses.at(step.source).pass;
        Accumulation* acc = mPointMode ? nullptr : &accumulationOf(st);
        int frame = mPointMode ? mFrames : acc->frames;
        const gl::Framebuffer& target = mPointMode ? mAccumFbo : acc->workingFbo;
        glDisable(GL_SCISSOR_TEST);
        setFrameUniforms(frame, spp);
        if (row0 == 0) pass.prepare(step, context, frame, spp);
        if (mBvh) {
            mBvhNodes.bindBase(GL_SHADER_STORAGE_BUFFER, gpu::kBindingBvhNodes);
            mBvhTris.bindBase(GL_SHADER_STORAGE_BUFFER, gpu::kBindingBvhTris);
        }
        mFrameUniforms.bindBase(GL_UNIFORM_BUFFER, gpu::kBindingFrame);
        glBindVertexArray(mEmptyVao.id());
        if (band) {
            // GL counts rows from the bottom; bands go from the top of the image down.
            glEnable(GL_SCISSOR_TEST);
            glScissor(0, height - row0 - rows, mGBuffer->width(), rows);
        }
        mTimer.timed(mStats, step.name, [&] { pass.shade(step, context, target); });
    }
    glDisable(GL_SCISSOR_TEST);
}

void Renderer::applyChanges() {
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
    if (mPending & (kChangeGeometry | kChangeLuminaires)) mGBuffer->setLuminaires(*mScene);
    // What every accumulation depends on: the view, the geometry (shadows), the settings.
    bool everything = (mPending & (kChangeCamera | kChangeGeometry | kChangeSettings)) != 0;
    mIndirectDirty = mIndirectDirty || everything;  // the interreflected light's image too
    mPlan = planFrame(*mScene, viewProj(), techniqueList(mSettings), mSettings.quantity);
    // Every record again when luminaires or geometry changed; else only those of new sources.
    syncSources((mPending & (kChangeGeometry | kChangeLuminaires)) != 0);
    if (mPlan.needsBvh && !mBvh) {
        mBvh = std::make_unique<Bvh>(Bvh::build(*mScene));
        auto bytes = [](const auto& v) { return GLsizeiptr(v.size() * sizeof(v[0])); };
        std::vector<gpu::BvhNode> nodes = mBvh->gpuNodes();  // then the bodies' boxes
        mBvhNodes = gl::Buffer(bytes(nodes), nodes.data(), 0);
        mBvhTris = gl::Buffer(bytes(mBvh->triangles), mBvh->triangles.data(), 0);
    }
    mPending = kChangeNone;

    gpu::FrameUniforms u{};
    u.viewProj = viewProj();
    u.cameraPos = glm::vec4(glm::vec3(mScene->camera.position), 1.f);
    mFrameUniforms.update(0, sizeof(u), &u);
    mFrameUniforms.bindBase(GL_UNIFORM_BUFFER, gpu::kBindingFrame);
    // Luminaires only mark their own pixels in the G-buffer (GBufferPass), so drawing it again
    // for a moved luminaire leaves what the others shade as it was.
    mTimer.timed(mStats, "gbuffer", [&] { mGBuffer->execute(mShaders, mSettings.quantity); });
    restartAccumulations(everything);
    mStats.converged = false;
    mNeedDisplay = true;
}

void Renderer::restartAccumulations(bool everything) {
    // A pass under way is dropped (what it shaded so far was kept apart, in `working`).
    for (const Luminaire* source : mPass)
        if (int st = stepOf(source); st >= 0)
            glClearNamedFramebufferfv(accumulationOf(st).workingFbo.id(), GL_COLOR, 0, kZero);
    mPass.clear();
    mBandRow = 0;
    // Each accumulation restarts when what it was shaded for changed: everything after a
    // camera, geometry or settings change, else a source whose record, technique, variant or
    // unit conversion differs (a moved luminaire); a new source (the environment's next map)
    // starts its own.
    std::map<const Luminaire*, Accumulation> kept;
    for (int st : planSteps()) {
        const ShadeStep& step = mPlan.shading[size_t(st)];
        std::vector<std::byte> key = mRecords[step.source];
        append(key, step.name);
        append(key, std::string(step.technique->name));
        for (const std::string& d : step.program.defines) append(key, d + ";");
        const auto* scale = reinterpret_cast<const std::byte*>(&step.unitScale);
        key.insert(key.end(), scale, scale + sizeof step.unitScale);
        Accumulation& a = accumulationOf(st);
        if (everything || a.key != key) {
            glClearNamedFramebufferfv(a.fbo.id(), GL_COLOR, 0, kZero);
            glClearNamedFramebufferfv(a.workingFbo.id(), GL_COLOR, 0, kZero);
            a.frames = 0;
            a.samples = 0;
            a.key = std::move(key);
            a.catchingUp = !everything;
        }
        kept[step.source] = std::move(a);
    }
    mAccumulations = std::move(kept);  // sources that left are dropped
}

void Renderer::updateIndirect() {
    if (mIndirectUpload) {
        mIndirect->set(mIndirectMesh, mIndirectIrradiance);
        mIndirectUpload = false;
        mIndirectDirty = true;
        mNeedDisplay = true;
    }
    if (mIndirectDirty && mIndirect->hasLight() && !mPointMode) {
        mFrameUniforms.bindBase(GL_UNIFORM_BUFFER, gpu::kBindingFrame);
        setFrameUniforms(0, 1);
        mTimer.timed(mStats, "indirect", [&] { mIndirect->execute(mShaders, *mGBuffer); });
        mNeedDisplay = true;
    }
    mIndirectDirty = false;
}

void Renderer::shadeBand() {
    if (mBandRow == 0) {
        mPass = choosePass();
        mStats.converged = mPass.empty();
        if (mStats.converged) return;
    }
    int spp = mPassSpp;
    int height = mGBuffer->height(), width = mGBuffer->width();
    int left = height - mBandRow;
    int rows = mSettings.bandRows > 0         ? std::min(mSettings.bandRows, left)
               : mSettings.bandBudgetMs > 0.0 ? bandRows(width, left)
                                              : left;
    auto start = std::chrono::steady_clock::now();
    bool first = mBandRow == 0;  // it also prepares the pass (shadow maps): not a band's cost
    runShading(spp, mBandRow, rows);
    if (mSettings.bandBudgetMs > 0.0) {
        glFinish();  // the band's real cost sizes the next bands
        double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        if (!first || mBands.empty()) timeBand(double(rows) * double(width), ms);
    }
    mBandRow += rows;
    // A step's first pass shows band by band (rows not done yet lack its light); later passes
    // show when complete, so the image never mixes sample counts.
    for (const Luminaire* source : mPass)
        if (int st = stepOf(source); st >= 0 && accumulationOf(st).frames == 0) mNeedDisplay = true;
    if (mBandRow < height) return;
    // The pass is complete: each step's working image (the pass's estimate) joins its
    // accumulation weighted by the pass's samples.
    mBandRow = 0;
    glBindVertexArray(mEmptyVao.id());
    for (const Luminaire* source : mPass)
        if (int st = stepOf(source); st >= 0) {
            Accumulation& a = accumulationOf(st);
            addScaled(mShaders, a.fbo, width, height, {{&a.working, float(spp)}});
            glClearNamedFramebufferfv(a.workingFbo.id(), GL_COLOR, 0, kZero);
            ++a.frames;
            a.samples += spp;
        }
    mPass.clear();
    mNeedDisplay = true;
    bool more = false;
    for (int st : planSteps()) more = more || refines(st);
    mStats.converged = !more;
}

void Renderer::timeBand(double pixels, double ms) {
    mBands.push_back({pixels, std::max(ms, 1e-3)});
    if (mBands.size() > kBandHistory) mBands.erase(mBands.begin());
    double n = double(mBands.size()), sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
    double fewest = 1e300;  // the lowest cost per pixel: an upper bound of the marginal cost
    for (const BandTime& b : mBands) {
        sx += b.pixels;
        sy += b.ms;
        sxx += b.pixels * b.pixels;
        sxy += b.pixels * b.ms;
        fewest = std::min(fewest, b.ms / b.pixels);
    }
    double variance = sxx / n - (sx / n) * (sx / n);
    double slope = variance > 1e-6 * (sxx / n) ? (sxy / n - sx / n * sy / n) / variance : 0.0;
    // A fit that the noise turned flat or negative says nothing of the marginal cost: the
    // cheapest band's cost per pixel bounds it from above (a band never costs less than its
    // pixels), and the fixed cost is what the bands took beyond it on average.
    mMsPerPixel = slope > 0.0 ? std::min(slope, fewest) : fewest;
    mBandOverheadMs = std::max(0.0, sy / n - mMsPerPixel * sx / n);
}

int Renderer::bandRows(int width, int left) {
    if (!(mMsPerPixel > 0.0)) return left;  // nothing measured yet: the whole pass at once
    double perRow = mMsPerPixel * width;
    // Within the budget after the band's fixed cost. Where that cost and showing the band (the
    // resolve and tone mapping of the whole image) alone fill the budget, as much shading as
    // they cost (half of each frame's time shades), rather than a row a frame: on llvmpipe a
    // pass of 700 rows took 700 frames of almost nothing but showing them.
    double fixed = mBandOverheadMs + mDisplayMs;
    double work = std::max(mSettings.bandBudgetMs - fixed, fixed);
    int rows = std::max(1, int(work / perRow));
    if (++mBandCount % 2 == 0) rows += std::max(1, rows / 2);  // two sizes for the fit
    return std::clamp(rows, 1, left);
}

void Renderer::resolve() {
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
    mTimer.timed(mStats, "resolve", [&] {
        mResolve->execute(mShaders, terms, mGBuffer->texture(gpu::kGBufferEmission));
    });
    mTimer.timed(mStats, "tonemap", [&] {
        mTonemap->execute(mShaders, mResolve->linear(), mResolve->luminance(),
                          mGBuffer->texture(gpu::kGBufferPosition),
                          mGBuffer->texture(gpu::kGBufferEmission), mSettings);
    });
    mNeedDisplay = false;
}

void Renderer::updateStatistics() {
    // The least refined progressive step's passes and samples (what every pixel has at least;
    // deterministic steps hold their one pass), or the one pass of a frame of deterministic
    // steps only.
    int fewest = -1, fewestProgressive = -1, fewestSamples = -1;
    for (int st : planSteps()) {
        const Accumulation& a = accumulationOf(st);
        bool progressive = progressiveStep(st);
        if (fewest < 0 || a.frames < fewest) fewest = a.frames;
        if (progressive && (fewestProgressive < 0 || a.frames < fewestProgressive))
            fewestProgressive = a.frames;
        if (progressive && (fewestSamples < 0 || a.samples < fewestSamples))
            fewestSamples = a.samples;
    }
    mStats.accumulatedFrames = std::max(fewestProgressive >= 0 ? fewestProgressive : fewest, 0);
    mStats.samplesPerPixel = mPlan.progressive() ? std::max(fewestSamples, 0) : 0;
}

void Renderer::allocateImages() {
    if (mGBuffer->width() == mSettings.width && mGBuffer->height() == mSettings.height) return;
    resize(mSettings.width, mSettings.height);
    mPending = kChangeAll;
}

void Renderer::renderFrame() {
    mStats.passes.clear();
    mTimer.collect();
    if (!mScene) return;
    if (!mPointMode && sourcesChanged()) mPending |= kChangeSources;
    if (mPending || mPointMode) applyChanges();
    updateIndirect();
    if (!mStats.converged) shadeBand();
    if (mNeedDisplay) {
        auto start = std::chrono::steady_clock::now();
        resolve();
        if (mSettings.bandBudgetMs > 0.0) {
            glFinish();  // what showing a band costs sizes the bands (bandRows)
            mDisplayMs =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                    .count();
        }
    }
    updateStatistics();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

const gl::Texture2D& Renderer::displayTexture() const {
    return mTonemap->display();
}

std::vector<float> Renderer::readLinear() const {
    const gl::Texture2D& t = mResolve->linear();
    int w = t.width(), h = t.height();
    std::vector<float> rgba(size_t(w) * size_t(h) * 4);
    glGetTextureImage(t.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(rgba.size() * sizeof(float)),
                      rgba.data());
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
    glGetTextureImage(t.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(rgba.size() * sizeof(float)),
                      rgba.data());
    // Alpha marks a luminaire's pixel from either side (shaders/gbuffer.frag); rows bottom-up.
    std::vector<unsigned char> mask(size_t(w) * size_t(h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            mask[size_t(y) * size_t(w) + size_t(x)] =
                rgba[(size_t(h - 1 - y) * size_t(w) + size_t(x)) * 4 + 3] > 0.5f;
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
    mPlan = planFrame(scene, viewProj(), techniqueList(mSettings), Quantity::Radiance);
    // Probes measure unshadowed irradiance on a Lambertian receiver: no shadow or glossy variant.
    for (ShadeStep& s : mPlan.shading) {
        s.program = programs::shading(*s.technique, false, false, false);
        s.shadows = false;
        s.shadowMaps = false;
        s.progressive = s.technique->progressive;
    }
    mPlan.needsBvh = false;
    syncSources(true);
    glClearNamedFramebufferfv(mAccumFbo.id(), GL_COLOR, 0, kZero);
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
