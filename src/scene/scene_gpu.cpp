#include "scene/scene_gpu.hpp"
#include "scene/tool_sources.hpp"

#include <glm/gtc/type_ptr.hpp>

#include <cstdio>
#include <string>

#include "gl/shader.hpp"
#include "starnt/error.hpp"
#include "scene/scene_constants.h"

namespace starnt {
namespace {

template <typename T>
gl::Buffer upload(const std::vector<T>& data) {
    return gl::Buffer(data.size() * sizeof(T), data.data(), 0);
}

}  // namespace

SurfaceShader SceneGpu::surfaceShader() {
    return {tools::toolSource("scene/scene_surface.vert.glsl"), tools::toolSource("scene/scene_surface.frag.glsl")};
}

SceneGpu::SceneGpu(const Scene& scene) : materials_(scene.materials) {
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    for (size_t i = 0; i < scene.textures.size(); ++i) {
        const Texture& t = scene.textures[i];
        const std::string label = "texture " + std::to_string(i) + (t.name.empty() ? "" : " (" + t.name + ")");
        if (t.width > maxSize || t.height > maxSize) {
            if (!textures_.empty()) glDeleteTextures(GLsizei(textures_.size()), textures_.data());
            throw Error(label + " is " + std::to_string(t.width) + "x" + std::to_string(t.height) +
                        " pixels: larger than this GL driver's GL_MAX_TEXTURE_SIZE of " + std::to_string(maxSize) +
                        " (scale the image down)");
        }
        while (glGetError() != GL_NO_ERROR) {
        }
        // Bind-to-edit calls that OpenGL 4.5 and OpenGL ES 3.2 share (the scene renderer runs on both).
        GLuint id = 0;
        glGenTextures(1, &id);
        glBindTexture(GL_TEXTURE_2D, id);
        int levels = 1;
        while ((std::max(t.width, t.height) >> levels) > 0) ++levels;
        glTexStorage2D(GL_TEXTURE_2D, levels, GL_SRGB8_ALPHA8, t.width, t.height);
        if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
            glDeleteTextures(1, &id);
            if (!textures_.empty()) glDeleteTextures(GLsizei(textures_.size()), textures_.data());
            throw Error(label + " (" + std::to_string(t.width) + "x" + std::to_string(t.height) +
                        "): the GL driver cannot allocate it (GL error 0x" + [e] {
                            char b[16];
                            std::snprintf(b, sizeof b, "%04x", unsigned(e));
                            return std::string(b);
                        }() + ")");
        }
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, t.width, t.height, GL_RGBA, GL_UNSIGNED_BYTE, t.rgba8.data());
        glGenerateMipmap(GL_TEXTURE_2D);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        textures_.push_back(id);
        bytes_ += size_t(t.width) * size_t(t.height) * 4 * 4 / 3;
    }
    for (const Mesh& m : scene.meshes) {
        MeshGpu g;
        // Separate attribute formats on the bound vertex array: GL 4.3+ and ES 3.1+ alike.
        GLuint vao = 0;
        glGenVertexArrays(1, &vao);
        glBindVertexArray(vao);
        g.vao = gl::VertexArrayHandle(vao);
        auto attach = [&](GLuint location, gl::Buffer buffer, GLint components) {
            glBindVertexBuffer(location, buffer.id(), 0, GLsizei(components * sizeof(float)));
            glVertexAttribFormat(location, components, GL_FLOAT, GL_FALSE, 0);
            glVertexAttribBinding(location, location);
            glEnableVertexAttribArray(location);
            bytes_ += buffer.bytes();
            g.buffers.push_back(std::move(buffer));
        };
        attach(STARNT_ATTRIB_POSITION, upload(m.positions), 3);
        if (!m.normals.empty()) attach(STARNT_ATTRIB_NORMAL, upload(m.normals), 3);
        if (!m.uvs.empty()) attach(STARNT_ATTRIB_UV, upload(m.uvs), 2);
        if (!m.colors.empty()) attach(STARNT_ATTRIB_COLOR, upload(m.colors), 4);
        gl::Buffer indices = upload(m.indices);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices.id());  // recorded in the bound vertex array
        bytes_ += indices.bytes();
        g.buffers.push_back(std::move(indices));
        g.indexCount = GLsizei(m.indices.size());
        g.material = m.material;
        g.hasNormals = !m.normals.empty();
        glBindVertexArray(0);
        meshes_.push_back(std::move(g));
    }
}

SceneGpu::~SceneGpu() {
    if (!textures_.empty()) glDeleteTextures(GLsizei(textures_.size()), textures_.data());
}

bool SceneGpu::isOpaque(const MeshGpu& m, const SurfaceOptions& options) const {
    return !options.alphaOverride && materials_[size_t(m.material)].alphaMode != AlphaMode::Blend;
}

bool SceneGpu::hasTransparent(const SurfaceOptions& options) const {
    for (const MeshGpu& m : meshes_) {
        if (!isOpaque(m, options)) return true;
    }
    return false;
}

bool SceneGpu::hasOpaque(const SurfaceOptions& options) const {
    for (const MeshGpu& m : meshes_) {
        if (isOpaque(m, options)) return true;
    }
    return false;
}

void SceneGpu::draw(const GeometryPass& pass, const glm::mat4& view, const glm::mat4& projection,
                    const SurfaceOptions& options) const {
    drawMeshes(pass.program, view, projection, options, false);
}

void SceneGpu::drawOpaque(FrameDesc& frame, const SurfaceOptions& options) const {
    frame.opaqueDepth = frame.backgroundTexture = 0;
    if (!hasOpaque(options)) return;
    if (!opaqueProgram_) {
        const SurfaceShader surface = surfaceShader();
        opaqueProgram_ = gl::buildProgram("scene_opaque", surface.vertex,
                                          surface.fragment + "\n" + tools::toolSource("scene/scene_opaque.frag.glsl"));
    }
    if (opaqueColor_.width() != frame.width || opaqueColor_.height() != frame.height) {
        opaqueColor_ = gl::Texture2D(GL_RGBA16F, frame.width, frame.height);
        opaqueDepth_ = gl::Texture2D(GL_DEPTH_COMPONENT32F, frame.width, frame.height);
        opaqueFb_ = gl::makeFramebuffer({&opaqueColor_}, &opaqueDepth_);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, opaqueFb_.id());
    glViewport(0, 0, frame.width, frame.height);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    const float background[4] = {frame.background.r, frame.background.g, frame.background.b, 1.0f}, farDepth = 1.0f;
    glClearBufferfv(GL_COLOR, 0, background);
    glClearBufferfv(GL_DEPTH, 0, &farDepth);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glUseProgram(opaqueProgram_.id());
    drawMeshes(opaqueProgram_.id(), frame.view, frame.projection, options, true);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    frame.opaqueDepth = opaqueDepth_.id();
    frame.backgroundTexture = opaqueColor_.id();
}

void SceneGpu::drawMeshes(GLuint p, const glm::mat4& view, const glm::mat4& projection, const SurfaceOptions& options,
                          bool opaque) const {
    auto loc = [p](const char* name) { return glGetUniformLocation(p, name); };
    glUniformMatrix4fv(loc("u_view"), 1, GL_FALSE, glm::value_ptr(view));
    glUniformMatrix4fv(loc("u_projection"), 1, GL_FALSE, glm::value_ptr(projection));
    glUniform1f(loc("u_alphaOverride"), options.alphaOverride ? *options.alphaOverride : -1.0f);
    const GLint baseColor = loc("u_baseColorFactor"), hasTexture = loc("u_hasTexture"), unlit = loc("u_unlit"),
                hasNormals = loc("u_hasNormals"), drawIndex = loc("u_drawIndex"), maskCutoff = loc("u_maskCutoff"),
                emissive = loc("u_emissive");
    // Single-sided materials (glTF doubleSided false) show their front faces only where the file
    // made them opaque or transparent itself; a material the --alpha override makes transparent
    // shows both (docs/DESIGN.md, "Scenes"). The loader keeps every front face counter-clockwise
    // (GL negates the facing area under an upper-left clip origin, so that needs nothing here).
    glFrontFace(GL_CCW);
    glCullFace(GL_BACK);
    // Absent attributes read these constants.
    glVertexAttrib3f(STARNT_ATTRIB_NORMAL, 0.0f, 0.0f, 0.0f);
    glVertexAttrib2f(STARNT_ATTRIB_UV, 0.0f, 0.0f);
    glVertexAttrib4f(STARNT_ATTRIB_COLOR, 1.0f, 1.0f, 1.0f, 1.0f);
    for (size_t i = 0; i < meshes_.size(); ++i) {
        const MeshGpu& m = meshes_[i];
        if (isOpaque(m, options) != opaque) continue;
        const Material& mat = materials_[size_t(m.material)];
        if (opaque) glUniform1f(maskCutoff, mat.alphaMode == AlphaMode::Mask ? mat.alphaCutoff : -1.0f);
        glUniform4fv(baseColor, 1, glm::value_ptr(mat.baseColorFactor));
        glUniform3fv(emissive, 1, glm::value_ptr(mat.emissive));
        const bool frontOnly = !mat.doubleSided && (opaque || mat.alphaMode == AlphaMode::Blend);
        if (frontOnly) glEnable(GL_CULL_FACE);
        else glDisable(GL_CULL_FACE);
        glUniform1i(unlit, (mat.unlit || options.forceUnlit) ? 1 : 0);
        glUniform1i(hasNormals, m.hasNormals ? 1 : 0);
        glUniform1i(hasTexture, mat.baseColorTexture >= 0 ? 1 : 0);
        if (mat.baseColorTexture >= 0) {
            gl::bindTexture(STARNT_SURFACE_TEXTURE_UNIT, textures_[size_t(mat.baseColorTexture)]);
        }
        if (drawIndex >= 0) glUniform1i(drawIndex, GLint(i));
        glBindVertexArray(m.vao.id());
        glDrawElements(GL_TRIANGLES, m.indexCount, GL_UNSIGNED_INT, nullptr);
    }
    glBindVertexArray(0);
    glDisable(GL_CULL_FACE);
    glFrontFace(GL_CCW);
}

DrawCallback SceneGpu::callback(const glm::mat4& view, const glm::mat4& projection,
                                const SurfaceOptions& options) const {
    return [this, view, projection, options](const GeometryPass& pass) { draw(pass, view, projection, options); };
}

}  // namespace starnt
