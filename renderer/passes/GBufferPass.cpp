#include "renderer/passes/GBufferPass.h"

#include <algorithm>
#include <cstddef>

#include "renderer/ProgramVariants.h"
#include "shaders/shared/Constants.h"
#include "shaders/shared/GpuTypes.h"

namespace candela {

void GBufferPass::resize(int width, int height) {
    mWidth = width;
    mHeight = height;
    for (auto& t : mTextures) t = gl::Texture2D(width, height, GL_RGBA32F);
    mDepth = gl::Texture2D(width, height, GL_DEPTH_COMPONENT32F);
    mFbo = gl::Framebuffer(
        {&mTextures[0], &mTextures[1], &mTextures[2], &mTextures[3], &mTextures[4]}, &mDepth);
}

GBufferPass::Draw GBufferPass::makeDraw(const std::vector<Vertex>& vertices,
                                        const std::vector<uint32_t>& indices) {
    Draw d;
    d.indexCount = GLsizei(indices.size());
    if (indices.empty()) return d;
    d.vbo = gl::Buffer(GLsizeiptr(vertices.size() * sizeof(Vertex)), vertices.data(), 0);
    d.ibo = gl::Buffer(GLsizeiptr(indices.size() * sizeof(uint32_t)), indices.data(), 0);
    GLuint vao = d.vao.id();
    glVertexArrayVertexBuffer(vao, 0, d.vbo.id(), 0, sizeof(Vertex));
    glVertexArrayElementBuffer(vao, d.ibo.id());
    struct Attr {
        GLint size;
        size_t offset;
    };
    const Attr attrs[] = {{3, offsetof(Vertex, position)}, {3, offsetof(Vertex, normal)},
                          {3, offsetof(Vertex, albedo)},   {4, offsetof(Vertex, specular)},
                          {3, offsetof(Vertex, emission)}, {1, offsetof(Vertex, flags)}};
    for (GLuint i = 0; i < 6; ++i) {
        glEnableVertexArrayAttrib(vao, i);
        glVertexArrayAttribFormat(vao, i, attrs[i].size, GL_FLOAT, GL_FALSE,
                                  GLuint(attrs[i].offset));
        glVertexArrayAttribBinding(vao, i, 0);
    }
    return d;
}

void GBufferPass::setGeometry(const Scene& scene) {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    for (const Mesh& mesh : scene.meshes) {
        if (mesh.hidden) continue;  // a luminous box: the camera sees the opening's light
        const Material& m = scene.materials.at(mesh.material);
        uint32_t base = uint32_t(vertices.size());
        float flags = m.isGlossy() ? float(gpu::kMaterialGlossy) : 0.f;
        for (size_t i = 0; i < mesh.positions.size(); ++i)
            vertices.push_back({mesh.positions[i], mesh.normals[i], m.albedo,
                                glm::vec4(m.specular, m.phongExponent()), glm::vec3(0.f), flags});
        for (uint32_t idx : mesh.indices) indices.push_back(base + idx);
    }
    mScene = makeDraw(vertices, indices);
}

void GBufferPass::setLuminaires(const Scene& scene) {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    for (const auto& lum : scene.luminaires) {
        std::vector<glm::dvec3> outline = lum->outline();
        if (outline.size() < 3) continue;
        glm::dvec3 x, y, z;
        lum->emitterPose().frame(x, y, z);
        // Emitters show the radiance they send along their axis (exact for Lambertian ones).
        glm::vec3 emission = glm::vec3(displayRadiance(*lum) * scene.lightScale(*lum));
        uint32_t base = uint32_t(vertices.size());
        for (const auto& p : outline)
            vertices.push_back({glm::vec3(p), glm::vec3(z), glm::vec3(0.05f), glm::vec4(0.f),
                                emission, float(gpu::kMaterialEmitter)});
        for (uint32_t i = 1; i + 1 < outline.size(); ++i) {
            indices.insert(indices.end(), {base, base + i, base + i + 1});
        }
    }
    mLuminaires = makeDraw(vertices, indices);
}

void GBufferPass::execute(ShaderLibrary& shaders, Quantity quantity) {
    GLuint program = shaders.program(programs::gbuffer());
    glUseProgram(program);
    glProgramUniform1i(program, 0, quantity == Quantity::Illuminance ? 1 : 0);
    glBindFramebuffer(GL_FRAMEBUFFER, mFbo.id());
    glViewport(0, 0, mWidth, mHeight);
    const float zero[4] = {0.f, 0.f, 0.f, 0.f};
    for (int i = 0; i < gpu::kGBufferCount; ++i)
        glClearNamedFramebufferfv(mFbo.id(), GL_COLOR, i, zero);
    const float one = 1.f;
    glClearNamedFramebufferfv(mFbo.id(), GL_DEPTH, 0, &one);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    for (const Draw* d : {&mScene, &mLuminaires}) {
        if (!d->indexCount) continue;
        // Luminaires only mark and light their pixels in the emission attachment: position,
        // normal and material stay those of the surface behind, so moving one luminaire leaves
        // every other luminaire's shading as it was (Renderer accumulates per luminaire).
        bool luminaires = d == &mLuminaires;
        for (int i = 0; i < gpu::kGBufferCount; ++i)
            if (i != gpu::kGBufferEmission)
                glColorMaski(GLuint(i), !luminaires, !luminaires, !luminaires, !luminaires);
        glBindVertexArray(d->vao.id());
        glDrawElements(GL_TRIANGLES, d->indexCount, GL_UNSIGNED_INT, nullptr);
    }
    for (int i = 0; i < gpu::kGBufferCount; ++i)
        glColorMaski(GLuint(i), GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_DEPTH_TEST);
}

void GBufferPass::uploadPoints(const std::vector<glm::vec3>& points,
                               const std::vector<glm::vec3>& normals, int width) {
    int w = std::max(1, width);
    int h = (int(points.size()) + w - 1) / w;
    size_t texels = size_t(w) * size_t(std::max(h, 1));
    std::vector<glm::vec4> pos(texels, glm::vec4(0.f)), nrm(texels, glm::vec4(0.f)),
        alb(texels, glm::vec4(0.f)), zero(texels, glm::vec4(0.f));
    for (size_t i = 0; i < points.size(); ++i) {
        pos[i] = glm::vec4(points[i], 1.f);
        nrm[i] = glm::vec4(glm::normalize(normals[i]), 1.f);
        alb[i] = glm::vec4(glm::vec3(float(gpu::kPi)), 0.f);
    }
    const std::vector<glm::vec4>* data[] = {&pos, &nrm, &alb, &zero, &zero};
    for (int i = 0; i < gpu::kGBufferCount; ++i)
        glTextureSubImage2D(mTextures[size_t(i)].id(), 0, 0, 0, w, std::max(h, 1), GL_RGBA,
                            GL_FLOAT, data[i]->data());
}

}  // namespace candela
