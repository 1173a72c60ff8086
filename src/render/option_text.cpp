#include "render/option_text.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "starnt/error.hpp"

namespace starnt {

void parseSpatialOption(const std::string& text, MethodOptions& options) {
    if (text.empty() || text == "default") options.neural.spatial.reset();
    else if (text == "on") options.neural.spatial = true;
    else if (text == "off") options.neural.spatial = false;
    else throw Error("--spatial '" + text + "': expected on, off or default");
}

void parseScalesOption(const std::string& text, MethodOptions& options) {
    if (text == "auto") {
        options.neural.fixedScale2 = options.neural.fixedScale3 = 0.0f;
        return;
    }
    std::istringstream in(text);
    double p2 = 0, p3 = 0;
    char comma = 0, extra = 0;
    if (!(in >> p2 >> comma >> p3) || comma != ',' || (in >> extra)) {
        throw Error("--scales '" + text + "': expected auto or P2,P3 in percent (e.g. 100,50)");
    }
    if (!(p2 >= 25.0 && p2 <= 100.0 && p3 >= 25.0 && p3 <= 100.0)) {
        throw Error("--scales '" + text + "': each scale must be within 25..100 percent");
    }
    options.neural.fixedScale2 = float(p2 / 100.0);
    options.neural.fixedScale3 = float(p3 / 100.0);
}

void parseInferenceOption(const std::string& text, MethodOptions& options) {
    if (text == "full") options.neural.inference = NeuralOptions::Inference::Full;
    else if (text == "corners") options.neural.inference = NeuralOptions::Inference::Corners;
    else throw Error("--inference '" + text + "': expected full or corners");
}

void parseTemporalOption(const std::string& text, MethodOptions& options) {
    options.neural.temporalAuto = false;
    if (text == "off") {
        options.neural.temporalInterval = 1;
    } else if (text == "auto") {
        options.neural.temporalAuto = true;
        options.neural.temporalInterval = 1;
    } else if (text.size() == 1 && text[0] >= '1' && text[0] - '0' <= kMaxTemporalInterval) {
        options.neural.temporalInterval = text[0] - '0';
    } else {
        throw Error("--temporal '" + text + "': expected off, auto or an interval K in 1.." + std::to_string(kMaxTemporalInterval));
    }
}

void parseScaleRuleOption(const std::string& text, MethodOptions& options) {
    using R = NeuralOptions::ScaleRule;
    if (text == "snapped") options.neural.scaleRule = R::Snapped;
    else if (text == "continuous") options.neural.scaleRule = R::Continuous;
    else if (text == "step") options.neural.scaleRule = R::Step;
    else throw Error("--scale-rule '" + text + "': expected snapped, continuous or step");
}

void parseUpsampleOption(const std::string& text, MethodOptions& options) {
    if (text == "bilinear") options.neural.upsample = NeuralOptions::Upsample::Bilinear;
    else if (text == "joint") options.neural.upsample = NeuralOptions::Upsample::Joint;
    else throw Error("--upsample '" + text + "': expected bilinear or joint");
}

void parseTileSignalOption(const std::string& text, MethodOptions& options) {
    if (text == "back") options.neural.tileSignal = NeuralOptions::TileSignal::Back;
    else if (text == "composite") options.neural.tileSignal = NeuralOptions::TileSignal::Composite;
    else throw Error("--tile-signal '" + text + "': expected back or composite");
}

void parseScaleGuardOption(const std::string& text, MethodOptions& options) {
    if (text == "on") options.neural.scaleGuard = true;
    else if (text == "off") options.neural.scaleGuard = false;
    else throw Error("--scale-guard '" + text + "': expected on or off");
}

void parseShadingRateImageOption(const std::string& text, MethodOptions& options) {
    using S = NeuralOptions::ShadingRateImage;
    if (text == "off") options.neural.shadingRateImage = S::Off;
    else if (text == "auto") options.neural.shadingRateImage = S::Auto;
    else if (text == "on") options.neural.shadingRateImage = S::On;
    else throw Error("--shading-rate-image '" + text + "': expected off, auto or on");
}

void parseTemporalModeOption(const std::string& text, MethodOptions& options) {
    if (text == "warp") options.neural.temporalMode = NeuralOptions::TemporalMode::Warp;
    else if (text == "refresh") options.neural.temporalMode = NeuralOptions::TemporalMode::Refresh;
    else if (text == "correct") options.neural.temporalMode = NeuralOptions::TemporalMode::Correct;
    else throw Error("--temporal-mode '" + text + "': expected warp, refresh or correct");
}

void parseCorrectedPassesOption(int passes, MethodOptions& options) {
    if (passes != 1 && passes != 2) throw Error("--corrected-passes " + std::to_string(passes) + ": expected 1 or 2");
    options.neural.correctedOnePass = passes == 1;
}

void parseCorrectedLayersOption(const std::string& text, MethodOptions& options) {
    using L = NeuralOptions::CorrectedLayers;
    if (text == "auto") options.neural.correctedLayers = L::Auto;
    else if (text == "1") options.neural.correctedLayers = L::One;
    else if (text == "2") options.neural.correctedLayers = L::Two;
    else if (text == "3") options.neural.correctedLayers = L::Three;
    else throw Error("--corrected-layers '" + text + "': expected auto, 1, 2 or 3");
}

void parseTargetsOption(const std::string& text, MethodOptions& options) {
    if (text == "compact") options.neural.targets = NeuralOptions::Targets::Compact;
    else if (text == "fp32") options.neural.targets = NeuralOptions::Targets::Float32;
    else throw Error("--targets '" + text + "': expected compact or fp32");
}

void parseTargetFpsOption(double fps, MethodOptions& options) {
    if (!std::isfinite(fps) || !(fps > 0.0) || fps > 1000.0) throw Error("--target-fps must be in (0, 1000]");
    options.neural.targetFps = fps;
}

size_t abufferCapBytes(double mib, const std::string& flag) {
    if (!std::isfinite(mib) || !(mib > 0.0) || !(mib <= kMaxAbufferCapMib)) {
        std::ostringstream msg;
        msg << std::setprecision(10) << flag << " " << mib << ": the A-buffer memory cap must be positive and at most " << kMaxAbufferCapMib << " MiB";
        throw Error(msg.str());
    }
    return size_t(mib * 1024.0 * 1024.0);  // <= 2^40: exact and in range
}

std::string spatialText(const MethodOptions& options) {
    return options.neural.spatial ? (*options.neural.spatial ? "on" : "off") : "default";
}

std::string scalesText(const MethodOptions& options) {
    if (options.neural.fixedScale2 <= 0.0f) return "auto";
    return std::to_string(int(std::lround(options.neural.fixedScale2 * 100))) + "," +
           std::to_string(int(std::lround(options.neural.fixedScale3 * 100)));
}

std::string temporalText(const MethodOptions& options) {
    if (options.neural.temporalAuto) return "auto";
    return options.neural.temporalInterval <= 1 ? "off" : std::to_string(options.neural.temporalInterval);
}

std::string scaleRuleText(NeuralOptions::ScaleRule rule) {
    switch (rule) {
        case NeuralOptions::ScaleRule::Continuous: return "continuous";
        case NeuralOptions::ScaleRule::Step: return "step";
        case NeuralOptions::ScaleRule::Snapped: break;
    }
    return "snapped";
}

std::string upsampleText(NeuralOptions::Upsample upsample) {
    return upsample == NeuralOptions::Upsample::Joint ? "joint" : "bilinear";
}

std::string tileSignalText(NeuralOptions::TileSignal signal) {
    return signal == NeuralOptions::TileSignal::Back ? "back" : "composite";
}

std::string targetsText(NeuralOptions::Targets targets) {
    return targets == NeuralOptions::Targets::Float32 ? "fp32" : "compact";
}

std::string temporalModeText(NeuralOptions::TemporalMode mode) {
    switch (mode) {
        case NeuralOptions::TemporalMode::Refresh: return "refresh";
        case NeuralOptions::TemporalMode::Correct: return "correct";
        case NeuralOptions::TemporalMode::Warp: break;
    }
    return "warp";
}

}  // namespace starnt
