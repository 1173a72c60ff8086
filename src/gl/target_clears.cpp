#include "gl/target_clears.hpp"

#include <algorithm>
#include <bit>

#include "gl/gpu_timer.hpp"

namespace starnt::gl {

TargetClears::TargetClears(Path path, int stripWidth, int stripRows)
    : path_(path), stripWidth_(std::max(stripWidth, 1)), stripRows_(std::max(stripRows, 1)) {}

bool TargetClears::copies() {
    if (path_ != Path::Auto) return path_ == Path::Copy;
    if (software_ < 0) software_ = currentContextIsSoftware() ? 1 : 0;
    return software_ == 1;
}

void TargetClears::color(GLint drawBuffer, const float value[4]) {
    Value v;
    for (int i = 0; i < 4; ++i) v.bits[size_t(i)] = std::bit_cast<GLuint>(value[i]);
    clear(drawBuffer, v);
}

void TargetClears::colorUint(GLint drawBuffer, const GLuint value[4]) {
    clear(drawBuffer, Value{{value[0], value[1], value[2], value[3]}, true});
}

void TargetClears::clearBuffer(GLint drawBuffer, const Value& value) {
    if (value.integer) {
        glClearBufferuiv(GL_COLOR, drawBuffer, value.bits.data());
    } else {
        float f[4];
        for (int i = 0; i < 4; ++i) f[i] = std::bit_cast<float>(value.bits[size_t(i)]);
        glClearBufferfv(GL_COLOR, drawBuffer, f);
    }
}

void TargetClears::clear(GLint drawBuffer, const Value& value) {
    if (copies()) {
        GLint attachment = GL_NONE;
        glGetIntegerv(GL_DRAW_BUFFER0 + drawBuffer, &attachment);
        if (attachment == GL_NONE) return;  // glClearBuffer leaves a draw buffer that is NONE alone
        GLboolean mask[4] = {GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE};
        glGetBooleani_v(GL_COLOR_WRITEMASK, GLuint(drawBuffer), mask);
        if (mask[0] && mask[1] && mask[2] && mask[3] && copyInto(GLenum(attachment), value)) return;
    }
    clearBuffer(drawBuffer, value);
}

bool TargetClears::copyInto(GLenum attachment, const Value& value) {
    GLint type = GL_NONE, name = 0, level = 0, layered = GL_FALSE;
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, attachment, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    if (type != GL_TEXTURE) return false;  // the default framebuffer or a renderbuffer
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, attachment, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &name);
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, attachment, GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL, &level);
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, attachment, GL_FRAMEBUFFER_ATTACHMENT_LAYERED, &layered);
    if (level != 0 || layered) return false;
    // On ES the description and a new strip bind textures to the active unit: the binding found
    // there is put back, so that a clear between a method's binds and its draw changes nothing.
    GLint activeUnit = GL_TEXTURE0, bound = 0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &activeUnit);
    if (isEs()) glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
    const bool copied = copyTo(GLuint(name), GLuint(activeUnit - GL_TEXTURE0), value);
    if (isEs()) glBindTexture(GL_TEXTURE_2D, GLuint(bound));
    return copied;
}

bool TargetClears::copyTo(GLuint name, GLuint activeUnit, const Value& value) {
    const TextureDescription target = describeTexture(name, activeUnit);
    // Only 16-byte texels: llvmpipe clears 4- and 8-byte ones at memory speed (0.3-0.5 ms at
    // 1280x720), where copies saved little and, in whole frames, cost more (DESIGN.md).
    // A float value into an integer target (or the reverse) is the clear's business (it converts).
    if (!target.is2D || !target.immutable || target.integer != value.integer || bytesPerTexel(target.internalFormat) != 16) {
        return false;
    }
    int x0 = 0, y0 = 0, x1 = target.width, y1 = target.height;
    if (glIsEnabled(GL_SCISSOR_TEST)) {
        GLint box[4] = {0, 0, 0, 0};
        glGetIntegerv(GL_SCISSOR_BOX, box);
        x0 = std::clamp(box[0], 0, target.width);
        y0 = std::clamp(box[1], 0, target.height);
        x1 = std::clamp(box[0] + std::max(box[2], 0), x0, target.width);
        y1 = std::clamp(box[1] + std::max(box[3], 0), y0, target.height);
    }
    const Strip& source = strip(target.internalFormat, value);
    for (int y = y0; y < y1; y += source.texture.height()) {
        for (int x = x0; x < x1; x += source.texture.width()) {
            glCopyImageSubData(source.texture.id(), GL_TEXTURE_2D, 0, 0, 0, 0, name, GL_TEXTURE_2D, 0, x, y, 0,
                               std::min(source.texture.width(), x1 - x), std::min(source.texture.height(), y1 - y), 1);
        }
    }
    return true;
}

const TargetClears::Strip& TargetClears::strip(GLenum format, const Value& value) {
    for (const Strip& s : strips_) {
        if (s.format == format && s.value == value) return s;
    }
    // A handful of constant values in practice; a caller whose values keep changing reuses the
    // oldest strip rather than growing the list.
    if (strips_.size() >= kMaxStrips) strips_.erase(strips_.begin());
    Strip s{format, value, Texture2D(format, stripWidth_, stripRows_)};
    // Filled once by the clear it stands in for, so that the value converts as that clear's does.
    GLint drawFramebuffer = 0, readFramebuffer = 0;  // makeFramebuffer binds both on ES
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFramebuffer);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readFramebuffer);
    const GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST);
    glDisable(GL_SCISSOR_TEST);
    {
        const FramebufferHandle fill = makeFramebuffer({&s.texture});
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fill.id());
        clearBuffer(0, value);
    }
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(drawFramebuffer));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(readFramebuffer));
    if (scissor) glEnable(GL_SCISSOR_TEST);
    strips_.push_back(std::move(s));
    return strips_.back();
}

size_t TargetClears::bytes() const {
    size_t total = 0;
    for (const Strip& s : strips_) total += s.texture.bytes();
    return total;
}

}  // namespace starnt::gl
