// GLSL program building.
//
// Shader files live beside the C++ that uses them (src/**/*.glsl) and are embedded in the library
// at build time. They are written in the common subset of GLSL 4.50 and GLSL ES 3.10: the version
// line and precision qualifiers are injected here, never written in the files, so the same source
// compiles for an OpenGL 4.5 core context and for an OpenGL ES 3.1+ context. `#include "path"`
// (relative to src/) is expanded here, which is how src/scene/scene_constants.h is shared by
// C++ and GLSL.
#pragma once
#include <epoxy/gl.h>

#include <map>
#include <string>
#include <unordered_map>

#include "gl/gl_util.hpp"

namespace starnt::gl {

enum class GlslDialect { Desktop450, Es320 };

// The dialect programs are built for: that of the current context (GLSL 4.50 on desktop GL, GLSL ES
// 3.20 on OpenGL ES), so a method built in an engine's ES context gets ES shaders. ES 3.20 rather
// than 3.10 since the context must be ES 3.2 anyway, and the tools' fragment capture reads
// gl_PrimitiveID in the fragment stage, which ES 3.10 has only through OES_geometry_shader.
GlslDialect glslDialect();

// An embedded file's text with its #include lines expanded. Throws starnt::Error when missing.
// The runtime's own files are always there; starnt::tools adds its files (scene renderer,
// fragment capture, viewer, plotting script) with addEmbeddedFiles before it builds programs.
std::string embeddedSource(const std::string& path);
using EmbeddedFiles = std::map<std::string, std::string>;
void addEmbeddedFiles(const EmbeddedFiles& files);  // idempotent; the table must outlive its use

class Program {
public:
    Program() = default;
    Program(GLuint id, std::string label) : handle_(id), label_(std::move(label)) {}
    GLuint id() const { return handle_.id(); }
    const std::string& label() const { return label_; }
    // Cached uniform location; -1 when the uniform is absent or optimised away (setting it is then a no-op).
    GLint uniform(const char* name) const;
    explicit operator bool() const { return bool(handle_); }

private:
    Handle<deleteProgram> handle_;
    std::string label_;
    mutable std::unordered_map<std::string, GLint> locations_;
};

// `defines` is inserted after the version header ("#define A 1\n..."). Bodies may contain
// #include lines. Compile or link failures throw starnt::Error with the label and the GL log.
Program buildProgram(const std::string& label, const std::string& vertexBody, const std::string& fragmentBody,
                     const std::string& defines = {});
Program buildComputeProgram(const std::string& label, const std::string& computeBody, const std::string& defines = {});

}  // namespace starnt::gl
