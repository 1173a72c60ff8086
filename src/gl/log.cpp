#include "starnt/log.hpp"

#include <mutex>
#include <utility>

namespace starnt {
namespace {

std::mutex& callbackMutex() {
    static std::mutex m;
    return m;
}
LogCallback& installed() {
    static LogCallback callback;
    return callback;
}

}  // namespace

void setLogCallback(LogCallback callback) {
    std::lock_guard lock(callbackMutex());
    installed() = std::move(callback);
}

void logMessage(LogLevel level, const std::string& message) {
    LogCallback callback;
    {
        std::lock_guard lock(callbackMutex());
        callback = installed();
    }
    if (callback) callback(level, message);
}

}  // namespace starnt
