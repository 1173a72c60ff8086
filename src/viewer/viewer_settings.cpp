#include "viewer/viewer_settings.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "render/option_text.hpp"
#include "starnt/error.hpp"

namespace starnt::viewer {
namespace {

constexpr std::array<const char*, 14> kKeys = {"method",     "split",       "view",        "alpha",     "background",
                                               "spatial",    "scales",      "inference",   "temporal",  "target-fps",
                                               "scale-rule", "tile-signal", "scale-guard", "temporal-mode"};

std::string checkedMethod(const std::string& name, const char* key) {
    const auto names = methodNames();
    if (std::find(names.begin(), names.end(), name) == names.end()) {
        std::string list;
        for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
        throw Error(std::string(key) + " '" + name + "': unknown method (one of " + list + ")");
    }
    return name;
}

double parseNumber(const std::string& text, const char* key) {
    std::istringstream in(text);
    double v = 0;
    char extra = 0;
    if (!(in >> v) || (in >> extra) || !std::isfinite(v)) throw Error(std::string(key) + " '" + text + "': expected a number");
    return v;
}

glm::vec3 parseBackground(const std::string& text) {
    std::istringstream in(text);
    glm::vec3 c;
    char comma1 = 0, comma2 = 0, extra = 0;
    if (!(in >> c.r >> comma1 >> c.g >> comma2 >> c.b) || comma1 != ',' || comma2 != ',' || (in >> extra)) {
        throw Error("background '" + text + "': expected R,G,B");
    }
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(c[i]) || c[i] < 0.0f || c[i] > 1.0f) throw Error("background '" + text + "': components must be in [0, 1]");
    }
    return c;
}

}  // namespace

const char* viewModeName(ViewMode mode) {
    switch (mode) {
        case ViewMode::Final: return "final";
        case ViewMode::Tiles: return "tiles";
        case ViewMode::Error: return "error";
    }
    return "?";
}

bool ViewerSettings::isKey(const std::string& key) {
    return std::find(kKeys.begin(), kKeys.end(), key) != kKeys.end();
}

void ViewerSettings::set(const std::string& key, const std::string& value) {
    ViewerSettings next = *this;  // all or nothing: a bad value changes nothing
    if (key == "method") {
        next.method = checkedMethod(value, "method");
    } else if (key == "split") {
        next.splitMethod = value == "off" ? "" : checkedMethod(value, "split");
    } else if (key == "view") {
        if (value == "final") next.view = ViewMode::Final;
        else if (value == "tiles") next.view = ViewMode::Tiles;
        else if (value == "error") next.view = ViewMode::Error;
        else throw Error("view '" + value + "': expected final, tiles or error");
    } else if (key == "alpha") {
        if (value == "off") {
            next.alpha.reset();
        } else {
            const double a = parseNumber(value, "alpha");
            if (a < 0.0 || a > 1.0) throw Error("alpha '" + value + "': must be in [0, 1] (or off)");
            next.alpha = float(a);
        }
    } else if (key == "background") {
        next.background = parseBackground(value);
    } else if (key == "spatial") {
        parseSpatialOption(value == "default" ? "" : value, next.options);
    } else if (key == "scales") {
        parseScalesOption(value, next.options);
    } else if (key == "inference") {
        parseInferenceOption(value, next.options);
    } else if (key == "temporal") {
        parseTemporalOption(value, next.options);
    } else if (key == "scale-rule") {
        parseScaleRuleOption(value, next.options);
    } else if (key == "tile-signal") {
        parseTileSignalOption(value, next.options);
    } else if (key == "scale-guard") {
        parseScaleGuardOption(value, next.options);
    } else if (key == "upsample") {
        parseUpsampleOption(value, next.options);
    } else if (key == "temporal-mode") {
        parseTemporalModeOption(value, next.options);
    } else if (key == "target-fps") {
        parseTargetFpsOption(parseNumber(value, "target-fps"), next.options);
    } else {
        throw Error("unknown setting '" + key + "'");
    }
    *this = std::move(next);
}

bool needsNewMethods(const ViewerSettings& a, const ViewerSettings& b) {
    const MethodOptions &x = a.options, &y = b.options;
    return a.method != b.method || a.splitMethod != b.splitMethod || x.neural.spatial != y.neural.spatial ||
           x.neural.fixedScale2 != y.neural.fixedScale2 || x.neural.fixedScale3 != y.neural.fixedScale3 || x.neural.inference != y.neural.inference ||
           x.neural.temporalInterval != y.neural.temporalInterval || x.neural.temporalAuto != y.neural.temporalAuto || x.neural.targetFps != y.neural.targetFps ||
           x.neural.scaleRule != y.neural.scaleRule || x.neural.tileSignal != y.neural.tileSignal || x.neural.scaleGuard != y.neural.scaleGuard || x.neural.upsample != y.neural.upsample ||
           x.neural.temporalMode != y.neural.temporalMode || x.mboit.moments != y.mboit.moments;
}

}  // namespace starnt::viewer
