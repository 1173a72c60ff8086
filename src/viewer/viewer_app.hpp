// `starnt view`: the interactive viewer's entry point.
#pragma once
#include <string>

#include "starnt/tools/gl_context.hpp"
#include "viewer/viewer_settings.hpp"

namespace starnt::viewer {

struct ViewerConfig {
    std::string scene = "builtin:tubes";  // builtin:NAME or a file
    ViewerSettings settings;
    int width = 1280, height = 720;  // window size
    std::string script;              // scripted input (see viewer_script.hpp); empty: none
    int framesLimit = 0;             // close after this many frames; 0: run until closed
    std::string scenesFolder;        // listed in the scene menu
    bool showUi = true;
    GlApi api = GlApi::Desktop;  // gl: a 4.5 core window context; gles: ES 3.2 through EGL
};

// Opens the window and runs until it is closed, the script says quit or the frame limit is reached.
// Throws starnt::Error for what prevents starting (no display, bad scene, bad script).
void runViewer(const ViewerConfig& config);

}  // namespace starnt::viewer
