// Progress on stderr: a live bar (percent, samples/s, elapsed, ETA) on a terminal; nothing
// until the one summary line otherwise (logs stay readable).
#pragma once

#include <string>

#include "render/renderer.h"

namespace rr {

class ProgressBar {
  public:
    ProgressBar();
    void update(const RenderProgress& p);
    // Clears the live bar and prints the final summary line.
    void finish(const std::string& summary);

  private:
    bool interactive_;
    bool drawn_ = false;
};

}  // namespace rr
