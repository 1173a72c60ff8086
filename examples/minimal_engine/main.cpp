// minimal_engine: an engine that owns its EGL context, its geometry and its shaders, and hands its
// transparent geometry to the STAR-NT OIT methods through the installed headers only.
//
//   minimal_engine [outdir] [gl|gles]
//
// Renders six overlapping semi-transparent quads with abuffer, peel, wboit, mboit and starnt,
// writes <outdir>/<method>.png and compares every method with the A-buffer (the exact reference).
// Then the engine's own opaque scene: it draws one slanted opaque quad through the stack into its own
// depth (DEPTH24_STENCIL8) and colour textures, hands them to the methods (FrameDesc::opaqueDepth,
// backgroundTexture), checks abuffer and peel against the exact composite it computes by ray casting,
// and blends starnt's premultiplied output (FrameDesc::premultipliedOutput) onto its colour itself.
// Exit code 0 when every check passes, 1 otherwise. `gles` makes the engine's context OpenGL ES 3.2
// instead of OpenGL 4.5 core: the methods read the API from the current context, nothing else
// changes (the engine's own GL calls below are the subset both APIs have).

// The engine's GL loader comes first; the STAR-NT headers include no GL header.
#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <starnt/bindings.h>
#include <starnt/error.hpp>
#include <starnt/tools/image.hpp>  // starnt::tools: savePng
#include <starnt/log.hpp>
#include <starnt/method_options.hpp>
#include <starnt/oit_method.hpp>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>
#include <utility>
#include <string>
#include <vector>

namespace {

constexpr int kSize = 256;

// ---------------------------------------------------------------------------------------------
// Headless OpenGL 4.5 core or OpenGL ES 3.2 context through EGL (the engine's own; no window system).

bool hasExtension(const char* list, const char* name) {
    if (!list) return false;
    const std::string all = std::string(" ") + list + " ";
    return all.find(std::string(" ") + name + " ") != std::string::npos;
}

struct EglContext {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    std::string platform;
    bool es = false;  // OpenGL ES 3.2 instead of OpenGL 4.5 core

    ~EglContext() {
        if (display != EGL_NO_DISPLAY) {
            eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
            eglTerminate(display);
        }
    }

    // Tries one display: initialise, bind desktop GL, create a 4.5 core context without a config
    // (or with a pbuffer config) and make it current without a surface. `why` gets the failure.
    bool tryDisplay(EGLDisplay dpy, const std::string& name, std::string& why) {
        if (dpy == EGL_NO_DISPLAY) {
            why += name + ": no display; ";
            return false;
        }
        EGLint major = 0, minor = 0;
        if (!eglInitialize(dpy, &major, &minor)) {
            why += name + ": eglInitialize failed; ";
            return false;
        }
        const char* extensions = eglQueryString(dpy, EGL_EXTENSIONS);
        if (!hasExtension(extensions, "EGL_KHR_surfaceless_context")) {
            why += name + ": no EGL_KHR_surfaceless_context; ";
            eglTerminate(dpy);
            return false;
        }
        if (!eglBindAPI(es ? EGL_OPENGL_ES_API : EGL_OPENGL_API)) {
            why += name + ": eglBindAPI failed; ";
            eglTerminate(dpy);
            return false;
        }
        EGLConfig config = EGL_NO_CONFIG_KHR;
        if (!hasExtension(extensions, "EGL_KHR_no_config_context")) {
            const EGLint configAttribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                            es ? EGL_OPENGL_ES3_BIT : EGL_OPENGL_BIT, EGL_NONE};
            EGLint count = 0;
            if (!eglChooseConfig(dpy, configAttribs, &config, 1, &count) || count < 1) {
                why += name + ": no OpenGL config; ";
                eglTerminate(dpy);
                return false;
            }
        }
        const EGLint desktopAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4,
                                         EGL_CONTEXT_MINOR_VERSION, 5,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                         EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                         EGL_NONE};
        const EGLint esAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 2, EGL_NONE};
        EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, es ? esAttribs : desktopAttribs);
        if (ctx == EGL_NO_CONTEXT) {
            why += name + (es ? ": no OpenGL ES 3.2 context" : ": no OpenGL 4.5 core context") + " (EGL error 0x" +
                   hex(eglGetError()) + "); ";
            eglTerminate(dpy);
            return false;
        }
        if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
            why += name + ": eglMakeCurrent failed; ";
            eglDestroyContext(dpy, ctx);
            eglTerminate(dpy);
            return false;
        }
        display = dpy;
        context = ctx;
        platform = name;
        return true;
    }

    static std::string hex(EGLint value) {
        char text[16];
        std::snprintf(text, sizeof text, "%04x", unsigned(value));
        return text;
    }

    // EGL_EXT_platform_device over every device, then EGL_MESA_platform_surfaceless.
    bool create(std::string& why) {
        const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
        if (!client) {
            why = "EGL has no client extensions";
            return false;
        }
        const bool platformBase = hasExtension(client, "EGL_EXT_platform_base");
        if (platformBase && hasExtension(client, "EGL_EXT_platform_device") &&
            (hasExtension(client, "EGL_EXT_device_enumeration") || hasExtension(client, "EGL_EXT_device_base"))) {
            EGLint count = 0;
            if (eglQueryDevicesEXT(0, nullptr, &count) && count > 0) {
                std::vector<EGLDeviceEXT> devices(static_cast<size_t>(count));
                eglQueryDevicesEXT(count, devices.data(), &count);
                for (EGLint i = 0; i < count; ++i) {
                    EGLDisplay dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[size_t(i)], nullptr);
                    if (tryDisplay(dpy, "device " + std::to_string(i), why)) return true;
                }
            } else {
                why += "device platform: no EGL devices; ";
            }
        } else {
            why += "no EGL_EXT_platform_device; ";
        }
        if (platformBase && hasExtension(client, "EGL_MESA_platform_surfaceless")) {
            EGLDisplay dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
            if (tryDisplay(dpy, "surfaceless", why)) return true;
        } else {
            why += "no EGL_MESA_platform_surfaceless; ";
        }
        return false;
    }
};

// ---------------------------------------------------------------------------------------------
// The engine's geometry: six quads parallel to the image plane at different depths, overlapping
// so that pixels are covered by 1, 2, 3, ... up to all 6 of them.

struct Vertex {
    float position[3];
    float colour[4];  // linear RGB, straight alpha
};

struct Quad {
    glm::vec2 centre, halfSize;
    float z;
    glm::vec4 colour;
};

const Quad kQuads[] = {
    {{-0.50f, 0.30f}, {0.70f, 0.60f}, 0.60f, {0.90f, 0.10f, 0.10f, 0.50f}},   // red, nearest
    {{0.40f, 0.20f}, {0.70f, 0.70f}, 0.30f, {0.10f, 0.80f, 0.20f, 0.40f}},    // green
    {{0.00f, -0.40f}, {0.80f, 0.50f}, 0.00f, {0.10f, 0.20f, 0.90f, 0.60f}},   // blue
    {{-0.20f, 0.00f}, {0.50f, 0.50f}, -0.30f, {0.95f, 0.85f, 0.10f, 0.30f}},  // yellow
    {{0.20f, -0.10f}, {0.45f, 0.45f}, -0.60f, {0.80f, 0.10f, 0.80f, 0.70f}},  // magenta
    {{0.00f, 0.10f}, {0.35f, 0.35f}, -0.90f, {0.10f, 0.85f, 0.85f, 0.50f}},   // cyan, farthest
};

struct Mesh {
    GLuint vao = 0, vbo = 0, ibo = 0;
    GLsizei indexCount = 0;

    void upload() {
        std::vector<Vertex> vertices;
        std::vector<GLuint> indices;
        for (const Quad& q : kQuads) {
            const GLuint base = GLuint(vertices.size());
            const float cx[4] = {-1, 1, 1, -1}, cy[4] = {-1, -1, 1, 1};
            for (int c = 0; c < 4; ++c)
                vertices.push_back({{q.centre.x + cx[c] * q.halfSize.x, q.centre.y + cy[c] * q.halfSize.y, q.z},
                                    {q.colour.r, q.colour.g, q.colour.b, q.colour.a}});
            for (GLuint i : {0u, 1u, 2u, 0u, 2u, 3u}) indices.push_back(base + i);
        }
        indexCount = GLsizei(indices.size());

        // Calls that OpenGL 4.5 core and OpenGL ES 3.1+ both have.
        glGenVertexArrays(1, &vao);
        glBindVertexArray(vao);
        glGenBuffers(1, &vbo);
        glBindBuffer(GL_ARRAY_BUFFER, vbo);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(Vertex)), vertices.data(), GL_STATIC_DRAW);
        glGenBuffers(1, &ibo);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo);  // recorded in the vertex array
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size() * sizeof(GLuint)), indices.data(), GL_STATIC_DRAW);
        glEnableVertexAttribArray(0);  // a_position
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<const void*>(offsetof(Vertex, position)));
        glEnableVertexAttribArray(1);  // a_colour
        glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<const void*>(offsetof(Vertex, colour)));
        glBindVertexArray(0);
    }

    void draw() const {
        glBindVertexArray(vao);
        glDrawElements(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, nullptr);
    }

    ~Mesh() {
        if (vao) glDeleteVertexArrays(1, &vao);
        if (vbo) glDeleteBuffers(1, &vbo);
        if (ibo) glDeleteBuffers(1, &ibo);
    }
};

// ---------------------------------------------------------------------------------------------
// The engine's surface shader (no #version: the method injects it).

const char* kVertexShader = R"GLSL(
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec4 a_colour;
uniform mat4 u_viewProjection;
out vec4 v_colour;
invariant gl_Position;
void main() {
    v_colour = a_colour;
    gl_Position = u_viewProjection * vec4(a_position, 1.0);
}
)GLSL";

// The engine's own opaque pass (not a STAR-NT pass): the same vertex shader, opaque colour out.
const char* kOpaqueFragment = R"GLSL(
in vec4 v_colour;
layout(location = 0) out vec4 o_colour;
void main() { o_colour = vec4(v_colour.rgb, 1.0); }
)GLSL";

// Blends a premultiplied output onto the bound target: the blend state does the compositing.
const char* kFullscreenVertex = R"GLSL(
void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)GLSL";
const char* kCopyFragment = R"GLSL(
uniform highp sampler2D u_source;
layout(location = 0) out vec4 o_colour;
void main() { o_colour = texelFetch(u_source, ivec2(gl_FragCoord.xy), 0); }
)GLSL";

const char* kSurfaceFunction = R"GLSL(
in vec4 v_colour;
vec4 starntSurface() {
    return v_colour;  // linear, straight colour and alpha
}
)GLSL";

// ---------------------------------------------------------------------------------------------
// The engine's opaque object: a quad slanted through the stack, z = -0.2 + 0.5 x over
// x in [-0.9, 0.9], y in [-0.8, 0.8].

const glm::vec3 kOpaqueColour(0.25f, 0.30f, 0.38f);
float opaqueZ(float x) { return -0.2f + 0.5f * x; }

GLuint compileProgram(bool es, const char* vertex, const char* fragment) {
    const std::string header = es ? "#version 320 es\nprecision highp float;\n" : "#version 450 core\n";
    GLuint program = glCreateProgram();
    for (auto [stage, body] : {std::pair{GL_VERTEX_SHADER, vertex}, std::pair{GL_FRAGMENT_SHADER, fragment}}) {
        GLuint shader = glCreateShader(stage);
        const std::string text = header + body;
        const char* source = text.c_str();
        glShaderSource(shader, 1, &source, nullptr);
        glCompileShader(shader);
        GLint ok = 0;
        glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
        if (!ok) throw std::runtime_error("engine shader does not compile");
        glAttachShader(program, shader);
        glDeleteShader(shader);
    }
    glLinkProgram(program);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) throw std::runtime_error("engine program does not link");
    return program;
}

struct OpaqueTarget {
    GLuint colour = 0, depth = 0, framebuffer = 0;
    ~OpaqueTarget() {
        glDeleteFramebuffers(1, &framebuffer);
        GLuint textures[2] = {colour, depth};
        glDeleteTextures(2, textures);
    }
};

// Draws the opaque quad into the engine's own colour (RGBA16F, cleared to `background`) and depth
// (DEPTH24_STENCIL8) textures, as an engine does before its transparent objects.
void drawOpaque(OpaqueTarget& t, bool es, const glm::mat4& viewProjection, const glm::vec3& background) {
    auto texture = [](GLenum format) {
        GLuint id = 0;
        glGenTextures(1, &id);
        glBindTexture(GL_TEXTURE_2D, id);
        glTexStorage2D(GL_TEXTURE_2D, 1, format, kSize, kSize);
        return id;
    };
    t.colour = texture(GL_RGBA16F);
    t.depth = texture(GL_DEPTH24_STENCIL8);
    glBindTexture(GL_TEXTURE_2D, 0);
    glGenFramebuffers(1, &t.framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, t.framebuffer);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t.colour, 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, t.depth, 0);
    glViewport(0, 0, kSize, kSize);
    const float clear[4] = {background.r, background.g, background.b, 1.0f};
    glClearBufferfv(GL_COLOR, 0, clear);
    glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    const GLuint program = compileProgram(es, kVertexShader, kOpaqueFragment);
    glUseProgram(program);
    glUniformMatrix4fv(glGetUniformLocation(program, "u_viewProjection"), 1, GL_FALSE, glm::value_ptr(viewProjection));
    const Vertex vertices[4] = {{{-0.9f, -0.8f, opaqueZ(-0.9f)}, {kOpaqueColour.r, kOpaqueColour.g, kOpaqueColour.b, 1.0f}},
                                {{0.9f, -0.8f, opaqueZ(0.9f)}, {kOpaqueColour.r, kOpaqueColour.g, kOpaqueColour.b, 1.0f}},
                                {{0.9f, 0.8f, opaqueZ(0.9f)}, {kOpaqueColour.r, kOpaqueColour.g, kOpaqueColour.b, 1.0f}},
                                {{-0.9f, 0.8f, opaqueZ(-0.9f)}, {kOpaqueColour.r, kOpaqueColour.g, kOpaqueColour.b, 1.0f}}};
    const GLuint indices[6] = {0, 1, 2, 0, 2, 3};
    GLuint vao = 0, buffers[2] = {0, 0};
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(2, buffers);
    glBindBuffer(GL_ARRAY_BUFFER, buffers[0]);
    glBufferData(GL_ARRAY_BUFFER, sizeof vertices, vertices, GL_STATIC_DRAW);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffers[1]);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, sizeof indices, indices, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<const void*>(offsetof(Vertex, position)));
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<const void*>(offsetof(Vertex, colour)));
    glDrawElements(GL_TRIANGLES, 6, GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
    glDeleteVertexArrays(1, &vao);
    glDeleteBuffers(2, buffers);
    glDeleteProgram(program);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

// The exact composite at pixel (x, y) (Image rows: 0 at the top) by casting its ray through the
// quads and the opaque quad; false where the pixel centre lies within `margin` of an edge or the
// opaque quad crosses a layer there (rasterisation decides those).
bool exactPixel(int x, int y, const glm::mat4& viewProjection, const glm::vec3& background, glm::vec3& out) {
    const glm::mat4 inverse = glm::inverse(viewProjection);
    const float nx = (float(x) + 0.5f) / float(kSize) * 2.0f - 1.0f, ny = 1.0f - (float(y) + 0.5f) / float(kSize) * 2.0f;
    const glm::vec4 a = inverse * glm::vec4(nx, ny, -1.0f, 1.0f), b = inverse * glm::vec4(nx, ny, 1.0f, 1.0f);
    const glm::vec3 origin = glm::vec3(a) / a.w, direction = glm::vec3(b) / b.w - origin;
    const float margin = 0.03f;
    // The opaque quad: z - 0.5 x = -0.2.
    const glm::vec3 normal(-0.5f, 0.0f, 1.0f);
    float opaqueT = 1e30f;
    glm::vec3 behind = background;
    const float tOpaque = (-0.2f - glm::dot(normal, origin)) / glm::dot(normal, direction);
    const glm::vec3 po = origin + tOpaque * direction;
    if (std::abs(std::abs(po.x) - 0.9f) < margin || std::abs(std::abs(po.y) - 0.8f) < margin) return false;
    if (std::abs(po.x) < 0.9f && std::abs(po.y) < 0.8f) {
        opaqueT = tOpaque;
        behind = kOpaqueColour;
    }
    std::vector<std::pair<float, glm::vec4>> hits;
    for (const Quad& q : kQuads) {
        const float t = (q.z - origin.z) / direction.z;
        const glm::vec3 p = origin + t * direction;
        const glm::vec2 d = glm::abs(glm::vec2(p) - q.centre) - q.halfSize;
        if (std::abs(d.x) < margin || std::abs(d.y) < margin) return false;
        if (d.x >= 0.0f || d.y >= 0.0f) continue;
        if (std::abs(t - opaqueT) < 0.01f) return false;
        if (t < opaqueT) hits.emplace_back(t, q.colour);
    }
    std::sort(hits.begin(), hits.end(), [](const auto& l, const auto& r) { return l.first < r.first; });
    glm::vec3 colour(0.0f);
    float transmittance = 1.0f;
    for (const auto& [t, c] : hits) {
        colour += transmittance * c.a * glm::vec3(c);
        transmittance *= 1.0f - c.a;
    }
    out = colour + transmittance * behind;
    return true;
}

// What an engine does with FrameDesc::premultipliedOutput: blends it onto its own colour with
// glBlendFunc(GL_ONE, GL_SRC_ALPHA), dst = src.rgb + src.a * dst.
void blendPremultiplied(GLuint premultiplied, GLuint framebuffer, bool es) {
    const GLuint program = compileProgram(es, kFullscreenVertex, kCopyFragment);
    GLuint vao = 0;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, kSize, kSize);
    glUseProgram(program);
    glActiveTexture(GL_TEXTURE0 + STARNT_ENGINE_FIRST_TEXTURE_UNIT);
    glBindTexture(GL_TEXTURE_2D, premultiplied);
    glUniform1i(glGetUniformLocation(program, "u_source"), STARNT_ENGINE_FIRST_TEXTURE_UNIT);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_SRC_ALPHA);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_BLEND);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteVertexArrays(1, &vao);
    glDeleteProgram(program);
}

starnt::Image readOutput(GLuint texture, int width, int height) {
    std::vector<float> pixels(size_t(width) * size_t(height) * 4);
    // render() may leave other state behind; make the pack state ours before reading.
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    // Through a read framebuffer, which both APIs have (ES has no glGetTexImage): RGBA/FLOAT is a
    // read format every float colour buffer allows.
    GLuint framebuffer = 0;
    glGenFramebuffers(1, &framebuffer);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, 0);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, pixels.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &framebuffer);
    starnt::Image image(width, height);
    const size_t row = size_t(width) * 4;
    for (int y = 0; y < height; ++y)  // GL row 0 is the bottom; Image row 0 is the top
        std::copy_n(&pixels[size_t(height - 1 - y) * row], row, &image.rgba[size_t(y) * row]);
    return image;
}

struct Difference {
    double mse = 0.0;      // mean over pixels and RGB of the squared linear difference
    double maxDiff = 0.0;  // largest absolute linear difference over pixels and RGB
};

Difference compare(const starnt::Image& reference, const starnt::Image& test) {
    Difference d;
    for (size_t p = 0; p < reference.pixelCount(); ++p)
        for (int c = 0; c < 3; ++c) {
            const double e = double(test.rgba[p * 4 + c]) - double(reference.rgba[p * 4 + c]);
            d.mse += e * e;
            d.maxDiff = std::max(d.maxDiff, std::abs(e));
        }
    d.mse /= double(reference.pixelCount() * 3);
    return d;
}

bool differsFromBackground(const starnt::Image& image, const glm::vec3& background) {
    for (size_t p = 0; p < image.pixelCount(); ++p)
        for (int c = 0; c < 3; ++c)
            if (std::abs(image.rgba[p * 4 + c] - background[c]) > 0.1f) return true;
    return false;
}

int run(const std::filesystem::path& outdir, bool es) {
    starnt::setLogCallback([](starnt::LogLevel level, const std::string& message) {
        std::fprintf(stderr, "starnt: %s: %s\n", level == starnt::LogLevel::Warning ? "warning" : "note",
                     message.c_str());
    });

    EglContext egl;
    egl.es = es;
    std::string why;
    if (!egl.create(why)) {
        std::fprintf(stderr, "minimal_engine: no headless %s context: %s\n", es ? "OpenGL ES 3.2" : "OpenGL 4.5 core",
                     why.c_str());
        return 1;
    }
    std::fprintf(stderr, "minimal_engine: EGL %s, %s, OpenGL %s\n", egl.platform.c_str(),
                 reinterpret_cast<const char*>(glGetString(GL_RENDERER)),
                 reinterpret_cast<const char*>(glGetString(GL_VERSION)));

    Mesh mesh;
    mesh.upload();

    const std::vector<std::string> wanted = {"abuffer", "peel", "wboit", "mboit", "starnt"};
    const std::vector<std::string> available = starnt::methodNames();
    for (const std::string& name : wanted)
        if (std::find(available.begin(), available.end(), name) == available.end()) {
            std::fprintf(stderr, "minimal_engine: the library has no method \"%s\"\n", name.c_str());
            return 1;
        }

    const glm::mat4 view = glm::lookAt(glm::vec3(0.4f, 0.3f, 4.0f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    const glm::mat4 projection = glm::perspective(glm::radians(45.0f), 1.0f, 0.1f, 100.0f);
    const glm::mat4 viewProjection = projection * view;

    starnt::FrameDesc frame;
    frame.width = kSize;
    frame.height = kSize;
    frame.background = glm::vec3(1.0f);
    frame.view = view;
    frame.projection = projection;

    const starnt::SurfaceShader surface{kVertexShader, kSurfaceFunction};
    const starnt::MethodOptions options;  // defaults: exact A-buffer and peel, eq10 wboit, 6 moments

    // The engine's transparent draws, as every geometry pass of every method calls them.
    const starnt::DrawCallback drawTransparent = [&](const starnt::GeometryPass& pass) {
        glUniformMatrix4fv(glGetUniformLocation(pass.program, "u_viewProjection"), 1, GL_FALSE,
                           glm::value_ptr(viewProjection));
        mesh.draw();
    };

    std::filesystem::create_directories(outdir);
    std::map<std::string, starnt::Image> images;
    for (const std::string& name : wanted) {
        auto method = starnt::createMethod(name, surface, options);
        method->render(frame, drawTransparent);
        images[name] = readOutput(method->outputTexture(), kSize, kSize);
        const starnt::FrameStats stats = method->lastFrameStats();
        if (stats.peel) std::fprintf(stderr, "minimal_engine: peel peeled %d layers\n", stats.peel->layers);
        if (stats.abuffer)
            std::fprintf(stderr, "minimal_engine: abuffer stored %llu fragments\n",
                         static_cast<unsigned long long>(stats.abuffer->fragments));
        starnt::savePng(images[name], (outdir / (name + ".png")).string());
    }
    if (GLenum error = glGetError(); error != GL_NO_ERROR) {
        std::fprintf(stderr, "minimal_engine: GL error 0x%04x\n", error);
        return 1;
    }

    const starnt::Image& reference = images.at("abuffer");
    std::map<std::string, Difference> diffs;
    std::printf("method MSE maxdiff (linear RGB, vs abuffer)\n");
    for (const std::string& name : wanted) {
        diffs[name] = compare(reference, images.at(name));
        std::printf("%s %.6g %.6g\n", name.c_str(), diffs[name].mse, diffs[name].maxDiff);
    }

    std::vector<std::string> failures;
    for (const std::string& name : wanted)
        if (!differsFromBackground(images.at(name), frame.background))
            failures.push_back(name + ": the image is uniformly the background");
    if (diffs["peel"].maxDiff > 1e-3)
        failures.push_back("peel: max abs difference " + std::to_string(diffs["peel"].maxDiff) + " > 1e-3");
    if (!(diffs["starnt"].mse < diffs["wboit"].mse))
        failures.push_back("starnt: MSE " + std::to_string(diffs["starnt"].mse) + " is not below wboit's " +
                           std::to_string(diffs["wboit"].mse));
    if (!(diffs["starnt"].mse < 1e-3))
        failures.push_back("starnt: MSE " + std::to_string(diffs["starnt"].mse) + " is not below 1e-3");

    // ---- The engine's opaque scene ----
    OpaqueTarget opaque;
    drawOpaque(opaque, es, viewProjection, frame.background);
    frame.opaqueDepth = opaque.depth;
    frame.backgroundTexture = opaque.colour;
    std::map<std::string, starnt::Image> withOpaque;
    std::unique_ptr<starnt::OitMethod> starntMethod;
    for (const std::string& name : wanted) {
        auto method = starnt::createMethod(name, surface, options);
        method->render(frame, drawTransparent);
        withOpaque[name] = readOutput(method->outputTexture(), kSize, kSize);
        starnt::savePng(withOpaque[name], (outdir / (name + "_opaque.png")).string());
        if (name == "starnt") starntMethod = std::move(method);
    }
    double worstExact[2] = {0.0, 0.0};  // abuffer, peel against the ray-cast composite
    double exactMse[5] = {};
    size_t exactPixels = 0, showOpaque = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            glm::vec3 want;
            if (!exactPixel(x, y, viewProjection, frame.background, want)) continue;
            ++exactPixels;
            showOpaque += glm::length(want - frame.background) > 0.3f;
            for (size_t m = 0; m < wanted.size(); ++m) {
                const float* got = &withOpaque.at(wanted[m]).rgba[(size_t(y) * kSize + size_t(x)) * 4];
                for (int c = 0; c < 3; ++c) {
                    const double e = std::abs(double(got[c]) - double(want[c]));
                    if (m < 2) worstExact[m] = std::max(worstExact[m], e);
                    exactMse[m] += e * e / 3.0;
                }
            }
        }
    std::printf("with the opaque quad: %zu pixels against the exact composite\n", exactPixels);
    for (size_t m = 0; m < wanted.size(); ++m) {
        exactMse[m] /= double(std::max<size_t>(exactPixels, 1));
        std::printf("%s MSE %.6g vs exact\n", wanted[m].c_str(), exactMse[m]);
    }
    if (exactPixels < size_t(kSize * kSize / 4) || showOpaque < 1000)
        failures.push_back("opaque: too few pixels to compare (" + std::to_string(exactPixels) + ")");
    for (int m = 0; m < 2; ++m)
        if (worstExact[m] > 2.0 / 255.0)
            failures.push_back(wanted[size_t(m)] + " with the opaque quad: max difference " + std::to_string(worstExact[m]) +
                               " from the exact composite (> 2/255)");
    if (!(exactMse[4] < exactMse[2]))  // starnt below wboit
        failures.push_back("starnt with the opaque quad: MSE not below wboit's");
    // The premultiplied output, blended by the engine onto its own colour, equals the composite.
    frame.premultipliedOutput = true;
    starntMethod->render(frame, drawTransparent);
    blendPremultiplied(starntMethod->outputTexture(), opaque.framebuffer, es);
    const Difference premultiplied = compare(withOpaque.at("starnt"), readOutput(opaque.colour, kSize, kSize));
    std::printf("starnt premultiplied, blended by the engine: max difference %.6g from the composite\n", premultiplied.maxDiff);
    if (premultiplied.maxDiff > 4e-3)
        failures.push_back("starnt premultiplied output blended by the engine differs by " + std::to_string(premultiplied.maxDiff));
    if (GLenum error = glGetError(); error != GL_NO_ERROR) failures.push_back("GL error after the opaque scene");

    for (const std::string& failure : failures) std::fprintf(stderr, "minimal_engine: FAILED: %s\n", failure.c_str());
    return failures.empty() ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    const std::filesystem::path outdir = argc > 1 ? argv[1] : ".";
    const std::string api = argc > 2 ? argv[2] : "gl";
    if (api != "gl" && api != "gles") {
        std::fprintf(stderr, "minimal_engine: unknown API \"%s\" (gl or gles)\n", api.c_str());
        return 1;
    }
    try {
        return run(outdir, api == "gles");
    } catch (const starnt::Error& e) {
        std::fprintf(stderr, "minimal_engine: starnt error: %s\n", e.what());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "minimal_engine: error: %s\n", e.what());
    }
    return 1;
}
