#include "gl/gl_util.hpp"
#include "gl/pass_blend.hpp"

#include <atomic>
#include <dlfcn.h>

#include <initializer_list>

#include "starnt/error.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <vector>

#include "starnt/error.hpp"

namespace starnt::gl {

bool hasCurrentContext() {
    using GetCurrent = void* (*)();
    struct Api {
        GetCurrent egl = nullptr, glx = nullptr;
    };
    static thread_local Api api;  // per thread: no lock, and cheap after the first look-up
    // Looked up until one is found (the engine may load its library after us), then never again:
    // render() and every released name ask, and a context can only be current once the library
    // that made it is loaded, so the first look-up with a context current finds it.
    if (!api.egl && !api.glx) {
        auto find = [](std::initializer_list<const char*> libraries, const char* symbol) -> GetCurrent {
            for (const char* library : libraries) {
                if (void* handle = dlopen(library, RTLD_LAZY | RTLD_NOLOAD)) {
                    void* f = dlsym(handle, symbol);
                    dlclose(handle);
                    if (f) return reinterpret_cast<GetCurrent>(f);
                }
            }
            return reinterpret_cast<GetCurrent>(dlsym(RTLD_DEFAULT, symbol));
        };
        if (!api.egl) api.egl = find({"libEGL.so.1", "libEGL.so"}, "eglGetCurrentContext");
        if (!api.glx) api.glx = find({"libGLX.so.0", "libGL.so.1", "libGL.so"}, "glXGetCurrentContext");
    }
    return (api.egl && api.egl()) || (api.glx && api.glx());
}

void checkFrameSize(int width, int height) {
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    if (width < 1 || height < 1) throw Error("frame size " + size + ": width and height must be at least 1");
    GLint maxTexture = 0, maxFbWidth = 0, maxFbHeight = 0, viewport[2] = {0, 0};
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &maxFbWidth);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &maxFbHeight);
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
    const int maxWidth = std::min({maxTexture, maxFbWidth, viewport[0]});
    const int maxHeight = std::min({maxTexture, maxFbHeight, viewport[1]});
    if (width > maxWidth || height > maxHeight) {
        throw Error("frame size " + size + " exceeds what this context can render into (" + std::to_string(maxWidth) + "x" +
                    std::to_string(maxHeight) + ": GL_MAX_TEXTURE_SIZE, GL_MAX_FRAMEBUFFER_WIDTH/HEIGHT, GL_MAX_VIEWPORT_DIMS)");
    }
}

ShadingRateImageSupport shadingRateImageSupport(int texelSize, int paletteEntries) {
    ShadingRateImageSupport support;
    if (!epoxy_is_desktop_gl() || !epoxy_has_gl_extension("GL_NV_shading_rate_image")) {
        support.missing = "GL_NV_shading_rate_image (a shading-rate image; GPU drivers only)";
        return support;
    }
    GLint width = 0, height = 0, palette = 0;
    glGetIntegerv(GL_SHADING_RATE_IMAGE_TEXEL_WIDTH_NV, &width);
    glGetIntegerv(GL_SHADING_RATE_IMAGE_TEXEL_HEIGHT_NV, &height);
    glGetIntegerv(GL_SHADING_RATE_IMAGE_PALETTE_SIZE_NV, &palette);
    if (width != texelSize || height != texelSize) {
        support.missing = "shading-rate image texels of " + std::to_string(texelSize) + "x" + std::to_string(texelSize) +
                          " pixels (this driver's: " + std::to_string(width) + "x" + std::to_string(height) + ")";
    } else if (palette < paletteEntries) {
        support.missing = "a shading-rate palette of " + std::to_string(paletteEntries) + " entries (this driver's: " +
                          std::to_string(palette) + ")";
    } else {
        support.usable = true;
    }
    return support;
}

void deleteTexture(GLuint id) { glDeleteTextures(1, &id); }
void deleteBuffer(GLuint id) { glDeleteBuffers(1, &id); }
void deleteFramebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
void deleteVertexArray(GLuint id) { glDeleteVertexArrays(1, &id); }
void deleteProgram(GLuint id) { glDeleteProgram(id); }
void deleteQuery(GLuint id) { glDeleteQueries(1, &id); }
void deleteSampler(GLuint id) { glDeleteSamplers(1, &id); }

size_t bytesPerTexel(GLenum f) {
    switch (f) {
        case GL_RGBA32F: case GL_RGBA32UI: return 16;
        case GL_RGBA16F: return 8;
        case GL_RGBA8: case GL_RGB10_A2: case GL_RG16F: return 4;
        case GL_RG32F: case GL_RG32UI: return 8;
        case GL_R32F: case GL_R32UI: case GL_DEPTH_COMPONENT32F: case GL_DEPTH24_STENCIL8: return 4;
        case GL_R16F: case GL_R16: case GL_DEPTH_COMPONENT16: return 2;
        case GL_R8: case GL_R8UI: return 1;
        default: {
            char hex[16];
            std::snprintf(hex, sizeof hex, "0x%04X", unsigned(f));
            throw Error(std::string("internal: unknown texture format ") + hex);
        }
    }
}

Texture2D::Texture2D(GLenum internalFormat, int width, int height, GLenum filter)
    : format_(internalFormat), width_(width), height_(height) {
    GLuint id = 0;
    if (isEs()) {
        glGenTextures(1, &id);
        handle_ = Handle<deleteTexture>(id);
        glBindTexture(GL_TEXTURE_2D, id);
        glTexStorage2D(GL_TEXTURE_2D, 1, internalFormat, width, height);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GLint(filter));
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GLint(filter));
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        return;
    }
    glCreateTextures(GL_TEXTURE_2D, 1, &id);
    handle_ = Handle<deleteTexture>(id);
    glTextureStorage2D(id, 1, internalFormat, width, height);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, filter);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, filter);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

Buffer::Buffer(size_t bytes, const void* data, GLbitfield flags) : bytes_(bytes) {
    GLuint id = 0;
    if (isEs()) {
        // ES 3.2 has no immutable buffer storage (EXT_buffer_storage is optional); a mutable store
        // of the same size serves: nothing here maps buffers persistently.
        glGenBuffers(1, &id);
        handle_ = Handle<deleteBuffer>(id);
        glBindBuffer(GL_COPY_WRITE_BUFFER, id);
        glBufferData(GL_COPY_WRITE_BUFFER, GLsizeiptr(bytes), data, GL_DYNAMIC_DRAW);
    } else {
        glCreateBuffers(1, &id);
        handle_ = Handle<deleteBuffer>(id);
        glNamedBufferStorage(id, GLsizeiptr(bytes), data, flags);
    }
    // A store the GL could not create leaves the size at 0 (GL_OUT_OF_MEMORY). Asked by the size, not
    // by glGetError, which would take an error the engine left pending before render().
    GLint64 size = 0;
    if (isEs()) glGetBufferParameteri64v(GL_COPY_WRITE_BUFFER, GL_BUFFER_SIZE, &size);
    else glGetNamedBufferParameteri64v(id, GL_BUFFER_SIZE, &size);
    if (size != GLint64(bytes)) {
        handle_.reset();
        throw Error("out of GPU memory allocating a buffer of " + std::to_string(bytes) + " bytes");
    }
}

FramebufferHandle makeFramebuffer(std::initializer_list<const Texture2D*> colors, const Texture2D* depth) {
    FramebufferHandle fb = makeFramebufferName();
    const GLuint id = fb.id();
    std::vector<GLenum> drawBuffers;
    GLenum slot = GL_COLOR_ATTACHMENT0;
    for (const Texture2D* t : colors) {
        attachTexture(id, slot, t->id());
        drawBuffers.push_back(slot++);
    }
    if (depth) attachTexture(id, GL_DEPTH_ATTACHMENT, depth->id());
    GLenum status = 0;
    if (isEs()) {
        glBindFramebuffer(GL_FRAMEBUFFER, id);
        const GLenum none = GL_NONE;
        if (drawBuffers.empty()) {
            glDrawBuffers(1, &none);
        } else {
            glDrawBuffers(GLsizei(drawBuffers.size()), drawBuffers.data());
        }
        status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    } else {
        if (drawBuffers.empty()) {
            glNamedFramebufferDrawBuffer(id, GL_NONE);
        } else {
            glNamedFramebufferDrawBuffers(id, GLsizei(drawBuffers.size()), drawBuffers.data());
        }
        status = glCheckNamedFramebufferStatus(id, GL_FRAMEBUFFER);
    }
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        char hex[16];
        std::snprintf(hex, sizeof hex, "0x%04X", unsigned(status));
        throw Error(std::string("internal: incomplete framebuffer (status ") + hex + ")");
    }
    return fb;
}

bool isEs() { return !epoxy_is_desktop_gl(); }

void bindTexture(GLuint unit, GLuint texture) {
    if (isEs()) {
        glActiveTexture(GL_TEXTURE0 + unit);
        glBindTexture(GL_TEXTURE_2D, texture);
    } else {
        glBindTextureUnit(unit, texture);
    }
}

ContextToken::ContextToken() : vertexArray_(makeEmptyVertexArray()) {
    static std::atomic<unsigned long long> next{0};
    label_ = "starnt context token " + std::to_string(next++);
    glObjectLabel(GL_VERTEX_ARRAY, vertexArray_.id(), GLsizei(label_.size()), label_.c_str());
}

bool ContextToken::current() const {
    if (!glIsVertexArray(vertexArray_.id())) return false;  // no GL error for a name that is not one here
    char label[64] = {};
    GLsizei length = 0;
    glGetObjectLabel(GL_VERTEX_ARRAY, vertexArray_.id(), GLsizei(sizeof label), &length, label);
    return std::string(label, size_t(std::max<GLsizei>(length, 0))) == label_;
}

QueryBufferUnbound::QueryBufferUnbound() {
    if (isEs()) return;
    glGetIntegerv(GL_QUERY_BUFFER_BINDING, &buffer_);
    if (buffer_ != 0) glBindBuffer(GL_QUERY_BUFFER, 0);
}

QueryBufferUnbound::~QueryBufferUnbound() {
    if (buffer_ != 0) glBindBuffer(GL_QUERY_BUFFER, GLuint(buffer_));
}

PixelStoreDefaults::PixelStoreDefaults(Direction direction, GLint alignment) : direction_(direction) {
    const bool pack = direction == Pack;
    // Every parameter of the direction, with its default; ES 3.2 lacks the byte-order ones and,
    // for packing, the image parameters.
    std::vector<std::pair<GLenum, GLint>> defaults =
        pack ? std::vector<std::pair<GLenum, GLint>>{{GL_PACK_ROW_LENGTH, 0}, {GL_PACK_SKIP_ROWS, 0}, {GL_PACK_SKIP_PIXELS, 0},
                                                     {GL_PACK_ALIGNMENT, alignment}}
             : std::vector<std::pair<GLenum, GLint>>{{GL_UNPACK_ROW_LENGTH, 0}, {GL_UNPACK_IMAGE_HEIGHT, 0}, {GL_UNPACK_SKIP_ROWS, 0},
                                                     {GL_UNPACK_SKIP_PIXELS, 0}, {GL_UNPACK_SKIP_IMAGES, 0}, {GL_UNPACK_ALIGNMENT, alignment}};
    if (!isEs()) {
        if (pack) {
            defaults.insert(defaults.end(), {{GL_PACK_IMAGE_HEIGHT, 0}, {GL_PACK_SKIP_IMAGES, 0}, {GL_PACK_SWAP_BYTES, GL_FALSE}, {GL_PACK_LSB_FIRST, GL_FALSE}});
        } else {
            defaults.insert(defaults.end(), {{GL_UNPACK_SWAP_BYTES, GL_FALSE}, {GL_UNPACK_LSB_FIRST, GL_FALSE}});
        }
    }
    for (const auto& [name, value] : defaults) {
        GLint current = 0;
        glGetIntegerv(name, &current);
        if (current == value) continue;
        saved_.emplace_back(name, current);
        glPixelStorei(name, value);
    }
    glGetIntegerv(pack ? GL_PIXEL_PACK_BUFFER_BINDING : GL_PIXEL_UNPACK_BUFFER_BINDING, &buffer_);
    if (buffer_ != 0) glBindBuffer(pack ? GL_PIXEL_PACK_BUFFER : GL_PIXEL_UNPACK_BUFFER, 0);
}

PixelStoreDefaults::~PixelStoreDefaults() {
    for (const auto& [name, value] : saved_) glPixelStorei(name, value);
    if (buffer_ != 0) glBindBuffer(direction_ == Pack ? GL_PIXEL_PACK_BUFFER : GL_PIXEL_UNPACK_BUFFER, GLuint(buffer_));
}

void fillBufferUint(const Buffer& buffer, uint32_t value) {
    if (isEs()) {
        const std::vector<uint32_t> words(buffer.bytes() / 4, value);
        glBindBuffer(GL_COPY_WRITE_BUFFER, buffer.id());
        glBufferSubData(GL_COPY_WRITE_BUFFER, 0, GLsizeiptr(words.size() * 4), words.data());
    } else {
        const PixelStoreDefaults unpack(PixelStoreDefaults::Unpack);
        glClearNamedBufferData(buffer.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &value);
    }
}

void readBuffer(GLuint buffer, size_t offset, size_t bytes, void* out) {
    if (bytes == 0) return;
    if (!isEs()) {
        glGetNamedBufferSubData(buffer, GLintptr(offset), GLsizeiptr(bytes), out);
        return;
    }
    glBindBuffer(GL_COPY_READ_BUFFER, buffer);
    const void* mapped = glMapBufferRange(GL_COPY_READ_BUFFER, GLintptr(offset), GLsizeiptr(bytes), GL_MAP_READ_BIT);
    if (!mapped) throw Error("internal: glMapBufferRange failed reading a buffer back");
    std::memcpy(out, mapped, bytes);
    glUnmapBuffer(GL_COPY_READ_BUFFER);
}

void copyBuffer(GLuint source, GLuint destination, size_t bytes) {
    if (isEs()) {
        glBindBuffer(GL_COPY_READ_BUFFER, source);
        glBindBuffer(GL_COPY_WRITE_BUFFER, destination);
        glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0, GLsizeiptr(bytes));
    } else {
        glCopyNamedBufferSubData(source, destination, 0, 0, GLsizeiptr(bytes));
    }
}

void readTexture(GLuint texture, int width, int height, GLenum format, GLenum type, void* out, size_t bytes) {
    const PixelStoreDefaults pack(PixelStoreDefaults::Pack);
    if (!isEs()) {
        glGetTextureImage(texture, 0, format, type, GLsizei(bytes), out);
        return;
    }
    GLuint fb = 0;
    glGenFramebuffers(1, &fb);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fb);
    glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, 0);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    const GLenum status = glCheckFramebufferStatus(GL_READ_FRAMEBUFFER);
    if (status == GL_FRAMEBUFFER_COMPLETE) glReadPixels(0, 0, width, height, format, type, out);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fb);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        throw Error("internal: texture read-back on OpenGL ES: the texture is not colour-renderable");
    }
}

std::vector<float> readTextureFloats(GLuint texture, int width, int height, int channels) {
    std::vector<float> out(size_t(width) * size_t(height) * size_t(channels));
    if (!isEs()) {
        readTexture(texture, width, height, channels == 1 ? GL_RED : GL_RGBA, GL_FLOAT, out.data(), out.size() * sizeof(float));
        return out;
    }
    std::vector<float> rgba(size_t(width) * size_t(height) * 4);
    readTexture(texture, width, height, GL_RGBA, GL_FLOAT, rgba.data(), rgba.size() * sizeof(float));
    if (channels == 4) return rgba;
    for (size_t i = 0; i < out.size(); ++i) out[i] = rgba[i * 4];
    return out;
}

void uploadTexture(GLuint texture, int width, int height, GLenum format, GLenum type, const void* pixels) {
    const PixelStoreDefaults unpack(PixelStoreDefaults::Unpack);
    if (isEs()) {
        glBindTexture(GL_TEXTURE_2D, texture);
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, format, type, pixels);
    } else {
        glTextureSubImage2D(texture, 0, 0, 0, width, height, format, type, pixels);
    }
}

GLenum textureInternalFormat(GLuint texture) {
    GLint format = 0;
    if (isEs()) {
        glBindTexture(GL_TEXTURE_2D, texture);
        glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    } else {
        glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    }
    return GLenum(format);
}

FramebufferHandle makeFramebufferName() {
    GLuint id = 0;
    if (isEs()) {
        glGenFramebuffers(1, &id);
        glBindFramebuffer(GL_FRAMEBUFFER, id);
    } else {
        glCreateFramebuffers(1, &id);
    }
    return FramebufferHandle(id);
}

bool isDepthFormat(GLenum f) {
    switch (f) {
        case GL_DEPTH_COMPONENT16:
        case GL_DEPTH_COMPONENT24:
        case GL_DEPTH_COMPONENT32:
        case GL_DEPTH_COMPONENT32F:
        case GL_DEPTH24_STENCIL8:
        case GL_DEPTH32F_STENCIL8:
            return true;
        default:
            return false;
    }
}

TextureDescription describeTexture(GLuint texture, GLuint unit) {
    TextureDescription d;
    if (texture == 0 || !glIsTexture(texture)) return d;
    if (isEs()) {
        glActiveTexture(GL_TEXTURE0 + unit);
        glBindTexture(GL_TEXTURE_2D, 0);
        glBindTexture(GL_TEXTURE_2D, texture);
        GLint bound = 0;
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
        if (GLuint(bound) != texture) {
            glGetError();  // the failed bind's GL_INVALID_OPERATION
            return d;
        }
    } else {
        GLint target = 0;
        glGetTextureParameteriv(texture, GL_TEXTURE_TARGET, &target);
        if (target != GL_TEXTURE_2D) return d;
    }
    // Level 0's parameters and the texture's: direct state access, or ES's bound texture.
    auto level = [&](GLenum pname) {
        GLint v = 0;
        if (isEs()) glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, pname, &v);
        else glGetTextureLevelParameteriv(texture, 0, pname, &v);
        return v;
    };
    GLint immutable = 0;
    if (isEs()) glGetTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_IMMUTABLE_FORMAT, &immutable);
    else glGetTextureParameteriv(texture, GL_TEXTURE_IMMUTABLE_FORMAT, &immutable);
    d.immutable = immutable != 0;
    const GLint width = level(GL_TEXTURE_WIDTH), height = level(GL_TEXTURE_HEIGHT), format = level(GL_TEXTURE_INTERNAL_FORMAT),
                redType = level(GL_TEXTURE_RED_TYPE);
    d.is2D = true;
    d.width = width;
    d.height = height;
    d.internalFormat = GLenum(format);
    d.integer = redType == GL_INT || redType == GL_UNSIGNED_INT;
    auto parameter = [&](GLenum pname) {
        GLint v = 0;
        if (isEs()) glGetTexParameteriv(GL_TEXTURE_2D, pname, &v);
        else glGetTextureParameteriv(texture, pname, &v);
        return v;
    };
    d.read.baseLevel = parameter(GL_TEXTURE_BASE_LEVEL);
    d.read.depthStencilMode = parameter(GL_DEPTH_STENCIL_TEXTURE_MODE);
    const GLenum swizzles[4] = {GL_TEXTURE_SWIZZLE_R, GL_TEXTURE_SWIZZLE_G, GL_TEXTURE_SWIZZLE_B, GL_TEXTURE_SWIZZLE_A};
    for (int i = 0; i < 4; ++i) d.read.swizzle[i] = parameter(swizzles[i]);
    return d;
}

void setTextureReadState(GLuint texture, GLuint unit, const TextureReadState& state) {
    auto set = [&](GLenum pname, GLint value) {
        if (isEs()) glTexParameteri(GL_TEXTURE_2D, pname, value);
        else glTextureParameteri(texture, pname, value);
    };
    if (isEs()) {
        glActiveTexture(GL_TEXTURE0 + unit);
        glBindTexture(GL_TEXTURE_2D, texture);
    }
    set(GL_TEXTURE_BASE_LEVEL, state.baseLevel);
    set(GL_DEPTH_STENCIL_TEXTURE_MODE, state.depthStencilMode);
    const GLenum swizzles[4] = {GL_TEXTURE_SWIZZLE_R, GL_TEXTURE_SWIZZLE_G, GL_TEXTURE_SWIZZLE_B, GL_TEXTURE_SWIZZLE_A};
    for (int i = 0; i < 4; ++i) set(swizzles[i], state.swizzle[i]);
}

GLenum attachTexture(GLuint framebuffer, GLenum attachment, GLuint texture) {
    if (isEs()) {
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        glFramebufferTexture2D(GL_FRAMEBUFFER, attachment, GL_TEXTURE_2D, texture, 0);
        return glCheckFramebufferStatus(GL_FRAMEBUFFER);
    }
    glNamedFramebufferTexture(framebuffer, attachment, texture, 0);
    return glCheckNamedFramebufferStatus(framebuffer, GL_FRAMEBUFFER);
}

void setFramebufferDefaultSize(GLuint framebuffer, int width, int height) {
    if (isEs()) {
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        glFramebufferParameteri(GL_FRAMEBUFFER, GL_FRAMEBUFFER_DEFAULT_WIDTH, width);
        glFramebufferParameteri(GL_FRAMEBUFFER, GL_FRAMEBUFFER_DEFAULT_HEIGHT, height);
    } else {
        glNamedFramebufferParameteri(framebuffer, GL_FRAMEBUFFER_DEFAULT_WIDTH, width);
        glNamedFramebufferParameteri(framebuffer, GL_FRAMEBUFFER_DEFAULT_HEIGHT, height);
    }
}


void setViewportF(float x, float y, float width, float height) {
    if (!isEs()) {
        glViewportIndexedf(0, x, y, width, height);
    } else if (epoxy_has_gl_extension("GL_OES_viewport_array")) {
        glViewportIndexedfOES(0, x, y, width, height);
    } else if (x == float(int(x)) && y == float(int(y))) {
        glViewport(int(x), int(y), int(width), int(height));
    } else {
        throw Error("this OpenGL ES context lacks GL_OES_viewport_array, which passes rendered at a reduced "
                    "scale need (their samples must fall on full-resolution pixel centres); use full-resolution "
                    "passes (--spatial off or --scales 100,100)");
    }
}

VertexArrayHandle makeEmptyVertexArray() {
    GLuint id = 0;
    if (isEs()) {
        glGenVertexArrays(1, &id);
        glBindVertexArray(id);  // a generated name becomes a vertex array at its first bind
    } else {
        glCreateVertexArrays(1, &id);
    }
    return VertexArrayHandle(id);
}

void drawFullscreenTriangle(const VertexArrayHandle& emptyVao) {
    // As MethodBase::runGeometryPass: no silent INVALID_OPERATION where ES cannot blend 32-bit floats.
    checkFloatBlend("a full-screen pass");
    glBindVertexArray(emptyVao.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace starnt::gl
