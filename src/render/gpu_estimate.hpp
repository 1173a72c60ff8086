// A GPU's frame time predicted from what a frame does, for machines without a GPU (docs/DESIGN.md,
// "Cost on a GPU"): each geometry pass costs its fragments times a cost per fragment that grows
// with the bytes each fragment blends into narrow (16 bits or less a channel) and wide (32-bit)
// targets; each full-screen pass costs its pixels times a cost per pixel of its kind. The
// coefficients are fitted to the per-pass GL_TIMESTAMP times of committed GPU runs
// (scripts/fit_gpu_estimate.py); an estimate, never a measurement, and reported apart from them.
#pragma once
#include <map>
#include <string>

#include "gl/gpu_timer.hpp"
#include "gl/pass_blend.hpp"

namespace starnt {

struct GpuEstimateModel {
    const char* source;           // the runs it was fitted to
    double nsPerFragment;         // a fragment of a geometry pass, whatever it writes
    double nsPerNarrowByte;       // per byte a fragment writes into a target of 16 bits or less a channel
    double nsPerWideByte;         // per byte a fragment writes into a 32-bit-channel target
    double nsPerPixelFullscreen;  // a full-screen pass (composite, inference, resolve, ...) per pixel
};

const GpuEstimateModel& gpuEstimateModel();

// True for the classes of 32-bit channels (float32, uint32, int32).
bool wideFormatClass(const std::string& cls);

// Milliseconds a GPU would take for one frame: the geometry passes of `counters` with the
// descriptions of `blend` (a pass without one counts its fragments alone), and every other pass
// named in `passMs` (the frame's timed passes) as a full-screen pass of width x height.
double gpuEstimateMs(const std::map<std::string, gl::PassCounters>& counters, const std::map<std::string, gl::PassBlend>& blend,
                     const std::map<std::string, double>& passMs, int width, int height);

}  // namespace starnt
