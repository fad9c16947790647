// The one error type for bad input. Every message names the JSON pointer of the offending
// value (or the file), so the command line can print one line and exit with status 2.
#pragma once

#include <stdexcept>
#include <string>

namespace rr {

class ConfigError : public std::runtime_error {
  public:
    // What kind of bad input: callers that can do without an asset (the experiment harness
    // skips scenes whose third-party files are absent) tell the kinds apart by this, never by
    // the message's wording.
    enum class Kind { Invalid, MissingAsset };

    ConfigError(std::string pointer, const std::string& message, Kind kind = Kind::Invalid)
        : std::runtime_error((pointer.empty() ? std::string("/") : pointer) + ": " + message),
          pointer_(std::move(pointer)),
          kind_(kind) {}
    const std::string& pointer() const { return pointer_; }
    Kind kind() const { return kind_; }

  private:
    std::string pointer_;
    Kind kind_;
};

}  // namespace rr
