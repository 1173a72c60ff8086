// The viewer's window: GLFW with an OpenGL 4.5 core (or ES 3.2) context, and the dropped-file queue.
#pragma once
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "starnt/tools/gl_context.hpp"

struct GLFWwindow;

namespace starnt::viewer {

// The message for a machine without a display, pointing at the headless commands.
std::string noDisplayMessage(const std::string& detail);

class GlfwWindow {
public:
    // Opens the window and makes its context current. Throws starnt::Error with noDisplayMessage
    // when there is no display, or naming what the driver lacks (GL 4.5 core).
    // api Es asks GLFW for an OpenGL ES 3.2 context created through EGL.
    GlfwWindow(int width, int height, const std::string& title, GlApi api = GlApi::Desktop);
    ~GlfwWindow();
    GlfwWindow(const GlfwWindow&) = delete;
    GlfwWindow& operator=(const GlfwWindow&) = delete;

    GLFWwindow* handle() const { return window_; }
    bool closeRequested() const;
    glm::ivec2 framebufferSize() const;
    void setTitle(const std::string& title);
    void swapBuffers();

    // Paths dropped on the window since the last call.
    std::vector<std::string> takeDroppedPaths();
    // Mouse wheel steps since the last call (GLFW reports the wheel only as events).
    float takeScroll();
    // Keys pressed since the last call (GLFW_KEY_* codes), for one-shot shortcuts.
    std::vector<int> takeKeyPresses();

private:
    static void onDrop(GLFWwindow* window, int count, const char** paths);
    static void onScroll(GLFWwindow* window, double dx, double dy);
    static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods);

    GLFWwindow* window_ = nullptr;
    std::vector<std::string> dropped_;
    float scroll_ = 0.0f;
    std::vector<int> keyPresses_;
};

}  // namespace starnt::viewer
