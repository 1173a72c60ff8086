#include "viewer/frame_statistics.hpp"

#include <algorithm>

namespace starnt::viewer {

void RunningMedian::add(double value) {
    values_.push_back(value);
    while (values_.size() > window_) values_.pop_front();
}

double RunningMedian::median() const {
    if (values_.empty()) return 0.0;
    std::vector<double> sorted(values_.begin(), values_.end());
    std::sort(sorted.begin(), sorted.end());
    const size_t n = sorted.size();
    return n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
}

void FrameStatistics::addFrame(double frameMs, const std::map<std::string, double>& passMs, bool interpolated) {
    frame_.add(frameMs);
    for (const auto& [name, ms] : passMs) passes_[name].add(ms);
    graph_.push_back(float(frameMs));
    if (graph_.size() > kGraphFrames) graph_.erase(graph_.begin());
    (interpolated ? interpolatedFrames_ : realFrames_) += 1;
}

void FrameStatistics::clear() { *this = FrameStatistics(); }

std::map<std::string, double> FrameStatistics::passMedianMs() const {
    std::map<std::string, double> out;
    for (const auto& [name, m] : passes_) out[name] = m.median();
    return out;
}

}  // namespace starnt::viewer
