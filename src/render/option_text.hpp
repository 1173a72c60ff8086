// Text forms of the acceleration options (docs/USAGE.md, "Command line"), shared by `render`, `bench` and `view`
// so every front end accepts and rejects exactly the same spellings.
#pragma once
#include <cstddef>
#include <string>

#include "starnt/oit_method.hpp"

namespace starnt {

// "on" | "off" | "default" or "" (the method's default).
void parseSpatialOption(const std::string& text, MethodOptions& options);
// "auto" | "P2,P3" in percent, each in 25..100 (e.g. "100,50").
void parseScalesOption(const std::string& text, MethodOptions& options);
// "full" | "corners".
void parseInferenceOption(const std::string& text, MethodOptions& options);
// "off" | "auto" | "K" with K in 1..kMaxTemporalInterval (8).
void parseTemporalOption(const std::string& text, MethodOptions& options);
// "snapped" | "continuous" | "step" (docs/DESIGN.md, "Adaptive tiles and tile-guided resolution").
void parseScaleRuleOption(const std::string& text, MethodOptions& options);
// "back" | "composite" (docs/DESIGN.md, "Adaptive tiles and tile-guided resolution").
void parseTileSignalOption(const std::string& text, MethodOptions& options);
// "on" | "off".
void parseScaleGuardOption(const std::string& text, MethodOptions& options);
void parseShadingRateImageOption(const std::string& text, MethodOptions& options);
// "bilinear" | "joint" (docs/DESIGN.md, "Adaptive tiles and tile-guided resolution").
void parseUpsampleOption(const std::string& text, MethodOptions& options);
// "warp" | "refresh" (docs/DESIGN.md, "Temporal reprojection") | "correct" (beyond it).
void parseTemporalModeOption(const std::string& text, MethodOptions& options);
// --corrected-passes 1|2: NeuralOptions::correctedOnePass.
void parseCorrectedPassesOption(int passes, MethodOptions& options);
// --corrected-layers auto|1|2|3: NeuralOptions::correctedLayers.
void parseCorrectedLayersOption(const std::string& text, MethodOptions& options);
// "compact" | "fp32" (docs/DESIGN.md, "Pipeline and formats": pass-target precision).
void parseTargetsOption(const std::string& text, MethodOptions& options);
// Target frame rate for --temporal auto: finite and in (0, 1000].
void parseTargetFpsOption(double fps, MethodOptions& options);

// The A-buffer memory cap from MiB (`flag` names the option in the message): finite, positive and at
// most kMaxAbufferCapMib (1 TiB), converted without wrapping (1e30 used to become a cap of 0).
inline constexpr double kMaxAbufferCapMib = 1024.0 * 1024.0;
size_t abufferCapBytes(double mib, const std::string& flag);

// The inverse, for stats and the viewer: e.g. "on"/"off", "auto" or "100,50", "auto" or "2".
std::string spatialText(const MethodOptions& options);
std::string scalesText(const MethodOptions& options);
std::string temporalText(const MethodOptions& options);
std::string scaleRuleText(NeuralOptions::ScaleRule rule);
std::string tileSignalText(NeuralOptions::TileSignal signal);
std::string temporalModeText(NeuralOptions::TemporalMode mode);
std::string upsampleText(NeuralOptions::Upsample upsample);
std::string targetsText(NeuralOptions::Targets targets);

}  // namespace starnt
