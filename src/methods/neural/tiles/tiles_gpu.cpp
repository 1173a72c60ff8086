#include "methods/neural/tiles/tiles_gpu.hpp"

#include "methods/neural/tiles/tile_constants.h"
#include "methods/neural/tiles/tile_rules.hpp"
#include "starnt/bindings.h"

namespace starnt::tiles {
namespace {

GLuint groups(int n, int size) { return GLuint((n + size - 1) / size); }

// The readback: the four level counts (uint), the guard sums (float), then the occupied tiles per
// shading rate (uint; tile_shading_rate.comp.glsl).
constexpr size_t kGuardOffset = 4 * sizeof(uint32_t);
constexpr size_t kRateTilesOffset = kGuardOffset + STARNT_GUARD_VALUES * sizeof(float);
constexpr size_t kReadbackBytes = kRateTilesOffset + STARNT_SHADING_RATE_CLASSES * sizeof(uint32_t);

gl::Program compute(const char* label, const char* file) {
    return gl::buildComputeProgram(label, "#include \"" + std::string(file) + "\"\n");
}

}  // namespace

GpuTiles::GpuTiles()
    : evaluate_(compute("tile_evaluate", "methods/neural/tiles/tile_evaluate.comp.glsl")),
      balance_(compute("tile_balance", "methods/neural/tiles/tile_balance.comp.glsl")),
      histogramProgram_(compute("tile_histogram", "methods/neural/tiles/tile_histogram.comp.glsl")),
      overlay_(compute("tile_overlay", "methods/neural/tiles/tile_overlay.comp.glsl")),
      guardTiles_(compute("tile_scale_guard", "methods/neural/tiles/tile_scale_guard.comp.glsl")),
      guardTotal_(compute("tile_scale_guard_total", "methods/neural/tiles/tile_scale_guard_total.comp.glsl")) {
    for (auto& r : readbacks_) r.buffer = gl::Buffer(kReadbackBytes);
    histogramBuffer_ = gl::Buffer(kReadbackBytes);
}

GpuTiles::~GpuTiles() {
    if (gl::hasCurrentContext()) clearReadbacks();  // else the fences die with their context
}

void GpuTiles::clearReadbacks() {
    for (auto& r : readbacks_) {
        if (r.fence) glDeleteSync(r.fence);
        r.fence = nullptr;
    }
    readbackSequence_ = {};
}

void GpuTiles::resize(int width, int height) {
    if (width == width_ && height == height_) return;
    width_ = width;
    height_ = height;
    const TileGrid grid = TileGrid::forImage(width, height);
    tilesX_ = grid.tilesX;
    tilesY_ = grid.tilesY;
    const size_t bytes = size_t(grid.count()) * sizeof(uint32_t);
    for (auto& m : masks_) m = gl::Buffer(bytes);
    occupancy_ = gl::Buffer(bytes);
    guardTileSums_ = gl::Buffer(bytes * STARNT_GUARD_VALUES);
    if (shadingRateProgram_) rates_ = gl::Texture2D(GL_R8UI, tilesX_, tilesY_);
    reset();
}

void GpuTiles::reset() {
    const uint32_t zero = 0;
    // Before the first frame nothing is allocated yet, and there is nothing to clear.
    for (auto& m : masks_) {
        if (m) gl::fillBufferUint(m, zero);
    }
    if (occupancy_) gl::fillBufferUint(occupancy_, zero);
    clearReadbacks();
    hasHistogram_ = false;
    histogram_ = {};
    wBar_ = 0.0;
    hasGuard_ = false;
    guard_ = {};
    ratesWritten_ = false;
    rateTiles_ = {};
    updates_ = 0;
}

void GpuTiles::enableShadingRates() {
    if (shadingRateProgram_) return;
    shadingRateProgram_ = compute("tile_shading_rate", "methods/neural/tiles/tile_shading_rate.comp.glsl");
    if (tilesX_ > 0) rates_ = gl::Texture2D(GL_R8UI, tilesX_, tilesY_);
}

std::vector<uint8_t> GpuTiles::readShadingRates() const {
    std::vector<uint8_t> out(size_t(tilesX_) * size_t(tilesY_));
    if (!rates_ || out.empty()) return out;
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    const gl::PixelStoreDefaults pack(gl::PixelStoreDefaults::Pack, 1);
    glGetTextureImage(rates_.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, GLsizei(out.size()), out.data());
    return out;
}

void GpuTiles::update(GLuint composite, GLuint nearest, TileSignal signal, GLuint second) {
    const int other = 1 - current_;
    // Evaluate: current -> other. Balance twice: other -> current -> other. Result in `other`.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(evaluate_.id());
    gl::bindTexture(0, composite);
    gl::bindTexture(1, nearest);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, STARNT_SSBO_TILE_MASKS_IN, masks_[current_].id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, STARNT_SSBO_TILE_MASKS_OUT, masks_[other].id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, STARNT_SSBO_TILE_OCCUPANCY, occupancy_.id());
    glUniform2i(evaluate_.uniform("u_size"), width_, height_);
    glUniform2i(evaluate_.uniform("u_tiles"), tilesX_, tilesY_);
    glUniform1i(evaluate_.uniform("u_backSignal"), signal == TileSignal::Back ? 1 : 0);
    glDispatchCompute(groups(tilesX_, 8), groups(tilesY_, 8), 1);

    glUseProgram(balance_.id());
    glUniform2i(balance_.uniform("u_tiles"), tilesX_, tilesY_);
    int source = other;
    for (int k = 0; k < STARNT_TILE_BALANCE_ITERATIONS; ++k) {
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, STARNT_SSBO_TILE_MASKS_IN, masks_[source].id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, STARNT_SSBO_TILE_MASKS_OUT, masks_[1 - source].id());
        glDispatchCompute(groups(tilesX_, 8), groups(tilesY_, 8), 1);
        source = 1 - source;
    }
    current_ = source;

    const uint32_t zero = 0;
    gl::fillBufferUint(histogramBuffer_, zero);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(histogramProgram_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, STARNT_SSBO_TILE_MASKS_IN, masks_[current_].id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, STARNT_SSBO_TILE_HISTOGRAM, histogramBuffer_.id());
    glUniform1ui(histogramProgram_.uniform("u_tileCount"), GLuint(tilesX_ * tilesY_));
    glDispatchCompute(groups(tilesX_ * tilesY_, 64), 1, 1);

    if (second) {
        glUseProgram(guardTiles_.id());
        gl::bindTexture(0, composite);
        gl::bindTexture(1, nearest);
        gl::bindTexture(2, second);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, STARNT_SSBO_TILE_GUARD, guardTileSums_.id());
        glUniform2i(guardTiles_.uniform("u_size"), width_, height_);
        glUniform2i(guardTiles_.uniform("u_tiles"), tilesX_, tilesY_);
        glDispatchCompute(GLuint(tilesX_), GLuint(tilesY_), 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        glUseProgram(guardTotal_.id());
        glUniform1ui(guardTotal_.uniform("u_tileCount"), GLuint(tilesX_ * tilesY_));
        glDispatchCompute(1, 1, 1);
        if (shadingRateProgram_) {
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
            glUseProgram(shadingRateProgram_.id());
            glBindImageTexture(0, rates_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R8UI);
            glUniform2i(shadingRateProgram_.uniform("u_tiles"), tilesX_, tilesY_);
            glDispatchCompute(groups(tilesX_, 8), groups(tilesY_, 8), 1);
            // The rasteriser reads the image in the next frame's pass 3 (and tests read it back).
            glMemoryBarrier(GL_ALL_BARRIER_BITS);
            ratesWritten_ = true;
        }
    }

    // Copy into the next readback slot and fence it; pollHistogram picks it up once finished.
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    Readback& slot = readbacks_[size_t(nextReadback_)];
    if (slot.fence) glDeleteSync(slot.fence);  // the GPU is 3 frames behind: drop the oldest
    gl::copyBuffer(histogramBuffer_.id(), slot.buffer.id(), kReadbackBytes);
    slot.hasGuard = second != 0;
    slot.fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    readbackSequence_[size_t(nextReadback_)] = ++submitted_;
    nextReadback_ = (nextReadback_ + 1) % int(readbacks_.size());
    glFlush();  // submit the fence so polling can see it complete
    ++updates_;
}

bool GpuTiles::pollHistogram() {
    int newest = -1;
    for (int i = 0; i < int(readbacks_.size()); ++i) {
        Readback& r = readbacks_[size_t(i)];
        if (!r.fence) continue;
        const GLenum state = glClientWaitSync(r.fence, 0, 0);
        if (state != GL_ALREADY_SIGNALED && state != GL_CONDITION_SATISFIED) continue;
        if (newest < 0 || readbackSequence_[size_t(i)] > readbackSequence_[size_t(newest)]) newest = i;
    }
    if (newest < 0 || readbackSequence_[size_t(newest)] <= consumedSequence_) return false;
    Readback& r = readbacks_[size_t(newest)];
    uint32_t counts[4];
    float guard[STARNT_GUARD_VALUES];
    gl::readBuffer(r.buffer.id(), 0, sizeof counts, counts);
    if (r.hasGuard) {
        gl::readBuffer(r.buffer.id(), kGuardOffset, sizeof guard, guard);
        if (shadingRateProgram_) {
            gl::readBuffer(r.buffer.id(), kRateTilesOffset, GLsizeiptr(sizeof(uint32_t) * rateTiles_.size()), rateTiles_.data());
        }
        guard_.occupied = guard[STARNT_GUARD_OCCUPIED];
        guard_.energy2 = guard[STARNT_GUARD_ENERGY_PASS2];
        guard_.energy3 = guard[STARNT_GUARD_ENERGY_PASS3];
        guard_.loss2 = {guard[STARNT_GUARD_LOSS_PASS2_HALF], guard[STARNT_GUARD_LOSS_PASS2_QUARTER]};
        guard_.loss3 = {guard[STARNT_GUARD_LOSS_PASS3_HALF], guard[STARNT_GUARD_LOSS_PASS3_QUARTER]};
        hasGuard_ = true;
        ++guardReadings_;
    }
    // Older finished slots are superseded by this one.
    for (int i = 0; i < int(readbacks_.size()); ++i) {
        Readback& old = readbacks_[size_t(i)];
        if (old.fence && readbackSequence_[size_t(i)] <= readbackSequence_[size_t(newest)]) {
            glDeleteSync(old.fence);
            old.fence = nullptr;
        }
    }
    consumedSequence_ = readbackSequence_[size_t(newest)];
    for (int l = 0; l < 4; ++l) histogram_[size_t(l)] = counts[l];
    wBar_ = meanLevel(histogram_);
    hasHistogram_ = true;
    return true;
}

void GpuTiles::bindMasks() const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, STARNT_SSBO_TILE_MASKS_IN, masks_[current_].id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, STARNT_SSBO_TILE_OCCUPANCY, occupancy_.id());
}

std::vector<uint32_t> GpuTiles::readMasks() const {
    std::vector<uint32_t> out(size_t(tilesX_ * tilesY_));
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl::readBuffer(masks_[current_].id(), 0, GLsizeiptr(out.size() * sizeof(uint32_t)), out.data());
    return out;
}

void GpuTiles::renderOverlay(GLuint composite, GLuint overlay) const {
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(overlay_.id());
    gl::bindTexture(0, composite);
    glBindImageTexture(0, overlay, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    bindMasks();
    glUniform2i(overlay_.uniform("u_size"), width_, height_);
    glUniform2i(overlay_.uniform("u_tiles"), tilesX_, tilesY_);
    glDispatchCompute(groups(width_, 8), groups(height_, 8), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

void GpuTiles::addMemoryTargets(OitMethod::MemoryTargets& out) const {
    size_t readbacks = 0;
    for (const auto& r : readbacks_) readbacks += r.buffer.bytes();
    out.insert(out.end(), {{"tile_masks", masks_[0].bytes() + masks_[1].bytes()},
                           {"tile_occupancy", occupancy_.bytes()},
                           {"tile_histogram", histogramBuffer_.bytes()},
                           {"tile_guard_sums", guardTileSums_.bytes()},
                           {"tile_shading_rates", rates_.bytes()},
                           {"tile_readbacks", readbacks}});
}

size_t GpuTiles::gpuMemoryBytes() const {
    size_t bytes = masks_[0].bytes() + masks_[1].bytes() + occupancy_.bytes() + histogramBuffer_.bytes() +
                   guardTileSums_.bytes() + rates_.bytes();
    for (const auto& r : readbacks_) bytes += r.buffer.bytes();
    return bytes;
}

}  // namespace starnt::tiles
