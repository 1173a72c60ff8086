// Which frames of a sequence are real (full pipeline) and which are interpolated (reprojected),
// SPEC section 6. Pure C++, no GL, so the rule is unit-tested on its own.
//
// Frames come in groups: one real frame, then interval - 1 interpolated frames. The interval of a
// group is fixed when its real frame is issued, so it changes only at real frames.
//   fixed K:  interval = K (1 = every frame real).
//   auto:     interval = clamp(floor(fps_real / targetFps), 1, 4), fps_real = 1000 / (mean of the
//             last kAverageWindow real-frame times in ms); 1 before any measurement, so rendering
//             below the target rate (or not yet measured) is plain rendering.
#pragma once
#include <array>

#include "starnt/oit_method.hpp"

namespace starnt {

class TemporalSchedule {
public:
    static constexpr int kMaxInterval = 4;
    static constexpr int kAverageWindow = 8;  // real frames in the running mean

    // Throws starnt::Error for an interval outside 1..4 or a target rate that is not finite and > 0.
    explicit TemporalSchedule(const MethodOptions& options);

    // Advances to the next frame and says whether it is real. The first frame, the first after
    // reset() and the first of every group are real.
    bool nextFrameIsReal();
    // One real frame's duration in milliseconds (auto mode reads it; fixed mode ignores it).
    // Non-finite or negative values are ignored; 0 counts as "very fast".
    void recordRealFrameMs(double ms);
    // The interval the next group would get: fixed K, or the auto rule on the measurements so far.
    int interval() const;
    // The interval of the group the current frame belongs to (0 before the first frame).
    int groupInterval() const { return groupInterval_; }
    // Mean real-frame time used by auto (0 when nothing was measured yet).
    double averageRealFrameMs() const;
    bool isAuto() const { return auto_; }
    // Forgets the position in the group (next frame real) and the measurements.
    void reset();

private:
    bool auto_ = false;
    int fixedInterval_ = 1;
    double targetFps_ = 60.0;
    bool started_ = false;
    int framesIntoGroup_ = 0;  // 0 = the current frame is the group's real frame
    int groupInterval_ = 0;
    std::array<double, kAverageWindow> samples_{};
    int sampleCount_ = 0;  // samples stored, at most kAverageWindow
    int nextSample_ = 0;   // ring position
};

}  // namespace starnt
