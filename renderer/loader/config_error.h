// The one error type for bad input. Every message names the JSON pointer of the offending
// value (or the file), so the command line can print one line and exit with status 2.
#pragma once

#include <stdexcept>
#include <string>

namespace rr {

class ConfigError : public std::runtime_error {
  public:
    ConfigError(std::string pointer, const std::string& message)
        : std::runtime_error((pointer.empty() ? std::string("/") : pointer) + ": " + message),
          pointer_(std::move(pointer)) {}
    const std::string& pointer() const { return pointer_; }

  private:
    std::string pointer_;
};

}  // namespace rr
