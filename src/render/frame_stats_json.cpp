#include "render/frame_stats_json.hpp"

#include "render/option_text.hpp"

namespace starnt {

nlohmann::json frameStatsJson(const FrameStats& stats) {
    nlohmann::json out = nlohmann::json::object();
    if (stats.abuffer) {
        out["fragments"] = stats.abuffer->fragments;
        out["pool_capacity"] = stats.abuffer->poolCapacity;
        out["pool_regrows"] = stats.abuffer->poolRegrows;
    }
    if (stats.peel) {
        out["layers"] = stats.peel->layers;
        out["max_fragments"] = stats.peel->layers;
    }
    if (stats.mboit) out["moments"] = stats.mboit->moments;
    if (stats.neural) {
        const NeuralFrameStats& n = *stats.neural;
        out["network"] = n.network;
        out["weights_training_samples"] = n.weightsTrainingSamples;
        out["peel_epsilon"] = n.peelEpsilon;
        out["spatial"] = n.spatial;
        out["inference"] = n.cornerInference ? "corners" : "full";
        out["corner_inference_used"] = n.cornerInferenceUsed;
        out["interpolated"] = n.interpolated;
        out["temporal_interval"] = n.temporalInterval;
        out["temporal_mode"] = temporalModeText(n.temporalMode);
        // Kept by --temporal auto only (the window it chooses K from): null where nothing measured them.
        out["real_frame_ms_average"] = n.realFrameMsAverage > 0 ? nlohmann::json(n.realFrameMsAverage) : nlohmann::json(nullptr);
        out["interpolated_frame_ms_average"] =
            n.interpolatedFrameMsAverage > 0 ? nlohmann::json(n.interpolatedFrameMsAverage) : nlohmann::json(nullptr);
        out["scale_pass2"] = n.scalePass2;
        out["scale_pass3"] = n.scalePass3;
        out["pass2_size"] = {n.pass2Size.width, n.pass2Size.height};
        out["pass3_size"] = {n.pass3Size.width, n.pass3Size.height};
        out["targets"] = targetsText(n.targets);
        out["output_target"] = n.outputTarget;
        if (n.tiles) {
            const NeuralFrameStats::Tiles& t = *n.tiles;
            out["w_bar"] = t.wBar ? nlohmann::json(*t.wBar) : nlohmann::json(nullptr);
            out["tile_levels"] = {t.levels[0], t.levels[1], t.levels[2], t.levels[3]};
            out["scale_rule"] = scaleRuleText(t.scaleRule);
            out["tile_signal"] = tileSignalText(t.tileSignal);
            out["upsample"] = upsampleText(t.upsample);
            out["scale_guard"] = t.scaleGuard;
            if (t.probeFrame) out["probe_frame"] = *t.probeFrame;
            if (t.probeInterval) out["probe_interval"] = *t.probeInterval;
            if (t.guard) {
                const NeuralFrameStats::Guard& g = *t.guard;
                out["guard"] = {{"occupied_pixels", g.occupiedPixels},
                                {"energy_pass2", g.energyPass2},
                                {"loss_pass2", {g.lossPass2[0], g.lossPass2[1]}},
                                {"energy_pass3", g.energyPass3},
                                {"loss_pass3", {g.lossPass3[0], g.lossPass3[1]}}};
            }
            if (t.shadingRateImage) out["shading_rate_image"] = *t.shadingRateImage;
            if (t.shadingRateTiles) {
                const auto& r = *t.shadingRateTiles;
                out["shading_rate_tiles"] = {r[0], r[1], r[2]};
            }
        }
    }
    return out;
}

}  // namespace starnt
