// A progress line for long benchmark runs: what is rendering, how far along, and an estimate of the
// time left. On a terminal it redraws one line; otherwise (logs, tests) it prints a line whenever
// the activity changes, so logs stay short.
#pragma once
#include <chrono>
#include <cstdio>
#include <string>

namespace starnt::bench {

class Progress {
public:
    // `totalUnits`: the whole run's work in frames (ground truth and every method, every scene).
    Progress(std::FILE* out, size_t totalUnits);
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    // Names what is being rendered now, e.g. "tree (2/3): starnt-total".
    void begin(const std::string& activity);
    // One frame done (`detail`, e.g. "frame 3/8", is shown after the activity).
    void step(const std::string& detail);
    // Skips the units of work that will not run (a failed scene or method), keeping the estimate honest.
    void skip(size_t units);
    void finish();

    // Seconds left at the current average rate; negative until a unit has completed.
    double estimateSecondsLeft() const;
    static std::string formatDuration(double seconds);

private:
    void draw(const std::string& detail);

    std::FILE* out_;
    bool interactive_;
    size_t total_, done_ = 0, skipped_ = 0;
    std::string activity_;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace starnt::bench
