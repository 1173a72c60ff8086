// Where the library's notes and warnings go. The runtime never writes to stdout or stderr: it hands
// each message to the callback installed here (none by default: messages are dropped). The
// starnt CLI installs one that writes "starnt: note: ..." / "starnt: warning: ..." to stderr.
#pragma once
#include <functional>
#include <string>

namespace starnt {

enum class LogLevel { Note, Warning };
using LogCallback = std::function<void(LogLevel, const std::string& message)>;

// Process-wide. Install it before creating methods; the callback runs on the thread that renders
// (the one whose GL context is current) and must not call back into a method.
void setLogCallback(LogCallback callback);
// Sends a message to the installed callback (used by the library; engines may use it too).
void logMessage(LogLevel level, const std::string& message);

}  // namespace starnt
