#pragma once
// Move-only RAII owners of GL 4.5 direct-state-access objects. No reference counting: an object
// has one owner, and moving it transfers the name.

#include <utility>

#include "renderer/gl/GlFunctions.h"

namespace candela::gl {

template <void (*Delete)(GLuint)>
class Handle {
  public:
    Handle() = default;
    explicit Handle(GLuint id) : mId(id) {}
    ~Handle() { reset(); }
    Handle(Handle&& o) noexcept : mId(std::exchange(o.mId, 0)) {}
    Handle& operator=(Handle&& o) noexcept {
        if (this != &o) {
            reset();
            mId = std::exchange(o.mId, 0);
        }
        return *this;
    }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;

    GLuint id() const { return mId; }
    explicit operator bool() const { return mId != 0; }
    void reset() {
        if (mId) Delete(mId);
        mId = 0;
    }

  private:
    GLuint mId = 0;
};

namespace detail {
inline void deleteBuffer(GLuint id) {
    glDeleteBuffers(1, &id);
}
inline void deleteTexture(GLuint id) {
    glDeleteTextures(1, &id);
}
inline void deleteFramebuffer(GLuint id) {
    glDeleteFramebuffers(1, &id);
}
inline void deleteVertexArray(GLuint id) {
    glDeleteVertexArrays(1, &id);
}
inline void deleteQuery(GLuint id) {
    glDeleteQueries(1, &id);
}
inline void deleteProgram(GLuint id) {
    glDeleteProgram(id);
}
}  // namespace detail

/// Immutable-storage buffer (glNamedBufferStorage), dynamic so it can be updated in place.
class Buffer {
  public:
    Buffer() = default;
    Buffer(GLsizeiptr size, const void* data, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);
    void update(GLintptr offset, GLsizeiptr size, const void* data);
    void bindBase(GLenum target, GLuint index) const { glBindBufferBase(target, index, id()); }
    GLuint id() const { return mHandle.id(); }
    GLsizeiptr size() const { return mSize; }

  private:
    Handle<detail::deleteBuffer> mHandle;
    GLsizeiptr mSize = 0;
};

/// 2D texture with immutable storage.
class Texture2D {
  public:
    Texture2D() = default;
    Texture2D(int width, int height, GLenum internalFormat, int levels = 1);
    GLuint id() const { return mHandle.id(); }
    int width() const { return mWidth; }
    int height() const { return mHeight; }
    GLenum format() const { return mFormat; }

  private:
    Handle<detail::deleteTexture> mHandle;
    int mWidth = 0, mHeight = 0;
    GLenum mFormat = 0;
};

/// Layered texture with immutable storage: GL_TEXTURE_2D_ARRAY or GL_TEXTURE_CUBE_MAP_ARRAY
/// (layers = 6 x cubes, face-major within a cube). Depth formats get linear filtering and
/// GL_LEQUAL comparison, for shadow samplers (hardware 2 x 2 percentage-closer filtering).
class TextureArray {
  public:
    TextureArray() = default;
    TextureArray(GLenum target, int width, int height, int layers, GLenum internalFormat);
    GLuint id() const { return mHandle.id(); }
    int width() const { return mWidth; }
    int height() const { return mHeight; }
    int layers() const { return mLayers; }

  private:
    Handle<detail::deleteTexture> mHandle;
    int mWidth = 0, mHeight = 0, mLayers = 0;
};

class Framebuffer {
  public:
    Framebuffer() = default;
    /// Attaches colour textures in order and an optional depth texture; throws if incomplete.
    Framebuffer(std::initializer_list<const Texture2D*> colour, const Texture2D* depth);
    /// A depth-only framebuffer (no colour buffer) for attachDepthLayer.
    static Framebuffer depthOnly();
    /// Renders depth into one layer of `array` from now on; throws if incomplete.
    void attachDepthLayer(const TextureArray& array, int layer);
    GLuint id() const { return mHandle.id(); }

  private:
    Handle<detail::deleteFramebuffer> mHandle;
};

class VertexArray {
  public:
    VertexArray();
    GLuint id() const { return mHandle.id(); }

  private:
    Handle<detail::deleteVertexArray> mHandle;
};

/// A linked program; created by ShaderLibrary.
class Program {
  public:
    Program() = default;
    explicit Program(GLuint id) : mHandle(id) {}
    GLuint id() const { return mHandle.id(); }
    explicit operator bool() const { return bool(mHandle); }

  private:
    Handle<detail::deleteProgram> mHandle;
};

/// GL_TIME_ELAPSED query, read back without stalling when possible.
class TimerQuery {
  public:
    TimerQuery();
    void begin() { glBeginQuery(GL_TIME_ELAPSED, mHandle.id()); }
    void end() { glEndQuery(GL_TIME_ELAPSED); }
    /// Whether the result is there (never waits).
    bool available() const;
    /// Elapsed GPU time in milliseconds (waits for the result).
    double milliseconds() const;

  private:
    Handle<detail::deleteQuery> mHandle;
};

}  // namespace candela::gl
