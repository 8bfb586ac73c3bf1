#include "renderer/passes/EnvironmentPass.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "luminaires/environment/EnvironmentLight.h"
#include "renderer/PassTimer.h"
#include "renderer/ProgramVariants.h"
#include "renderer/passes/GBufferPass.h"
#include "renderer/passes/ShadePass.h"
#include "shaders/shared/Constants.h"
#include "util/FloatFloat.h"

namespace candela {

namespace {

template <class T>
std::vector<T> readBuffer(const gl::Buffer& buffer, size_t count) {
    std::vector<T> out(count);
    if (count > 0)
        glGetNamedBufferSubData(buffer.id(), 0, GLsizeiptr(count * sizeof(T)), out.data());
    return out;
}

std::vector<double> fromFloatFloats(const std::vector<glm::vec2>& pairs) {
    std::vector<double> out(pairs.size());
    std::transform(pairs.begin(), pairs.end(), out.begin(), fromFloatFloat);
    return out;
}

}  // namespace

EnvironmentPass::EnvironmentPass() : mUniformBuffer(sizeof(gpu::EnvironmentGpu), nullptr) {}

int EnvironmentPass::defaultFaceSize(const EnvironmentMap& map) {
    return std::clamp(map.width() / 2, 8, 256);
}

bool EnvironmentPass::setMap(std::shared_ptr<const EnvironmentMap> map, int faceSize) {
    int n = faceSize > 0 ? faceSize : (map ? defaultFaceSize(*map) : 0);
    bool changed = map != mMap || n != mN;
    if (!changed) return false;
    bool resized =
        !mMap || !map || map->width() != mMap->width() || map->height() != mMap->height();
    mMap = std::move(map);
    mBuilt = false;
    mExtraFor.reset();
    mGlobalCdfFor.reset();
    if (!mMap) return true;
    if (resized || !mTexture.id())
        mTexture = gl::Texture2D(mMap->width(), mMap->height(), GL_RGB32F);
    std::vector<float> rgb(size_t(mMap->width()) * size_t(mMap->height()) * 3);
    for (int y = 0; y < mMap->height(); ++y)
        for (int x = 0; x < mMap->width(); ++x) {
            glm::dvec3 c = mMap->texel(x, y);  // intensity applied
            float* o = &rgb[(size_t(y) * size_t(mMap->width()) + size_t(x)) * 3];
            o[0] = float(c.x), o[1] = float(c.y), o[2] = float(c.z);
        }
    glTextureSubImage2D(mTexture.id(), 0, 0, 0, mMap->width(), mMap->height(), GL_RGB, GL_FLOAT,
                        rgb.data());
    if (n != mN) {
        mN = n;
        size_t texels = 6 * size_t(n) * size_t(n);
        mCube = gl::Buffer(GLsizeiptr(texels * sizeof(glm::vec2)), nullptr);
        mRowCdf = gl::TextureArray(GL_TEXTURE_2D_ARRAY, n + 1, n, 6, GL_RG32F);
        mColumnCdf = gl::Texture2D(n + 1, 12, GL_RG32F);  // rows 6-11: the columns' totals
        mFaces = gl::Buffer(GLsizeiptr(6 * sizeof(gpu::EnvironmentFaceGpu)), nullptr);
    }
    mUniforms.dims = glm::ivec4(mMap->width(), mMap->height(), mN, mPool);
    mUniforms.params = glm::vec4(float(mMap->rotation()), 0.f, 0.f, 0.f);
    // k x k subsamples, k >= 2 W / (pi N), as the CPU twin.
    mUniforms.frame.y = std::clamp(int(std::ceil(2.0 * mMap->width() / (gpu::kPi * n))), 1, 8);
    return true;
}

void EnvironmentPass::bindAll() const {
    mUniformBuffer.bindBase(GL_UNIFORM_BUFFER, gpu::kBindingEnvironment);
    glBindTextureUnit(GLuint(gpu::kUnitEnvironmentMap), mTexture.id());
    mCube.bindBase(GL_SHADER_STORAGE_BUFFER, gpu::kBindingEnvCube);
    glBindImageTexture(GLuint(gpu::kImageEnvRowCdf), mRowCdf.id(), 0, GL_TRUE, 0, GL_READ_WRITE,
                       GL_RG32F);
    glBindImageTexture(GLuint(gpu::kImageEnvColumnCdf), mColumnCdf.id(), 0, GL_FALSE, 0,
                       GL_READ_WRITE, GL_RG32F);
    glBindTextureUnit(GLuint(gpu::kUnitEnvRowCdf), mRowCdf.id());
    glBindTextureUnit(GLuint(gpu::kUnitEnvColumnCdf), mColumnCdf.id());
    if (mGlobalCdf.id()) glBindTextureUnit(GLuint(gpu::kUnitEnvGlobalCdf), mGlobalCdf.id());
    mFaces.bindBase(GL_SHADER_STORAGE_BUFFER, gpu::kBindingEnvFaces);
    if (mSamples.id()) mSamples.bindBase(GL_SHADER_STORAGE_BUFFER, gpu::kBindingEnvSamples);
    if (mExtra.id()) mExtra.bindBase(GL_SHADER_STORAGE_BUFFER, gpu::kBindingEnvExtra);
}

void EnvironmentPass::dispatch(ShaderLibrary& shaders, programs::EnvironmentTables pass, GLuint x,
                               GLuint y, GLuint z) {
    glUseProgram(shaders.program(programs::environmentTables(pass)));
    glDispatchCompute(x, y, z);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                    GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                    GL_TEXTURE_UPDATE_BARRIER_BIT);
}

void EnvironmentPass::buildTables(ShaderLibrary& shaders) {
    if (!mMap || mBuilt) return;
    mUniformBuffer.update(0, sizeof(mUniforms), &mUniforms);
    bindAll();
    GLuint n = GLuint(mN);
    dispatch(shaders, programs::EnvironmentTables::Cube, (n + 7) / 8, (n + 7) / 8, 6);
    dispatch(shaders, programs::EnvironmentTables::Energy, 6, 1, 1);
    dispatch(shaders, programs::EnvironmentTables::Rows, n, 6, 1);
    dispatch(shaders, programs::EnvironmentTables::Columns, 6, 1, 1);
    mBuilt = true;
}

void EnvironmentPass::drawSamples(ShaderLibrary& shaders, uint32_t seed, int pool) {
    if (!mMap) return;
    if (pool != mPool) {
        mPool = pool;
        mSamples =
            gl::Buffer(GLsizeiptr(6 * size_t(pool) * sizeof(gpu::EnvironmentSampleGpu)), nullptr);
    }
    mUniforms.dims.w = mPool;
    mUniforms.frame.x = int(seed);
    mUniformBuffer.update(0, sizeof(mUniforms), &mUniforms);
    bindAll();
    dispatch(shaders, programs::EnvironmentTables::Samples, GLuint((pool + 63) / 64), 1, 6);
}

std::vector<float> cdfSearchGuide(const float* cdf, int n) {
    std::vector<float> guide(size_t(std::max(n, 0)), 0.f);
    auto entry = [cdf](int i) { return i == 0 ? 0.f : cdf[i - 1]; };
    auto bucket = [n](float u) { return std::min(int(u * float(n)), n - 1); };
    int i = 0;
    for (int j = 0; j < n; ++j) {
        // The smallest float the shader puts in bucket j (float(j) / n give or take an ulp).
        float start = float(j) / float(n);
        while (start > 0.f && bucket(std::nextafter(start, 0.f)) >= j)
            start = std::nextafter(start, 0.f);
        while (bucket(start) < j) start = std::nextafter(start, 2.f);
        while (i + 1 < n && entry(i + 1) <= start) ++i;  // entries never decrease
        guide[size_t(j)] = float(i);                     // exact: n is at most GL's texture width
    }
    return guide;
}

void EnvironmentPass::prepareGlobalCdf() {
    if (!mMap || mGlobalCdfFor.lock() == mMap) return;
    LatLongDistribution global(*mMap);
    int w = mMap->width(), h = mMap->height(), width = std::max(w, h);
    // Per texel (kUnitEnvGlobalCdf in GpuTypes.h): .r entry i + 1 of the line's CDF (entry 0 is
    // 0), .g entry i of its search guide, which leaves one or two of the binary searches'
    // dependent fetches: the pass 1.14x faster on an H100, 1.17x on llvmpipe (docs/bench/gpu-h100).
    std::vector<float> cdf(size_t(width) * size_t(h + 1), 0.f);
    if (!global.empty()) {
        for (int y = 1; y <= h; ++y) cdf[size_t(y - 1)] = float(global.rows().cdf[size_t(y)]);
        for (int y = 0; y < h; ++y)
            for (int x = 1; x <= w; ++x)
                cdf[size_t(y + 1) * size_t(width) + size_t(x - 1)] =
                    float(global.columns(y).cdf[size_t(x)]);
    }
    std::vector<glm::vec2> table(cdf.size(), glm::vec2(0.f));
    for (int line = 0; line <= h; ++line) {
        const float* row = cdf.data() + size_t(line) * size_t(width);
        std::vector<float> guide = cdfSearchGuide(row, line == 0 ? h : w);
        for (size_t i = 0; i < guide.size(); ++i)
            table[size_t(line) * size_t(width) + i] = glm::vec2(row[i], guide[i]);
    }
    mGlobalCdf = gl::Texture2D(width, h + 1, GL_RG32F);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(mGlobalCdf.id(), 0, 0, 0, width, h + 1, GL_RG, GL_FLOAT, table.data());
    mGlobalCdfFor = mMap;
}

void EnvironmentPass::prepareHavran() {
    if (!mMap || (mExtraFor.lock() == mMap && mUniforms.extra.x > 0)) return;
    // One filter for the pass's lifetime: its history carries over from map to map (the frames
    // of a sequence, a moving sun), which is what the temporal filtering is for.
    if (!mHavran) mHavran = std::make_unique<HavranLights>(256);
    if (mHavranFor.lock() != mMap) mHavran->update(*mMap);
    mHavranFor = mMap;
    std::vector<glm::vec4> data;
    for (const HavranLights::Light& l : mHavran->lights()) {
        data.push_back(glm::vec4(glm::vec3(l.direction), 0.f));
        data.push_back(glm::vec4(glm::vec3(l.power), 0.f));
    }
    mExtra = gl::Buffer(GLsizeiptr(data.size() * sizeof(glm::vec4)), data.data());
    mUniforms.extra = glm::ivec4(int(mHavran->lights().size()), 0, 0, 0);
    mExtraFor = mMap;
}

std::vector<glm::dvec3> EnvironmentPass::havranDirections() const {
    std::vector<glm::dvec3> out;
    if (mHavran)
        for (const HavranLights::Light& l : mHavran->lights()) out.push_back(l.direction);
    return out;
}

void EnvironmentPass::shade(ShaderLibrary& shaders, const ShadeStep& step,
                            const GBufferPass& gbuffer, const gl::Framebuffer& target, int width,
                            int height, bool background) {
    if (!mMap) return;
    mUniforms.params.y = background ? 1.f : 0.f;
    mUniformBuffer.update(0, sizeof(mUniforms), &mUniforms);
    bindAll();
    glUseProgram(shaders.program(step.program));
    ShadePass::drawAdditive(gbuffer, target, width, height, step.unitScale);
}

namespace {

bool reads(const TechniqueInfo& technique, std::string_view resource) {
    std::istringstream names{std::string(technique.resources)};
    for (std::string name; names >> name;)
        if (name == resource) return true;
    return false;
}

}  // namespace

std::vector<std::string> EnvironmentPass::prepassNames(const TechniqueInfo& technique) {
    if (reads(technique, "cube")) return {"env:cdf", "env:samples"};
    return {};
}

void EnvironmentPass::setSource(const Luminaire& source, const std::vector<std::byte>&) {
    mSourceMap = environmentModel(source)->sharedMap();
}

void EnvironmentPass::prepare(const ShadeStep& step, SourceContext& context, int frame, int spp) {
    setMap(mSourceMap, context.settings.environmentFaceSize);
    const TechniqueInfo& t = *step.technique;
    if (reads(t, "cube")) {
        if (!tablesBuilt())
            context.timer.timed(context.stats, "env:cdf", [&] { buildTables(context.shaders); });
        // Enough samples per face that a pixel whose faces balance to one face still draws
        // distinct ones; a fresh pool every pass (every band of a pass shares it).
        int pool = std::max(256, spp);
        uint32_t seed =
            uint32_t(context.settings.seed) * 2654435761u ^ uint32_t(frame) * 40503u ^ 0x5bd1e995u;
        context.timer.timed(context.stats, "env:samples",
                            [&] { drawSamples(context.shaders, seed, pool); });
    }
    if (reads(t, "latlong")) prepareGlobalCdf();
    if (reads(t, "lights")) {
        prepareHavran();
        if (step.shadowMaps) {
            std::vector<glm::dvec3> directions = havranDirections();
            if (mShadows.stale(directions, context.settings.shadowMaps,
                               context.geometryGeneration)) {
                const ShadowGeometry& geometry = context.geometry();
                context.timer.timed(context.stats, shadowPassName(step), [&] {
                    mShadows.render(context.shaders, geometry, directions,
                                    context.settings.shadowMaps, context.geometryGeneration);
                });
            }
        }
    }
}

void EnvironmentPass::shade(const ShadeStep& step, SourceContext& context,
                            const gl::Framebuffer& target) {
    if (step.shadowMaps) mShadows.bind();
    // The map shows behind the scene in an image of radiance (not in probes or illuminance).
    bool background = !context.pointMode && context.settings.quantity == Quantity::Radiance;
    shade(context.shaders, step, context.gbuffer, target, context.gbuffer.width(),
          context.gbuffer.height(), background);
}

std::vector<glm::vec2> EnvironmentPass::readCube() const {
    return readBuffer<glm::vec2>(mCube, 6 * size_t(mN) * size_t(mN));
}
std::vector<double> EnvironmentPass::readRowCdf() const {
    std::vector<glm::vec2> pairs(6 * size_t(mN) * size_t(mN + 1));
    glGetTextureImage(mRowCdf.id(), 0, GL_RG, GL_FLOAT, GLsizei(pairs.size() * sizeof(glm::vec2)),
                      pairs.data());
    return fromFloatFloats(pairs);
}
std::vector<double> EnvironmentPass::readColumnCdf() const {
    std::vector<glm::vec2> pairs(6 * size_t(mN + 1));
    glGetTextureSubImage(mColumnCdf.id(), 0, 0, 0, 0, mN + 1, 6, 1, GL_RG, GL_FLOAT,
                         GLsizei(pairs.size() * sizeof(glm::vec2)), pairs.data());
    return fromFloatFloats(pairs);
}
std::vector<gpu::EnvironmentFaceGpu> EnvironmentPass::readFaces() const {
    return readBuffer<gpu::EnvironmentFaceGpu>(mFaces, 6);
}
std::vector<gpu::EnvironmentSampleGpu> EnvironmentPass::readSamples() const {
    return readBuffer<gpu::EnvironmentSampleGpu>(mSamples, 6 * size_t(mPool));
}

}  // namespace candela
