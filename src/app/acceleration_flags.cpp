#include "app/commands.hpp"
#include "render/option_text.hpp"

namespace starnt::app {

std::string methodNameList() {
    std::string list;
    for (const auto& name : methodNames()) list += (list.empty() ? "" : "|") + name;
    return list;
}

void addAccelerationOptions(CLI::App* command, AccelerationFlags& flags) {
    command->add_option("--spatial", flags.spatial, "neural methods: adaptive tiles on|off|default (default: on for starnt)")
        ->capture_default_str();
    command->add_option("--scales", flags.scales, "neural methods: pass 2/3 scales, auto or P2,P3 in %")->capture_default_str();
    command->add_option("--inference", flags.inference, "neural methods: full|corners")->capture_default_str();
    command->add_option("--temporal", flags.temporal, "neural methods: off|auto|K (K in 1..4)")->capture_default_str();
    command->add_option("--target-fps", flags.targetFps, "frame rate that --temporal auto aims for")->capture_default_str();
    command->add_option("--scale-rule", flags.scaleRule, "neural methods: w_bar -> scales: snapped|continuous|step")
        ->capture_default_str();
    command->add_option("--tile-signal", flags.tileSignal, "neural methods: what the tiles measure: back|composite")
        ->capture_default_str();
    command->add_option("--scale-guard", flags.scaleGuard,
                        "neural methods: probe frames that keep passes at full resolution where reducing loses detail: on|off")
        ->capture_default_str();
    command->add_option("--upsample", flags.upsample,
                        "neural methods: reduced passes back to full resolution: bilinear | joint (bilateral, guided by pass-1 depth)")
        ->capture_default_str();
    command->add_option("--temporal-mode", flags.temporalMode,
                        "neural methods: interpolated frames: warp (the paper) | refresh (fresh pass 1) | correct (fresh sums and nearest layer, the last real frame's network correction)")
        ->capture_default_str();
    command->add_option("--corrected-passes", flags.correctedPasses,
                        "neural methods: geometry passes of a corrected frame: 1 (pass 3 finds the nearest fragment too) | 2 (pass 1, then pass 3)")
        ->capture_default_str();
    command->add_option("--targets", flags.targets,
                        "neural methods: pass-target precision: compact (16-bit colours and sums, 36 B/pixel) | fp32")
        ->capture_default_str();
}

void applyAccelerationFlags(const AccelerationFlags& flags, MethodOptions& options) {
    parseSpatialOption(flags.spatial, options);
    parseScalesOption(flags.scales, options);
    parseInferenceOption(flags.inference, options);
    parseTemporalOption(flags.temporal, options);
    parseTargetFpsOption(flags.targetFps, options);
    parseScaleRuleOption(flags.scaleRule, options);
    parseTileSignalOption(flags.tileSignal, options);
    parseScaleGuardOption(flags.scaleGuard, options);
    parseTemporalModeOption(flags.temporalMode, options);
    parseCorrectedPassesOption(flags.correctedPasses, options);
    parseUpsampleOption(flags.upsample, options);
    parseTargetsOption(flags.targets, options);
}

}  // namespace starnt::app
