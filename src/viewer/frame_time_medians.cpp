#include "viewer/frame_time_medians.hpp"

#include "render/offscreen_renderer.hpp"

#include <algorithm>

namespace starnt::viewer {

void RunningMedian::add(double value) {
    values_.push_back(value);
    while (values_.size() > window_) values_.pop_front();
}

double RunningMedian::median() const {
    return starnt::median(std::vector<double>(values_.begin(), values_.end()));  // 0 when empty
}

void FrameTimeMedians::addFrame(double frameMs, const std::map<std::string, double>& passMs, bool interpolated) {
    frame_.add(frameMs);
    for (const auto& [name, ms] : passMs) passes_[name].add(ms);
    graph_.push_back(float(frameMs));
    if (graph_.size() > kGraphFrames) graph_.erase(graph_.begin());
    (interpolated ? interpolatedFrames_ : realFrames_) += 1;
}

void FrameTimeMedians::clear() { *this = FrameTimeMedians(); }

std::map<std::string, double> FrameTimeMedians::passMedianMs() const {
    std::map<std::string, double> out;
    for (const auto& [name, m] : passes_) out[name] = m.median();
    return out;
}

}  // namespace starnt::viewer
