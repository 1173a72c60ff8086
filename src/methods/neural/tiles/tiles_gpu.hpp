// GPU adaptive tiles (docs/DESIGN.md, "Adaptive tiles and tile-guided resolution"): evaluation, one-level limit, neighbour balance and the occupied-tile
// histogram, run after each real frame's composite. The histogram is copied into a small ring of
// readback buffers guarded by fences and picked up without waiting (pollHistogram), so the next
// frame's passes never stall on it; the scales then lag by one real frame more only when the GPU
// has not finished the previous frame yet.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "gl/gl_util.hpp"
#include "gl/gpu_timer.hpp"
#include "gl/shader.hpp"
#include "methods/neural/tiles/tile_constants.h"
#include "methods/neural/tiles/tile_rules.hpp"

namespace starnt::tiles {

class GpuTiles {
public:
    GpuTiles();
    ~GpuTiles();
    GpuTiles(const GpuTiles&) = delete;
    GpuTiles& operator=(const GpuTiles&) = delete;

    // New image size: all masks back to level 0 and no histogram.
    void resize(int width, int height);
    // Forget the history (masks to 0, histogram unknown).
    void reset();

    // Updates the masks from a real frame: `composite` is the method's full-resolution output,
    // `nearest` the pass-1 colour (alpha > 0 marks occupied pixels); `signal` says what D is
    // measured on. With `second` (the pass-2 colour at full resolution; 0 = none) it also
    // computes the scale guard's sums, read back with the histogram.
    void update(GLuint composite, GLuint nearest, TileSignal signal = TileSignal::Back, GLuint second = 0);
    // Takes the newest finished histogram readback, without waiting. True when one arrived.
    bool pollHistogram();
    bool hasHistogram() const { return hasHistogram_; }
    const std::array<uint32_t, 4>& histogram() const { return histogram_; }
    double wBar() const { return wBar_; }
    // The guard sums of the newest histogram readback whose update computed them.
    bool hasGuard() const { return hasGuard_; }
    const ScaleGuard& guard() const { return guard_; }
    // Guard measurements picked up so far (grows by one with each probe's readback; never reset).
    int guardReadings() const { return guardReadings_; }
    // Per-tile pass-3 shading rates (tile_constants.h, STARNT_SHADING_RATE_*): from now on every
    // update that computes the guard also writes the shading-rate image (R8UI, one texel per tile)
    // and counts the occupied tiles of each rate into the readback. Desktop GL (an r8ui image).
    void enableShadingRates();
    // The rate image of the newest guard update since the last reset; 0 before one.
    GLuint shadingRateImage() const { return ratesWritten_ ? rates_.id() : 0; }
    // Occupied tiles per rate of the newest guard readback (zeros before one).
    const std::array<uint32_t, STARNT_SHADING_RATE_CLASSES>& shadingRateTiles() const { return rateTiles_; }
    // Blocking readback of the rate image, row-major from the bottom-left tile (tests).
    std::vector<uint8_t> readShadingRates() const;
    // Number of updates run since the last reset (0: the masks are all level 0 from the start).
    int updates() const { return updates_; }

    // The current masks, bound to STARNT_SSBO_TILE_MASKS_IN (and the occupancy to its binding) for
    // the passes that read them (corner inference, overlay).
    void bindMasks() const;
    // Blocking readbacks for tests and debugging.
    std::vector<uint32_t> readMasks() const;
    // Writes the level overlay of the current masks over `composite` into `overlay` (RGBA32F).
    void renderOverlay(GLuint composite, GLuint overlay) const;

    int tilesX() const { return tilesX_; }
    int tilesY() const { return tilesY_; }
    size_t gpuMemoryBytes() const;
    // Appends (name, bytes) of every buffer.
    void addMemoryTargets(OitMethod::MemoryTargets& out) const;

private:
    struct Readback {
        gl::Buffer buffer;
        GLsync fence = nullptr;
        bool hasGuard = false;
    };
    void clearReadbacks();

    gl::Program evaluate_, balance_, histogramProgram_, overlay_, guardTiles_, guardTotal_, shadingRateProgram_;
    gl::Texture2D rates_;  // with enableShadingRates: one R8UI texel per tile
    bool ratesWritten_ = false;
    std::array<uint32_t, STARNT_SHADING_RATE_CLASSES> rateTiles_{};
    int width_ = 0, height_ = 0, tilesX_ = 0, tilesY_ = 0;
    gl::Buffer masks_[2], occupancy_, histogramBuffer_, guardTileSums_;
    int current_ = 0;  // masks_[current_] holds the latest masks
    std::array<Readback, 3> readbacks_;
    int nextReadback_ = 0;
    uint64_t submitted_ = 0;  // sequence numbers to pick the newest finished readback
    std::array<uint64_t, 3> readbackSequence_{};
    uint64_t consumedSequence_ = 0;
    bool hasHistogram_ = false;
    std::array<uint32_t, 4> histogram_{};
    double wBar_ = 0.0;
    bool hasGuard_ = false;
    ScaleGuard guard_;
    int updates_ = 0;
    int guardReadings_ = 0;
};

}  // namespace starnt::tiles
