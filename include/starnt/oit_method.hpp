// The interface every OIT method implements, and how an engine drives one.
//
// A method never owns the scene. The engine gives it
//   - a SurfaceShader: the engine's vertex shader and a fragment function `vec4 starntSurface()`
//     returning the fragment's linear, straight (not premultiplied) colour and alpha; the method
//     wraps it in each of its geometry passes' fragment `main`;
//   - a DrawCallback, called once per geometry pass with the pass's program already bound and the
//     pass's GL state set; the engine sets its own uniforms on that program and issues its draws.
// After render() the result is in outputTexture(): linear RGBA32F, composited over the background,
// alpha 1, at the frame size.
//
//   auto method = starnt::createMethod("wboit", engineSurface, {});
//   method->render(frame, [&](const starnt::GeometryPass& pass) { engine.drawTransparent(pass.program); });
#pragma once
#include <utility>
#include <epoxy/gl.h>

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace starnt {
namespace gl {
class GpuPassTimer;
}

struct SurfaceShader {
    // Vertex shader body without #version. It must declare `invariant gl_Position;`: depth peeling
    // compares depths of the same fragment across passes bit for bit.
    std::string vertex;
    // Fragment-stage code without #version or main; defines `vec4 starntSurface()`.
    std::string fragment;
};

struct GeometryPass {
    const char* name;  // e.g. "abuffer_build", "peel", "pass1"
    GLuint program;    // bound; set the engine's uniforms on it
};
using DrawCallback = std::function<void(const GeometryPass&)>;

struct FrameDesc {
    int width = 0;
    int height = 0;
    glm::vec3 background{1.0f};  // linear
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};
    float alphaCutoff = 0.03f;                // fragments with alpha below are discarded in every pass
    gl::GpuPassTimer* timer = nullptr;        // optional per-pass GPU timing
};

struct MethodOptions {
    // abuffer
    double abufferInitialNodesPerPixel = 4.0;  // initial pool size; it grows on overflow
    size_t abufferMemoryCapBytes = size_t(2) << 30;  // fail with a clear error beyond this
    // peel: number of layers; 0 peels until a layer comes back empty (exact)
    int peelLayers = 0;
    // wboit weight function: "eq10" (default, SPEC), "eq7", "eq8", "eq9" (McGuire & Bavoil 2013)
    std::string wboitWeight = "eq10";
    // mboit (moment-based OIT, Muenstermann et al. 2018): "4" or "6" power moments (default "6"),
    // "t2" or "t3" trigonometric moments (2 or 3 complex moments); 32-bit float storage
    std::string mboitMoments = "6";
    // neural methods: weights file; empty = the shipped default for the method
    std::string weightsPath;

    // ---- acceleration of the neural methods (SPEC sections 4-6); the other methods ignore it ----
    // Adaptive screen-space tiles evaluated after every real frame; their level histogram (w_bar)
    // sets the pass 2/3 scales of the next real frame. Unset: on for starnt, off for dfaoit.
    std::optional<bool> spatial;
    // Fixed pass 2/3 scales per axis in [0.25, 1] for ablations; 0 = chosen by the tiles (1 when
    // spatial is off).
    float fixedScale2 = 0.0f;
    float fixedScale3 = 0.0f;
    // How the tiles' w_bar becomes the scales (SPEC 5): Snapped (default) = the paper's value
    // snapped to 1, 1/2 or 1/4 (integer ratios keep reduced samples on pixel centres);
    // Continuous = the paper's formula as printed; Step = the authors' release.
    enum class ScaleRule { Snapped, Continuous, Step };
    ScaleRule scaleRule = ScaleRule::Snapped;
    // What the tiles measure (SPEC 4): Back (default) = the composite minus the nearest layer's
    // own term, C - a1 C1, what the reduced passes produce; Composite = the paper.
    enum class TileSignal { Back, Composite };
    TileSignal tileSignal = TileSignal::Back;
    // Scale guard (beyond the paper): passes 2/3 run at full resolution on probe frames (the first
    // real frames after a reset, then every 8th real frame); there the tiles update and the loss
    // of each reduced scale is predicted from the full-resolution image, and a pass is reduced
    // only as far as that loss stays within a fixed share of what the pass adds. It keeps thin
    // structures (hair, strands) that fall between tile corners at full resolution. Off: the
    // tiles update on every real frame and the rule alone decides (the paper).
    bool scaleGuard = true;
    // How reduced passes 2/3 come back to full resolution (SPEC 5): Bilinear = the four nearest
    // reduced samples by distance; Joint = joint bilateral, the same taps weighted down where the
    // nearest surface at a tap's sample lies at another depth than at the pixel (pass-1 depth
    // guides: a tap across a silhouette carries another surface's layers).
    enum class Upsample { Bilinear, Joint };
    Upsample upsample = Upsample::Bilinear;
    // Full: the network at every pixel. Corners: only at quadtree leaf corners, bilinear inside each
    // leaf (beyond the paper; needs the tiles, so it turns them on).
    enum class Inference { Full, Corners };
    Inference inference = Inference::Full;
    // Temporal reprojection: one real frame, then temporalInterval - 1 interpolated frames
    // (1 = off, at most 4). temporalAuto picks the largest interval whose group (one real frame,
    // interval - 1 interpolated ones, at their measured costs) fits in one frame at targetFps.
    int temporalInterval = 1;
    bool temporalAuto = false;
    // What an interpolated frame renders (SPEC 6): Warp = the paper (the last real frame's
    // composite reprojected; no geometry pass); Refresh = pass 1 at the current camera, so the
    // nearest layer is exact, over what lay behind it in the last real frame, reprojected.
    enum class TemporalMode { Warp, Refresh };
    TemporalMode temporalMode = TemporalMode::Refresh;
    double targetFps = 60.0;
};

class OitMethod {
public:
    virtual ~OitMethod() = default;
    virtual std::string name() const = 0;
    virtual void render(const FrameDesc& frame, const DrawCallback& draw) = 0;
    virtual GLuint outputTexture() const = 0;
    // Bytes of every GPU buffer and texture the method holds now.
    virtual size_t gpuMemoryBytes() const = 0;
    // The same by target (name -> bytes; the values sum to gpuMemoryBytes()). Methods that do not
    // break it down report one entry, "all".
    using MemoryTargets = std::vector<std::pair<std::string, size_t>>;
    virtual MemoryTargets gpuMemoryTargets() const { return {{"all", gpuMemoryBytes()}}; }
    // Method-specific counters of the last frame (e.g. max fragments per pixel). The neural methods
    // report "interpolated" (bool), "w_bar", "scale_pass2", "scale_pass3" and "tile_levels" (N_0..N_3).
    virtual nlohmann::json lastFrameStats() const { return nlohmann::json::object(); }
    // The output of the last frame with the tile levels of the last real frame blended over it
    // (RGBA32F, frame size); 0 when the method has no tiles.
    virtual GLuint tileOverlayTexture() { return 0; }
    // Forgets temporal history (last real frame, tile masks), e.g. after a scene change or a cut.
    virtual void resetHistory() {}
};

// Names accepted by createMethod, in a stable order.
std::vector<std::string> methodNames();
// Throws starnt::Error for an unknown name (listing the valid ones) or bad options.
std::unique_ptr<OitMethod> createMethod(const std::string& name, const SurfaceShader& surface,
                                        const MethodOptions& options = {});

}  // namespace starnt
