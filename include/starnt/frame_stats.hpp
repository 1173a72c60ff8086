// What a method reports about its last frame (OitMethod::lastFrameStats). Each method family
// fills its own group; the others stay empty. The starnt CLI writes it as JSON (--stats,
// --frame-stats) with the keys named beside each field.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "starnt/method_options.hpp"

namespace starnt {

struct AbufferFrameStats {
    uint64_t fragments = 0;     // "fragments": fragments stored this frame
    uint64_t poolCapacity = 0;  // "pool_capacity": nodes the pool holds
    uint32_t poolRegrows = 0;   // "pool_regrows": times the pool grew (re-rendering the frame)
};

struct PeelFrameStats {
    int layers = 0;  // "layers" (and "max_fragments"): layers peeled
};

struct MboitFrameStats {
    std::string moments;  // "moments": "4", "6", "t2" or "t3"
};

struct NeuralFrameStats {
    struct Size {
        int width = 0, height = 0;
    };
    // What the scale guard measured on its last probe frame (see NeuralOptions::scaleGuard): sums
    // over the occupied pixels it samples of the squared sRGB error.
    struct Guard {
        float occupiedPixels = 0;             // "occupied_pixels"
        float energyPass2 = 0, energyPass3 = 0;  // "energy_pass2", "energy_pass3": what each pass adds
        std::array<float, 2> lossPass2{}, lossPass3{};  // "loss_pass2/3": lost at scale 1/2, 1/4
    };
    // The adaptive tiles (present when the method runs them).
    struct Tiles {
        std::optional<double> wBar;               // "w_bar": mean tile level; empty until measured
        std::array<uint32_t, 4> levels{};         // "tile_levels": occupied tiles per level N_0..N_3
        NeuralOptions::ScaleRule scaleRule{};     // "scale_rule"
        NeuralOptions::TileSignal tileSignal{};   // "tile_signal"
        NeuralOptions::Upsample upsample{};       // "upsample"
        bool scaleGuard = false;                  // "scale_guard"
        std::optional<bool> probeFrame;           // "probe_frame" (with the guard): full-resolution probe
        std::optional<int> probeInterval;         // "probe_interval" (with the guard): real frames between probes
        std::optional<Guard> guard;               // "guard" (with the guard, once measured)
        // With per-tile shading rates (NeuralOptions::shadingRateImage): "shading_rate_image", pass
        // 3 of this frame ran with them; "shading_rate_tiles", occupied tiles shaded per pixel, per
        // 2x2 and per 4x4 pixels at the newest probe.
        std::optional<bool> shadingRateImage;
        std::optional<std::array<uint32_t, 3>> shadingRateTiles;
    };

    std::string network;                  // "network": "starnt", "dfaoit" (hybrid: "starnt" inputs)
    uint64_t weightsTrainingSamples = 0;  // "weights_training_samples"
    float peelEpsilon = 0;                // "peel_epsilon": pass 2's depth offset
    bool spatial = false;                 // "spatial": tiles choose the scales
    bool cornerInference = false;         // "inference": "corners" (true) or "full"
    bool cornerInferenceUsed = false;     // "corner_inference_used": this frame inferred at corners
    bool interpolated = false;            // "interpolated": this frame came from temporal reuse
    int temporalInterval = 1;             // "temporal_interval": frames per real frame now
    NeuralOptions::TemporalMode temporalMode{};  // "temporal_mode"
    double realFrameMsAverage = 0;               // "real_frame_ms_average" (temporal auto's window)
    double interpolatedFrameMsAverage = 0;       // "interpolated_frame_ms_average"
    float scalePass2 = 1, scalePass3 = 1;        // "scale_pass2", "scale_pass3": per axis
    Size pass2Size, pass3Size;                   // "pass2_size", "pass3_size": [width, height]
    NeuralOptions::Targets targets{};            // "targets": "compact" or "fp32"
    // "output_target": where this frame's output lives: "pass3_alpha_color", "pass2_color" or
    // "pass1_color" (written in place over a target the inference reads only at its own pixel and
    // nothing reads afterwards) or "output" (a texture of its own).
    std::string outputTarget;
    std::optional<Tiles> tiles;
};

struct FrameStats {
    std::optional<AbufferFrameStats> abuffer;
    std::optional<PeelFrameStats> peel;
    std::optional<MboitFrameStats> mboit;
    std::optional<NeuralFrameStats> neural;
    // True when the frame was interpolated (temporal reuse of the neural methods).
    bool interpolated() const { return neural && neural->interpolated; }
};

}  // namespace starnt
