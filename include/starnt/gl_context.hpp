// Headless OpenGL 4.5 core context through EGL.
//
// Tries EGL_EXT_platform_device first (a GPU, or Mesa's software device), then
// EGL_MESA_platform_surfaceless. No window system is needed: all rendering goes to framebuffer
// objects. When neither platform gives a 4.5 core context, the constructor throws starnt::Error
// naming what was missing. In builds with STARNT_GL_DEBUG (Debug), KHR_debug messages of high
// severity are turned into exceptions carrying the GL message.
#pragma once
#include <memory>
#include <string>

#include "starnt/oit_method.hpp"

namespace starnt {

struct GlContextInfo {
    std::string platform;  // "device" or "surfaceless"
    std::string vendor;
    std::string renderer;
    std::string version;
    bool software = false;  // llvmpipe/softpipe: true
};

class HeadlessGlContext {
public:
    HeadlessGlContext();
    ~HeadlessGlContext();
    HeadlessGlContext(const HeadlessGlContext&) = delete;
    HeadlessGlContext& operator=(const HeadlessGlContext&) = delete;

    const GlContextInfo& info() const;
    void makeCurrent();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// checkGlRequirements() (starnt/oit_method.hpp) checks the current context: HeadlessGlContext
// calls it, and so does createMethod in an engine's own context.
// Sanitizer builds (STARNT_SANITIZE): keeps the loaded GL driver libraries mapped until exit, so
// LeakSanitizer can name the driver's leaks and tests/lsan.supp suppress them; call it before a
// context ends (eglTerminate / glfwTerminate unload the driver). Does nothing in other builds.
void keepGlDriverLoadedAtExit();

}  // namespace starnt
