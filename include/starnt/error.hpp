// Error type used across STAR-NT. Every failure a user can cause (bad file, bad flag, missing GL
// feature) is thrown as starnt::Error with a message that names the thing at fault; the CLI prints
// it as one line on stderr and exits non-zero.
#pragma once
#include <stdexcept>
#include <string>

namespace starnt {

class Error : public std::runtime_error {
public:
    explicit Error(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace starnt
