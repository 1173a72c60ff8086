// The built-in scene renderer: uploads a Scene once and draws it inside any method's geometry
// passes. It is an "engine" as far as the methods are concerned: it supplies the SurfaceShader and
// the draw callback, exactly what a user's engine would.
#pragma once
#include <optional>
#include <vector>

#include "gl/gl_util.hpp"
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

    // Draws every mesh with `pass.program` (already bound by the method).
    void draw(const GeometryPass& pass, const glm::mat4& view, const glm::mat4& projection,
              const SurfaceOptions& options) const;
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
};

}  // namespace starnt
