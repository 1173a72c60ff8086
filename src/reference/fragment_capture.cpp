#include "reference/fragment_capture.hpp"

#include "gl/pass_blend.hpp"
#include "scene/tool_sources.hpp"

#include <algorithm>


#include "scene/scene_constants.h"

namespace starnt {

size_t CapturedFrame::maxDepthComplexity() const {
    size_t m = 0;
    for (const auto& p : pixels) m = std::max(m, p.size());
    return m;
}

FragmentCapture::FragmentCapture(const SurfaceShader& surface, const MethodOptions& options)
    : MethodBase(surface),
      lists_(true, options),
      build_(buildGeometryProgram("abuffer_capture", "methods/abuffer/abuffer_build.frag.glsl",
                                  "#define STARNT_ABUFFER_CAPTURE_ORDER 1\n")) {}

CapturedFrame FragmentCapture::capture(const FrameDesc& frame, const DrawCallback& draw) {
    CapturedFrame out = captureCanonical(beginDepthConvention(frame), draw);
    glDepthRangef(0.0f, 1.0f);  // as MethodBase::render leaves it
    return out;
}

CapturedFrame FragmentCapture::captureCanonical(const FrameDesc& frame, const DrawCallback& draw) {
    opaque_.begin(frame);
    lists_.build(frame, draw, build_, &opaque_);
    opaque_.end();
    glFinish();
    const size_t pixelCount = size_t(frame.width) * size_t(frame.height);
    const size_t count = size_t(lists_.fragmentCount());
    std::vector<uint32_t> heads(pixelCount);
    std::vector<glm::uvec4> nodes(count), extras(count);
    gl::readBuffer(lists_.heads().id(), 0, GLsizeiptr(pixelCount * 4), heads.data());
    if (count) {
        gl::readBuffer(lists_.nodes().id(), 0, GLsizeiptr(count * 16), nodes.data());
        gl::readBuffer(lists_.orders().id(), 0, GLsizeiptr(count * 16), extras.data());
    }
    CapturedFrame out;
    out.width = frame.width;
    out.height = frame.height;
    out.pixels.resize(pixelCount);
    for (int y = 0; y < frame.height; ++y) {
        for (int x = 0; x < frame.width; ++x) {
            // GL rows start at the bottom; CapturedFrame rows start at the top like Image.
            FragmentList& list = out.pixels[size_t(frame.height - 1 - y) * size_t(frame.width) + size_t(x)];
            for (uint32_t i = heads[size_t(y) * size_t(frame.width) + size_t(x)]; i != STARNT_ABUFFER_END;
                 i = nodes[i].w) {
                Fragment f;
                f.color = glm::vec3(glm::uintBitsToFloat(extras[i].x), glm::uintBitsToFloat(extras[i].y),
                                    glm::uintBitsToFloat(extras[i].z));
                f.alpha = glm::uintBitsToFloat(extras[i].w);
                f.depth = glm::uintBitsToFloat(nodes[i].z);
                f.order = nodes[i].x;
                list.push_back(f);
            }
        }
    }
    return out;
}

DepthComplexityCounter::DepthComplexityCounter(const SurfaceShader& surface)
    : MethodBase(surface), program_((tools::useToolSources(), buildGeometryProgram("count", "reference/count.frag.glsl"))) {}

unsigned DepthComplexityCounter::count(const FrameDesc& frame, const DrawCallback& draw) {
    const unsigned maximum = countCanonical(beginDepthConvention(frame), draw);
    glDepthRangef(0.0f, 1.0f);  // as MethodBase::render leaves it
    return maximum;
}

unsigned DepthComplexityCounter::countCanonical(const FrameDesc& frame, const DrawCallback& draw) {
    if (frame.width != width_ || frame.height != height_ || !output_) {
        width_ = frame.width;
        height_ = frame.height;
        // R16F where ES cannot blend 32-bit floats: its counts are exact up to 2048 fragments a pixel.
        output_ = gl::Texture2D(gl::floatBlendAvailable() ? GL_R32F : GL_R16F, width_, height_);
        outputFb_ = gl::makeFramebuffer({&output_});
    }
    resetPassState();
    bindOutputFramebuffer();
    const float zero[4] = {0, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 0, zero);
    opaque_.begin(frame);
    opaque_.beginDepthTest(outputFb_.id(), width_, height_, width_, height_);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    runGeometryPass("count", program_, frame, draw);
    opaque_.endDepthTest(outputFb_.id());
    opaque_.end();
    resetPassState();
    const std::vector<float> counts = gl::readTextureFloats(output_.id(), width_, height_, 1);
    float m = 0.0f;
    for (float c : counts) m = std::max(m, c);
    return unsigned(m + 0.5f);
}

}  // namespace starnt
