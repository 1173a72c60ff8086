// Scripted input for `starnt view --script`: a small command language so tests (and users making
// reproducible screenshots) can drive the viewer without a person at the mouse.
//
// Commands are separated by ';' or new lines; '#' starts a comment. They run in order at the start
// of a frame; `frames N` lets N frames render before the next command. Commands:
//   frames N                 render N frames (N >= 1)
//   orbit AZ EL              orbit camera at these angles in degrees (as --camera orbit:AZ,EL)
//   drag DX DY               primary mouse drag by DX, DY pixels (orbit: rotate; fly: look)
//   pan DX DY                secondary mouse drag (orbit: pan)
//   scroll S                 mouse wheel steps (orbit: zoom; fly: speed)
//   camera orbit|fly|reset   camera mode, or re-frame the scene
//   fly F R U SECONDS        hold the fly keys (each in -1..1: forward, right, up) for SECONDS
//   scene SPEC | drop PATH   load a scene (builtin:NAME or a file) as if chosen or dropped; a
//                            failure is shown in the UI and the previous scene stays
//   flip                     compute the FLIP error against the A-buffer for the current camera
//   screenshot FILE.png [ui] after this frame: the displayed image and FILE.json with stats; the
//                            panels are left out unless `ui` is given
//   quit                     close the viewer after this frame
//   KEY VALUE                a live setting, KEY one of: method, split, view, alpha, background,
//                            spatial, scales, inference, temporal, target-fps (see ViewerSettings)
#pragma once
#include <string>
#include <vector>

namespace starnt::viewer {

struct ScriptCommand {
    std::string verb;               // first word
    std::vector<std::string> args;  // the rest, as written
    std::vector<float> numbers;     // args as numbers, for the commands that take numbers
    int frames = 0;                 // for `frames`
    std::string source;             // the command as written, for messages
};

// Parses and validates the whole script (unknown commands, wrong argument counts, bad numbers, bad
// setting values): a script that parses runs without input errors. Throws starnt::Error naming
// the command.
std::vector<ScriptCommand> parseScript(const std::string& text);

}  // namespace starnt::viewer
