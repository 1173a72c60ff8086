// The interface every OIT method implements, and how an engine drives one.
//
// A method never owns the scene. The engine gives it
//   - a SurfaceShader: the engine's vertex shader and a fragment function `vec4 starntSurface()`
//     returning the fragment's linear, straight (not premultiplied) colour and alpha; the method
//     wraps it in each of its geometry passes' fragment `main`;
//   - a DrawCallback, called once per geometry pass with the pass's program already bound and the
//     pass's GL state set; the engine sets its own uniforms on that program and issues its draws.
// After render() the result is in outputTexture(): linear RGBA float, composited over the background
// (FrameDesc::background or backgroundTexture), alpha 1 (or premultiplied: FrameDesc::premultipliedOutput),
// at the frame size; RGBA32F for most methods, RGBA16F for starnt, dfaoit, hybrid,
// starnt-residual and recommended with their default compact targets (NeuralOptions::Targets;
// hybrid-moments and starnt-d: 16-bit values in an RGBA32F texture), which may hand out one of
// their pass targets, written over in place. Ask the texture for its format (glGetTextureLevelParameteriv,
// GL_TEXTURE_INTERNAL_FORMAT) before copying it with glCopyImageSubData. Read it before the next render().
//
//   auto method = starnt::createMethod("wboit", engineSurface, {});
//   method->render(frame, [&](const starnt::GeometryPass& pass) { engine.drawTransparent(pass.program); });
//
// The public headers include no GL header, so an engine keeps its own loader (glad, epoxy, GLEW or
// the system's): GL names appear as GLname, the same type as GLuint.
#pragma once
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "starnt/error.hpp"
#include "starnt/frame_stats.hpp"
#include "starnt/method_options.hpp"

namespace starnt {

// A GL object name (GLuint in every GL header).
using GLname = unsigned int;

struct SurfaceShader {
    // Vertex shader body without #version. It must declare `invariant gl_Position;`: depth peeling
    // compares depths of the same fragment across passes bit for bit.
    std::string vertex;
    // Fragment-stage code without #version or main; defines `vec4 starntSurface()`. Its textures
    // and buffers must use the binding points starnt/bindings.h leaves to the engine.
    std::string fragment;
};

struct GeometryPass {
    const char* name;  // e.g. "abuffer_build", "peel", "pass1"
    GLname program;    // bound; set the engine's uniforms on it
};
using DrawCallback = std::function<void(const GeometryPass&)>;

// Per-pass timing and work counting, implemented by the engine (or by the tools' GPU timer). A
// method calls beginPass/endPass around each of its passes (geometry passes by their GeometryPass
// name, the others e.g. "composite", "tiles", "reproject"; a name may come back within a frame,
// e.g. peel layers), and beginGeometry/endGeometry right around the engine's draws of a geometry
// pass, inside its beginPass/endPass. Calls never nest beyond that. The hook runs on the rendering
// thread with the method's GL state bound: it may issue queries but must not change other state.
class PassTimingHook {
public:
    virtual ~PassTimingHook() = default;
    virtual void beginPass(const std::string& name) = 0;
    virtual void endPass() = 0;
    virtual void beginGeometry(const std::string& /*name*/) {}
    virtual void endGeometry() {}
};

struct FrameDesc {
    int width = 0;
    int height = 0;
    glm::vec3 background{1.0f};  // linear; where backgroundTexture is 0
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};
    float alphaCutoff = 0.03f;          // fragments with alpha below are discarded in every pass
    PassTimingHook* timing = nullptr;   // optional per-pass timing (not owned)

    // The engine's opaque scene, drawn before the methods run (docs/INTEGRATION.md, "Opaque
    // geometry"). Both are read, never written; 0 = none.
    // opaqueDepth: the engine's depth texture (GL_TEXTURE_2D, DEPTH_COMPONENT16/24/32F or
    // DEPTH24_STENCIL8 / DEPTH32F_STENCIL8, frame size, written with this view and projection and
    // depth range 0..1). Every geometry pass of every method drops the fragments at or behind it
    // (window depth >= the opaque depth), by a depth test before the fragment shader runs.
    GLname opaqueDepth = 0;
    // backgroundTexture: the engine's opaque colour (GL_TEXTURE_2D, a colour format, linear RGB,
    // frame size). The output is composited over it per pixel instead of over `background`.
    GLname backgroundTexture = 0;
    // Premultiplied output for engines that blend the result into their own target: the output's
    // RGB is the transparent layers composited over black and its alpha the total transmittance
    // prod(1 - a), so that blending it with glBlendFunc(GL_ONE, GL_SRC_ALPHA) onto the engine's
    // colour (dst = src.rgb + src.a * dst) gives the composite over that colour. backgroundTexture
    // and background are then not read.
    bool premultipliedOutput = false;
};

class OitMethod {
public:
    virtual ~OitMethod() = default;
    virtual std::string name() const = 0;  // the name createMethod was given ("recommended" included)
    virtual void render(const FrameDesc& frame, const DrawCallback& draw) = 0;
    // Valid until the next render(); the name may change from frame to frame.
    virtual GLname outputTexture() const = 0;
    // Bytes of every GPU buffer and texture the method holds now.
    virtual size_t gpuMemoryBytes() const = 0;
    // The same by target (name -> bytes; the values sum to gpuMemoryBytes()). Methods that do not
    // break it down report one entry, "all".
    using MemoryTargets = std::vector<std::pair<std::string, size_t>>;
    virtual MemoryTargets gpuMemoryTargets() const { return {{"all", gpuMemoryBytes()}}; }
    // What the last frame did (fragments stored, layers peeled, scales, tiles, temporal reuse):
    // each method family fills its own group of FrameStats.
    virtual FrameStats lastFrameStats() const { return {}; }
    // The output of the last frame with the tile levels of the last real frame blended over it
    // (RGBA32F, frame size); 0 when the method has no tiles.
    virtual GLname tileOverlayTexture() { return 0; }
    // Forgets temporal history (last real frame, tile masks), e.g. after a scene change or a cut.
    virtual void resetHistory() {}
};

// The configuration the project recommends, `createMethod("recommended", ...)`, chosen per context
// (docs/INTEGRATION.md, "Which method"; docs/DESIGN.md, "The recommended configuration"):
// - where the caller left the temporal settings at their defaults (interval 1, not auto, corrected
//   mode, Auto layers, one pass) and the context has GL_EXT_shader_framebuffer_fetch and 5 draw
//   buffers: kbuffer-moments, one geometry pass a frame (the nearest three fragments exact, the
//   ordered closed form of the depth moments behind them);
// - elsewhere with the defaults: starnt-d with every frame real (interpolated frames of one exact
//   layer measured no faster on a GPU, and flashing: docs/DESIGN.md, "The recommended configuration
//   without framebuffer fetch");
// - where the caller asked for temporal frames: starnt-d with them (recommendedOptions).
// recommendedMethodInContext names the method, recommendedOptionsInContext gives its options; both
// need the context current.
// recommendedOptions returns `options` with kRecommendedTemporalInterval where it asks for every
// frame real (interval 1, not auto): starnt-d's interval of choice where interpolated frames are
// wanted.
constexpr int kRecommendedTemporalInterval = 8;
MethodOptions recommendedOptions(MethodOptions options = {});
MethodOptions recommendedOptionsInContext(MethodOptions options = {});
std::string recommendedMethodInContext(const MethodOptions& options = {});

// Names accepted by createMethod, in a stable order.
std::vector<std::string> methodNames();
// Needs the engine's GL context current on this thread. Throws starnt::Error for an unknown name
// (listing the valid ones), bad options, a context that lacks what the methods need
// (checkGlRequirements) or a shader the driver rejects.
std::unique_ptr<OitMethod> createMethod(const std::string& name, const SurfaceShader& surface,
                                        const MethodOptions& options = {});

// Throws starnt::Error naming what the current context lacks (no current context, desktop OpenGL
// below 4.5 core, OpenGL ES below 3.2 or without EXT_color_buffer_float, EXT_float_blend and
// OES_texture_float_linear, too few fragment storage blocks or draw buffers). createMethod calls
// it. Both APIs run the same passes: the methods read the API from the current context and pick
// the GLSL dialect (450 core or 320 es) and the few calls that differ (docs/INTEGRATION.md).
void checkGlRequirements();

}  // namespace starnt
