// How long a path runs: the path tracers' settings from the scene's "render" object
// (path_tracer.h describes the rules). Apart from the tracers, so that what reads or passes the
// settings (the loader, the technique registry) need not see the path walk.
#pragma once

#include <nlohmann/json.hpp>

namespace rr {

struct PathSettings {
    // Hard cap on "unlimited" paths (max_depth −1): only pathological scenes (a closed glass
    // shell with total internal reflection) ever reach it.
    static constexpr int kDepthCap = 1000;

    int maxDepth = 16;
    // Russian roulette from the first vertex, played only where the throughput-driven survival
    // probability is below 0.25: the rule of best geometric-mean efficiency over the paper
    // scenes (results/tables/rr_efficiency.md).
    int rrDepth = 1;
    // Russian roulette's survival probability: 0 for min(1, max throughput component × η²),
    // else this fixed value (pbrt-v1's path integrator: 0.5).
    float rrSurvival = 0;
    // The throughput-driven survival probability is played only where it is below this (1:
    // wherever it is below 1). A fixed rrSurvival is played always and ignores it.
    float rrThreshold = 0.25f;

    // Adds max_depth, rr_depth and the survival rule (rr_survival when fixed, else
    // rr_threshold) to an integrator's parameters.
    void addTo(nlohmann::json* parameters) const {
        (*parameters)["max_depth"] = maxDepth;
        (*parameters)["rr_depth"] = rrDepth;
        if (rrSurvival > 0)
            (*parameters)["rr_survival"] = rrSurvival;
        else
            (*parameters)["rr_threshold"] = rrThreshold;
    }
};

}  // namespace rr
