// Per-pass GPU timing with GL_TIMESTAMP query pairs.
//
// GL_TIME_ELAPSED returns garbage on Mesa llvmpipe, so each pass is bracketed by two timestamp
// queries with a glFlush after each (llvmpipe records a timestamp when the flushed work before it
// has run). Results are read after the frame; medians over frames come from PassTimeLog.
#pragma once
#include <epoxy/gl.h>

#include <map>
#include <string>
#include <vector>

namespace starnt::gl {

class GpuPassTimer {
public:
    GpuPassTimer();
    ~GpuPassTimer();
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
};

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
