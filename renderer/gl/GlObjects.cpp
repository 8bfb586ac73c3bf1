#include "renderer/gl/GlObjects.h"

#include <string>

#include "util/Error.h"

namespace candela::gl {

static GLuint createName(void (*create)(GLsizei, GLuint*)) {
    GLuint id = 0;
    create(1, &id);
    return id;
}

Buffer::Buffer(GLsizeiptr size, const void* data, GLbitfield flags) : mSize(size) {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    mHandle = Handle<detail::deleteBuffer>(id);
    glNamedBufferStorage(id, size > 0 ? size : 16, size > 0 ? data : nullptr, flags);
}

void Buffer::update(GLintptr offset, GLsizeiptr size, const void* data) {
    glNamedBufferSubData(id(), offset, size, data);
}

Texture2D::Texture2D(int width, int height, GLenum internalFormat, int levels)
    : mWidth(width), mHeight(height), mFormat(internalFormat) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &id);
    mHandle = Handle<detail::deleteTexture>(id);
    glTextureStorage2D(id, levels, internalFormat, width, height);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER,
                        levels > 1 ? GL_LINEAR_MIPMAP_NEAREST : GL_NEAREST);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

namespace {

/// "0x8CD6, an image is incomplete": a framebuffer status in hex, with what it means.
/// What an incomplete framebuffer's status means, in words.
const char* statusText(GLenum status) {
    return status == GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT           ? "an image is incomplete"
           : status == GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT ? "no image attached"
           : status == GL_FRAMEBUFFER_UNSUPPORTED                   ? "unsupported formats"
                                                                    : "incomplete";
}

}  // namespace

Framebuffer::Framebuffer(std::initializer_list<const Texture2D*> colour, const Texture2D* depth) {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    mHandle = Handle<detail::deleteFramebuffer>(id);
    GLenum buffers[8];
    GLsizei n = 0;
    for (const Texture2D* t : colour) {
        glNamedFramebufferTexture(id, GL_COLOR_ATTACHMENT0 + n, t->id(), 0);
        buffers[n] = GL_COLOR_ATTACHMENT0 + n;
        ++n;
    }
    glNamedFramebufferDrawBuffers(id, n, buffers);
    if (depth) glNamedFramebufferTexture(id, GL_DEPTH_ATTACHMENT, depth->id(), 0);
    GLenum status = glCheckNamedFramebufferStatus(id, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        // Usually images too large for this OpenGL's memory: say how large they were.
        const Texture2D* any = colour.size() > 0 ? *colour.begin() : depth;
        std::string size =
            any ? std::to_string(any->width()) + " x " + std::to_string(any->height()) + " pixels"
                : std::string("no image");
        throw RuntimeError("OpenGL could not make an image of " + size + " (" + statusText(status) +
                           "): too large for this OpenGL's memory? A smaller image size may fit");
    }
}

TextureArray::TextureArray(GLenum target, int width, int height, int layers, GLenum internalFormat)
    : mWidth(width), mHeight(height), mLayers(layers) {
    GLuint id = 0;
    glCreateTextures(target, 1, &id);
    mHandle = Handle<detail::deleteTexture>(id);
    glTextureStorage3D(id, 1, internalFormat, width, height, layers);
    bool depth = internalFormat == GL_DEPTH_COMPONENT32F ||
                 internalFormat == GL_DEPTH_COMPONENT24 || internalFormat == GL_DEPTH_COMPONENT16;
    GLint filter = depth ? GL_LINEAR : GL_NEAREST;
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, filter);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, filter);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    if (depth) {
        glTextureParameteri(id, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glTextureParameteri(id, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    }
}

Framebuffer Framebuffer::depthOnly() {
    Framebuffer f;
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    f.mHandle = Handle<detail::deleteFramebuffer>(id);
    glNamedFramebufferDrawBuffer(id, GL_NONE);
    glNamedFramebufferReadBuffer(id, GL_NONE);
    return f;
}

void Framebuffer::attachDepthLayer(const TextureArray& array, int layer) {
    glNamedFramebufferTextureLayer(id(), GL_DEPTH_ATTACHMENT, array.id(), 0, layer);
    GLenum status = glCheckNamedFramebufferStatus(id(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw RuntimeError("OpenGL could not make a shadow map of " +
                           std::to_string(array.width()) + " x " + std::to_string(array.height()) +
                           " pixels (framebuffer status " + statusText(status) + ")");
}

VertexArray::VertexArray() {
    mHandle = Handle<detail::deleteVertexArray>(
        createName([](GLsizei n, GLuint* ids) { glCreateVertexArrays(n, ids); }));
}

TimerQuery::TimerQuery() {
    mHandle = Handle<detail::deleteQuery>(
        createName([](GLsizei n, GLuint* ids) { glCreateQueries(GL_TIME_ELAPSED, n, ids); }));
}

bool TimerQuery::available() const {
    GLuint ready = GL_FALSE;
    glGetQueryObjectuiv(mHandle.id(), GL_QUERY_RESULT_AVAILABLE, &ready);
    return ready == GL_TRUE;
}

double TimerQuery::milliseconds() const {
    GLuint64 ns = 0;
    glGetQueryObjectui64v(mHandle.id(), GL_QUERY_RESULT, &ns);
    return double(ns) * 1e-6;
}

}  // namespace candela::gl
