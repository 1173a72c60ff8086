#include "gl/shader.hpp"

#include <algorithm>
#include <map>
#include <sstream>
#include <vector>

#include "starnt/error.hpp"

namespace starnt::detail {
const std::map<std::string, std::string>& embeddedShaderSources();
}

namespace starnt::gl {
namespace {

std::string expandIncludes(const std::string& text, const std::string& origin, int depth) {
    if (depth > 16) throw Error("internal: #include nesting too deep in " + origin);
    std::istringstream in(text);
    std::ostringstream out;
    std::string line;
    while (std::getline(in, line)) {
        size_t p = line.find_first_not_of(" \t");
        if (p != std::string::npos && line.compare(p, 8, "#include") == 0) {
            size_t a = line.find('"', p), b = line.find('"', a + 1);
            if (a == std::string::npos || b == std::string::npos) {
                throw Error("internal: malformed #include in " + origin + ": " + line);
            }
            std::string path = line.substr(a + 1, b - a - 1);
            out << expandIncludes(embeddedSource(path), path, depth + 1) << "\n";
        } else {
            out << line << "\n";
        }
    }
    return out.str();
}

std::string header(GLenum stage) {
    std::string h;
    if (glslDialect() == GlslDialect::Desktop450) {
        h = "#version 450 core\n";
    } else {
        h = "#version 320 es\n"
            "precision highp float;\nprecision highp int;\nprecision highp sampler2D;\n"
            "precision highp image2D;\nprecision highp uimage2D;\n#define STARNT_GLSL_ES 1\n";
    }
    h += "#define STARNT_GLSL 1\n";
    if (stage == GL_VERTEX_SHADER) h += "#define STARNT_VERTEX_STAGE 1\n";
    if (stage == GL_FRAGMENT_SHADER) h += "#define STARNT_FRAGMENT_STAGE 1\n";
    if (stage == GL_COMPUTE_SHADER) h += "#define STARNT_COMPUTE_STAGE 1\n";
    return h;
}

std::string numbered(const std::string& src) {
    std::istringstream in(src);
    std::ostringstream out;
    std::string line;
    int n = 1;
    while (std::getline(in, line)) out << n++ << ": " << line << "\n";
    return out.str();
}

// The info log of a shader (glGetShaderiv, glGetShaderInfoLog) or a program (the glGetProgram* pair).
template <class GetIv, class GetLog>
std::string infoLog(GLuint object, GetIv getIv, GetLog getLog) {
    GLint len = 0;
    getIv(object, GL_INFO_LOG_LENGTH, &len);
    std::string log(size_t(len > 0 ? len : 1), '\0');
    getLog(object, len, nullptr, log.data());
    return log;
}

GLuint compile(GLenum stage, const std::string& label, const std::string& body, const std::string& defines) {
    // "#extension" lines among the defines go right after #version, before any other token (GLSL
    // ES requires it; the ES header declares precisions), and only into fragment shaders (the
    // extensions asked for so far are fragment ones: EXT_shader_framebuffer_fetch).
    std::string extensions, rest;
    {
        std::istringstream in(defines);
        std::string line;
        while (std::getline(in, line)) (line.rfind("#extension", 0) == 0 ? extensions : rest) += line + "\n";
    }
    std::string head = header(stage);
    if (stage == GL_FRAGMENT_SHADER && !extensions.empty()) head.insert(head.find('\n') + 1, extensions);
    std::string src = head + rest + "\n" + expandIncludes(body, label, 0);
    GLuint s = glCreateShader(stage);
    const char* ptr = src.c_str();
    glShaderSource(s, 1, &ptr, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        const std::string log = infoLog(s, glGetShaderiv, glGetShaderInfoLog);
        glDeleteShader(s);
        const char* kind = stage == GL_VERTEX_SHADER ? "vertex" : stage == GL_FRAGMENT_SHADER ? "fragment" : "compute";
        std::string message = "shader compile failed (" + label + ", " + kind + "): " + log;
        if (std::getenv("STARNT_DUMP_SHADERS")) message += "\n" + numbered(src);
        throw Error(message);
    }
    return s;
}

Program link(const std::string& label, const std::vector<GLuint>& shaders) {
    GLuint p = glCreateProgram();
    for (GLuint s : shaders) glAttachShader(p, s);
    glLinkProgram(p);
    for (GLuint s : shaders) {
        glDetachShader(p, s);
        glDeleteShader(s);
    }
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        const std::string log = infoLog(p, glGetProgramiv, glGetProgramInfoLog);
        glDeleteProgram(p);
        throw Error("shader link failed (" + label + "): " + log);
    }
    return Program(p, label);
}

}  // namespace

GlslDialect glslDialect() { return epoxy_is_desktop_gl() ? GlslDialect::Desktop450 : GlslDialect::Es320; }

namespace {
std::vector<const EmbeddedFiles*>& extraTables() {
    static std::vector<const EmbeddedFiles*> tables;
    return tables;
}
}  // namespace

void addEmbeddedFiles(const EmbeddedFiles& files) {
    auto& tables = extraTables();
    if (std::find(tables.begin(), tables.end(), &files) == tables.end()) tables.push_back(&files);
}

std::string embeddedSource(const std::string& path) {
    const auto& own = detail::embeddedShaderSources();
    if (auto it = own.find(path); it != own.end()) return expandIncludes(it->second, path, 0);
    for (const EmbeddedFiles* table : extraTables()) {
        if (auto it = table->find(path); it != table->end()) return expandIncludes(it->second, path, 0);
    }
    throw Error("internal: no embedded shader file '" + path + "'");
}

GLint Program::uniform(const char* name) const {
    auto it = locations_.find(name);
    if (it != locations_.end()) return it->second;
    GLint loc = glGetUniformLocation(handle_.id(), name);
    locations_.emplace(name, loc);
    return loc;
}

Program buildProgram(const std::string& label, const std::string& vertexBody, const std::string& fragmentBody,
                     const std::string& defines) {
    GLuint vs = compile(GL_VERTEX_SHADER, label, vertexBody, defines);
    GLuint fs = 0;
    try {
        fs = compile(GL_FRAGMENT_SHADER, label, fragmentBody, defines);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    return link(label, {vs, fs});
}

Program buildComputeProgram(const std::string& label, const std::string& computeBody, const std::string& defines) {
    return link(label, {compile(GL_COMPUTE_SHADER, label, computeBody, defines)});
}

}  // namespace starnt::gl
