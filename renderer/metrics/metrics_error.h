// Bad input to the metrics tool: unreadable or inconsistent images, malformed point lists, option
// values out of range. The message names the file and, where relevant, the pixel and channel or
// the JSON pointer, so the command line prints it as one line and exits with status 2.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace rr {

class MetricsError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// A number as a message shows it (6 significant digits, no trailing zeros).
inline std::string messageNumber(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

}  // namespace rr
