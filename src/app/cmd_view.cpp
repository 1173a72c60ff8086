// `starnt view`: the interactive viewer (src/viewer). Built only with STARNT_BUILD_VIEWER; without
// it the subcommand still exists and says how to get it.
#include <fstream>
#include <sstream>

#include "app/commands.hpp"
#include "starnt/error.hpp"

#ifdef STARNT_HAVE_VIEWER
#include "viewer/scene_catalog.hpp"
#include "viewer/viewer_app.hpp"
#endif

namespace starnt::app {

void addViewCommand(CLI::App& app) {
    struct Args {
        std::string scene = "builtin:tubes", method = "recommended", split, view = "final", alpha, background = "1,1,1";
        AccelerationFlags acceleration;
        std::string script, scriptFile, scenesDir, api = "gl";
        int width = 1280, height = 720, framesLimit = 0;
        bool noUi = false;
    };
    auto a = std::make_shared<Args>();
    CLI::App* cmd = app.add_subcommand("view", "interactive viewer window (needs a display; see README, Viewer)");
    cmd->add_option("--scene", a->scene, "scene file (.gltf/.glb/.obj) or builtin:NAME")->capture_default_str();
    cmd->add_option("--method", a->method, methodNameList())->capture_default_str();
    cmd->add_option("--split", a->split, "show this second method on the right half");
    cmd->add_option("--view", a->view, "final|tiles|error")->capture_default_str();
    cmd->add_option("--alpha", a->alpha, "override every material's alpha (0..1)");
    cmd->add_option("--background", a->background, "background colour R,G,B (linear, 0..1)")->capture_default_str();
    addAccelerationOptions(cmd, a->acceleration);
    cmd->add_option("--width", a->width, "window width")->capture_default_str();
    cmd->add_option("--height", a->height, "window height")->capture_default_str();
    cmd->add_option("--script", a->script, "scripted input, e.g. \"frames 5; orbit 30 10; screenshot a.png; quit\"");
    cmd->add_option("--script-file", a->scriptFile, "scripted input from a file (one command per line)");
    cmd->add_option("--frames-limit", a->framesLimit, "close after this many frames (0: never)")->capture_default_str();
    cmd->add_option("--scenes-dir", a->scenesDir, "folder listed in the scene menu (default ../shared/scenes)");
    cmd->add_option("--api", a->api, "gl (OpenGL 4.5 core) or gles (OpenGL ES 3.2 through EGL)")->capture_default_str();
    cmd->add_flag("--no-ui", a->noUi, "start with the panels hidden (H toggles them)");
    cmd->callback([a] {
#ifdef STARNT_HAVE_VIEWER
        viewer::ViewerConfig config;
        config.scene = a->scene;
        config.width = a->width;
        config.height = a->height;
        config.framesLimit = a->framesLimit;
        config.showUi = !a->noUi;
        config.api = parseGlApi(a->api);
        config.scenesFolder = a->scenesDir.empty() ? viewer::defaultScenesFolder() : a->scenesDir;
        // The same spellings as the script commands and `starnt render`, checked by one parser.
        viewer::ViewerSettings& s = config.settings;
        s.set("method", a->method);
        if (!a->split.empty()) s.set("split", a->split);
        s.set("view", a->view);
        if (!a->alpha.empty()) s.set("alpha", a->alpha);
        s.set("background", a->background);
        s.set("spatial", a->acceleration.spatial);
        s.set("scales", a->acceleration.scales);
        s.set("inference", a->acceleration.inference);
        s.set("temporal", a->acceleration.temporal);
        s.set("target-fps", std::to_string(a->acceleration.targetFps));
        if (!a->script.empty() && !a->scriptFile.empty()) throw Error("--script and --script-file exclude each other");
        config.script = a->script;
        if (!a->scriptFile.empty()) {
            std::ifstream file(a->scriptFile);
            if (!file) throw Error("cannot read --script-file " + a->scriptFile);
            std::ostringstream text;
            text << file.rdbuf();
            config.script = text.str();
        }
        viewer::runViewer(config);
#else
        throw Error("this starnt was built without the viewer (configure with -DSTARNT_BUILD_VIEWER=ON and install "
                    "libglfw3-dev and libimgui-dev, see scripts/setup.sh); for headless use, `starnt render` and "
                    "`starnt bench` need no display");
#endif
    });
}

}  // namespace starnt::app
