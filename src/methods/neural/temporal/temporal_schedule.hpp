// Which frames of a sequence are real (full pipeline) and which are interpolated (reprojected),
// docs/DESIGN.md, "Temporal reprojection". Pure C++, no GL, so the rule is unit-tested on its own.
//
// Frames come in groups: one real frame, then interval - 1 interpolated frames. The interval of a
// group is fixed when its real frame is issued, so it changes only at real frames.
//   fixed K:  interval = K (1 = every frame real).
//   fixed K is at most kMaxTemporalInterval (8).
//   auto:     the largest interval k <= 4 (SPEC 6) whose group (one real frame of R ms, k - 1 interpolated
//             frames of I ms) fits in one target frame time T = 1000 / targetFps:
//                 R + (k - 1) I <= T   ->   k = clamp(1 + floor((T - R) / I), 1, 4),
//             R and I the means of the last kAverageWindow real and interpolated frames. Real
//             frames then come at least at the target rate and the interpolated ones raise the
//             displayed rate. docs/DESIGN.md, "Temporal reprojection"'s k = floor(fps_real / targetFps) is this rule with
//             I = R (every frame counted at a real frame's cost); it applies until an interpolated
//             frame was measured, except that k is then at least 2: one interpolated frame must run
//             to be measured (at a rate between T and T/2 the paper's rule would never try one).
//             A refresh frame renders pass 1, so it is not nearly free: its measured cost keeps k
//             lower than a warp frame's does. R > T (below the target) or no measurement yet:
//             k = 1, plain rendering.
#pragma once
#include <array>

#include "starnt/oit_method.hpp"

namespace starnt {

class TemporalSchedule {
public:
    static constexpr int kMaxAutoInterval = 4;  // SPEC 6's cap for auto
    static constexpr int kAverageWindow = 8;  // real frames in the running mean

    // Throws starnt::Error for a fixed interval outside 1..kMaxTemporalInterval or a target rate that is not finite and > 0.
    explicit TemporalSchedule(const MethodOptions& options);

    // Advances to the next frame and says whether it is real. The first frame, the first after
    // reset() and the first of every group are real.
    bool nextFrameIsReal();
    // One real frame's duration in milliseconds (auto mode reads it; fixed mode ignores it).
    // Non-finite or negative values are ignored; 0 counts as "very fast".
    void recordRealFrameMs(double ms);
    // The same for an interpolated frame.
    void recordInterpolatedFrameMs(double ms);
    // The interval the next group would get: fixed K, or the auto rule on the measurements so far.
    int interval() const;
    // The interval of the group the current frame belongs to (0 before the first frame).
    int groupInterval() const { return groupInterval_; }
    // The current frame is its group's last: the next one is real (unless a reset intervenes).
    bool lastOfGroup() const { return started_ && framesIntoGroup_ + 1 >= groupInterval_; }
    // Mean real- and interpolated-frame times used by auto (0 when nothing was measured yet).
    double averageRealFrameMs() const { return real_.mean(); }
    double averageInterpolatedFrameMs() const { return interpolated_.mean(); }
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
    // The last kAverageWindow durations of one kind of frame (a plain window mean: bounded memory,
    // exact in tests).
    class Window {
    public:
        void add(double ms);
        double mean() const;
        bool empty() const { return count_ == 0; }
        void clear() { count_ = next_ = 0; }

    private:
        std::array<double, kAverageWindow> samples_{};
        int count_ = 0;  // samples stored, at most kAverageWindow
        int next_ = 0;   // ring position
    };
    Window real_, interpolated_;
};

}  // namespace starnt
