#include "render/gpu_estimate.hpp"

namespace starnt {

const GpuEstimateModel& gpuEstimateModel() {
    // Fitted by scripts/fit_gpu_estimate.py to run A of the NVIDIA H200 (commit a409641; wboit, mboit,
    // dfaoit, starnt-full, starnt, hybrid-moments, starnt-d, and run B's hybrid; six scenes at 1080p),
    // each pass's GL_TIMESTAMP time against llvmpipe's GL_SAMPLES_PASSED counts of the same variants and
    // camera path (docs/results/gpu_estimate_fit_counts.csv; fit, residuals and caveats in
    // docs/results/gpu_estimate_fit.md). Relative least squares, coefficients >= 0. Off on average by
    // 28 % a geometry pass, 15 % a frame, 11 % (max 32 %) in time / DFAOIT. samples_passed matches the
    // GPU's own count (within 3 %) where every fragment is shaded (wboit, mboit, pass 3), but is 0.2-0.76x
    // it for passes 1 and 2 (depth test GL_LESS with writes: the GPU shades fragments that then fail it).
    static const GpuEstimateModel model{
        .source = "NVIDIA H200, gpu preset at 1920x1080, run A (docs/results/gpu_estimate_fit.md), with llvmpipe's samples_passed",
        .nsPerFragment = 1.10,
        .nsPerNarrowByte = 0.0548,
        .nsPerWideByte = 0.0756,
        .nsPerPixelFullscreen = 0.284,
    };
    return model;
}

bool wideFormatClass(const std::string& cls) { return cls == "float32" || cls == "uint32" || cls == "int32"; }

double gpuEstimateMs(const std::map<std::string, gl::PassCounters>& counters, const std::map<std::string, gl::PassBlend>& blend,
                     const std::map<std::string, double>& passMs, int width, int height) {
    const GpuEstimateModel& m = gpuEstimateModel();
    double ns = 0.0;
    for (const auto& [name, c] : counters) {
        double perFragment = m.nsPerFragment;
        if (auto it = blend.find(name); it != blend.end()) {
            for (const auto& [cls, bytes] : it->second.bytesByClass) {
                perFragment += bytes * (wideFormatClass(cls) ? m.nsPerWideByte : m.nsPerNarrowByte);
            }
        }
        // The exact count where there is one (llvmpipe's invocations count whole 4x4 blocks).
        ns += double(c.samplesCounted ? c.samplesPassed : c.fragmentInvocations) * perFragment;
    }
    // A timed pass is a geometry pass when its counters carry its name, or the method's prefix
    // before it (wboit times "accumulate" and counts "wboit_accumulate").
    const auto geometry = [&](const std::string& timed) {
        if (counters.count(timed) || blend.count(timed)) return true;
        const std::string suffix = "_" + timed;
        for (const auto& [name, c] : counters)
            if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0) return true;
        return false;
    };
    for (const auto& [name, ms] : passMs) {
        if (!geometry(name)) ns += double(width) * double(height) * m.nsPerPixelFullscreen;
    }
    return ns * 1e-6;
}

}  // namespace starnt
