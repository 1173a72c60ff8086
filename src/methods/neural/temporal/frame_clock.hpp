// Measures how long real and interpolated frames take, for `--temporal auto` (docs/DESIGN.md, "Temporal reprojection").
//
// On a GPU: a GL_TIMESTAMP query pair around the frame, read back without stalling at a later
// frame once the result is available (a measurement still in flight skips the next frame).
// On a software rasteriser (llvmpipe) timestamps are taken at submission, not execution (see
// gl/gpu_timer.hpp), so there the frame is bracketed by glFinish and timed with the wall clock;
// a CPU "GPU" has no pipelining to lose.
#pragma once
#include <epoxy/gl.h>

#include <optional>

#include "gl/gl_util.hpp"

namespace starnt::temporal {

class FrameClock {
public:
    struct Measurement {
        double ms = 0.0;
        bool real = true;  // a real frame (else an interpolated one)
    };
    // `wallClock`: glFinish + steady_clock (software rasterisers); otherwise timestamp queries.
    explicit FrameClock(bool wallClock);
    void start(bool real);  // at the beginning of a frame
    void stop();            // at its end
    // The newest finished measurement, once; nothing while none is ready.
    std::optional<Measurement> take();

private:
    void poll();  // GPU: moves a finished query pair's result into ready_
    bool wallClock_;
    bool running_ = false;    // between start() and stop()
    bool inFlight_ = false;   // GPU: queries issued, result not read yet
    bool real_ = true;        // the kind of the frame being measured
    double startMs_ = 0.0;
    std::optional<Measurement> ready_;
    gl::QueryHandle begin_, end_;
};

}  // namespace starnt::temporal
