// The frame time a temporal schedule costs over a long run (docs/DESIGN.md, "Benchmark"): each kind
// of frame's mean over the timed frames, weighted by its share in the schedule, 1/K real frames at
// interval K. A short window of timed frames holds a whole number of real frames, so its plain mean
// counts them at a share that depends on where the window starts: 3 in 10 frames at K = 4 from a
// real frame (0.30 instead of 0.25), 2 in 10 from the frame after it.
#pragma once
#include <optional>
#include <vector>

namespace starnt {

// `realShare` is the mean over the timed frames of 1 / K (the interval in force at each frame). Empty
// when a kind of frame the schedule has is missing from the window (the window mean then stands).
inline std::optional<double> longRunFrameMs(const std::vector<double>& real, const std::vector<double>& interpolated,
                                            double realShare) {
    auto mean = [](const std::vector<double>& v) {
        double s = 0.0;
        for (double x : v) s += x;
        return s / double(v.size());
    };
    if (!(realShare > 0.0 && realShare <= 1.0)) return std::nullopt;
    if (real.empty()) return std::nullopt;
    if (realShare == 1.0) return mean(real);
    if (interpolated.empty()) return std::nullopt;
    return realShare * mean(real) + (1.0 - realShare) * mean(interpolated);
}

}  // namespace starnt
