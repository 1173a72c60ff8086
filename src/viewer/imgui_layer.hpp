// Dear ImGui on the viewer's window, through the GLFW and OpenGL 3 backends that Debian's
// libimgui-dev ships inside libimgui.a.
#pragma once

struct GLFWwindow;

namespace starnt::viewer {

class ImGuiLayer {
public:
    explicit ImGuiLayer(GLFWwindow* window);  // throws starnt::Error when a backend fails
    ~ImGuiLayer();
    ImGuiLayer(const ImGuiLayer&) = delete;
    ImGuiLayer& operator=(const ImGuiLayer&) = delete;

    void beginFrame();
    void endFrame();  // draws the UI over whatever is in the back buffer

    bool wantsMouse() const;
    bool wantsKeyboard() const;
};

}  // namespace starnt::viewer
