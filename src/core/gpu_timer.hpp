// Per-pass GPU timing.
//
// On a GPU: GL_TIMESTAMP query pairs around each pass, with a glFlush after each, read after the
// frame (no stall inside the frame). GL_TIME_ELAPSED is not used: it returns garbage on llvmpipe.
// On a software rasteriser (llvmpipe) timestamp queries are taken when the command is submitted,
// not when the binned triangles are rasterised, so they measured e.g. 0.04 ms for an A-buffer build
// that takes tens of ms; there each pass is bracketed by glFinish and timed with the wall clock
// (a CPU "GPU" has no pipelining to lose).
#pragma once
#include <epoxy/gl.h>

#include <map>
#include <string>
#include <vector>

namespace starnt::gl {

class GpuPassTimer {
public:
    // `finishAndWallClock`: time passes with glFinish + steady_clock (software rasterisers).
    explicit GpuPassTimer(bool finishAndWallClock = false);
    ~GpuPassTimer();
    bool usesWallClock() const { return wallClock_; }
    GpuPassTimer(const GpuPassTimer&) = delete;
    GpuPassTimer& operator=(const GpuPassTimer&) = delete;

    void begin(const std::string& pass);  // passes may repeat (e.g. peel layers): times add up
    void end();
    // Waits for the queries of this frame and returns milliseconds per pass name; resets.
    std::map<std::string, double> collect();

private:
    struct Pending {
        std::string name;
        GLuint begin, end;
    };
    GLuint acquire();
    std::vector<GLuint> free_;
    std::vector<Pending> pending_;
    std::string open_;
    GLuint openQuery_ = 0;
    bool wallClock_ = false;
    double openStartMs_ = 0.0;
    bool open_wall_ = false;
    std::map<std::string, double> wallMs_;
};

// True when the current context is a software rasteriser (llvmpipe, softpipe, swrast).
bool currentContextIsSoftware();

// RAII: times the enclosed GL work as `pass` when a timer is given; no-op for nullptr.
class ScopedPass {
public:
    ScopedPass(GpuPassTimer* timer, const std::string& pass) : timer_(timer) {
        if (timer_) timer_->begin(pass);
    }
    ~ScopedPass() {
        if (timer_) timer_->end();
    }
    ScopedPass(const ScopedPass&) = delete;
    ScopedPass& operator=(const ScopedPass&) = delete;

private:
    GpuPassTimer* timer_;
};

}  // namespace starnt::gl
