// The `ris` integrator's schedule: the pilot rounds of the M and N choice, inside the timed
// render, then uniform passes.
//  1. costs (robust and optimal, unless given): `pilot_rays` primary rays spread evenly over
//     the image, each timing both stages at its first hit (RisEstimator::measureCosts);
//  2. terms (optimal): every pixel estimates eq. (2)'s e1, e2, e3 at one first hit;
//  3. the integrator resolves M and N, and uniform passes render the image.
// The pilots use sample index kMaxSpp, which no kept sample has, and keep nothing.
#pragma once

#include <mutex>

#include "render/tile_grid.h"
#include "render/uniform_passes.h"
#include "techniques/ris/ris_integrator.h"

namespace rr::ris {

class RisSchedule final : public RenderSchedule {
  public:
    RisSchedule(RisIntegrator& integrator, const ScheduleInputs& inputs);

    bool supportsTimeLimit() const override { return true; }
    uint64_t plannedSamples() const override { return passes_.plannedSamples(); }
    bool nextRound(const Film& film, const RoundTiming& timing, Round* round) override;
    void unitVisits(size_t unit, std::vector<PixelVisit>* visits) const override;
    std::unique_ptr<PixelRenderer> pixelRenderer(const Sampler& sampler) const override;

    // Adds a pilot unit's measurements.
    void addTally(const CostTally& tally) const;

  private:
    enum class Stage : uint8_t { Start, Costs, Terms, Passes };

    RisIntegrator& integrator_;
    const Scene& scene_;
    int width_, height_;
    TileGrid grid_;
    UniformPasses passes_;
    Stage stage_ = Stage::Start;
    mutable std::mutex mutex_;
    mutable CostTally tally_;
};

}  // namespace rr::ris
