#include "methods/neural/temporal/temporal_schedule.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "starnt/error.hpp"

namespace starnt {

TemporalSchedule::TemporalSchedule(const MethodOptions& options)
    : auto_(options.temporalAuto), fixedInterval_(options.temporalInterval), targetFps_(options.targetFps) {
    if (!auto_ && (fixedInterval_ < 1 || fixedInterval_ > kMaxInterval)) {
        throw Error("temporal interval must be in 1..4, got " + std::to_string(fixedInterval_));
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

void TemporalSchedule::recordRealFrameMs(double ms) {
    if (!std::isfinite(ms) || ms < 0.0) return;
    samples_[size_t(nextSample_)] = ms;
    nextSample_ = (nextSample_ + 1) % kAverageWindow;
    sampleCount_ = std::min(sampleCount_ + 1, kAverageWindow);
}

double TemporalSchedule::averageRealFrameMs() const {
    if (sampleCount_ == 0) return 0.0;
    double sum = 0.0;
    for (int i = 0; i < sampleCount_; ++i) sum += samples_[size_t(i)];
    return sum / sampleCount_;
}

int TemporalSchedule::interval() const {
    if (!auto_) return fixedInterval_;
    if (sampleCount_ == 0) return 1;
    const double ms = averageRealFrameMs();
    if (ms <= 0.0) return kMaxInterval;  // immeasurably fast
    const double ratio = (1000.0 / ms) / targetFps_;
    // Compare before converting: a huge ratio must not overflow the int.
    if (!(ratio < double(kMaxInterval))) return kMaxInterval;
    return std::max(1, int(std::floor(ratio)));
}

void TemporalSchedule::reset() {
    started_ = false;
    framesIntoGroup_ = 0;
    groupInterval_ = 0;
    sampleCount_ = 0;
    nextSample_ = 0;
}

}  // namespace starnt
