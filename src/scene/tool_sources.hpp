// The files starnt::tools embeds (the scene renderer's and fragment capture's GLSL, the viewer's,
// the bench's plotting script), next to the runtime's own (gl/shader.hpp).
#pragma once
#include <string>

namespace starnt::tools {

// Makes the tools' files visible to gl::embeddedSource (and so to programs that #include them).
// Idempotent; call before building a program from a tools file.
void useToolSources();
// useToolSources(), then the file's text with its #include lines expanded.
std::string toolSource(const std::string& path);

}  // namespace starnt::tools
