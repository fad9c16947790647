// Progress on stderr: a live bar (percent, samples/s, elapsed, ETA) on a terminal, nothing
// otherwise (logs stay readable: the command prints its one summary line).
#pragma once

#include "render/renderer.h"

namespace rr {

class ProgressBar {
  public:
    // disabled: never draws (e.g. `renderer serve`, whose replies carry the summary).
    explicit ProgressBar(bool enabled = true);
    void update(const RenderProgress& p);
    // Clears the live bar, so that the summary line can follow.
    void clear();

  private:
    bool interactive_;
    bool drawn_ = false;
};

}  // namespace rr
