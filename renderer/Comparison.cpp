#include "renderer/Comparison.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "renderer/gl/GlFunctions.h"

namespace candela {

namespace {

/// The reference's environment technique (an override list's "reference" would name the
/// environment's CPU-only quadrature).
constexpr const char* kReferenceEnvironment = "balanced-mis";
/// Display re-tone-mapped when the reference's mean moves by more than this fraction.
constexpr double kToneAverageTolerance = 0.005;

/// Shading work of a pass: what a technique costs (the G-buffer, resolve and tone mapping are
/// the same for every pane and are left out).
bool countsAsShading(const std::string& pass) {
    return pass != "gbuffer" && pass != "resolve" && pass != "tonemap";
}

/// CIELAB of an sRGB8 image, float per channel.
std::vector<glm::vec3> labImage(const std::vector<unsigned char>& srgb) {
    std::vector<glm::vec3> out(srgb.size() / 3);
    for (size_t i = 0; i < out.size(); ++i) out[i] = glm::vec3(lab(&srgb[3 * i]));
    return out;
}

double meanDistance(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
    size_t n = std::min(a.size(), b.size());
    double sum = 0.0;
    for (size_t i = 0; i < n; ++i) sum += double(glm::length(a[i] - b[i]));
    return n ? sum / double(n) : 0.0;
}

bool powerOfTwo(int n) {
    return n > 0 && (n & (n - 1)) == 0;
}

}  // namespace

std::string techniqueSummary(const FramePlan& plan) {
    std::vector<std::string> names;
    auto add = [&](std::string_view name) {
        if (std::find(names.begin(), names.end(), name) == names.end()) names.emplace_back(name);
    };
    // The luminaires' techniques first, then a source at infinity's (the environment's).
    for (bool atInfinity : {false, true})
        for (const ShadeStep& step : plan.shading)
            if (step.atInfinity == atInfinity) add(step.technique->name);
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : " + ") + n;
    return out.empty() ? "nothing to shade" : out;
}

Comparison::Comparison(ShaderLibrary& shaders) : mShaders(shaders) {
    mReference.renderer = std::make_unique<Renderer>(shaders);
    mReference.renderer->setExactTimes(true);  // accuracy versus time: each frame's own times
}

Comparison::~Comparison() = default;

RenderSettings Comparison::paneSettings(size_t index) const {
    RenderSettings s = mShared;
    const PaneSpec& spec = mPanes[index].spec;
    s.techniqueOverride = spec.technique;
    s.maxSamples = std::max(1, spec.samples);
    s.samplesPerFrame = std::clamp(mShared.samplesPerFrame, 1, s.maxSamples);
    // Independent of each other and of the reference (the noise removal assumes it).
    s.seed = mShared.seed * 7919u + 101u + uint32_t(index);
    if (mToneAverage > 0.0) s.fixedAverage = float(mToneAverage);
    return s;
}

RenderSettings Comparison::referenceSettings() const {
    RenderSettings s = mShared;
    s.techniqueOverride = kReferenceTechniques;
    s.environmentTechnique = kReferenceEnvironment;
    s.maxSamples = std::max(1, mReferenceSamples);
    s.samplesPerFrame = std::clamp(mShared.samplesPerFrame, 1, s.maxSamples);
    s.seed = mShared.seed * 7919u + 1000003u;
    if (mToneAverage > 0.0) s.fixedAverage = float(mToneAverage);
    return s;
}

void Comparison::configure(const std::vector<PaneSpec>& panes, const RenderSettings& shared,
                           int referenceSamples) {
    RenderSettings s = shared;
    s.techniqueOverride.clear();
    s.environmentTechnique.clear();
    s.maxSamples = 0;
    s.bandBudgetMs = 0.0;
    // What makes every image a different one: the size, the quantity, the sampling settings.
    bool restartAll = s.width != mShared.width || s.height != mShared.height ||
                      s.quantity != mShared.quantity ||
                      s.samplesPerFrame != mShared.samplesPerFrame || s.seed != mShared.seed ||
                      s.environmentFaceSize != mShared.environmentFaceSize ||
                      !(s.shadowMaps == mShared.shadowMaps);
    bool toneChanged = s.toneMap != mShared.toneMap || s.exposure != mShared.exposure ||
                       s.legend != mShared.legend;
    mShared = s;
    if (referenceSamples != mReferenceSamples || restartAll) {
        mReferenceSamples = referenceSamples;
        restartReference();
    }
    mReference.renderer->setSettings(referenceSettings());
    size_t count = std::clamp<size_t>(panes.size(), 1, 4);
    if (mPanes.size() > count) mPanes.resize(count);
    while (mPanes.size() < count) {
        Pane pane;
        pane.renderer = std::make_unique<Renderer>(mShaders);
        pane.renderer->setExactTimes(true);
        if (mScene) pane.renderer->update(*mScene, kChangeAll);
        mPanes.push_back(std::move(pane));
    }
    for (size_t i = 0; i < count; ++i) {
        Pane& pane = mPanes[i];
        if (!(pane.spec == panes[i]) || restartAll) {
            pane.spec = panes[i];
            restartPane(pane);
        }
        pane.renderer->setSettings(paneSettings(i));
    }
    if (toneChanged) remeasureAll();  // Delta E is taken through the tone mapping
}

void Comparison::update(const Scene& scene, unsigned changes) {
    bool newScene = mScene != &scene;
    mScene = &scene;
    if (changes == kChangeNone && !newScene) return;
    // Every image starts over (kChangeSettings restarts every accumulation of a renderer): a
    // pane's GPU time is that of the image it shows, not of a kept part of it.
    unsigned all = newScene ? kChangeAll : changes | kChangeSettings;
    mReference.renderer->update(scene, all);
    restartReference();
    for (Pane& pane : mPanes) {
        pane.renderer->update(scene, all);
        restartPane(pane);
    }
}

void Comparison::restartPane(Pane& pane) {
    pane.result = PaneResult{};
    pane.passGpuMs = 0.0;
    pane.frames = 0;
    pane.snapshotFrames = 0;
    pane.displayStale = false;
    pane.nextSnapshot = 1;
    pane.snapshots.clear();
    pane.errorRgb.clear();
    pane.errorTexture = gl::Texture2D();
}

void Comparison::restartReference() {
    Reference& r = mReference;
    r.frames = 0;
    r.spp = 0;
    r.gpuMs = 0.0;
    r.image.set({});
    r.imageFrames = 0;
    r.displayStale = false;
    r.half.clear();
    r.halfFrames = 0;
    r.noise2 = -1.0;
    r.noiseSpp = 0;
    r.emitters.clear();
    mToneAverage = 0.0;
}

bool Comparison::panesDone() const {
    return std::all_of(mPanes.begin(), mPanes.end(), [](const Pane& p) { return p.result.done; });
}

bool Comparison::referenceDone() const {
    return mReference.renderer->converged() && !mReference.image.empty();
}

double Comparison::referenceNoise() const {
    const Reference& r = mReference;
    if (r.noise2 < 0.0 || r.spp <= 0) return std::numeric_limits<double>::quiet_NaN();
    // Noise variance goes as 1 / samples.
    return std::sqrt(r.noise2 * double(r.noiseSpp) / double(r.spp));
}

void Comparison::setErrorScale(float scale) {
    scale = std::clamp(scale, 1e-4f, 100.f);
    if (scale == mErrorScale) return;
    mErrorScale = scale;
    for (Pane& pane : mPanes)
        if (!pane.snapshots.empty() && pane.result.measured)
            updateErrorMap(pane, pane.snapshots.back());
}

bool Comparison::advance(Renderer& r, int& frames, double& gpuMs) {
    r.renderFrame();
    const FrameStats& stats = r.stats();
    for (const PassTiming& p : stats.passes) {
        if (p.name == "gbuffer") gpuMs = 0.0;  // a new accumulation
    }
    for (const PassTiming& p : stats.passes)
        if (countsAsShading(p.name)) gpuMs += p.gpuMs;
    bool completed = stats.accumulatedFrames != frames;
    frames = stats.accumulatedFrames;
    return completed;
}

void Comparison::step(double budgetMs) {
    if (!mScene) return;
    size_t active = 0;
    for (const Pane& pane : mPanes) active += pane.result.done ? 0 : 1;
    bool referenceActive = !mReference.renderer->converged() || mReference.image.empty();
    size_t shares = active + (referenceActive ? 1 : 0);
    double share = shares > 0 ? budgetMs / double(shares) : 0.0;

    for (size_t i = 0; i < mPanes.size(); ++i) {
        Pane& pane = mPanes[i];
        if (pane.result.done) {
            // Shaded already: only tone-mapped again against a newer average (no shading pass).
            if (pane.displayStale) pane.renderer->renderFrame();
            pane.displayStale = false;
            continue;
        }
        pane.displayStale = false;
        RenderSettings s = paneSettings(i);
        s.bandBudgetMs = share;
        pane.renderer->setSettings(s);
        if (!advance(*pane.renderer, pane.frames, pane.result.gpuMs)) continue;
        const FrameStats& stats = pane.renderer->stats();
        pane.passGpuMs = pane.result.gpuMs;
        pane.result.spp = stats.samplesPerPixel;
        pane.result.done = pane.renderer->converged();
        // Measured at 1, 2, 4, ... passes and at the last one.
        if (pane.frames >= pane.nextSnapshot || pane.result.done) {
            while (pane.nextSnapshot <= pane.frames) pane.nextSnapshot *= 2;
            snapshot(pane);
        }
    }
    if (!referenceActive && mReference.displayStale) mReference.renderer->renderFrame();
    mReference.displayStale = false;
    if (referenceActive) {
        Reference& r = mReference;
        RenderSettings s = referenceSettings();
        s.bandBudgetMs = share;
        r.renderer->setSettings(s);
        if (advance(*r.renderer, r.frames, r.gpuMs)) referenceAdvanced();
    }
}

void Comparison::snapshot(Pane& pane) {
    Snapshot shot;
    shot.point.timeMs = pane.passGpuMs;  // the image is that of the last complete pass
    shot.point.spp = pane.result.spp;
    shot.image.set(pane.renderer->readLinear());
    pane.snapshotFrames = pane.frames;
    pane.snapshots.push_back(std::move(shot));
    if (mReference.image.empty()) return;  // measured when the reference has a pass
    measure(pane, pane.snapshots.back());
    pane.result.series.push_back(pane.snapshots.back().point);
    updateErrorMap(pane, pane.snapshots.back());
}

void Comparison::referenceAdvanced() {
    Reference& r = mReference;
    const FrameStats& stats = r.renderer->stats();
    r.spp = stats.samplesPerPixel;
    bool done = r.renderer->converged();
    bool first = r.image.empty();
    // Measured again when its passes double (and at the first and the last): each pane's
    // measurements then use the better reference without paying for them at every pass.
    if (!first && !done && !powerOfTwo(r.frames)) return;
    r.image.set(r.renderer->readLinear());
    r.imageFrames = r.frames;
    if (first) r.emitters = r.renderer->readEmitterMask();
    if (powerOfTwo(r.frames)) {
        if (!r.half.empty() && r.halfFrames * 2 == r.frames) {
            // ref_N - ref_(N/2) = (B - A) / 2 for the two halves A, B of the samples: its
            // expected square is the variance of ref_N itself.
            double e = relRmse(r.half, r.image.linear(), r.emitters);
            r.noise2 = e * e;
            r.noiseSpp = r.spp;
        }
        r.half = r.image.linear();
        r.halfFrames = r.frames;
    }
    if (!r.renderer->plan().progressive()) {
        r.noise2 = 0.0;  // deterministic: exact for its model
        r.noiseSpp = std::max(1, r.spp);
    }
    setToneAverage(meanLuminance(r.image.linear()));
    remeasureAll();
}

void Comparison::setToneAverage(double average) {
    if (!(average > 0.0) || !std::isfinite(average)) return;
    if (mToneAverage > 0.0 &&
        std::abs(average - mToneAverage) <= kToneAverageTolerance * mToneAverage)
        return;
    mToneAverage = average;
    mReference.renderer->setSettings(referenceSettings());
    mReference.displayStale = true;
    for (size_t i = 0; i < mPanes.size(); ++i) {
        mPanes[i].renderer->setSettings(paneSettings(i));
        mPanes[i].displayStale = true;
    }
}

void Comparison::measureNow() {
    Reference& r = mReference;
    if (r.frames > 0 && r.frames != r.imageFrames) {
        r.image.set(r.renderer->readLinear());
        r.imageFrames = r.frames;
        if (r.emitters.empty()) r.emitters = r.renderer->readEmitterMask();
        setToneAverage(meanLuminance(r.image.linear()));
        remeasureAll();
    }
    for (Pane& pane : mPanes) {
        pane.result.spp = pane.renderer->stats().samplesPerPixel;
        if (pane.frames > pane.snapshotFrames) snapshot(pane);
    }
}

bool Comparison::measurable() const {
    return mReference.frames > 0 &&
           std::all_of(mPanes.begin(), mPanes.end(), [](const Pane& p) { return p.frames > 0; });
}

const std::vector<float>& Comparison::paneImage(size_t pane) const {
    static const std::vector<float> kNone;
    const Pane& p = mPanes[pane];
    return p.snapshots.empty() ? kNone : p.snapshots.back().image.linear();
}

std::vector<unsigned char> Comparison::toneMapped(const std::vector<float>& linear) const {
    double average = mToneAverage > 0.0 ? mToneAverage : meanLuminance(linear);
    return toneMapSrgb8(linear, average, mShared.exposure,
                        mShared.toneMap == ToneMapOperator::Reinhard);
}

const std::vector<glm::vec3>& Comparison::Measured::lab(const Comparison& c) {
    if (mLab.empty() || mLabAverage != c.mToneAverage) {
        mLab = labImage(c.toneMapped(mLinear));
        mLabAverage = c.mToneAverage;
    }
    return mLab;
}

void Comparison::measure(Pane& pane, Snapshot& shot) {
    Reference& r = mReference;
    double raw = relRmse(shot.image.linear(), r.image.linear(), r.emitters);
    double noise = referenceNoise();
    // The pane and the reference are independent: E|x - r|^2 = |x - truth|^2 + |r - truth|^2.
    double corrected =
        std::isfinite(noise) ? std::sqrt(std::max(0.0, raw * raw - noise * noise)) : raw;
    shot.point.relRmse = corrected;
    shot.point.deltaE = meanDistance(shot.image.lab(*this), r.image.lab(*this));
    if (&shot == &pane.snapshots.back()) {
        pane.result.latest = shot.point;
        pane.result.rawRelRmse = raw;
        pane.result.measured = true;
    }
}

void Comparison::remeasureAll() {
    if (mReference.image.empty()) return;  // nothing to measure against yet
    for (Pane& pane : mPanes) {
        if (pane.snapshots.empty()) continue;
        pane.result.series.clear();
        for (Snapshot& shot : pane.snapshots) {
            measure(pane, shot);
            pane.result.series.push_back(shot.point);
        }
        updateErrorMap(pane, pane.snapshots.back());
    }
}

void Comparison::updateErrorMap(Pane& pane, const Snapshot& shot) {
    const std::vector<float>& ref = mReference.image.linear();
    const std::vector<float>& linear = shot.image.linear();
    if (ref.size() != linear.size() || !(mToneAverage > 0.0)) return;
    int w = pane.renderer->settings().width, h = pane.renderer->settings().height;
    if (size_t(w) * size_t(h) * 3 != ref.size()) return;
    double scale = double(mErrorScale) * mToneAverage;
    const glm::dvec3 above(1.0, 0.45, 0.1), below(0.2, 0.55, 1.0);
    pane.errorRgb.assign(ref.size(), 0);
    std::vector<unsigned char> rgba(size_t(w) * size_t(h) * 4, 255);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            size_t i = (size_t(y) * size_t(w) + size_t(x)) * 3;
            double e = (luma(&linear[i]) - luma(&ref[i])) / scale;
            if (!std::isfinite(e)) e = 0.0;
            e = std::clamp(e, -1.0, 1.0);
            glm::dvec3 c = e >= 0.0 ? e * above : -e * below;
            // Rows bottom-up in the texture, as the renderer's display.
            size_t t = (size_t(h - 1 - y) * size_t(w) + size_t(x)) * 4;
            for (int k = 0; k < 3; ++k) {
                double s =
                    c[k] <= 0.0031308 ? 12.92 * c[k] : 1.055 * std::pow(c[k], 1.0 / 2.4) - 0.055;
                auto v = static_cast<unsigned char>(std::lround(std::clamp(s, 0.0, 1.0) * 255.0));
                pane.errorRgb[i + size_t(k)] = v;
                rgba[t + size_t(k)] = v;
            }
        }
    if (pane.errorTexture.width() != w || pane.errorTexture.height() != h)
        pane.errorTexture = gl::Texture2D(w, h, GL_RGBA8);
    glTextureSubImage2D(pane.errorTexture.id(), 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE,
                        rgba.data());
}

}  // namespace candela
