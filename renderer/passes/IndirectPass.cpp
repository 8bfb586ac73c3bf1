#include "renderer/passes/IndirectPass.h"

#include "calculation/Radiosity.h"
#include "renderer/ProgramVariants.h"
#include "renderer/passes/GBufferPass.h"
#include "shaders/shared/GpuTypes.h"

namespace candela {

void IndirectPass::resize(int width, int height) {
    mWidth = width;
    mHeight = height;
    mImage = gl::Texture2D(width, height, GL_RGBA32F);
    mDepth = gl::Texture2D(width, height, GL_DEPTH_COMPONENT32F);
    mFbo = gl::Framebuffer({&mImage}, &mDepth);
}

void IndirectPass::clear() {
    mMesh.reset();
    mIndexCount = 0;
}

void IndirectPass::set(const std::shared_ptr<const RadiosityMesh>& mesh,
                       const std::vector<glm::vec3>& vertexIrradiance) {
    if (!mesh || mesh->patches.empty() || vertexIrradiance.size() != mesh->vertices.size()) {
        clear();
        return;
    }
    if (mesh != mMesh) {
        std::vector<glm::vec3> positions;
        positions.reserve(mesh->vertices.size());
        for (const glm::dvec3& v : mesh->vertices) positions.push_back(glm::vec3(v));
        std::vector<uint32_t> indices;
        indices.reserve(3 * mesh->patches.size());
        // Not a luminous box (it blocks, the camera sees through it), nor a cluster's stand-in
        // (its triangles are drawn instead).
        for (const auto& p : mesh->patches)
            if (!p.hidden && !p.cluster)
                indices.insert(indices.end(), p.vertex.begin(), p.vertex.end());
        for (size_t t = 0; t < mesh->displayTriangles.size(); ++t)
            if (!mesh->patches[mesh->displayPatch[t]].hidden)
                indices.insert(indices.end(), mesh->displayTriangles[t].begin(),
                               mesh->displayTriangles[t].end());
        mPositions =
            gl::Buffer(GLsizeiptr(positions.size() * sizeof(glm::vec3)), positions.data(), 0);
        mIndices = gl::Buffer(GLsizeiptr(indices.size() * sizeof(uint32_t)), indices.data(), 0);
        mIrradiance = gl::Buffer(GLsizeiptr(vertexIrradiance.size() * sizeof(glm::vec3)), nullptr);
        mVao = gl::VertexArray();
        GLuint vao = mVao.id();
        glVertexArrayVertexBuffer(vao, 0, mPositions.id(), 0, sizeof(glm::vec3));
        glVertexArrayVertexBuffer(vao, 1, mIrradiance.id(), 0, sizeof(glm::vec3));
        glVertexArrayElementBuffer(vao, mIndices.id());
        for (GLuint i = 0; i < 2; ++i) {
            glEnableVertexArrayAttrib(vao, i);
            glVertexArrayAttribFormat(vao, i, 3, GL_FLOAT, GL_FALSE, 0);
            glVertexArrayAttribBinding(vao, i, i);
        }
        mIndexCount = GLsizei(indices.size());
        mMesh = mesh;
    }
    mIrradiance.update(0, GLsizeiptr(vertexIrradiance.size() * sizeof(glm::vec3)),
                       vertexIrradiance.data());
}

void IndirectPass::execute(ShaderLibrary& shaders, const GBufferPass& gbuffer) {
    const float zero[4] = {0.f, 0.f, 0.f, 0.f};
    glClearNamedFramebufferfv(mFbo.id(), GL_COLOR, 0, zero);
    const float one = 1.f;
    glClearNamedFramebufferfv(mFbo.id(), GL_DEPTH, 0, &one);
    if (!mIndexCount) return;
    GLuint program = shaders.program(programs::indirect());
    glUseProgram(program);
    glBindTextureUnit(2, gbuffer.texture(gpu::kGBufferAlbedo).id());
    glBindFramebuffer(GL_FRAMEBUFFER, mFbo.id());
    glViewport(0, 0, mWidth, mHeight);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glBindVertexArray(mVao.id());
    glDrawElements(GL_TRIANGLES, mIndexCount, GL_UNSIGNED_INT, nullptr);
    glDisable(GL_DEPTH_TEST);
}

}  // namespace candela
