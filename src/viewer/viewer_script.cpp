#include "viewer/viewer_script.hpp"

#include <cmath>
#include <map>
#include <sstream>

#include "starnt/error.hpp"
#include "viewer/viewer_settings.hpp"

namespace starnt::viewer {
namespace {

std::vector<std::string> splitCommands(const std::string& text) {
    std::vector<std::string> commands;
    std::string current;
    bool comment = false;
    for (char c : text) {
        if (c == '\n' || c == ';') {
            commands.push_back(current);
            current.clear();
            comment = false;
        } else if (c == '#') {
            comment = true;
        } else if (!comment) {
            current += c;
        }
    }
    commands.push_back(current);
    return commands;
}

float parseFloat(const std::string& word, const std::string& source) {
    std::istringstream in(word);
    float v = 0;
    char extra = 0;
    if (!(in >> v) || (in >> extra) || !std::isfinite(v)) {
        throw Error("script command '" + source + "': '" + word + "' is not a number");
    }
    return v;
}

// Commands with only numeric arguments, and how many they take.
const std::map<std::string, size_t> kNumericCommands = {
    {"orbit", 2}, {"drag", 2}, {"pan", 2}, {"scroll", 1}, {"fly", 4}};

}  // namespace

std::vector<ScriptCommand> parseScript(const std::string& text) {
    std::vector<ScriptCommand> script;
    for (const std::string& line : splitCommands(text)) {
        std::istringstream words(line);
        ScriptCommand cmd;
        if (!(words >> cmd.verb)) continue;  // blank
        for (std::string w; words >> w;) cmd.args.push_back(w);
        cmd.source = cmd.verb;
        for (const auto& a : cmd.args) cmd.source += " " + a;
        auto expectArgs = [&](size_t n, const char* usage) {
            if (cmd.args.size() != n) throw Error("script command '" + cmd.source + "': expected " + usage);
        };

        if (auto numeric = kNumericCommands.find(cmd.verb); numeric != kNumericCommands.end()) {
            if (cmd.args.size() != numeric->second) {
                throw Error("script command '" + cmd.source + "': expected " + std::to_string(numeric->second) + " numbers");
            }
            for (const auto& a : cmd.args) cmd.numbers.push_back(parseFloat(a, cmd.source));
            if (cmd.verb == "orbit" && std::abs(cmd.numbers[1]) > 90.0f) {
                throw Error("script command '" + cmd.source + "': elevation must be within -90..90 degrees");
            }
            if (cmd.verb == "fly") {
                for (int i = 0; i < 3; ++i) {
                    if (std::abs(cmd.numbers[i]) > 1.0f) throw Error("script command '" + cmd.source + "': key amounts must be in -1..1");
                }
                if (cmd.numbers[3] < 0.0f) throw Error("script command '" + cmd.source + "': seconds must not be negative");
            }
        } else if (cmd.verb == "frames") {
            expectArgs(1, "frames N");
            const float n = parseFloat(cmd.args[0], cmd.source);
            if (n < 1.0f || n > 100000.0f || n != std::floor(n)) throw Error("script command '" + cmd.source + "': N must be a whole number in 1..100000");
            cmd.frames = int(n);
        } else if (cmd.verb == "camera") {
            expectArgs(1, "camera orbit|fly|reset");
            if (cmd.args[0] != "orbit" && cmd.args[0] != "fly" && cmd.args[0] != "reset") {
                throw Error("script command '" + cmd.source + "': expected camera orbit|fly|reset");
            }
        } else if (cmd.verb == "scene" || cmd.verb == "drop") {
            expectArgs(1, "a scene (builtin:NAME or a file path without spaces)");
        } else if (cmd.verb == "screenshot") {
            if (cmd.args.size() == 2 && cmd.args[1] != "ui") throw Error("script command '" + cmd.source + "': expected screenshot FILE.png [ui]");
            if (cmd.args.size() != 2) expectArgs(1, "screenshot FILE.png [ui]");
            const std::string& p = cmd.args[0];
            if (p.size() < 5 || p.substr(p.size() - 4) != ".png") throw Error("script command '" + cmd.source + "': the screenshot must be a .png file");
        } else if (cmd.verb == "flip" || cmd.verb == "quit") {
            expectArgs(0, std::string(cmd.verb + " without arguments").c_str());
        } else if (ViewerSettings::isKey(cmd.verb)) {
            expectArgs(1, (cmd.verb + " VALUE").c_str());
            ViewerSettings probe;
            try {
                probe.set(cmd.verb, cmd.args[0]);
            } catch (const Error& e) {
                throw Error("script command '" + cmd.source + "': " + e.what());
            }
        } else {
            throw Error("script command '" + cmd.source + "': unknown command '" + cmd.verb +
                        "' (see README, section Viewer)");
        }
        script.push_back(std::move(cmd));
    }
    return script;
}

}  // namespace starnt::viewer
