#include "methods/abuffer/abuffer_lists.hpp"

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <vector>

#include "starnt/bindings.h"
#include "starnt/error.hpp"
#include "starnt/log.hpp"

namespace starnt {

ABufferLists::ABufferLists(bool captureOrder, const MethodOptions& options)
    : captureOrder_(captureOrder), options_(options) {
    // The pool grows on overflow, so any start works; past this bound the first frame's size would
    // overflow its count before the memory cap could name it.
    const double initial = options.abuffer.initialNodesPerPixel;
    if (!(initial >= 0.0 && initial <= kMaxInitialNodesPerPixel)) {
        throw Error("MethodOptions::abuffer.initialNodesPerPixel must be within 0.." + std::to_string(int(kMaxInitialNodesPerPixel)) +
                    " (got " + std::to_string(initial) + ")");
    }
}

void ABufferLists::allocate(int width, int height, uint64_t capacity) {
    const size_t perNode = kABufferNodeBytes * (captureOrder_ ? 2 : 1);
    const size_t total = size_t(width) * size_t(height) * 4 + size_t(capacity) * perNode + 16;
    if (total > options_.abuffer.memoryCapBytes) {
        auto mib = [](size_t bytes) {
            char text[32];
            std::snprintf(text, sizeof text, "%.3g", double(bytes) / 1048576.0);
            return std::string(text);
        };
        throw Error("A-buffer needs " + mib(total) + " MiB for " + std::to_string(capacity) +
                    " fragments, over its memory cap of " + mib(options_.abuffer.memoryCapBytes) + " MiB (raise MethodOptions::abuffer.memoryCapBytes, the CLI's --abuffer-cap-mib, or lower the resolution)");
    }
    if (width != width_ || height != height_) {
        heads_ = gl::Buffer(size_t(width) * size_t(height) * 4);
        emptyFb_ = gl::makeFramebufferName();
        gl::setFramebufferDefaultSize(emptyFb_.id(), width, height);
        width_ = width;
        height_ = height;
    }
    if (capacity != capacity_) {
        nodes_ = gl::Buffer(size_t(capacity) * kABufferNodeBytes);
        if (captureOrder_) orders_ = gl::Buffer(size_t(capacity) * kABufferNodeBytes);
        capacity_ = capacity;
    }
    if (!counters_) counters_ = gl::Buffer(16);
}

void ABufferLists::bindBuffers() const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, STARNT_SSBO_ABUFFER_HEADS, heads_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, STARNT_SSBO_ABUFFER_NODES, nodes_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, STARNT_SSBO_ABUFFER_COUNTERS, counters_.id());
    if (captureOrder_) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, STARNT_SSBO_ABUFFER_ORDERS, orders_.id());
}

void ABufferLists::build(const FrameDesc& frame, const DrawCallback& draw, const gl::Program& program,
                         OpaqueScene* clip) {
    const double initial = double(frame.width) * double(frame.height) * std::max(0.0, options_.abuffer.initialNodesPerPixel);
    uint64_t wanted = std::max<uint64_t>({capacity_, uint64_t(initial), 16});
    if (frame.width != width_ || frame.height != height_ || wanted != capacity_) {
        allocate(frame.width, frame.height, wanted);
    }
    regrows_ = 0;
    for (;;) {
        const GLuint end = STARNT_ABUFFER_END, zero = 0;
        gl::fillBufferUint(heads_, end);
        gl::fillBufferUint(counters_, zero);
        bindBuffers();
        resetPassState();
        glBindFramebuffer(GL_FRAMEBUFFER, emptyFb_.id());
        glViewport(0, 0, width_, height_);
        glUseProgram(program.id());
        glUniform1ui(program.uniform("u_capacity"), GLuint(std::min<uint64_t>(capacity_, 0xFFFFFFFFull)));
        glUniform1i(program.uniform("u_width"), width_);
        {
            gl::ScopedPass timing(frame.timing, "build");
            if (clip) clip->beginDepthTest(emptyFb_.id(), width_, height_, width_, height_);
            glUseProgram(program.id());
            glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
            MethodBase::runGeometryPass(captureOrder_ ? "abuffer_capture" : "abuffer_build", program, frame, draw);
            glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
            if (clip) clip->endDepthTest(emptyFb_.id());
        }
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        GLuint count = 0;
        gl::readBuffer(counters_.id(), 0, 4, &count);
        lastCount_ = count;
        if (count <= capacity_) break;
        // The counter is 32-bit: a frame of more than 4G fragments cannot be represented at all.
        uint64_t grown = uint64_t(std::ceil(double(count) * 1.25));
        logMessage(LogLevel::Note, "A-buffer pool overflow (" + std::to_string(count) + " fragments, capacity " +
                                std::to_string(capacity_) + "); growing to " + std::to_string(grown) +
                                " and rendering the frame again");
        allocate(width_, height_, grown);
        ++regrows_;
    }
}

}  // namespace starnt
