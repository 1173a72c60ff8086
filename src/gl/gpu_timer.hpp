// Per-pass GPU timing.
//
// On a GPU: GL_TIMESTAMP query pairs around each pass, with a glFlush after each, read after the
// frame (no stall inside the frame). GL_TIME_ELAPSED is not used: it returns garbage on llvmpipe.
// On a software rasteriser (llvmpipe) timestamp queries are taken when the command is submitted,
// not when the binned triangles are rasterised, so they measured e.g. 0.04 ms for an A-buffer build
// that takes tens of ms; there each pass is bracketed by glFinish and timed with the wall clock
// (a CPU "GPU" has no pipelining to lose).
#pragma once
#include <epoxy/gl.h>

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "gl/pass_blend.hpp"
#include "starnt/oit_method.hpp"

namespace starnt::gl {

// Work done by one geometry pass (GL_ARB_pipeline_statistics_query, core in GL 4.6, on llvmpipe
// and the GPU drivers): they do not depend on the machine's speed, so they show what a GPU saves
// where llvmpipe's single-threaded vertex stage hides it in the timings.
struct PassCounters {
    uint64_t vertexInvocations = 0;
    uint64_t fragmentInvocations = 0;
    uint64_t primitives = 0;  // primitives submitted
    // Samples that passed the depth test and reached the targets (GL_SAMPLES_PASSED): exact on
    // every driver, where llvmpipe's fragment invocations count whole 4x4 blocks, partly covered
    // ones too (2-8x a GPU's count on the suite: docs/results/gpu_estimate_fit.md). Counted
    // where no other occlusion query is active (peel's, an engine's), else 0 with samplesCounted false.
    uint64_t samplesPassed = 0;
    bool samplesCounted = false;
    PassCounters& operator+=(const PassCounters& o) {
        vertexInvocations += o.vertexInvocations;
        fragmentInvocations += o.fragmentInvocations;
        primitives += o.primitives;
        samplesPassed += o.samplesPassed;
        samplesCounted = samplesCounted || o.samplesCounted;
        return *this;
    }
};

// The tools' PassTimingHook: GPU timestamps (wall clock on software rasterisers) per pass name and
// pipeline-statistics work counters per geometry pass.
class GpuPassTimer final : public PassTimingHook {
public:
    // `finishAndWallClock`: time passes with glFinish + steady_clock (software rasterisers).
    explicit GpuPassTimer(bool finishAndWallClock = false);
    ~GpuPassTimer();
    GpuPassTimer(const GpuPassTimer&) = delete;
    GpuPassTimer& operator=(const GpuPassTimer&) = delete;

    void begin(const std::string& pass);  // passes may repeat (e.g. peel layers): times add up
    void end();
    void beginPass(const std::string& name) override { begin(name); }
    void endPass() override { end(); }
    void beginGeometry(const std::string& name) override { beginCounters(name); }
    void endGeometry() override { endCounters(); }

    // Waits for the queries of this frame and returns milliseconds per pass name; resets.
    std::map<std::string, double> collect();

    // Work counters around a geometry pass (MethodBase::runGeometryPass brackets the engine's
    // draws with them); a pass counted twice in a frame adds up. No-ops when the context lacks
    // pipeline statistics queries (countersAvailable() is false).
    bool countersAvailable() const { return countersAvailable_; }
    void beginCounters(const std::string& pass);
    void endCounters();
    // Waits for this frame's counter queries and returns them per pass name; resets.
    std::map<std::string, PassCounters> collectCounters();
    // What each geometry pass of this frame writes into its colour targets (pass_blend.hpp), read
    // at beginCounters whether or not the context counts; the first description of a name in a
    // frame stands. Returns it per pass name; resets.
    std::map<std::string, PassBlend> collectBlend();

private:
    struct Pending {
        std::string name;
        GLuint begin, end;
    };
    GLuint acquire();
    std::vector<GLuint> free_;
    std::vector<Pending> pending_;
    std::string open_;
    GLuint openQuery_ = 0;
    bool wallClock_ = false;
    double openStartMs_ = 0.0;
    bool open_wall_ = false;
    std::map<std::string, double> wallMs_;

    struct PendingCounters {
        std::string name;
        std::array<GLuint, 3> queries;
        GLuint samples = 0;  // GL_SAMPLES_PASSED, 0 where not counted
    };
    std::vector<GLuint> freeSampleQueries_;
    std::map<std::string, PassBlend> blend_;
    bool countersAvailable_ = false;
    bool countersOpen_ = false;
    std::vector<PendingCounters> pendingCounters_;
    std::array<std::vector<GLuint>, 3> freeCounterQueries_;  // per target: a query's target is fixed at first use
};

// True when the current context is a software rasteriser (llvmpipe, softpipe, swrast).
bool currentContextIsSoftware();
// True when pass timing must use glFinish + wall clock: a software rasteriser (its GL_TIME_ELAPSED
// and timestamps are not GPU times), or OpenGL ES without EXT_disjoint_timer_query (ES 3.2 has no
// timestamp queries of its own).
bool wallClockTimingNeeded();
// How the current context's passes are timed, for stats and the viewer.
const char* passTimingDescription();

// RAII: reports the enclosed GL work as pass `pass` to the engine's timing hook; no-op for nullptr.
class ScopedPass {
public:
    ScopedPass(PassTimingHook* timer, const std::string& pass) : timer_(timer) {
        if (timer_) timer_->beginPass(pass);
    }
    ~ScopedPass() {
        if (timer_) timer_->endPass();
    }
    ScopedPass(const ScopedPass&) = delete;
    ScopedPass& operator=(const ScopedPass&) = delete;

private:
    PassTimingHook* timer_;
};

}  // namespace starnt::gl
