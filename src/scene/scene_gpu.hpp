// The built-in scene renderer: uploads a Scene once and draws it inside any method's geometry
// passes. It is an "engine" as far as the methods are concerned: it supplies the SurfaceShader and
// the draw callback, exactly what a user's engine would.
#pragma once
#include <optional>
#include <vector>

#include "gl/gl_util.hpp"
#include "gl/shader.hpp"
#include "starnt/oit_method.hpp"
#include "starnt/tools/scene.hpp"

namespace starnt {

struct SurfaceOptions {
    std::optional<float> alphaOverride;  // --alpha
    bool forceUnlit = false;             // --unlit
};

class SceneGpu {
public:
    explicit SceneGpu(const Scene& scene);
    ~SceneGpu();
    SceneGpu(const SceneGpu&) = delete;
    SceneGpu& operator=(const SceneGpu&) = delete;

    static SurfaceShader surfaceShader();

    // Draws the transparent meshes with `pass.program` (already bound by the method): those whose
    // material is BLEND, or every mesh under an alpha override (SurfaceOptions::alphaOverride, which
    // turns every material into BLEND with that alpha).
    void draw(const GeometryPass& pass, const glm::mat4& view, const glm::mat4& projection,
              const SurfaceOptions& options) const;
    // Whether the scene has an opaque part under these options: a mesh whose material is OPAQUE or
    // MASK, and no alpha override.
    bool hasOpaque(const SurfaceOptions& options) const;
    // Whether any mesh is drawn transparent (by the method) with these options.
    bool hasTransparent(const SurfaceOptions& options) const;
    // What an engine does before the transparent methods run: draws the opaque part at the frame's
    // camera into this renderer's opaque colour (RGBA16F, cleared to frame.background) and depth
    // (DEPTH_COMPONENT32F, cleared to the far plane) textures, and points frame.opaqueDepth and
    // frame.backgroundTexture at them. Without an opaque part it leaves both 0 and draws nothing.
    // The textures are kept until the next call.
    void drawOpaque(FrameDesc& frame, const SurfaceOptions& options) const;
    // A DrawCallback bound to this scene, camera and options.
    DrawCallback callback(const glm::mat4& view, const glm::mat4& projection, const SurfaceOptions& options) const;

    size_t gpuMemoryBytes() const { return bytes_; }

private:
    struct MeshGpu {
        gl::VertexArrayHandle vao;
        std::vector<gl::Buffer> buffers;
        GLsizei indexCount = 0;
        int material = 0;
        bool hasNormals = false;
    };
    std::vector<MeshGpu> meshes_;
    std::vector<Material> materials_;
    std::vector<GLuint> textures_;
    size_t bytes_ = 0;
    bool isOpaque(const MeshGpu& m, const SurfaceOptions& options) const;
    void drawMeshes(GLuint program, const glm::mat4& view, const glm::mat4& projection, const SurfaceOptions& options,
                    bool opaque) const;
    // The opaque pass (drawOpaque), built and allocated on first use.
    mutable gl::Program opaqueProgram_;
    mutable gl::Texture2D opaqueColor_, opaqueDepth_;
    mutable gl::FramebufferHandle opaqueFb_;
};

}  // namespace starnt
