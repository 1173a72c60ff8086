// Measures how long real frames take, for `--temporal auto` (SPEC section 6).
//
// On a GPU: a GL_TIMESTAMP query pair around the real frame, read back without stalling at a later
// frame once the result is available (a measurement still in flight skips the next real frame).
// On a software rasteriser (llvmpipe) timestamps are taken at submission, not execution (see
// core/gpu_timer.hpp), so there the frame is bracketed by glFinish and timed with the wall clock;
// a CPU "GPU" has no pipelining to lose.
#pragma once
#include <epoxy/gl.h>

#include <optional>

#include "core/gl_util.hpp"

namespace starnt::temporal {

class RealFrameClock {
public:
    // `wallClock`: glFinish + steady_clock (software rasterisers); otherwise timestamp queries.
    explicit RealFrameClock(bool wallClock);
    void start();  // at the beginning of a real frame
    void stop();   // at its end
    // The newest finished measurement in milliseconds, once; nothing while none is ready.
    std::optional<double> take();

private:
    void poll();  // GPU: moves a finished query pair's result into ready_
    bool wallClock_;
    bool running_ = false;    // between start() and stop()
    bool inFlight_ = false;   // GPU: queries issued, result not read yet
    double startMs_ = 0.0;
    std::optional<double> ready_;
    gl::QueryHandle begin_, end_;
};

}  // namespace starnt::temporal
