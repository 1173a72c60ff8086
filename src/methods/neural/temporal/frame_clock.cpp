#include "methods/neural/temporal/frame_clock.hpp"

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

FrameClock::FrameClock(bool wallClock) : wallClock_(wallClock) {
    if (!wallClock_) {
        begin_ = makeQuery();
        end_ = makeQuery();
    }
}

void FrameClock::start(bool real) {
    if (wallClock_) {
        real_ = real;
        glFinish();  // earlier frames' work must not count
        startMs_ = wallMs();
        running_ = true;
        return;
    }
    poll();  // collects the previous pair if it is done
    if (inFlight_) return;  // still busy: this frame goes unmeasured
    glQueryCounter(begin_.id(), GL_TIMESTAMP);
    real_ = real;
    running_ = true;
}

void FrameClock::stop() {
    if (!running_) return;
    running_ = false;
    if (wallClock_) {
        glFinish();
        ready_ = Measurement{wallMs() - startMs_, real_};
        return;
    }
    glQueryCounter(end_.id(), GL_TIMESTAMP);
    glFlush();
    inFlight_ = true;
}

void FrameClock::poll() {
    if (inFlight_) {
        const gl::QueryBufferUnbound queryBuffer;  // (an engine's would receive the results)
        GLint available = 0;
        glGetQueryObjectiv(end_.id(), GL_QUERY_RESULT_AVAILABLE, &available);
        if (available) {
            GLuint64 t0 = 0, t1 = 0;
            glGetQueryObjectui64v(begin_.id(), GL_QUERY_RESULT, &t0);
            glGetQueryObjectui64v(end_.id(), GL_QUERY_RESULT, &t1);
            ready_ = Measurement{t1 > t0 ? double(t1 - t0) * 1e-6 : 0.0, real_};
            inFlight_ = false;
        }
    }
}

std::optional<FrameClock::Measurement> FrameClock::take() {
    poll();
    std::optional<Measurement> out = ready_;
    ready_.reset();
    return out;
}

}  // namespace starnt::temporal
