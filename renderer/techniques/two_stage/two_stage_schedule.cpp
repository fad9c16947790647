#include "techniques/two_stage/two_stage_schedule.h"

#include <algorithm>

#include "render/renderer.h"

namespace rr::two_stage {

namespace {

// The preprocess's pixels are cut into this many units of work.
constexpr size_t kPilotUnits = 16;
// The preprocess's sample index: no kept sample has it.
constexpr uint32_t kPilotSample = kMaxSpp;

uint32_t pixelIndex(const PixelVisit& v, int width) {
    return uint32_t(v.y) * uint32_t(width) + uint32_t(v.x);
}

// σ at each visited pixel with N samples; the unit's sum goes to the integrator when it ends.
class PilotHook final : public PixelRenderer {
  public:
    PilotHook(const TwoStageIntegrator& integrator, const Scene& scene, const Sampler& sampler,
              int width)
        : integrator_(integrator), scene_(scene), sampler_(sampler), width_(width) {}
    ~PilotHook() override { integrator_.addPilot(sigmaSum_, pixels_); }

    void render(const PixelVisit& v, PixelWork& work) override {
        SampleMoments moments;
        integrator_.estimate(scene_, v.x, v.y, sampler_.at(pixelIndex(v, width_), v.first),
                             integrator_.settings().estimator.samples, work.rays, &moments);
        sigmaSum_ += moments.standardDeviation();
        ++pixels_;
    }

  private:
    const TwoStageIntegrator& integrator_;
    const Scene& scene_;
    const Sampler& sampler_;
    int width_;
    double sigmaSum_ = 0;
    uint64_t pixels_ = 0;
};

// One band's scan: σ_p runs from pixel to pixel (eq. 8), each pixel's count from it (eq. 9).
class BandHook final : public PixelRenderer {
  public:
    BandHook(const TwoStageIntegrator& integrator, const Scene& scene, const Sampler& sampler,
             int width, uint32_t spp)
        : integrator_(integrator), scene_(scene), sampler_(sampler), width_(width), spp_(spp) {}

    void render(const PixelVisit& v, PixelWork& work) override {
        const bool rerender = integrator_.settings().allocation == Allocation::VariableRerender;
        const double sigmaAverage = integrator_.sigmaAverage();
        for (uint32_t s = v.first; s < v.first + v.count; ++s) {
            uint32_t samples = integrator_.allocate(sigmaP_), drawn = samples;
            SampleMoments moments;
            PixelSample sample = sampler_.at(pixelIndex(v, width_), s);
            Rgb value = render(v, sample, samples, work, &moments);
            double sigma = moments.standardDeviation();
            bool again = false;
            if (rerender && sigma > sigmaP_ + sigmaAverage) {
                // Fresh samples (index spp + s, which no kept sample has), the first estimate
                // dropped: the pixel's own samples chose this, hence the slight bias.
                sigmaP_ = sigma;
                samples = integrator_.allocate(sigmaP_);
                drawn += samples;
                moments = {};
                sample = sampler_.at(pixelIndex(v, width_), spp_ + s);
                value = render(v, sample, samples, work, &moments);
                sigma = moments.standardDeviation();
                again = true;
            }
            work.add(value, scene_.camera(), sample);
            integrator_.recordPixel(v.x, v.y, drawn, again);
            sigmaP_ = 0.75 * sigmaP_ + 0.25 * sigma;  // eq. (8)
        }
    }

  private:
    Rgb render(const PixelVisit& v, const PixelSample& sample, uint32_t samples, PixelWork& work,
               SampleMoments* moments) {
        return integrator_.estimate(scene_, v.x, v.y, sample, samples, work.rays, moments);
    }

    const TwoStageIntegrator& integrator_;
    const Scene& scene_;
    const Sampler& sampler_;
    int width_;
    uint32_t spp_;
    double sigmaP_ = 0;  // σ_p starts at 0 in each band
};

}  // namespace

TwoStageSchedule::TwoStageSchedule(TwoStageIntegrator& integrator, const ScheduleInputs& in)
    : integrator_(integrator),
      scene_(in.scene),
      width_(in.width),
      height_(in.height),
      spp_(in.spp) {}

bool TwoStageSchedule::nextRound(const Film&, const RoundTiming&, Round* round) {
    switch (stage_) {
        case Stage::Start:
            stage_ = Stage::Pilot;
            *round = Round{kPilotUnits, false};
            return true;
        case Stage::Pilot: {
            integrator_.resolveSigmaAverage();
            stage_ = Stage::Bands;
            const int rows = integrator_.settings().bandRows;
            *round = Round{size_t((height_ + rows - 1) / rows), /*interruptible=*/true};
            return true;
        }
        case Stage::Bands:
        case Stage::Done:
            stage_ = Stage::Done;
            break;
    }
    return false;
}

void TwoStageSchedule::unitVisits(size_t unit, std::vector<PixelVisit>* visits) const {
    visits->clear();
    if (stage_ == Stage::Pilot) {
        // Pixels spread evenly over the image, in pixel order.
        const uint64_t pixels = uint64_t(width_) * height_;
        const uint64_t count = std::min<uint64_t>(integrator_.settings().pilotPixels, pixels);
        for (uint64_t k = unit * count / kPilotUnits; k < (unit + 1) * count / kPilotUnits; ++k) {
            const uint64_t pixel = (2 * k + 1) * pixels / (2 * count);
            visits->push_back(
                {int(pixel % width_), int(pixel / width_), kPilotSample, 1, /*keep=*/false});
        }
        return;
    }
    const int rows = integrator_.settings().bandRows;
    const int y0 = static_cast<int>(unit) * rows, y1 = std::min(y0 + rows, height_);
    serpentineVisits(width_, y0, y1, 0, spp_, true, visits);
}

std::unique_ptr<PixelRenderer> TwoStageSchedule::pixelRenderer(const Sampler& sampler) const {
    if (stage_ == Stage::Pilot)
        return std::make_unique<PilotHook>(integrator_, scene_, sampler, width_);
    return std::make_unique<BandHook>(integrator_, scene_, sampler, width_, spp_);
}

}  // namespace rr::two_stage
