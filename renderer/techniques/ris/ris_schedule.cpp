#include "techniques/ris/ris_schedule.h"

#include <algorithm>

#include "render/renderer.h"

namespace rr::ris {

namespace {

// The cost pilot's rays are cut into this many units of work.
constexpr size_t kCostUnits = 16;
// The first visits of each unit warm the caches up (the scene's and the lights' tables, cold at
// the start of a render), untimed: the pilot measures steady-state costs.
constexpr int kWarmUpVisits = 16;

// The pilots' sample index: no kept sample has it.
constexpr uint32_t kPilotSample = kMaxSpp;

// Times both stages at the first hit of each visited pixel; the unit's tally goes to the
// schedule when the unit ends.
class CostPilot final : public PixelRenderer {
  public:
    CostPilot(const RisSchedule& schedule, const RisIntegrator& integrator, const Scene& scene,
              const Sampler& sampler, int width)
        : schedule_(schedule),
          integrator_(integrator),
          scene_(scene),
          sampler_(sampler),
          width_(width) {}
    ~CostPilot() override { schedule_.addTally(tally_); }

    void render(const PixelVisit& v, PixelWork& work) override {
        const uint32_t pixel = uint32_t(v.y) * uint32_t(width_) + uint32_t(v.x);
        const bool timed = visits_++ >= kWarmUpVisits;
        integrator_.measureCosts(scene_, v.x, v.y, sampler_.at(pixel, v.first), work.rays, timed,
                                 &tally_);
    }

  private:
    const RisSchedule& schedule_;
    const RisIntegrator& integrator_;
    const Scene& scene_;
    const Sampler& sampler_;
    int width_;
    int visits_ = 0;
    CostTally tally_;
};

// Estimates eq. (2)'s terms at each visited pixel.
class TermsPilot final : public PixelRenderer {
  public:
    TermsPilot(RisIntegrator& integrator, const Scene& scene, const Sampler& sampler, int width)
        : integrator_(integrator), scene_(scene), sampler_(sampler), width_(width) {}

    void render(const PixelVisit& v, PixelWork& work) override {
        const uint32_t pixel = uint32_t(v.y) * uint32_t(width_) + uint32_t(v.x);
        integrator_.measureTerms(scene_, v.x, v.y, sampler_.at(pixel, v.first), work.rays);
    }

  private:
    RisIntegrator& integrator_;
    const Scene& scene_;
    const Sampler& sampler_;
    int width_;
};

}  // namespace

RisSchedule::RisSchedule(RisIntegrator& integrator, const ScheduleInputs& in)
    : integrator_(integrator),
      scene_(in.scene),
      width_(in.width),
      height_(in.height),
      grid_(in.width, in.height),
      passes_(in.scene, integrator, in.width, in.height, in.spp, in.timeLimit, in.splattingFilm()) {
}

void RisSchedule::addTally(const CostTally& tally) const {
    std::lock_guard lock(mutex_);
    tally_ += tally;
}

bool RisSchedule::nextRound(const Film& film, const RoundTiming& timing, Round* round) {
    if (stage_ == Stage::Start && integrator_.needsCostPilot()) {
        stage_ = Stage::Costs;
        *round = Round{kCostUnits, false};
        return true;
    }
    if (stage_ < Stage::Terms && integrator_.needsTermsPilot()) {
        stage_ = Stage::Terms;
        *round = Round{grid_.tiles(), false};
        return true;
    }
    if (stage_ != Stage::Passes) {
        integrator_.resolveCounts(tally_.costs());
        stage_ = Stage::Passes;
    }
    return passes_.nextRound(film, timing, round);
}

void RisSchedule::unitVisits(size_t unit, std::vector<PixelVisit>* visits) const {
    visits->clear();
    switch (stage_) {
        case Stage::Costs: {
            // Pilot rays spread evenly over the image, pixel by pixel.
            const uint64_t pixels = uint64_t(width_) * height_;
            const uint64_t rays = std::min<uint64_t>(integrator_.settings().pilotRays, pixels);
            for (uint64_t k = unit * rays / kCostUnits; k < (unit + 1) * rays / kCostUnits; ++k) {
                const uint64_t pixel = (2 * k + 1) * pixels / (2 * rays);
                visits->push_back({int(pixel % width_), int(pixel / width_), kPilotSample, 1,
                                   /*keep=*/false});
            }
            return;
        }
        case Stage::Terms:
            grid_.forEachPixel(unit, [&](int x, int y) {
                visits->push_back({x, y, kPilotSample, 1, /*keep=*/false});
            });
            return;
        case Stage::Start:
        case Stage::Passes:
            break;
    }
    passes_.unitVisits(unit, visits);
}

std::unique_ptr<PixelRenderer> RisSchedule::pixelRenderer(const Sampler& sampler) const {
    switch (stage_) {
        case Stage::Costs:
            return std::make_unique<CostPilot>(*this, integrator_, scene_, sampler, width_);
        case Stage::Terms:
            return std::make_unique<TermsPilot>(integrator_, scene_, sampler, width_);
        case Stage::Start:
        case Stage::Passes:
            break;
    }
    return passes_.pixelRenderer(sampler);
}

}  // namespace rr::ris
