#include "viewer/glfw_window.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <utility>

#include "starnt/error.hpp"
#include "starnt/tools/gl_context.hpp"

namespace starnt::viewer {
namespace {

// GLFW reports failures through a callback; keep the last one for our error messages.
std::string& lastGlfwError() {
    static std::string message;
    return message;
}

void recordGlfwError(int code, const char* description) {
    lastGlfwError() = std::string(description ? description : "unknown") + " (GLFW error " + std::to_string(code) + ")";
}

bool haveDisplayVariable() {
    const char* x11 = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    return (x11 && *x11) || (wayland && *wayland);
}

}  // namespace

std::string noDisplayMessage(const std::string& detail) {
    return "starnt view needs a display (" + detail +
           "); set DISPLAY or run it under a virtual one, e.g. `xvfb-run -a starnt view ...`. For headless "
           "use, `starnt render` (images, stats, --camera-path sequences) and `starnt bench` need no display.";
}

GlfwWindow::GlfwWindow(int width, int height, const std::string& title, GlApi api) {
    // Checked first: without it GLFW's X11 message is correct but does not say what to do instead.
    if (!haveDisplayVariable()) throw Error(noDisplayMessage("neither DISPLAY nor WAYLAND_DISPLAY is set"));
    glfwSetErrorCallback(recordGlfwError);
    if (!glfwInit()) throw Error(noDisplayMessage("cannot open it: " + lastGlfwError()));
    if (api == GlApi::Es) {
        glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_ES_API);
        glfwWindowHint(GLFW_CONTEXT_CREATION_API, GLFW_EGL_CONTEXT_API);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 2);
    } else {
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    }
    // No depth/stencil on the window: every method renders into its own framebuffers.
    glfwWindowHint(GLFW_DEPTH_BITS, 0);
    glfwWindowHint(GLFW_STENCIL_BITS, 0);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) {
        const std::string why = lastGlfwError();
        glfwTerminate();
        throw Error(std::string("cannot create a window with an ") +
                    (api == GlApi::Es ? "OpenGL ES 3.2" : "OpenGL 4.5 core") + " context: " + why);
    }
    glfwMakeContextCurrent(window_);
    // Uncapped: the timing panel should show what the methods cost, not the monitor's refresh.
    glfwSwapInterval(0);
    glfwSetWindowUserPointer(window_, this);
    glfwSetDropCallback(window_, onDrop);
    glfwSetScrollCallback(window_, onScroll);
    glfwSetKeyCallback(window_, onKey);  // installed before ImGui's, which chains to it
    try {
        checkGlRequirements();
    } catch (...) {
        glfwDestroyWindow(window_);
        glfwTerminate();
        throw;
    }
}

GlfwWindow::~GlfwWindow() {
    keepGlDriverLoadedAtExit();
    glfwDestroyWindow(window_);
    glfwTerminate();
}

bool GlfwWindow::closeRequested() const { return glfwWindowShouldClose(window_); }

glm::ivec2 GlfwWindow::framebufferSize() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return {w, h};
}

void GlfwWindow::setTitle(const std::string& title) { glfwSetWindowTitle(window_, title.c_str()); }

void GlfwWindow::swapBuffers() { glfwSwapBuffers(window_); }

std::vector<std::string> GlfwWindow::takeDroppedPaths() { return std::exchange(dropped_, {}); }

float GlfwWindow::takeScroll() { return std::exchange(scroll_, 0.0f); }

std::vector<int> GlfwWindow::takeKeyPresses() { return std::exchange(keyPresses_, {}); }

void GlfwWindow::onKey(GLFWwindow* window, int key, int, int action, int) {
    if (action == GLFW_PRESS) static_cast<GlfwWindow*>(glfwGetWindowUserPointer(window))->keyPresses_.push_back(key);
}

void GlfwWindow::onDrop(GLFWwindow* window, int count, const char** paths) {
    auto* self = static_cast<GlfwWindow*>(glfwGetWindowUserPointer(window));
    for (int i = 0; i < count; ++i) self->dropped_.emplace_back(paths[i]);
}

void GlfwWindow::onScroll(GLFWwindow* window, double, double dy) {
    static_cast<GlfwWindow*>(glfwGetWindowUserPointer(window))->scroll_ += float(dy);
}

}  // namespace starnt::viewer
