// Captures every fragment of a frame, per pixel, for the CPU references and the trainer: the
// A-buffer build pass in capture mode (with a submission-order key per fragment), read back.
#pragma once
#include <vector>

#include "methods/abuffer/abuffer_lists.hpp"
#include "starnt/tools/fragments.hpp"

namespace starnt {

struct CapturedFrame {
    int width = 0, height = 0;
    std::vector<FragmentList> pixels;  // row 0 = top (as Image), each list in arbitrary order
    const FragmentList& at(int x, int y) const { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
    size_t maxDepthComplexity() const;
};

class FragmentCapture : public MethodBase {
public:
    explicit FragmentCapture(const SurfaceShader& surface, const MethodOptions& options = {});
    // Every fragment the methods' passes see: clipped by the frame's opaque depth, if it has one.
    CapturedFrame capture(const FrameDesc& frame, const DrawCallback& draw);

    // OitMethod (unused: capture has no image output)
    std::string name() const override { return "capture"; }
    void renderFrame(const FrameDesc& canonical, const DrawCallback& draw) override { captureCanonical(canonical, draw); }

private:
    // capture() of a frame already in the canonical depth convention (beginDepthConvention).
    CapturedFrame captureCanonical(const FrameDesc& canonical, const DrawCallback& draw);

public:
    size_t gpuMemoryBytes() const override { return lists_.gpuMemoryBytes(); }

private:
    ABufferLists lists_;
    gl::Program build_;
};

// Counts fragments per pixel (after the alpha cut-off) with one additive pass; returns the maximum.
// Used for the `max_fragments` statistic of every method.
class DepthComplexityCounter : public MethodBase {
public:
    explicit DepthComplexityCounter(const SurfaceShader& surface);
    // Clipped by the frame's opaque depth, if it has one.
    unsigned count(const FrameDesc& frame, const DrawCallback& draw);

    std::string name() const override { return "count"; }
    void renderFrame(const FrameDesc& canonical, const DrawCallback& draw) override { countCanonical(canonical, draw); }

private:
    unsigned countCanonical(const FrameDesc& canonical, const DrawCallback& draw);

public:
    size_t gpuMemoryBytes() const override { return outputBytes(); }

private:
    gl::Program program_;
};

}  // namespace starnt
