#include "methods/neural/temporal/temporal_schedule.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "starnt/error.hpp"

namespace starnt {

TemporalSchedule::TemporalSchedule(const MethodOptions& options)
    : auto_(options.neural.temporalAuto), fixedInterval_(options.neural.temporalInterval), targetFps_(options.neural.targetFps) {
    if (!auto_ && (fixedInterval_ < 1 || fixedInterval_ > kMaxTemporalInterval)) {
        throw Error("temporal interval must be in 1.." + std::to_string(kMaxTemporalInterval) + ", got " + std::to_string(fixedInterval_));
    }
    if (!std::isfinite(targetFps_) || !(targetFps_ > 0.0)) {
        throw Error("temporal target frame rate must be finite and positive, got " + std::to_string(targetFps_));
    }
}

bool TemporalSchedule::nextFrameIsReal() {
    if (started_ && framesIntoGroup_ + 1 < groupInterval_) {
        ++framesIntoGroup_;
        return false;
    }
    started_ = true;
    framesIntoGroup_ = 0;
    groupInterval_ = interval();
    return true;
}

void TemporalSchedule::Window::add(double ms) {
    if (!std::isfinite(ms) || ms < 0.0) return;
    samples_[size_t(next_)] = ms;
    next_ = (next_ + 1) % kAverageWindow;
    count_ = std::min(count_ + 1, kAverageWindow);
}

double TemporalSchedule::Window::mean() const {
    if (count_ == 0) return 0.0;
    double sum = 0.0;
    for (int i = 0; i < count_; ++i) sum += samples_[size_t(i)];
    return sum / count_;
}

void TemporalSchedule::recordRealFrameMs(double ms) { real_.add(ms); }
void TemporalSchedule::recordInterpolatedFrameMs(double ms) { interpolated_.add(ms); }

int TemporalSchedule::interval() const {
    if (!auto_) return fixedInterval_;
    if (real_.empty()) return 1;
    const double targetMs = 1000.0 / targetFps_;
    const double real = real_.mean();
    if (real > targetMs) return 1;  // below the target rate: plain rendering
    // Until an interpolated frame was timed, count it at a real frame's cost (the paper's rule),
    // but interpolate at least once so that its cost gets measured: without a measurement a rate
    // between the target and twice the target would keep k = 1 for ever.
    if (interpolated_.empty()) return std::clamp(int(std::min(targetMs / std::max(real, 1e-9), double(kMaxAutoInterval))), 2, kMaxAutoInterval);
    const double interpolated = interpolated_.mean();
    if (interpolated <= 0.0) return kMaxAutoInterval;  // immeasurably fast
    // Compare before converting: a huge quotient must not overflow the int.
    const double extra = std::floor((targetMs - real) / interpolated);
    if (!(extra < double(kMaxAutoInterval - 1))) return kMaxAutoInterval;
    return 1 + int(extra);
}

void TemporalSchedule::reset() {
    started_ = false;
    framesIntoGroup_ = 0;
    groupInterval_ = 0;
    real_.clear();
    interpolated_.clear();
}

}  // namespace starnt
