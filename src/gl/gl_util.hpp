// Small RAII wrappers for the GL objects the methods allocate, with byte accounting so every
// method can report the GPU memory it holds (docs/DESIGN.md, "Benchmark").
#pragma once
#include <epoxy/gl.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>


namespace starnt::gl {

// True when an EGL or GLX context is current on this thread (asked of whichever of libEGL and
// libGL/libGLX the process has loaded, without loading either: a GL call through epoxy without a
// context aborts the process). Handles release their names only then; otherwise the names die
// with their context (docs/INTEGRATION.md, "Misuse").
bool hasCurrentContext();
// Throws starnt::Error naming the size unless 1 <= width, height <= the context's
// GL_MAX_TEXTURE_SIZE, GL_MAX_FRAMEBUFFER_WIDTH / HEIGHT and GL_MAX_VIEWPORT_DIMS: checked before
// anything of that size is allocated.
void checkFrameSize(int width, int height);

// Whether the current context offers a shading-rate image (GL_NV_shading_rate_image) whose
// texels cover `texelSize` x `texelSize` pixels, with a palette of at least `paletteEntries`
// rates; `missing` says what is not there otherwise (docs/DESIGN.md, "Per-tile shading rates on GPUs").
struct ShadingRateImageSupport {
    bool usable = false;
    std::string missing;
};
ShadingRateImageSupport shadingRateImageSupport(int texelSize, int paletteEntries);

// Owns one GL name; Deleter is called with the name on destruction, when a context is current.
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
        if (id_ && hasCurrentContext()) Deleter(id_);
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
void deleteSampler(GLuint id);

using FramebufferHandle = Handle<deleteFramebuffer>;
using VertexArrayHandle = Handle<deleteVertexArray>;
using QueryHandle = Handle<deleteQuery>;
using SamplerHandle = Handle<deleteSampler>;

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

// Which context made an object set: an empty vertex array labelled with a name unique in the
// process. Vertex arrays (like framebuffers) are not shared between contexts, so `current()` is
// true only in the context that made it: a method used with another context current is refused
// instead of touching that context's objects by coincidence of names (docs/INTEGRATION.md, "Misuse").
class ContextToken {
public:
    ContextToken();
    bool current() const;

private:
    VertexArrayHandle vertexArray_;
    std::string label_;
};

// The engine's GL_QUERY_BUFFER unbound for the guard's life (desktop GL 4.4+; nothing on ES): with
// one bound, glGetQueryObject* writes into it at the pointer's value as an offset instead of into
// client memory.
class QueryBufferUnbound {
public:
    QueryBufferUnbound();
    ~QueryBufferUnbound();
    QueryBufferUnbound(const QueryBufferUnbound&) = delete;
    QueryBufferUnbound& operator=(const QueryBufferUnbound&) = delete;

private:
    GLint buffer_ = 0;
};

// A framebuffer with the given colour attachments (in order) and an optional depth texture.
FramebufferHandle makeFramebuffer(std::initializer_list<const Texture2D*> colors, const Texture2D* depth = nullptr);

// ---- One code for OpenGL 4.5 core and OpenGL ES 3.2 -------------------------------------------
// The methods run the same passes and shaders on both APIs. Where GL 4.5 has a direct-state-access
// call that ES 3.2 lacks, the calls below keep the desktop call (so desktop behaviour is what it
// was) and use the ES 3.2 bind-to-edit equivalent on ES; each says which. The binding points they
// touch on ES (GL_TEXTURE_2D of the active unit, GL_COPY_READ/WRITE_BUFFER, GL_READ_FRAMEBUFFER,
// GL_FRAMEBUFFER) are in the list of state docs/INTEGRATION.md says render() may change.

// True when the current context is OpenGL ES.
bool isEs();

// The pixel-store state of one direction (pack: reads back; unpack: uploads and buffer clears) set
// to GL's defaults with `alignment`, and the pixel buffer of that direction unbound, for the
// guard's life; the engine's values come back after it. Mesa applies the unpack skips even to
// glClearNamedBufferData's one-element source, so an engine's GL_UNPACK_SKIP_PIXELS made it read
// past the value on the stack (docs/INTEGRATION.md, "State").
class PixelStoreDefaults {
public:
    enum Direction { Pack, Unpack };
    explicit PixelStoreDefaults(Direction direction, GLint alignment = 4);
    ~PixelStoreDefaults();
    PixelStoreDefaults(const PixelStoreDefaults&) = delete;
    PixelStoreDefaults& operator=(const PixelStoreDefaults&) = delete;

private:
    Direction direction_;
    GLint buffer_ = 0;
    std::vector<std::pair<GLenum, GLint>> saved_;
};
// glBindTextureUnit (ES: glActiveTexture + glBindTexture(GL_TEXTURE_2D); every texture the methods
// bind is 2D).
void bindTexture(GLuint unit, GLuint texture);
// Sets every 32-bit word of a buffer to `value` (glClearNamedBufferData; ES: glBufferSubData).
void fillBufferUint(const Buffer& buffer, uint32_t value);
// Reads `bytes` at `offset` (glGetNamedBufferSubData; ES: glMapBufferRange for reading).
void readBuffer(GLuint buffer, size_t offset, size_t bytes, void* out);
// glCopyNamedBufferSubData (ES: glCopyBufferSubData through the copy binding points).
void copyBuffer(GLuint source, GLuint destination, size_t bytes);
// Level 0 of a 2D colour texture as floats: `channels` 1 (GL_RED) or 4 (GL_RGBA), rows bottom-up
// as GL stores them (glGetTextureImage; ES, which cannot read textures back, attaches it to a
// framebuffer and calls glReadPixels with RGBA/FLOAT, which EXT_color_buffer_float guarantees).
std::vector<float> readTextureFloats(GLuint texture, int width, int height, int channels);
// Level 0 of a colour texture as `format` / `type` texels (glGetTextureImage; on ES the texture on a
// read framebuffer, glReadPixels, which takes RGBA with FLOAT or RGBA_INTEGER with UNSIGNED_INT).
void readTexture(GLuint texture, int width, int height, GLenum format, GLenum type, void* out, size_t bytes);
// glTextureSubImage2D of the whole level 0 (ES: glBindTexture + glTexSubImage2D).
void uploadTexture(GLuint texture, int width, int height, GLenum format, GLenum type, const void* pixels);
// The sized internal format of level 0 (glGetTextureLevelParameteriv; ES 3.1: glGetTexLevelParameteriv).
GLenum textureInternalFormat(GLuint texture);
// What a texture name the engine gave is (FrameDesc::opaqueDepth, backgroundTexture): whether it
// names a 2D texture, and level 0's size and sized internal format. Desktop: glIsTexture and the
// direct-state queries, which raise no GL error. ES cannot ask a texture's target: it binds the name
// to GL_TEXTURE_2D of `unit` and reads the binding back (a texture of another target fails that
// bind with a GL_INVALID_OPERATION, which this then clears).
// The texture state that a sampler object does not hold and that texelFetch(..., 0) obeys: which
// level the fetch's level 0 is, what a depth-stencil texture returns, and the component swizzle.
// An engine's own texture may have any of it set (a depth pyramid's base level, a stencil view).
struct TextureReadState {
    GLint baseLevel = 0;
    GLint depthStencilMode = GL_DEPTH_COMPONENT;
    GLint swizzle[4] = {GL_RED, GL_GREEN, GL_BLUE, GL_ALPHA};
    bool operator==(const TextureReadState&) const = default;
};
struct TextureDescription {
    bool is2D = false;
    int width = 0, height = 0;
    GLenum internalFormat = 0;
    bool integer = false;  // an integer colour format (sampled by a float sampler: undefined)
    bool immutable = false;  // glTexStorage: complete whatever its filter (glCopyImageSubData needs that)
    TextureReadState read;
};
TextureDescription describeTexture(GLuint texture, GLuint unit);
// Sets `texture`'s read state (ES: through `unit`, which it leaves bound to it).
void setTextureReadState(GLuint texture, GLuint unit, const TextureReadState& state);
bool isDepthFormat(GLenum internalFormat);
// A framebuffer name (glCreateFramebuffers; ES: glGenFramebuffers + a first bind, which creates it).
FramebufferHandle makeFramebufferName();
// Attaches level 0 of `texture` (or 0 to detach) and checks completeness; returns the status.
GLenum attachTexture(GLuint framebuffer, GLenum attachment, GLuint texture);
// The size a framebuffer without attachments rasterises at (glNamedFramebufferParameteri; ES 3.1:
// glFramebufferParameteri).
void setFramebufferDefaultSize(GLuint framebuffer, int width, int height);
// Viewport 0 with a fractional origin (glViewportIndexedf). ES needs OES_viewport_array for it
// (llvmpipe and most ES 3.2 drivers have it); without it, a fractional origin is an error, since
// the reduced passes' samples would miss the full-resolution pixel centres.
void setViewportF(float x, float y, float width, float height);

// An empty vertex array for attribute-less full-screen triangles (gl_VertexID based). Each
// owner keeps its own: vertex arrays are not shared between contexts.
VertexArrayHandle makeEmptyVertexArray();
// Draws one full-screen triangle with the currently bound program.
void drawFullscreenTriangle(const VertexArrayHandle& emptyVao);

}  // namespace starnt::gl
