// Timing history for the viewer's timing panel: running medians per pass (robust to the odd slow
// frame a desktop compositor or a shader recompile causes) and a frame-time graph.
#pragma once
#include <deque>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace starnt::viewer {

// Median of the last `window` values added.
class RunningMedian {
public:
    explicit RunningMedian(size_t window = 60) : window_(window) {}
    void add(double value);
    double median() const;  // 0 when empty
    size_t size() const { return values_.size(); }

private:
    size_t window_;
    std::deque<double> values_;
};

class FrameTimeMedians {
public:
    static constexpr size_t kGraphFrames = 240;

    // One displayed frame: its total time, per-pass times and whether it was interpolated.
    void addFrame(double frameMs, const std::map<std::string, double>& passMs, bool interpolated);
    // Time of a whole displayed frame (method, display, UI, swap), measured between frame starts.
    void addDisplayFrame(double ms) { display_.add(ms); }
    // Drops the history (new scene or method: old timings would mix two workloads).
    void clear();
    double displayFrameMedianMs() const { return display_.median(); }

    double frameMedianMs() const { return frame_.median(); }
    std::map<std::string, double> passMedianMs() const;
    const std::vector<float>& frameGraphMs() const { return graph_; }
    int realFrames() const { return realFrames_; }
    int interpolatedFrames() const { return interpolatedFrames_; }

private:
    RunningMedian frame_, display_;
    std::map<std::string, RunningMedian> passes_;
    std::vector<float> graph_;
    int realFrames_ = 0, interpolatedFrames_ = 0;
};

}  // namespace starnt::viewer
