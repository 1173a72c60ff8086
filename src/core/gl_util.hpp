// Small RAII wrappers for the GL objects the methods allocate, with byte accounting so every
// method can report the GPU memory it holds (SPEC section 8).
#pragma once
#include <epoxy/gl.h>

#include <cstddef>
#include <string>
#include <utility>


namespace starnt::gl {

// Owns one GL name; Deleter is called with the name on destruction.
template <void (*Deleter)(GLuint)>
class Handle {
public:
    Handle() = default;
    explicit Handle(GLuint id) : id_(id) {}
    ~Handle() { reset(); }
    Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
    Handle& operator=(Handle&& o) noexcept {
        if (this != &o) {
            reset();
            id_ = std::exchange(o.id_, 0);
        }
        return *this;
    }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    void reset() {
        if (id_) Deleter(id_);
        id_ = 0;
    }
    GLuint id() const { return id_; }
    explicit operator bool() const { return id_ != 0; }

private:
    GLuint id_ = 0;
};

void deleteTexture(GLuint id);
void deleteBuffer(GLuint id);
void deleteFramebuffer(GLuint id);
void deleteVertexArray(GLuint id);
void deleteProgram(GLuint id);
void deleteQuery(GLuint id);

using FramebufferHandle = Handle<deleteFramebuffer>;
using VertexArrayHandle = Handle<deleteVertexArray>;
using QueryHandle = Handle<deleteQuery>;

// Bytes per texel of the sized internal formats we use.
size_t bytesPerTexel(GLenum internalFormat);

class Texture2D {
public:
    Texture2D() = default;
    Texture2D(GLenum internalFormat, int width, int height, GLenum filter = GL_NEAREST);
    GLuint id() const { return handle_.id(); }
    int width() const { return width_; }
    int height() const { return height_; }
    GLenum format() const { return format_; }
    size_t bytes() const { return handle_ ? size_t(width_) * size_t(height_) * bytesPerTexel(format_) : 0; }
    explicit operator bool() const { return bool(handle_); }

private:
    Handle<deleteTexture> handle_;
    GLenum format_ = 0;
    int width_ = 0, height_ = 0;
};

class Buffer {
public:
    Buffer() = default;
    explicit Buffer(size_t bytes, const void* data = nullptr, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);
    GLuint id() const { return handle_.id(); }
    size_t bytes() const { return bytes_; }
    explicit operator bool() const { return bool(handle_); }

private:
    Handle<deleteBuffer> handle_;
    size_t bytes_ = 0;
};

// A framebuffer with the given colour attachments (in order) and an optional depth texture.
FramebufferHandle makeFramebuffer(std::initializer_list<const Texture2D*> colors, const Texture2D* depth = nullptr);

// An empty vertex array for attribute-less full-screen triangles (gl_VertexID based). Each
// owner keeps its own: vertex arrays are not shared between contexts.
VertexArrayHandle makeEmptyVertexArray();
// Draws one full-screen triangle with the currently bound program.
void drawFullscreenTriangle(const VertexArrayHandle& emptyVao);

}  // namespace starnt::gl
