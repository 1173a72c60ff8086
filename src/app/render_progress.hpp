// A progress line on stderr for long `render` sequences: frame i/N, elapsed time and an estimate of
// the time left. Silent for the first 2 seconds (short renders print nothing); then, on a
// terminal, one line redrawn every second, otherwise (logs, pipes) a new line every 10 seconds.
// STARNT_PROGRESS_SECONDS=S sets both the silent start and the interval to S (tests use 0).
#pragma once
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unistd.h>

namespace starnt::app {

class RenderProgress {
public:
    RenderProgress(std::FILE* out, int totalFrames)
        : out_(out), total_(totalFrames), interactive_(::isatty(::fileno(out)) != 0),
          start_(std::chrono::steady_clock::now()) {
        delay_ = 2.0;
        interval_ = interactive_ ? 1.0 : 10.0;
        if (const char* s = std::getenv("STARNT_PROGRESS_SECONDS")) {
            char* end = nullptr;
            const double v = std::strtod(s, &end);
            if (end != s && v >= 0.0 && v < 1e6) delay_ = interval_ = v;
        }
    }
    RenderProgress(const RenderProgress&) = delete;
    RenderProgress& operator=(const RenderProgress&) = delete;

    // Frame `index` (0-based) is done.
    void frameDone(int index) {
        if (total_ <= 1) return;
        const double elapsed = seconds();
        const bool lastFrame = index + 1 >= total_;
        if (elapsed < delay_ || (!lastFrame && printed_ && elapsed - lastPrint_ < interval_)) return;
        if (lastFrame && !printed_) return;  // finished before the first line was due
        const int done = index + 1;
        const double left = elapsed / done * (total_ - done);
        std::fprintf(out_, "%srender: frame %d/%d, %.0f s elapsed, about %.0f s left%s", interactive_ ? "\r" : "", done,
                     total_, elapsed, left, interactive_ ? "   " : "\n");
        std::fflush(out_);
        printed_ = true;
        lastPrint_ = elapsed;
    }
    ~RenderProgress() {
        if (printed_ && interactive_) std::fprintf(out_, "\n");
    }

private:
    double seconds() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }
    std::FILE* out_;
    int total_;
    bool interactive_;
    std::chrono::steady_clock::time_point start_;
    double delay_ = 2.0, interval_ = 10.0, lastPrint_ = 0.0;
    bool printed_ = false;
};

}  // namespace starnt::app
