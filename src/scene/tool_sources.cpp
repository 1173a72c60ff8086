#include "scene/tool_sources.hpp"

#include "gl/shader.hpp"

namespace starnt::detail {
const std::map<std::string, std::string>& embeddedToolSources();  // generated (embedded_tools.cpp)
}

namespace starnt::tools {

void useToolSources() { gl::addEmbeddedFiles(detail::embeddedToolSources()); }

std::string toolSource(const std::string& path) {
    useToolSources();
    return gl::embeddedSource(path);
}

}  // namespace starnt::tools
