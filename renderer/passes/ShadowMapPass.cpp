#include "renderer/passes/ShadowMapPass.h"

#include <algorithm>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>

#include "renderer/ProgramVariants.h"
#include "shaders/shared/GpuTypes.h"

namespace candela {

namespace {

/// An immutable buffer holding `header` followed by the elements of `array` (the std430 layout
/// of a block with a fixed member and a runtime-sized array).
template <class Header, class T>
gl::Buffer headerAndArray(const Header& header, const std::vector<T>& array) {
    std::vector<std::byte> bytes(sizeof(Header) + array.size() * sizeof(T));
    std::memcpy(bytes.data(), &header, sizeof(Header));
    std::memcpy(bytes.data() + sizeof(Header), array.data(), array.size() * sizeof(T));
    return gl::Buffer(GLsizeiptr(bytes.size()), bytes.data(), 0);
}

/// Binds the depth-only program, `fbo` and a res x res viewport with depth testing, no culling
/// (triangles are two-sided); returns the program, whose location 0 takes the view-projection.
GLuint beginDepthPass(ShaderLibrary& shaders, const gl::Framebuffer& fbo, int res) {
    GLuint program = shaders.program(programs::shadowDepth());
    glUseProgram(program);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    glViewport(0, 0, res, res);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    return program;
}

}  // namespace

void ShadowGeometry::set(const Scene& scene) {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
    lo = glm::dvec3(1e300);
    hi = glm::dvec3(-1e300);
    mBodies.clear();
    auto add = [&](const Mesh& mesh) {
        uint32_t base = uint32_t(positions.size());
        for (const glm::vec3& p : mesh.positions) {
            positions.push_back(p);
            lo = glm::min(lo, glm::dvec3(p));
            hi = glm::max(hi, glm::dvec3(p));
        }
        for (uint32_t i : mesh.indices) indices.push_back(base + i);
    };
    for (const Mesh& mesh : scene.meshes)
        if (!mesh.luminaireBody) add(mesh);
    mSceneCount = GLsizei(indices.size());
    for (const Mesh& mesh : scene.meshes)
        if (mesh.luminaireBody) {
            GLsizei first = GLsizei(indices.size());
            add(mesh);
            mBodies.push_back({first, GLsizei(indices.size()) - first, glm::dvec3(mesh.boundsMin),
                               glm::dvec3(mesh.boundsMax)});
        }
    if (positions.empty()) lo = hi = glm::dvec3(0.0);
    mIndexCount = GLsizei(indices.size());
    mVao = gl::VertexArray();
    if (indices.empty()) return;
    mVertices = gl::Buffer(GLsizeiptr(positions.size() * sizeof(glm::vec3)), positions.data(), 0);
    mIndices = gl::Buffer(GLsizeiptr(indices.size() * sizeof(uint32_t)), indices.data(), 0);
    glVertexArrayVertexBuffer(mVao.id(), 0, mVertices.id(), 0, sizeof(glm::vec3));
    glVertexArrayElementBuffer(mVao.id(), mIndices.id());
    glEnableVertexArrayAttrib(mVao.id(), 0);
    glVertexArrayAttribFormat(mVao.id(), 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(mVao.id(), 0, 0);
}

void ShadowGeometry::draw(const glm::dvec3* light) const {
    if (mIndexCount == 0) return;
    glBindVertexArray(mVao.id());
    if (!light || mBodies.empty()) {
        glDrawElements(GL_TRIANGLES, mIndexCount, GL_UNSIGNED_INT, nullptr);
        return;
    }
    auto range = [](GLsizei first, GLsizei count) {
        if (count > 0)
            glDrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT,
                           reinterpret_cast<const void*>(uintptr_t(first) * sizeof(uint32_t)));
    };
    range(0, mSceneCount);
    for (const Body& b : mBodies)
        if (!insideBody(*light, b.lo, b.hi)) range(b.first, b.count);
}

bool ShadowMaps::stale(const ShadowLights& lights, const ShadowMapSettings& settings,
                       int geometryGeneration) const {
    return geometryGeneration != mGeneration || !(settings == mSettings) || !(lights == mLights);
}

void ShadowMaps::render(ShaderLibrary& shaders, const ShadowGeometry& geometry,
                        const ShadowLights& lights, const ShadowMapSettings& settings,
                        int geometryGeneration) {
    mLights = lights;
    mSettings = settings;
    mGeneration = geometryGeneration;
    int maps = std::max(1, mapCount());
    int res = std::max(8, settings.resolution);
    if (mDepth.layers() != 6 * maps || mDepth.width() != res) {
        mDepth =
            gl::TextureArray(GL_TEXTURE_CUBE_MAP_ARRAY, res, res, 6 * maps, GL_DEPTH_COMPONENT32F);
        mFbo = gl::Framebuffer::depthOnly();
    }

    // Far plane: beyond the farthest corner of the scene's bounds from any light.
    double far = 1.0;
    for (const glm::dvec3& l : lights.lights)
        for (int c = 0; c < 8; ++c) {
            glm::dvec3 corner((c & 1) ? geometry.hi.x : geometry.lo.x,
                              (c & 2) ? geometry.hi.y : geometry.lo.y,
                              (c & 4) ? geometry.hi.z : geometry.lo.z);
            far = std::max(far, 1.01 * glm::length(corner - l) + 2.0 * kNear);
        }

    gpu::ShadowMapsGpu header{};
    header.dims = glm::ivec4(mapCount(), res, lights.sharesPerItem, 0);
    header.params =
        glm::vec4(float(kNear), float(far), settings.normalOffset, settings.depthOffset);
    std::vector<gpu::ShadowMapGpu> records(static_cast<size_t>(maps));
    for (size_t k = 0; k < lights.lights.size(); ++k)
        records[k].light = glm::vec4(glm::vec3(lights.lights[k]), lights.lit[k] ? 1.f : 0.f);
    mHeader = headerAndArray(header, records);
    std::vector<glm::vec2> shares;
    for (const ShadowLights::Share& s : lights.shares) shares.push_back({float(s.map), s.weight});
    if (shares.empty()) shares.push_back(glm::vec2(0.f));
    mShares = gl::Buffer(GLsizeiptr(shares.size() * sizeof(glm::vec2)), shares.data(), 0);

    // The GL cube-map faces (+x, -x, +y, -y, +z, -z) seen from the light: forward and up as
    // the cube-map lookup expects them, so that a face's texel (s, t) is where it stores depth.
    static const glm::dvec3 kForward[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                           {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
    static const glm::dvec3 kUp[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1},
                                      {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
    glm::dmat4 proj = glm::perspective(glm::radians(90.0), 1.0, kNear, far);
    GLuint program = beginDepthPass(shaders, mFbo, res);
    for (size_t k = 0; k < lights.lights.size(); ++k) {
        for (int f = 0; f < 6; ++f) {
            mFbo.attachDepthLayer(mDepth, int(k) * 6 + f);
            glClear(GL_DEPTH_BUFFER_BIT);
            if (!lights.lit[k]) continue;  // cleared to the far plane: read as lit
            glm::dvec3 l = lights.lights[k];
            glm::mat4 viewProj = glm::mat4(proj * glm::lookAt(l, l + kForward[f], kUp[f]));
            glProgramUniformMatrix4fv(program, 0, 1, GL_FALSE, &viewProj[0][0]);
            geometry.draw(&l);
        }
    }
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void ShadowMaps::bind() const {
    glBindTextureUnit(GLuint(gpu::kUnitShadowMaps), mDepth.id());
    mHeader.bindBase(GL_SHADER_STORAGE_BUFFER, gpu::kBindingShadowMaps);
    mShares.bindBase(GL_SHADER_STORAGE_BUFFER, gpu::kBindingShadowShares);
}

bool DirectionalShadowMaps::stale(const std::vector<glm::dvec3>& directions,
                                  const ShadowMapSettings& settings, int geometryGeneration) const {
    return geometryGeneration != mGeneration || !(settings == mSettings) ||
           directions != mDirections;
}

void DirectionalShadowMaps::render(ShaderLibrary& shaders, const ShadowGeometry& geometry,
                                   const std::vector<glm::dvec3>& directions,
                                   const ShadowMapSettings& settings, int geometryGeneration) {
    mDirections = directions;
    mSettings = settings;
    mGeneration = geometryGeneration;
    int count = std::max(1, int(directions.size()));
    int res = std::max(8, settings.directionalResolution);
    if (mDepth.layers() != count || mDepth.width() != res) {
        mDepth = gl::TextureArray(GL_TEXTURE_2D_ARRAY, res, res, count, GL_DEPTH_COMPONENT32F);
        mFbo = gl::Framebuffer::depthOnly();
    }
    // The bounding sphere of the scene's bounds, a little larger so nothing grazes the edges.
    glm::dvec3 centre = 0.5 * (geometry.lo + geometry.hi);
    double radius = std::max(1e-3, 0.5 * glm::length(geometry.hi - geometry.lo) * 1.01);
    gpu::ShadowMapsGpu header{};
    header.dims = glm::ivec4(int(directions.size()), res, 0, 0);
    // x: world size of a texel (m); z, w: the offsets in texels.
    header.params = glm::vec4(float(2.0 * radius / res), float(radius), settings.normalOffset,
                              settings.depthOffset);
    std::vector<glm::mat4> matrices;
    glm::dmat4 proj = glm::ortho(-radius, radius, -radius, radius, 0.0, 2.0 * radius);
    for (const glm::dvec3& w : directions) {
        glm::dvec3 up = std::abs(w.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
        matrices.push_back(glm::mat4(proj * glm::lookAt(centre + w * radius, centre, up)));
    }
    if (matrices.empty()) matrices.push_back(glm::mat4(1.f));
    mData = headerAndArray(header, matrices);

    GLuint program = beginDepthPass(shaders, mFbo, res);
    for (size_t k = 0; k < directions.size(); ++k) {
        mFbo.attachDepthLayer(mDepth, int(k));
        glClear(GL_DEPTH_BUFFER_BIT);
        glProgramUniformMatrix4fv(program, 0, 1, GL_FALSE, &matrices[k][0][0]);
        geometry.draw();
    }
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void DirectionalShadowMaps::bind() const {
    glBindTextureUnit(GLuint(gpu::kUnitDirectionalShadowMaps), mDepth.id());
    mData.bindBase(GL_SHADER_STORAGE_BUFFER, gpu::kBindingDirectionalShadowMaps);
}

}  // namespace candela
