#include "gl/gpu_timer.hpp"
#include "gl/gl_util.hpp"

#include <chrono>
#include <string_view>

#include "starnt/error.hpp"

namespace starnt::gl {

namespace {
double nowMs() {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}  // namespace

bool currentContextIsSoftware() {
    const GLubyte* r = glGetString(GL_RENDERER);
    if (!r) return false;
    std::string_view renderer(reinterpret_cast<const char*>(r));
    return renderer.find("llvmpipe") != std::string_view::npos || renderer.find("softpipe") != std::string_view::npos ||
           renderer.find("swrast") != std::string_view::npos;
}

bool wallClockTimingNeeded() {
    return currentContextIsSoftware() || (!epoxy_is_desktop_gl() && !epoxy_has_gl_extension("GL_EXT_disjoint_timer_query"));
}

const char* passTimingDescription() {
    if (currentContextIsSoftware()) return "glFinish + wall clock (software rasteriser)";
    if (!epoxy_is_desktop_gl()) {
        return wallClockTimingNeeded() ? "glFinish + wall clock (OpenGL ES without EXT_disjoint_timer_query)"
                                       : "GL_TIMESTAMP_EXT pairs (EXT_disjoint_timer_query)";
    }
    return "GL_TIMESTAMP pairs";
}

namespace {
constexpr std::array<GLenum, 3> kCounterTargets = {GL_VERTEX_SHADER_INVOCATIONS_ARB,
                                                   GL_FRAGMENT_SHADER_INVOCATIONS_ARB,
                                                   GL_PRIMITIVES_SUBMITTED_ARB};
}  // namespace

GpuPassTimer::GpuPassTimer(bool finishAndWallClock)
    : wallClock_(finishAndWallClock),
      countersAvailable_(epoxy_is_desktop_gl() && (epoxy_gl_version() >= 46 || epoxy_has_gl_extension("GL_ARB_pipeline_statistics_query"))) {}

GpuPassTimer::~GpuPassTimer() {
    if (!hasCurrentContext()) return;  // the queries die with their context
    for (auto& p : pendingCounters_) {
        for (size_t i = 0; i < 3; ++i) freeCounterQueries_[i].push_back(p.queries[i]);
        if (p.samples) freeSampleQueries_.push_back(p.samples);
    }
    for (auto& list : freeCounterQueries_)
        if (!list.empty()) glDeleteQueries(GLsizei(list.size()), list.data());
    if (!freeSampleQueries_.empty()) glDeleteQueries(GLsizei(freeSampleQueries_.size()), freeSampleQueries_.data());
    for (auto& p : pending_) {
        free_.push_back(p.begin);
        free_.push_back(p.end);
    }
    if (openQuery_) free_.push_back(openQuery_);
    if (!free_.empty()) glDeleteQueries(GLsizei(free_.size()), free_.data());
}

GLuint GpuPassTimer::acquire() {
    if (!free_.empty()) {
        GLuint q = free_.back();
        free_.pop_back();
        return q;
    }
    GLuint q = 0;
    glGenQueries(1, &q);
    return q;
}

void GpuPassTimer::begin(const std::string& pass) {
    if (wallClock_) {
        if (open_wall_) throw Error("internal: GpuPassTimer::begin('" + pass + "') inside '" + open_ + "'");
        glFinish();
        open_ = pass;
        open_wall_ = true;
        openStartMs_ = nowMs();
        return;
    }
    if (openQuery_) throw Error("internal: GpuPassTimer::begin('" + pass + "') inside '" + open_ + "'");
    glFlush();
    openQuery_ = acquire();
    open_ = pass;
    glQueryCounter(openQuery_, GL_TIMESTAMP);
}

void GpuPassTimer::end() {
    if (wallClock_) {
        if (!open_wall_) throw Error("internal: GpuPassTimer::end without begin");
        glFinish();
        wallMs_[open_] += nowMs() - openStartMs_;
        open_wall_ = false;
        open_.clear();
        return;
    }
    if (!openQuery_) throw Error("internal: GpuPassTimer::end without begin");
    GLuint q = acquire();
    glQueryCounter(q, GL_TIMESTAMP);
    glFlush();
    pending_.push_back({open_, openQuery_, q});
    openQuery_ = 0;
    open_.clear();
}

std::map<std::string, double> GpuPassTimer::collect() {
    std::map<std::string, double> ms;
    ms.swap(wallMs_);
    for (const Pending& p : pending_) {
        GLuint64 t0 = 0, t1 = 0;
        glGetQueryObjectui64v(p.begin, GL_QUERY_RESULT, &t0);
        glGetQueryObjectui64v(p.end, GL_QUERY_RESULT, &t1);
        ms[p.name] += t1 > t0 ? double(t1 - t0) * 1e-6 : 0.0;
        free_.push_back(p.begin);
        free_.push_back(p.end);
    }
    pending_.clear();
    return ms;
}

void GpuPassTimer::beginCounters(const std::string& pass) {
    if (!blend_.count(pass)) blend_[pass] = describeBoundColourTargets();
    if (!countersAvailable_) return;
    if (countersOpen_) throw Error("internal: GpuPassTimer::beginCounters('" + pass + "') inside another pass");
    PendingCounters p{pass, {}};
    for (size_t i = 0; i < kCounterTargets.size(); ++i) {
        if (freeCounterQueries_[i].empty()) {
            glGenQueries(1, &p.queries[i]);
        } else {
            p.queries[i] = freeCounterQueries_[i].back();
            freeCounterQueries_[i].pop_back();
        }
        glBeginQuery(kCounterTargets[i], p.queries[i]);
    }
    // GL allows one occlusion query at a time: none while peel's (or an engine's) runs.
    bool occlusionActive = false;
    for (GLenum target : {GL_SAMPLES_PASSED, GL_ANY_SAMPLES_PASSED, GL_ANY_SAMPLES_PASSED_CONSERVATIVE}) {
        GLint current = 0;
        glGetQueryiv(target, GL_CURRENT_QUERY, &current);
        occlusionActive = occlusionActive || current != 0;
    }
    if (!occlusionActive) {
        if (freeSampleQueries_.empty()) {
            glGenQueries(1, &p.samples);
        } else {
            p.samples = freeSampleQueries_.back();
            freeSampleQueries_.pop_back();
        }
        glBeginQuery(GL_SAMPLES_PASSED, p.samples);
    }
    pendingCounters_.push_back(std::move(p));
    countersOpen_ = true;
}

void GpuPassTimer::endCounters() {
    if (!countersAvailable_) return;
    if (!countersOpen_) throw Error("internal: GpuPassTimer::endCounters without beginCounters");
    for (GLenum target : kCounterTargets) glEndQuery(target);
    if (!pendingCounters_.empty() && pendingCounters_.back().samples) glEndQuery(GL_SAMPLES_PASSED);
    countersOpen_ = false;
}

std::map<std::string, PassCounters> GpuPassTimer::collectCounters() {
    std::map<std::string, PassCounters> out;
    for (const PendingCounters& p : pendingCounters_) {
        GLuint64 v[3] = {0, 0, 0};
        for (size_t i = 0; i < 3; ++i) glGetQueryObjectui64v(p.queries[i], GL_QUERY_RESULT, &v[i]);
        PassCounters c{v[0], v[1], v[2]};
        if (p.samples) {
            GLuint64 samples = 0;
            glGetQueryObjectui64v(p.samples, GL_QUERY_RESULT, &samples);
            c.samplesPassed = samples;
            c.samplesCounted = true;
            freeSampleQueries_.push_back(p.samples);
        }
        out[p.name] += c;
        for (size_t i = 0; i < 3; ++i) freeCounterQueries_[i].push_back(p.queries[i]);
    }
    pendingCounters_.clear();
    return out;
}

std::map<std::string, PassBlend> GpuPassTimer::collectBlend() {
    std::map<std::string, PassBlend> out;
    out.swap(blend_);
    return out;
}

}  // namespace starnt::gl
