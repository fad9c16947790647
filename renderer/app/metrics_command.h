// The `metrics` tool's subcommands. Each returns the exit status: 0 done, 1 unexpected
// failure, 2 bad input (one "error: ..." line on stderr naming the file, nothing written).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "metrics/image_metrics.h"

namespace rr {

// `metrics compare IMAGE REFERENCE`: error metrics and, when the render time is known,
// efficiencies.
struct CompareCommandOptions {
    std::string image, reference;
    std::optional<double> time;  // seconds; default: IMAGE's renderer.renderTime
    bool json = false;
    double relmseReject = 0;
    double cdPerUnit = kDefaultCdPerUnit;
};
int runCompareCommand(const CompareCommandOptions& options);

// `metrics slope FILE`: convergence slopes of a JSON list of {spp, error, time} points.
struct SlopeCommandOptions {
    std::string file;
    bool json = false;
};
int runSlopeCommand(const SlopeCommandOptions& options);

// `metrics merge A B [C ...] --out OUT`: an spp-weighted average as a reference image.
struct MergeCommandOptions {
    std::vector<std::string> inputs;
    std::string out;
    bool json = false;
};
int runMergeCommand(const MergeCommandOptions& options);

}  // namespace rr
