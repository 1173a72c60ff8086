#include "app/commands.hpp"
#include "render/option_text.hpp"

namespace starnt::app {

std::string methodNameList() {
    std::string list;
    for (const auto& name : methodNames()) list += (list.empty() ? "" : "|") + name;
    return list;
}

namespace {

// The acceleration flags whose value is a word: one row each, so that the help text and the parsing
// cannot list different options.
struct WordFlag {
    const char* name;
    std::string AccelerationFlags::*value;
    void (*parse)(const std::string&, MethodOptions&);
    const char* help;
};

const WordFlag kWordFlags[] = {
    {"--spatial", &AccelerationFlags::spatial, parseSpatialOption,
     "neural methods: adaptive tiles on|off|default (default: on for starnt)"},
    {"--scales", &AccelerationFlags::scales, parseScalesOption, "neural methods: pass 2/3 scales, auto or P2,P3 in %"},
    {"--inference", &AccelerationFlags::inference, parseInferenceOption, "neural methods: full|corners"},
    {"--temporal", &AccelerationFlags::temporal, parseTemporalOption, "neural methods: off|auto|K (K in 1..8; auto up to 4)"},
    {"--scale-rule", &AccelerationFlags::scaleRule, parseScaleRuleOption,
     "neural methods: w_bar -> scales: snapped|continuous|step"},
    {"--tile-signal", &AccelerationFlags::tileSignal, parseTileSignalOption,
     "neural methods: what the tiles measure: back|composite"},
    {"--scale-guard", &AccelerationFlags::scaleGuard, parseScaleGuardOption,
     "neural methods: probe frames that keep passes at full resolution where reducing loses detail: on|off"},
    {"--shading-rate-image", &AccelerationFlags::shadingRateImage, parseShadingRateImageOption,
     "neural methods with tiles: per-tile pass-3 shading rates from the guard through GL_NV_shading_rate_image "
     "(GPU only): off|auto (where the driver has it)|on (required)"},
    {"--temporal-mode", &AccelerationFlags::temporalMode, parseTemporalModeOption,
     "neural methods: interpolated frames: warp (the paper) | refresh (fresh pass 1) | correct (fresh sums and "
     "nearest layer, the last real frame's network correction)"},
    {"--corrected-layers", &AccelerationFlags::correctedLayers, parseCorrectedLayersOption,
     "tail-moment methods: layers a corrected frame finds exactly in its one geometry pass: 1 | 2 (by framebuffer "
     "fetch, GL_EXT_shader_framebuffer_fetch, with the real frames' correction) | 3 (the same, no correction) | "
     "auto (3 where the driver allows)"},
    {"--upsample", &AccelerationFlags::upsample, parseUpsampleOption,
     "neural methods: reduced passes back to full resolution: bilinear | joint (bilateral, guided by pass-1 depth)"},
    {"--targets", &AccelerationFlags::targets, parseTargetsOption,
     "neural methods: pass-target precision: compact (16-bit colours and sums, 36 B/pixel) | fp32"},
};

}  // namespace

void addAccelerationOptions(CLI::App* command, AccelerationFlags& flags) {
    for (const WordFlag& flag : kWordFlags) command->add_option(flag.name, flags.*flag.value, flag.help)->capture_default_str();
    command->add_option("--target-fps", flags.targetFps, "frame rate that --temporal auto aims for")->capture_default_str();
    command->add_option("--corrected-passes", flags.correctedPasses,
                        "neural methods: geometry passes of a corrected frame: 1 (pass 3 finds the nearest fragment too) | 2 (pass 1, then pass 3)")
        ->capture_default_str();
}

std::vector<std::string> givenAccelerationFlags(const CLI::App* command) {
    std::vector<std::string> given;
    for (const WordFlag& flag : kWordFlags)
        if (command->get_option(flag.name)->count() > 0) given.emplace_back(flag.name);
    for (const char* name : {"--target-fps", "--corrected-passes"})
        if (command->get_option(name)->count() > 0) given.emplace_back(name);
    return given;
}

void applyAccelerationFlags(const AccelerationFlags& flags, MethodOptions& options) {
    for (const WordFlag& flag : kWordFlags) flag.parse(flags.*flag.value, options);
    parseTargetFpsOption(flags.targetFps, options);
    parseCorrectedPassesOption(flags.correctedPasses, options);
}

}  // namespace starnt::app
