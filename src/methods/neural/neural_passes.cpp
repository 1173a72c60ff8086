#include "methods/neural/neural_passes.hpp"

#include <bit>
#include <cstdio>

#include "gl/gpu_timer.hpp"

#include "methods/neural/temporal/packed_nearest.h"
#include "methods/neural/tiles/tile_constants.h"
#include "starnt/error.hpp"
#include "starnt/network.hpp"

namespace starnt {
namespace {

std::string floatLiteral(float v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9e", double(v));
    return buf;
}

// Restricts clears and rasterisation to the lower-left rectangle a pass renders into.
void useRectangle(Size2 size) {
    glViewport(0, 0, size.width, size.height);
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, size.width, size.height);
}

// The same for a geometry pass at a reduced size: the viewport moves by a fraction of a reduced
// pixel so that its samples fall on full-resolution pixel centres (upsample_cpu.hpp). GL keeps
// viewport origins as floats; GL_VIEWPORT_SUBPIXEL_BITS may round them (llvmpipe reports 0 bits
// but applies them exactly, GlTiles.ReducedPassesSampleFullPixelCentres checks it; NVIDIA keeps 8).
void useReducedRectangle(Size2 size, Size2 full) {
    useRectangle(size);
    gl::setViewportF(reducedViewportOffset(size.width, full.width), reducedViewportOffset(size.height, full.height),
                     float(size.width), float(size.height));
}

}  // namespace

std::string neuralEpsilonDefines() {
    return "#define STARNT_EPS_TRANSMITTANCE " + floatLiteral(nn::kTransmittanceEpsilon) + "\n#define STARNT_EPS_TAIL_ALPHA " +
           floatLiteral(nn::kTailAlphaEpsilon) + "\n";
}

gl::Program buildTailResolveProgram(const std::string& defines) {
    return gl::buildProgram("tail_resolve", gl::embeddedSource("methods/common/fullscreen.vert.glsl"),
                            gl::embeddedSource("methods/neural/tail_resolve.frag.glsl"), defines + neuralEpsilonDefines());
}

void resolveTails(const TailResolveInputs& in, GLuint pass3Framebuffer, const gl::VertexArrayHandle& emptyVao,
                  TailResolveCopies& esCopies) {
    GLuint sums[3] = {in.alphaColor, in.colorCount, in.transmittance};
    if (gl::isEs()) {
        // No glTextureBarrier on ES: read copies of the pass-3 rectangle (24 or 36 bytes per reduced
        // pass-3 texel) instead of the targets this draw writes.
        gl::Texture2D* copies[3] = {&esCopies.alphaColor, &esCopies.colorCount, &esCopies.transmittance};
        for (int i = 0; i < 3; ++i) {
            gl::Texture2D& copy = *copies[i];
            const GLenum format = gl::textureInternalFormat(sums[i]);  // the count may be R32F (count only)
            if (copy.width() != in.pass3.width || copy.height() != in.pass3.height || copy.format() != format) {
                copy = gl::Texture2D(format, in.pass3.width, in.pass3.height);
            }
            glCopyImageSubData(sums[i], GL_TEXTURE_2D, 0, 0, 0, 0, copy.id(), GL_TEXTURE_2D, 0, 0, 0, 0, in.pass3.width,
                               in.pass3.height, 1);
            sums[i] = copy.id();
        }
    } else {
        glTextureBarrier();  // pass 3's blended writes become visible to this draw's fetches
    }
    glUseProgram(in.program->id());
    const GLuint textures[] = {in.nearest, in.second, sums[0], sums[1], sums[2]};
    for (GLuint unit = 0; unit < 5; ++unit) gl::bindTexture(unit, textures[unit]);
    glUniform2i(in.program->uniform("u_fullSize"), in.full.width, in.full.height);
    glUniform2i(in.program->uniform("u_pass2Size"), in.pass2.width, in.pass2.height);
    glUniform2i(in.program->uniform("u_pass3Size"), in.pass3.width, in.pass3.height);
    glBindFramebuffer(GL_FRAMEBUFFER, pass3Framebuffer);
    resetPassState();
    useRectangle(in.pass3);
    gl::drawFullscreenTriangle(emptyVao);
    resetPassState();
}

namespace {

// Narrow layers exist only in the compact layout.
bool narrowLayersUsed(NeuralOptions::Targets targets, bool narrowLayers) {
    return narrowLayers && targets == NeuralOptions::Targets::Compact;
}

// The define of pass 3 with the tail moments, after checking that the context has the 5 colour
// targets it writes (ES 3.2 guarantees 4): a clear error rather than a shader that fails to link.
std::string tailMomentsDefine(bool tailMoments) {
    if (!tailMoments) return "";
    GLint drawBuffers = 0;
    glGetIntegerv(GL_MAX_DRAW_BUFFERS, &drawBuffers);
    if (drawBuffers < 5) {
        throw Error("the tail moments need 5 colour targets in pass 3; this GL context allows " +
                    std::to_string(drawBuffers) + " (GL_MAX_DRAW_BUFFERS)");
    }
    return "#define STARNT_TAIL_MOMENTS\n";
}

// The defines of passes 1 and 2, which write the layers.
std::string layerPassDefines(NeuralOptions::Targets targets, bool narrowLayers) {
    return std::string(NeuralPasses::targetsDefine(targets)) +
           NeuralPasses::layerDefine(narrowLayersUsed(targets, narrowLayers));
}

}  // namespace

NeuralPasses::NeuralPasses(const SurfaceShader& surface, OpaqueScene& opaque, bool colorSums, NeuralOptions::Targets targets,
                           bool narrowLayers, bool tailMoments)
    : opaque_(opaque),
      pass1_(surface, "neural_pass1", "methods/neural/pass1_nearest.frag.glsl", layerPassDefines(targets, narrowLayers)),
      pass2_(surface, "neural_pass2", "methods/neural/pass2_second.frag.glsl", layerPassDefines(targets, narrowLayers)),
      pass3_(surface, "neural_pass3", "methods/neural/pass3_accumulate.frag.glsl",
             std::string(colorSums ? "" : "#define STARNT_COUNT_ONLY\n") + tailMomentsDefine(tailMoments)),
      tailResolve_(buildTailResolveProgram(std::string(colorSums ? "" : "#define STARNT_COUNT_ONLY\n") + targetsDefine(targets))),
      emptyVao_(gl::makeEmptyVertexArray()),
      colorSums_(colorSums),
      targets_(targets),
      narrowLayers_(narrowLayersUsed(targets, narrowLayers)),
      tailMoments_(tailMoments),
      surface_(surface) {
    GLint drawBuffers = 0;
    glGetIntegerv(GL_MAX_DRAW_BUFFERS, &drawBuffers);
    behindMomentsFit_ = drawBuffers >= 6;  // a real frame's pass 3 with the moments behind (runSums)
}

// The compact layout's transmittance, prod (1 - a) blended over up to hundreds of fragments. In a
// 16-bit float target every blended multiply loses up to a step of 2^-11 relative, and llvmpipe
// truncates, so the product drifts low: on the smoke suite scene (56 layers of alpha 0.012-0.03,
// 320x180) hybrid's MSE went from 2.4e-9 with 32-bit targets to 8.2e-8, above WBOIT's 1.4e-8. 16-bit
// unsigned normalised steps are 1/65535 apart, finer than the float's wherever T > 1/32, for the
// same 2 bytes: 3.4e-9 there. ES 3.2 has GL_R16 only with EXT_texture_norm16 (llvmpipe has it);
// without it the target stays 16-bit float.
GLenum NeuralPasses::compactTransmittanceFormat() {
    return !gl::isEs() || epoxy_has_gl_extension("GL_EXT_texture_norm16") ? GL_R16 : GL_R16F;
}

GLenum NeuralPasses::outputFormat() const {
    return targets_ == NeuralOptions::Targets::Compact ? GL_RGBA16F : GL_RGBA32F;
}

NeuralPasses::OutputSlot NeuralPasses::outputSlot(bool nearestFree) const {
    const Size2 full{width_, height_};
    if (gl::isEs()) return {};
    if (pass3Size_ == full) return {alphaColor_.id(), alphaColorOnlyFb_.id(), "pass3_alpha_color"};
    if (narrowLayers_) return {};  // the layer colours are unsigned normalised: no place for an output
    if (pass2Size_ == full) return {second_.id(), secondOnlyFb_.id(), "pass2_color"};
    if (nearestFree) return {nearest_.id(), nearestOnlyFb_.id(), "pass1_color"};
    return {};
}

GLenum NeuralPasses::sumsFormat(int channels) const {
    const bool half = packedOnly_ && targets_ == NeuralOptions::Targets::Compact;
    return channels == 4 ? (half ? GL_RGBA16F : GL_RGBA32F) : (half ? GL_RG16F : GL_RG32F);
}

void NeuralPasses::resize(int width, int height) {
    if (width == width_ && height == height_) return;
    width_ = width;
    height_ = height;
    forgetTargets();  // new textures
    const bool compact = targets_ == NeuralOptions::Targets::Compact;
    const GLenum color = compact ? GL_RGBA16F : GL_RGBA32F, single = compact ? GL_R16F : GL_R32F;
    const GLenum layer = narrowLayers_ ? GL_RGB10_A2 : color;
    nearestDepth_ = gl::Texture2D(GL_DEPTH_COMPONENT32F, width, height);
    if (!packedOnly_) {
        nearest_ = gl::Texture2D(layer, width, height);
        second_ = gl::Texture2D(layer, width, height);
        secondDepth_ = gl::Texture2D(narrowLayers_ ? GL_DEPTH_COMPONENT16 : GL_DEPTH_COMPONENT32F, width, height);
    }
    if (narrowLayers_) layerAlpha_ = gl::Texture2D(GL_RG16F, width, height);
    // The tail moments are centred with sum a C at read time, which a 16-bit sum would spoil
    // (measured on chess 320x180: MSE 2.9e-6 against 1.2e-6 with 32-bit sums), and weighted by the
    // tail's optical depth -ln t_tail, which a 16-bit transmittance clamps beyond about 11. Behind
    // the three exact layers of kbuffer-moments (packedOnly_) the sums weigh little: there compact
    // targets keep them in 16-bit floats (docs/DESIGN.md, "kbuffer-moments").
    alphaColor_ = gl::Texture2D(tailMoments_ ? sumsFormat(4) : color, width, height, GL_LINEAR);
    colorCount_ = gl::Texture2D(colorSums_ ? color : countBesideBehind_ ? sumsFormat(2) : single, width, height, GL_LINEAR);
    alphaColorOnlyFb_ = gl::makeFramebuffer({&alphaColor_});
    packedFb_.reset();  // runPackedNearestAndSums makes it again around the new targets
    if (tailMoments_) tailMoment1_ = gl::Texture2D(sumsFormat(4), width, height);
    if (packedOnly_) {
        makeSumsFramebuffer();
        return;
    }
    transmittance_ = gl::Texture2D(compact && !tailMoments_ ? compactTransmittanceFormat() : GL_R32F, width, height, GL_LINEAR);
    if (narrowLayers_) {
        pass1Fb_ = gl::makeFramebuffer({&nearest_, &layerAlpha_}, &nearestDepth_);
        pass2Fb_ = gl::makeFramebuffer({&second_, &layerAlpha_}, &secondDepth_);
    } else {
        pass1Fb_ = gl::makeFramebuffer({&nearest_}, &nearestDepth_);
        pass2Fb_ = gl::makeFramebuffer({&second_}, &secondDepth_);
    }
    if (tailMoments_) tailMoment2_ = gl::Texture2D(GL_RGBA32F, width, height);
    makePass3Framebuffer();
    makeSumsFramebuffer();
    pass3BehindFb_.reset();
    pass3TailFb_.reset();
    nearestOnlyFb_ = gl::makeFramebuffer({&nearest_});
    secondOnlyFb_ = gl::makeFramebuffer({&second_});
}

void NeuralPasses::makeSumsFramebuffer() {
    // Corrected frames' sums: the tail-moment methods sum a u^2 and the optical depth into the
    // count's target once it is two channels wide (widenCountBesideBehind), the moments into their
    // first moment target, both free in an interpolated frame (pass3_accumulate.frag.glsl).
    sumsFb_ = tailMoments_ ? gl::makeFramebuffer({&alphaColor_, &colorCount_, &tailMoment1_})
                           : gl::makeFramebuffer({&alphaColor_, &transmittance_});
}

void NeuralPasses::widenCountBesideBehind() {
    if (countBesideBehind_) return;
    // RG32F from now on: beside the count, sum a v^2 in a real frame and, in an interpolated frame,
    // sum a v^2 and the optical depth; 32-bit, as the spread the closed form takes from the moments
    // (m2 / a - mean^2) needs it.
    countBesideBehind_ = true;
    colorCount_ = gl::Texture2D(sumsFormat(2), width_, height_, GL_LINEAR);
    forgetTargets();  // a new texture
    if (!packedOnly_) makePass3Framebuffer();
    makeSumsFramebuffer();
    packedFb_.reset();
    pass3BehindFb_.reset();
    pass3TailFb_.reset();
}

void NeuralPasses::makePass3Framebuffer() {
    pass3Fb_ = tailMoments_ ? gl::makeFramebuffer({&alphaColor_, &colorCount_, &transmittance_, &tailMoment1_, &tailMoment2_})
                            : gl::makeFramebuffer({&alphaColor_, &colorCount_, &transmittance_});
}

void NeuralPasses::addMemoryTargets(OitMethod::MemoryTargets& out) const {
    out.insert(out.end(), {{"pass1_color", nearest_.bytes()},
                           {"pass1_depth", nearestDepth_.bytes()},
                           {"pass2_color", second_.bytes()},
                           {"pass2_depth", secondDepth_.bytes()},
                           {"pass3_alpha_color", alphaColor_.bytes()},
                           {colorSums_ ? "pass3_color_count" : "pass3_count", colorCount_.bytes()},
                           {"pass3_transmittance", transmittance_.bytes()},
                           {"layer_alphas", layerAlpha_.bytes()},
                           {"pass3_tail_moments", tailMoment1_.bytes() + tailMoment2_.bytes()},
                           {"corrected_packed_nearest", packedNearest_.bytes()},
                           {"corrected_packed_layers", packedLayers_.bytes()},
                           {"corrected_third_layer", thirdLayer_.bytes()},
                           {"pass3_resolve_copies_es", esResolveCopies_.bytes()},
                           {"clear_strips", clears_.bytes()}});
}

size_t NeuralPasses::gpuMemoryBytes() const {
    return nearest_.bytes() + nearestDepth_.bytes() + second_.bytes() + secondDepth_.bytes() +
           alphaColor_.bytes() + colorCount_.bytes() + transmittance_.bytes() + layerAlpha_.bytes() +
           tailMoment1_.bytes() + tailMoment2_.bytes() + packedNearest_.bytes() + packedLayers_.bytes() + thirdLayer_.bytes() + esResolveCopies_.bytes() + clears_.bytes();
}

void NeuralPasses::runNearest(const FrameDesc& frame, const DrawCallback& draw) {
    resize(frame.width, frame.height);
    const float zero[4] = {0, 0, 0, 0};
    resetPassState();
    gl::ScopedPass timing(frame.timing, "pass1");
    useRectangle({width_, height_});
    glBindFramebuffer(GL_FRAMEBUFFER, pass1Fb_.id());
    clears_.color(0, zero);
    const float farDepth = 1.0f;
    glClearBufferfv(GL_DEPTH, 0, &farDepth);
    if (narrowLayers_) {
        clears_.color(1, zero);                                    // both alphas (before the mask)
        glColorMaski(1, GL_TRUE, GL_FALSE, GL_FALSE, GL_FALSE);  // pass 1 writes a1 alone
    }
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    const gl::Program& pass1 = opaque_.clipInShader(pass1_, width_, height_, width_, height_);
    MethodBase::runGeometryPass("pass1", pass1, frame, draw);
    resetPassState();
}

void NeuralPasses::run(const FrameDesc& frame, const DrawCallback& draw, float peelEpsilon, Size2 pass2Size,
                       Size2 pass3Size, const std::function<GLuint()>& behindReference) {
    // Pass 1 rewrites the depth that marked the last interpolated pass 3's pixels, and this frame
    // makes a new reference depth (referenceStale_); pass 3 writes sharedSumTargets() (runSums).
    coverMarked_ = false;
    referenceStale_ = true;
    runNearest(frame, draw);
    const Size2 full{width_, height_};
    pass2Size_ = pass2Size;
    pass3Size_ = pass3Size;
    const float zero[4] = {0, 0, 0, 0};
    const bool reduced2 = !(pass2Size == full);
    {
        gl::ScopedPass timing(frame.timing, "pass2");
        useReducedRectangle(pass2Size, full);
        glBindFramebuffer(GL_FRAMEBUFFER, pass2Fb_.id());
        clears_.color(0, zero);
        const float farDepth = 1.0f;
        glClearBufferfv(GL_DEPTH, 0, &farDepth);
        if (narrowLayers_) glColorMaski(1, GL_FALSE, GL_TRUE, GL_FALSE, GL_FALSE);  // a2 beside pass 1's a1
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        if (reduced2 && !pass2Reduced_.id()) {
            pass2Reduced_ = SurfaceProgram(surface_, "neural_pass2_reduced", "methods/neural/pass2_second.frag.glsl",
                                           layerPassDefines(targets_, narrowLayers_) + "#define STARNT_REDUCED_PEEL\n");
        }
        const gl::Program& pass2 =
            opaque_.clipInShader(reduced2 ? pass2Reduced_ : pass2_, pass2Size.width, pass2Size.height, full.width, full.height);
        glUniform1f(pass2.uniform("u_peelEpsilon"), peelEpsilon);
        glUniform2i(pass2.uniform("u_fullSize"), full.width, full.height);
        glUniform2i(pass2.uniform("u_reducedSize"), pass2Size.width, pass2Size.height);
        gl::bindTexture(0, nearestDepth_.id());
        MethodBase::runGeometryPass("pass2", pass2, frame, draw);
        resetPassState();
    }
    runSums(frame, draw, pass3Size, behindReference && tailMoments_ && pass3Size == full ? behindReference() : 0);
    if (reduced2 || !(pass3Size == full)) {
        gl::ScopedPass timing(frame.timing, "tail_resolve");
        resolveTails({&tailResolve_, nearest_.id(), second_.id(), alphaColor_.id(), colorCount_.id(), transmittance_.id(),
                      full, pass2Size, pass3Size},
                     pass3Fb_.id(), emptyVao_, esResolveCopies_);
    }
    glViewport(0, 0, width_, height_);
}

void NeuralPasses::prepareRealBehindMoments() {
    if (!pass3Behind_.id()) {
        pass3Behind_ = SurfaceProgram(surface_, "neural_pass3_behind", "methods/neural/pass3_accumulate.frag.glsl",
                                           std::string(colorSums_ ? "" : "#define STARNT_COUNT_ONLY\n") +
                                               tailMomentsDefine(tailMoments_) + behindMomentsDefine() +
                                               (twoLayers_ ? "#define STARNT_BEHIND_SECOND\n" : ""));
    }
}

void NeuralPasses::allocatePackedNearest() {
    if (packedNearest_.width() != width_ || packedNearest_.height() != height_) {
        packedNearest_ = gl::Texture2D(GL_RGBA32F, width_, height_);
        packedFb_.reset();
        pass3BehindFb_.reset();
    }
}

void NeuralPasses::runSums(const FrameDesc& frame, const DrawCallback& draw, Size2 pass3Size, GLuint behindReference) {
    const Size2 full{width_, height_};
    const float zero[4] = {0, 0, 0, 0}, one[4] = {1, 1, 1, 1};
    gl::ScopedPass timing(frame.timing, "pass3");
    useReducedRectangle(pass3Size, full);
    behindSummed_ = behindReference != 0 && behindMomentsFit_;
    behindReference_ = behindSummed_ ? behindReference : 0;
    GLuint framebuffer = pass3Fb_.id();
    SurfaceProgram* program = &pass3_;
    // Targets 0, 1 and 3 are sharedSumTargets(): zero everywhere after a clearing composite.
    const bool sumsClear = sumsClear_ && compositeClears_ && pass3Size == full;
    sumsClear_ = false;  // (and the output may go into one)
    if (behindSummed_) {
        prepareRealBehindMoments();
        allocatePackedNearest();
        widenCountBesideBehind();  // sum a v^2 beside the count (pass3_accumulate.frag.glsl)
        if (!pass3BehindFb_.id()) {
            pass3BehindFb_ =
                gl::makeFramebuffer({&alphaColor_, &colorCount_, &transmittance_, &tailMoment1_, &tailMoment2_, &packedNearest_});
        }
        framebuffer = pass3BehindFb_.id();
        program = &pass3Behind_;
    }
    // With per-tile shading rates, pass 3 sums only the fragments behind pass 2's layer, by a depth
    // test per pixel against its depth: a coarse fragment's colour must not stand in for the exact
    // layers 1 and 2, which the inference adds back (the reduced passes' "targets hold tails").
    pass3HoldsTails_ = (pass3Rates_ != 0 || pass3TailsOnly_) && pass3Size == full && !tailMoments_ && !behindSummed_;
    if (pass3HoldsTails_) {
        if (!pass3TailFb_.id()) pass3TailFb_ = gl::makeFramebuffer({&alphaColor_, &colorCount_, &transmittance_}, &secondDepth_);
        framebuffer = pass3TailFb_.id();
    }
    const gl::Program* drawn = &program->plain();  // the variant that clips in its shader where it does
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    if (!sumsClear) {
        clears_.color(0, zero);
        clears_.color(1, zero);
    }
    clears_.color(2, one);
    if (pass3HoldsTails_) {
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_GREATER);  // behind the second layer, which pass 2's depth holds (1 where none)
        glDepthMask(GL_FALSE);
        drawn = &opaque_.clipInShader(*program, full.width, full.height, full.width, full.height);
    } else {
        opaque_.beginDepthTest(framebuffer, pass3Size.width, pass3Size.height, full.width, full.height);
    }
    glEnable(GL_BLEND);
    // Per-target blend functions: core in GL 4.0 and GLES 3.2 (EXT_draw_buffers_indexed on 3.1).
    glBlendFunci(0, GL_ONE, GL_ONE);
    glBlendFunci(1, GL_ONE, GL_ONE);
    glBlendFunci(2, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
    if (tailMoments_) {
        if (!sumsClear) clears_.color(3, zero);
        clears_.color(4, zero);
        glBlendFunci(3, GL_ONE, GL_ONE);
        glBlendFunci(4, GL_ONE, GL_ONE);
        gl::bindTexture(0, secondDepth_.id());  // z2 (tail moments run at full resolution only)
    }
    if (behindSummed_) beginBehindMoment(5, behindReference);
    // docs/DESIGN.md, "Per-tile shading rates on GPUs": the palette of viewport 0 maps the tile
    // classes; the rates are off again (image unbound) after the pass, also when the draw throws.
    struct ShadingRates {
        bool on;
        explicit ShadingRates(GLuint image) : on(image != 0) {
            if (!on) return;
            const GLenum palette[STARNT_SHADING_RATE_CLASSES] = {GL_SHADING_RATE_1_INVOCATION_PER_PIXEL_NV,
                                                                GL_SHADING_RATE_1_INVOCATION_PER_2X2_PIXELS_NV,
                                                                GL_SHADING_RATE_1_INVOCATION_PER_4X4_PIXELS_NV};
            glBindShadingRateImageNV(image);
            glShadingRateImagePaletteNV(0, 0, STARNT_SHADING_RATE_CLASSES, palette);
            glEnable(GL_SHADING_RATE_IMAGE_NV);
        }
        ~ShadingRates() {
            if (!on) return;
            glDisable(GL_SHADING_RATE_IMAGE_NV);
            glBindShadingRateImageNV(0);
        }
    } rates(pass3Size == full ? pass3Rates_ : 0);
    MethodBase::runGeometryPass("pass3", *drawn, frame, draw);
    if (!pass3HoldsTails_) opaque_.endDepthTest(framebuffer);
    resetPassState();
}

void NeuralPasses::prepareNearestAndSums() {
    if (!pass3Sums_.id()) {
        pass3Sums_ = buildSurfaceProgram(surface_, "neural_pass3_sums", "methods/neural/pass3_accumulate.frag.glsl",
                                         std::string("#define STARNT_SUMS_ONLY\n") + behindMomentsDefine());
    }
}

void NeuralPasses::runNearestAndSums(const FrameDesc& frame, const DrawCallback& draw, GLuint reference) {
    forgetTargets();  // its pass 3 writes three of them, its pass 1 the depth
    runNearest(frame, draw);
    prepareNearestAndSums();
    if (tailMoments_) widenCountBesideBehind();
    pass3Size_ = {width_, height_};
    gl::ScopedPass timing(frame.timing, "pass3");
    beginSumAndProduct(sumsFb_.id(), width_, height_, opaque_, GL_ONE_MINUS_SRC_ALPHA, clears_);  // sum a C, sum a; prod (1 - a)
    if (tailMoments_) {
        beginSecondMomentAndOpticalDepth(1);
        beginBehindMoment(2, reference);
    }
    MethodBase::runGeometryPass("pass3", pass3Sums_, frame, draw);
    opaque_.endDepthTest(sumsFb_.id());
    resetPassState();
}

void NeuralPasses::findThreeLayers(bool compositeClears) {
    twoLayers_ = threeLayers_ = tailMoments_;
    // Only where a clear costs what writing every texel does (a software rasteriser) and where the
    // composite may write the textures it reads: the GL 4.5 exception for a texel read and written
    // by the same fragment invocation (section 9.3.1), which OpenGL ES does not make.
    compositeClears_ = threeLayers_ && compositeClears && !gl::isEs() && gl::currentContextIsSoftware();
}

std::array<GLuint, 5> NeuralPasses::packedTargets() const {
    return {packedLayers_.id(), thirdLayer_.id(), alphaColor_.id(), tailMoment1_.id(), colorCount_.id()};
}

void NeuralPasses::targetsClearedByComposite() {
    if (!compositeClears_) throw Error("internal: the composite cleared the targets of a pass that clears them itself");
    sumsClear_ = layersClear_ = true;
}

void NeuralPasses::sharedSumsClearedByInference() {
    if (!compositeClears_) throw Error("internal: the inference cleared the targets of a pass that clears them itself");
    sumsClear_ = true;
}

void NeuralPasses::preparePackedNearestAndSums() {
    if (!pass3Packed_.id()) {
        pass3Packed_ = SurfaceProgram(surface_, "neural_pass3_packed", "methods/neural/pass3_accumulate.frag.glsl",
                                           std::string("#define STARNT_SUMS_ONLY\n#define STARNT_PACKED_NEAREST\n") +
                                               behindMomentsDefine() +
                                               (threeLayers_ ? "#define STARNT_PACKED_THREE_LAYERS\n" : "") +
                                               (twoLayers_ ? "#extension GL_EXT_shader_framebuffer_fetch : require\n"
                                                             "#define STARNT_PACKED_TWO_LAYERS\n"
                                                           : ""));
    }
    // The count's target two channels wide from the first frame (its .r, the count, is the same
    // either way): a real frame's composite that writes it back (sharedSumTargets) would otherwise
    // meet a new format at the first real frame after an interpolated one, and the rasteriser
    // compile a new variant of it in that frame (260 ms on llvmpipe).
    if (tailMoments_) {
        if (width_ > 0) widenCountBesideBehind();
        else countBesideBehind_ = true;
    }
}

void NeuralPasses::beginBehindMoment(GLuint target, GLuint reference, bool clear) {
    const float zero[4] = {0, 0, 0, 0};
    if (clear) clears_.color(GLint(target), zero);
    glBlendFunci(target, GL_ONE, GL_ONE);
    gl::bindTexture(1, reference);  // pass3_accumulate.frag.glsl's u_reference
}

void NeuralPasses::beginSecondMomentAndOpticalDepth(GLuint target, bool clear) {
    const float zero[4] = {0, 0, 0, 0};
    if (clear) clears_.color(GLint(target), zero);
    glBlendFunci(target, GL_ONE, GL_ONE);  // sum a u^2; sum -ln(1 - a)
}

void NeuralPasses::runPackedNearestAndSums(const FrameDesc& frame, const DrawCallback& draw, GLuint reference) {
    resize(frame.width, frame.height);
    preparePackedNearestAndSums();
    gl::Texture2D& packed = twoLayers_ ? packedLayers_ : packedNearest_;
    if (packed.width() != width_ || packed.height() != height_) {
        // The two layers: an integer target of their own (the real frames keep their moments behind
        // the reference in packedNearest_, a float one).
        if (twoLayers_) packedLayers_ = gl::Texture2D(GL_RGBA32UI, width_, height_);
        if (threeLayers_) thirdLayer_ = gl::Texture2D(GL_RGBA32UI, width_, height_);
        else allocatePackedNearest();
        packedFb_.reset();
        thirdLayerClearFb_.reset();
        thirdLayerClearMarkedFb_.reset();
        forgetTargets();  // new textures
    }
    if (tailMoments_) widenCountBesideBehind();
    if (!packedFb_.id()) {
        // Pass 1's depth target, free in an interpolated frame, records which pixels any fragment
        // covered (depth test ALWAYS: the last fragment's depth, < 1 where anything is) for the
        // composite's early empty-pixel test; so the opaque clip runs in the shader, as in pass 1.
        // The tail-moment methods sum their moments behind the nearest layer into their first
        // moment target and the count's, free in an interpolated frame (makeSumsFramebuffer).
        // The third layer, where found, is target 4 (pass3_accumulate.frag.glsl).
        packedFb_ = threeLayers_   ? gl::makeFramebuffer({&alphaColor_, &colorCount_, &packed, &tailMoment1_, &thirdLayer_}, &nearestDepth_)
                    : tailMoments_ ? gl::makeFramebuffer({&alphaColor_, &colorCount_, &packed, &tailMoment1_}, &nearestDepth_)
                                 : gl::makeFramebuffer({&alphaColor_, &transmittance_, &packedNearest_}, &nearestDepth_);
    }
    pass3Size_ = {width_, height_};
    resetPassState();
    gl::ScopedPass timing(frame.timing, "pass3");
    // The last interpolated frame's composite wrote back the clear values wherever this pass wrote
    // (compositeClearsTargets()), and a real frame since wrote none of the layers' and, where its
    // inference wrote 0 back, none of the sums' (sharedSumsClearedByInference()). A real frame's
    // new reference depth goes beside the third layer at every pixel.
    const bool clearSums = !compositeClears_ || !sumsClear_;
    const bool clearLayers = !compositeClears_ || !layersClear_;
    const bool marked = coverMarked_;
    if (threeLayers_ && (clearLayers || referenceStale_)) clearThirdLayer(reference, clearLayers && marked);
    sumsClear_ = layersClear_ = referenceStale_ = false;
    glBindFramebuffer(GL_FRAMEBUFFER, packedFb_.id());
    glViewport(0, 0, width_, height_);
    const float zero[4] = {0, 0, 0, 0}, one[4] = {1, 1, 1, 1}, farDepth = 1.0f;
    if (clearSums) clears_.color(0, zero);
    if (clearSums && !tailMoments_) clears_.color(1, one);  // the tail-moment methods' target 1 is cleared below
    glClearBufferfv(GL_DEPTH, 0, &farDepth);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glEnable(GL_BLEND);
    glBlendFunci(0, GL_ONE, GL_ONE);                   // sum a C, sum a
    glBlendFunci(1, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);  // prod (1 - a)
    if (twoLayers_) {
        // Read and rewritten by every fragment (framebuffer fetch); an integer target blends nothing.
        const GLuint empty[4] = {STARNT_PACKED_LAYER_EMPTY, 0u, STARNT_PACKED_LAYER_EMPTY, 0u};
        if (clearLayers) clears_.colorUint(2, empty);  // (the third layer's: clearThirdLayer)
    } else {
        const float emptyPixel = std::bit_cast<float>(STARNT_PACKED_EMPTY_BITS);
        const float empty[4] = {emptyPixel, emptyPixel, emptyPixel, emptyPixel};
        clears_.color(2, empty);
        glBlendEquationi(2, GL_MIN);  // blend factors do not apply to MIN
    }
    if (tailMoments_) {
        beginSecondMomentAndOpticalDepth(1, clearSums);
        beginBehindMoment(3, reference, clearSums);
    }
    const gl::Program& pass3 = opaque_.clipInShader(pass3Packed_, width_, height_, width_, height_);
    MethodBase::runGeometryPass("pass3", pass3, frame, draw);
    resetPassState();
    coverMarked_ = threeLayers_;
}

void NeuralPasses::clearThirdLayer(GLuint reference, bool onlyMarked) {
    if (!thirdLayerClear_.id()) {
        thirdLayerClear_ = gl::buildProgram("third_layer_clear", gl::embeddedSource("methods/common/fullscreen.vert.glsl"),
                                            gl::embeddedSource("methods/neural/temporal/third_layer_clear.frag.glsl"));
    }
    // Where the last interpolated pass 3 marked the pixels it wrote (coverMarked_), only those hold
    // anything but the clear value: the others keep their reference depth, as the composite that
    // clears the targets leaves them, so both ways give the same frames bit for bit. The marks are
    // the depth target's, tested against the far-plane triangle (GREATER: below 1 where written).
    gl::FramebufferHandle& framebuffer = onlyMarked ? thirdLayerClearMarkedFb_ : thirdLayerClearFb_;
    if (!framebuffer.id()) framebuffer = gl::makeFramebuffer({&thirdLayer_}, onlyMarked ? &nearestDepth_ : nullptr);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
    glViewport(0, 0, width_, height_);
    if (onlyMarked) {
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_GREATER);
        glDepthMask(GL_FALSE);
    } else {
        glDisable(GL_DEPTH_TEST);
    }
    glDisable(GL_BLEND);
    // The triangle at window depth 1 whatever the depth convention: the passes of a reversed
    // projection run with the depth range (1, 0) (resetPassState), which would put it at 0, where
    // GREATER fails at every pixel (as EmptyPixelSkip::bindCovered).
    glDepthRangef(1.0f, 1.0f);
    glUseProgram(thirdLayerClear_.id());
    gl::bindTexture(1, reference);  // third_layer_clear.frag.glsl's u_reference
    gl::drawFullscreenTriangle(emptyVao_);
    resetPassState();  // the convention's depth range back; the depth mask on for the depth clear that follows
}

void NeuralPasses::bindInputs(const gl::Program& program) const {
    gl::bindTexture(kUnitNearest, nearest_.id());
    gl::bindTexture(kUnitSecond, second_.id());
    gl::bindTexture(kUnitAlphaColor, alphaColor_.id());
    gl::bindTexture(kUnitColorCount, colorCount_.id());
    gl::bindTexture(kUnitTransmittance, transmittance_.id());
    gl::bindTexture(kUnitNearestDepth, nearestDepth_.id());
    if (narrowLayers_) gl::bindTexture(STARNT_UNIT_LAYER_ALPHA, layerAlpha_.id());
    if (tailMoments_) {
        gl::bindTexture(STARNT_UNIT_TAIL_MOMENT1, tailMoment1_.id());
        gl::bindTexture(STARNT_UNIT_TAIL_MOMENT2, tailMoment2_.id());
    }
    glUniform2i(program.uniform("u_fullSize"), width_, height_);
    glUniform2i(program.uniform("u_pass2Size"), pass2Size_.width, pass2Size_.height);
    glUniform2i(program.uniform("u_pass3Size"), pass3Size_.width, pass3Size_.height);
}

}  // namespace starnt
