#include "methods/neural/temporal/real_frame_clock.hpp"

#include <chrono>

namespace starnt::temporal {
namespace {

double wallMs() {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

gl::QueryHandle makeQuery() {
    GLuint id = 0;
    glGenQueries(1, &id);
    return gl::QueryHandle(id);
}

}  // namespace

RealFrameClock::RealFrameClock(bool wallClock) : wallClock_(wallClock) {
    if (!wallClock_) {
        begin_ = makeQuery();
        end_ = makeQuery();
    }
}

void RealFrameClock::start() {
    if (wallClock_) {
        glFinish();  // earlier frames' work must not count
        startMs_ = wallMs();
        running_ = true;
        return;
    }
    poll();  // collects the previous pair if it is done
    if (inFlight_) return;  // still busy: this frame goes unmeasured
    glQueryCounter(begin_.id(), GL_TIMESTAMP);
    running_ = true;
}

void RealFrameClock::stop() {
    if (!running_) return;
    running_ = false;
    if (wallClock_) {
        glFinish();
        ready_ = wallMs() - startMs_;
        return;
    }
    glQueryCounter(end_.id(), GL_TIMESTAMP);
    glFlush();
    inFlight_ = true;
}

void RealFrameClock::poll() {
    if (inFlight_) {
        GLint available = 0;
        glGetQueryObjectiv(end_.id(), GL_QUERY_RESULT_AVAILABLE, &available);
        if (available) {
            GLuint64 t0 = 0, t1 = 0;
            glGetQueryObjectui64v(begin_.id(), GL_QUERY_RESULT, &t0);
            glGetQueryObjectui64v(end_.id(), GL_QUERY_RESULT, &t1);
            ready_ = t1 > t0 ? double(t1 - t0) * 1e-6 : 0.0;
            inFlight_ = false;
        }
    }
}

std::optional<double> RealFrameClock::take() {
    poll();
    std::optional<double> out = ready_;
    ready_.reset();
    return out;
}

}  // namespace starnt::temporal
