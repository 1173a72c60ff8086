#include "bench/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace starnt::bench {

Progress::Progress(std::FILE* out, size_t totalUnits)
    : out_(out), interactive_(out && isatty(fileno(out))), total_(std::max<size_t>(totalUnits, 1)),
      start_(std::chrono::steady_clock::now()) {}

double Progress::estimateSecondsLeft() const {
    if (done_ == 0) return -1.0;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const size_t remaining = total_ - std::min(total_, done_ + skipped_);
    // Average seconds per frame so far. Frames differ in cost between scenes and methods, so the
    // estimate wanders, but it converges as the run samples every kind of frame.
    return elapsed / double(done_) * double(remaining);
}

std::string Progress::formatDuration(double seconds) {
    if (seconds < 0.0) return "--:--";
    const long s = std::lround(seconds);
    char text[32];
    if (s >= 3600) std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
    else std::snprintf(text, sizeof text, "%ld:%02ld", s / 60, s % 60);
    return text;
}

void Progress::begin(const std::string& activity) {
    activity_ = activity;
    if (!interactive_ && out_) draw("");
}

void Progress::step(const std::string& detail) {
    ++done_;
    if (interactive_) draw(detail);
}

void Progress::skip(size_t units) { skipped_ += units; }

void Progress::draw(const std::string& detail) {
    if (!out_) return;
    const double fraction = std::min(1.0, double(done_ + skipped_) / double(total_));
    constexpr int kWidth = 24;
    const int filled = int(fraction * kWidth);
    std::string bar = std::string(size_t(filled), '#') + std::string(size_t(kWidth - filled), '.');
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::string line = "[" + bar + "] " + std::to_string(int(fraction * 100.0)) + "% " + activity_;
    if (!detail.empty()) line += " " + detail;
    line += "  elapsed " + formatDuration(elapsed) + ", left ~" + formatDuration(estimateSecondsLeft());
    if (interactive_) {
        std::fprintf(out_, "\r\033[K%s", line.c_str());  // redraw in place, clearing the old line
    } else {
        std::fprintf(out_, "%s\n", line.c_str());
    }
    std::fflush(out_);
}

void Progress::finish() {
    if (!out_) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (interactive_) std::fprintf(out_, "\r\033[K");
    std::fprintf(out_, "bench: done in %s\n", formatDuration(elapsed).c_str());
    std::fflush(out_);
}

}  // namespace starnt::bench
