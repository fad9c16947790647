#include "app/progress_bar.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace rr {

namespace {

std::string formatSeconds(double s) {
    char buf[32];
    if (s < 60)
        std::snprintf(buf, sizeof buf, "%.1fs", s);
    else if (s < 3600)
        std::snprintf(buf, sizeof buf, "%dm%02ds", int(s) / 60, int(s) % 60);
    else
        std::snprintf(buf, sizeof buf, "%dh%02dm", int(s) / 3600, (int(s) / 60) % 60);
    return buf;
}

}  // namespace

ProgressBar::ProgressBar(bool enabled) : interactive_(enabled && ::isatty(STDERR_FILENO) == 1) {}

void ProgressBar::update(const RenderProgress& p) {
    if (!interactive_ || p.elapsed <= 0) return;
    double fraction = p.samplesPlanned > 0 ? double(p.samplesDone) / double(p.samplesPlanned)
                                           : p.elapsed / p.timeLimit;
    fraction = std::clamp(fraction, 0.0, 1.0);
    const double rate = double(p.samplesDone) / p.elapsed;
    const double eta =
        p.samplesPlanned > 0 && rate > 0
            ? double(p.samplesPlanned - std::min(p.samplesDone, p.samplesPlanned)) / rate
            : std::max(0.0, p.timeLimit - p.elapsed);
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(fraction * kWidth);
    std::string bar(filled, '#');
    bar.resize(kWidth, '.');
    std::fprintf(stderr, "\r[%s] %3.0f%%  %.2f Msamples/s  elapsed %s  ETA %s  spp %u   ",
                 bar.c_str(), fraction * 100, rate * 1e-6, formatSeconds(p.elapsed).c_str(),
                 formatSeconds(eta).c_str(), p.sppDone);
    std::fflush(stderr);
    drawn_ = true;
}

void ProgressBar::clear() {
    if (drawn_) std::fprintf(stderr, "\r%*s\r", 110, "");
    drawn_ = false;
}

}  // namespace rr
