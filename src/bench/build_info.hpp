// What the running binary was built from (cmake/build_info.cmake writes the definitions at every
// build, so the commit is never stale).
#pragma once

namespace starnt {

const char* buildCommit();    // `git describe --always --dirty`, or "unknown" outside a git checkout
const char* buildType();      // CMAKE_BUILD_TYPE, e.g. "Release"
const char* buildCompiler();  // e.g. "GNU 12.2.0"

}  // namespace starnt
