// Per-pixel fragment linked lists (the A-buffer's build stage), shared by the `abuffer` method and
// the fragment capture used by the references and the trainer.
//
// build() clears the lists, runs the geometry pass, and reads back how many nodes the frame
// needed. When the pool was too small it reports it on stderr, grows the pool and renders the frame
// again; past the memory cap it throws starnt::Error. So a finished build always holds every
// fragment.
#pragma once
#include <cstdint>

#include "methods/common/method_base.hpp"

namespace starnt {

class ABufferLists {
public:
    ABufferLists(bool captureOrder, const MethodOptions& options);

    // `clip` (the method's opaque scene, or null for a capture of every fragment) drops the
    // fragments behind the engine's opaque depth.
    void build(const FrameDesc& frame, const DrawCallback& draw, const gl::Program& program, OpaqueScene* clip = nullptr);
    // Binds heads, nodes and counters (and orders in capture mode) to their SSBO slots.
    void bindBuffers() const;

    uint64_t fragmentCount() const { return lastCount_; }
    uint64_t capacity() const { return capacity_; }
    int regrows() const { return regrows_; }
    size_t gpuMemoryBytes() const { return heads_.bytes() + nodes_.bytes() + counters_.bytes() + orders_.bytes(); }
    const gl::Buffer& heads() const { return heads_; }
    const gl::Buffer& nodes() const { return nodes_; }
    const gl::Buffer& counters() const { return counters_; }
    const gl::Buffer& orders() const { return orders_; }
    bool captureOrder() const { return captureOrder_; }

private:
    void allocate(int width, int height, uint64_t capacity);

    bool captureOrder_;
    MethodOptions options_;
    int width_ = 0, height_ = 0;
    uint64_t capacity_ = 0;
    uint64_t lastCount_ = 0;
    int regrows_ = 0;
    gl::Buffer heads_, nodes_, counters_, orders_;
    gl::FramebufferHandle emptyFb_;
};

// Bytes one A-buffer node takes (uvec4); twice that in capture mode (full-precision colour).
constexpr size_t kABufferNodeBytes = 16;
// MethodOptions::abuffer.initialNodesPerPixel at most this (the pool grows from there on overflow).
constexpr double kMaxInitialNodesPerPixel = 65536.0;

}  // namespace starnt
