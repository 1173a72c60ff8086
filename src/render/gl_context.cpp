#include "starnt/tools/gl_context.hpp"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstdio>
#include <cstring>
#include <vector>

#include "starnt/error.hpp"

#ifdef STARNT_SANITIZE
#include <dlfcn.h>
#include <link.h>
#endif

namespace starnt {
namespace {

#ifdef STARNT_SANITIZE
// Sanitizer builds only: eglTerminate unloads the driver (libgallium, LLVM, ...), and LeakSanitizer
// then reports the driver's leaks at exit as "<unknown module>", which tests/lsan.supp cannot match
// by library name. Marking every loaded library RTLD_NODELETE keeps them mapped until exit. Done
// when a context ends (the command line's case): pinning in processes that keep their context
// made LeakSanitizer's thread tracer crash at exit.
void pinLoadedLibraries() {
    dl_iterate_phdr(
        [](dl_phdr_info* info, size_t, void*) {
            if (info->dlpi_name && info->dlpi_name[0] != '\0') dlopen(info->dlpi_name, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
            return 0;
        },
        nullptr);
}
#endif

bool hasExtension(const char* list, const char* name) {
    if (!list) return false;
    size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n) {
        bool startOk = (p == list) || p[-1] == ' ';
        bool endOk = p[n] == ' ' || p[n] == '\0';
        if (startOk && endOk) return true;
    }
    return false;
}

#ifdef STARNT_GL_DEBUG
void GLAPIENTRY onGlDebugMessage(GLenum, GLenum type, GLuint id, GLenum severity, GLsizei,
                                 const GLchar* message, const void*) {
    if (severity == GL_DEBUG_SEVERITY_HIGH || type == GL_DEBUG_TYPE_ERROR) {
        throw Error(std::string("OpenGL error (id ") + std::to_string(id) + "): " + message);
    }
}
#endif

}  // namespace

struct HeadlessGlContext::Impl {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    GlContextInfo info;

    // Creates a 4.5 core (or ES 3.2) context on `dpy`; returns false (with a reason) when it cannot.
    bool tryDisplay(EGLDisplay dpy, const char* platform, GlApi api, std::string& why) {
        EGLint major = 0, minor = 0;
        if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, &major, &minor)) {
            why += std::string(platform) + ": eglInitialize failed; ";
            return false;
        }
        const char* exts = eglQueryString(dpy, EGL_EXTENSIONS);
        if (!hasExtension(exts, "EGL_KHR_surfaceless_context") && !(major > 1 || minor >= 5)) {
            why += std::string(platform) + ": no surfaceless contexts; ";
            eglTerminate(dpy);
            return false;
        }
        const bool es = api == GlApi::Es;
        if (!eglBindAPI(es ? EGL_OPENGL_ES_API : EGL_OPENGL_API)) {
            why += std::string(platform) + (es ? ": OpenGL ES API unavailable; " : ": desktop OpenGL API unavailable; ");
            eglTerminate(dpy);
            return false;
        }
        const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, es ? EGL_OPENGL_ES3_BIT : EGL_OPENGL_BIT, EGL_NONE};
        EGLConfig config = nullptr;
        EGLint numConfigs = 0;
        bool haveConfig = eglChooseConfig(dpy, configAttribs, &config, 1, &numConfigs) && numConfigs > 0;
        std::vector<EGLint> ctxAttribs = {EGL_CONTEXT_MAJOR_VERSION, es ? 3 : 4, EGL_CONTEXT_MINOR_VERSION, es ? 2 : 5};
        if (!es) {
            ctxAttribs.push_back(EGL_CONTEXT_OPENGL_PROFILE_MASK);
            ctxAttribs.push_back(EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT);
        }
#ifdef STARNT_GL_DEBUG
        ctxAttribs.push_back(EGL_CONTEXT_OPENGL_DEBUG);
        ctxAttribs.push_back(EGL_TRUE);
#endif
        ctxAttribs.push_back(EGL_NONE);
        EGLContext ctx = eglCreateContext(dpy, haveConfig ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT,
                                          ctxAttribs.data());
        if (ctx == EGL_NO_CONTEXT) {
            why += std::string(platform) + (es ? ": no OpenGL ES 3.2 context" : ": no OpenGL 4.5 core context") + " (EGL error 0x" +
                   std::to_string(eglGetError()) + "); ";
            eglTerminate(dpy);
            return false;
        }
        if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
            why += std::string(platform) + ": eglMakeCurrent failed; ";
            eglDestroyContext(dpy, ctx);
            eglTerminate(dpy);
            return false;
        }
        display = dpy;
        context = ctx;
        info.platform = platform;
        info.api = api;
        return true;
    }
};

GlApi parseGlApi(const std::string& name) {
    if (name == "gl") return GlApi::Desktop;
    if (name == "gles") return GlApi::Es;
    throw Error("unknown --api '" + name + "' (expected gl or gles)");
}

const char* glApiName(GlApi api) { return api == GlApi::Es ? "gles" : "gl"; }

HeadlessGlContext::HeadlessGlContext(GlApi api) : impl_(std::make_unique<Impl>()) {
    std::string why;
    const char* clientExts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!clientExts) {
        throw Error("EGL is not usable (no client extensions); install libegl1 and libegl-mesa0 "
                    "(or the NVIDIA EGL driver)");
    }
    bool done = false;
    if (hasExtension(clientExts, "EGL_EXT_platform_device") && hasExtension(clientExts, "EGL_EXT_device_enumeration")) {
        EGLint count = 0;
        eglQueryDevicesEXT(0, nullptr, &count);
        std::vector<EGLDeviceEXT> devices(size_t(count > 0 ? count : 0));
        if (count > 0) eglQueryDevicesEXT(count, devices.data(), &count);
        // Prefer hardware devices: Mesa lists its software device too, and on an NVIDIA machine we
        // want the GPU. A device without EGL_MESA_device_software is taken as hardware.
        std::vector<EGLDeviceEXT> ordered;
        for (int pass = 0; pass < 2; ++pass) {
            for (EGLDeviceEXT dev : devices) {
                const char* devExts = eglQueryDeviceStringEXT(dev, EGL_EXTENSIONS);
                bool software = hasExtension(devExts, "EGL_MESA_device_software");
                if ((pass == 0) != software) ordered.push_back(dev);
            }
        }
        for (EGLDeviceEXT dev : ordered) {
            EGLDisplay dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, dev, nullptr);
            if (impl_->tryDisplay(dpy, "device", api, why)) {
                done = true;
                break;
            }
        }
        if (!done && ordered.empty()) why += "device: no EGL devices; ";
    } else {
        why += "EGL_EXT_platform_device not offered; ";
    }
    if (!done && hasExtension(clientExts, "EGL_MESA_platform_surfaceless")) {
        EGLDisplay dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        done = impl_->tryDisplay(dpy, "surfaceless", api, why);
    } else if (!done) {
        why += "EGL_MESA_platform_surfaceless not offered; ";
    }
    if (!done) {
        throw Error(std::string("cannot create a headless ") +
                    (api == GlApi::Es ? "OpenGL ES 3.2" : "OpenGL 4.5 core") + " context: " + why +
                    "install libgl1-mesa-dri and libegl-mesa0 (Mesa llvmpipe) or a GPU driver with EGL");
    }
    auto str = [](GLenum e) {
        const GLubyte* s = glGetString(e);
        return s ? std::string(reinterpret_cast<const char*>(s)) : std::string();
    };
    impl_->info.refused = why;
    impl_->info.vendor = str(GL_VENDOR);
    impl_->info.renderer = str(GL_RENDERER);
    impl_->info.version = str(GL_VERSION);
    impl_->info.software = impl_->info.renderer.find("llvmpipe") != std::string::npos ||
                           impl_->info.renderer.find("softpipe") != std::string::npos;
    checkGlRequirements();
#ifdef STARNT_GL_DEBUG
    if (epoxy_has_gl_extension("GL_KHR_debug") || epoxy_gl_version() >= 43) {
        glEnable(GL_DEBUG_OUTPUT);
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        glDebugMessageCallback(onGlDebugMessage, nullptr);
    }
#endif
}

void keepGlDriverLoadedAtExit() {
#ifdef STARNT_SANITIZE
    pinLoadedLibraries();
#endif
}

HeadlessGlContext::~HeadlessGlContext() {
    keepGlDriverLoadedAtExit();  // before eglTerminate unloads the driver (processes that end the context)
    if (impl_->display != EGL_NO_DISPLAY) {
        eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (impl_->context != EGL_NO_CONTEXT) eglDestroyContext(impl_->display, impl_->context);
        eglTerminate(impl_->display);
    }
}

const GlContextInfo& HeadlessGlContext::info() const { return impl_->info; }

void HeadlessGlContext::makeCurrent() {
    eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl_->context);
}

}  // namespace starnt
