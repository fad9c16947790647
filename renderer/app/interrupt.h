// Ctrl-C handling: the first SIGINT asks the render loop to stop after the current pass (so a
// valid image is saved); a second one terminates immediately.
#pragma once

#include <atomic>

namespace rr {

// Installs the handler and returns the flag it sets.
const std::atomic<bool>& installInterruptHandler();

}  // namespace rr
