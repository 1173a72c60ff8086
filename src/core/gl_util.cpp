#include "core/gl_util.hpp"

#include <algorithm>
#include <vector>

#include "starnt/error.hpp"

namespace starnt::gl {

void deleteTexture(GLuint id) { glDeleteTextures(1, &id); }
void deleteBuffer(GLuint id) { glDeleteBuffers(1, &id); }
void deleteFramebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
void deleteVertexArray(GLuint id) { glDeleteVertexArrays(1, &id); }
void deleteProgram(GLuint id) { glDeleteProgram(id); }
void deleteQuery(GLuint id) { glDeleteQueries(1, &id); }

size_t bytesPerTexel(GLenum f) {
    switch (f) {
        case GL_RGBA32F: return 16;
        case GL_RGBA16F: return 8;
        case GL_RGBA8: return 4;
        case GL_RG32F: return 8;
        case GL_R32F: case GL_R32UI: case GL_DEPTH_COMPONENT32F: case GL_DEPTH24_STENCIL8: return 4;
        case GL_R16F: return 2;
        case GL_R8: return 1;
        default: throw Error("internal: unknown texture format 0x" + std::to_string(f));
    }
}

Texture2D::Texture2D(GLenum internalFormat, int width, int height, GLenum filter)
    : format_(internalFormat), width_(width), height_(height) {
    GLuint id = 0;
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
    glCreateBuffers(1, &id);
    handle_ = Handle<deleteBuffer>(id);
    glNamedBufferStorage(id, GLsizeiptr(bytes), data, flags);
    if (glGetError() == GL_OUT_OF_MEMORY) {
        handle_.reset();
        throw Error("out of GPU memory allocating a buffer of " + std::to_string(bytes) + " bytes");
    }
}

FramebufferHandle makeFramebuffer(std::initializer_list<const Texture2D*> colors, const Texture2D* depth) {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    FramebufferHandle fb(id);
    std::vector<GLenum> drawBuffers;
    GLenum slot = GL_COLOR_ATTACHMENT0;
    for (const Texture2D* t : colors) {
        glNamedFramebufferTexture(id, slot, t->id(), 0);
        drawBuffers.push_back(slot++);
    }
    if (depth) glNamedFramebufferTexture(id, GL_DEPTH_ATTACHMENT, depth->id(), 0);
    if (drawBuffers.empty()) {
        glNamedFramebufferDrawBuffer(id, GL_NONE);
    } else {
        glNamedFramebufferDrawBuffers(id, GLsizei(drawBuffers.size()), drawBuffers.data());
    }
    GLenum status = glCheckNamedFramebufferStatus(id, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        throw Error("internal: incomplete framebuffer (status 0x" + std::to_string(status) + ")");
    }
    return fb;
}

VertexArrayHandle makeEmptyVertexArray() {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    return VertexArrayHandle(id);
}

void drawFullscreenTriangle(const VertexArrayHandle& emptyVao) {
    glBindVertexArray(emptyVao.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace starnt::gl
