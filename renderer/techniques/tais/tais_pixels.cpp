#include "techniques/tais/tais_pixels.h"

#include "integrators/path_walk.h"
#include "techniques/tais/contribution_filter.h"
#include "techniques/tais/map_guide.h"

namespace rr::tais {

namespace {

int lightCount(const Scene& scene) {
    return static_cast<int>(scene.lights().size());
}

}  // namespace

TaisPixels::TaisPixels(const Scene& scene, const TaisIntegrator& tais, const Sampler& sampler)
    : scene_(scene),
      tais_(tais),
      sampler_(sampler),
      rows_(scene.camera().width(), PixelMaps::uniform(tais.settings(), lightCount(scene))),
      maps_(PixelMaps::uniform(tais.settings(), lightCount(scene))),
      temporary_(tais.settings(), lightCount(scene)) {}

Rgb TaisPixels::renderSample(int x, int y, const PixelSample& sample, RayCounters& rays) {
    MapGuide guide(scene_, sample, maps_, tais_.settings(), tais_.invertibleLights());
    const Rgb value =
        tracePath(scene_, guide, x, y, tais_.settings().path, tais_.nextEventEstimator(), rays);
    if (value.isFinite()) guide.splat(value, temporary_);
    return value;
}

void TaisPixels::render(const PixelVisit& visit, PixelWork& work) {
    if (firstRow_ < 0) firstRow_ = visit.y;
    if (visit.y - firstRow_ != row_) {
        rows_.nextRow();
        row_ = visit.y - firstRow_;
    }
    // Fig. 3: the neighbours' average, normalised (which makes it independent of how many
    // were averaged) so that it and this pixel's own samples, normalised too, weigh equally in
    // what the pixel passes on.
    maps_.assignSum(rows_.neighbours(visit.x, row_).list(), /*normalize=*/true);
    temporary_.clear();
    const uint32_t pixel =
        uint32_t(visit.y) * uint32_t(scene_.camera().width()) + uint32_t(visit.x);
    for (uint32_t s = visit.first; s < visit.first + visit.count; ++s) {
        const PixelSample sample = sampler_.at(pixel, s);
        const Rgb value = renderSample(visit.x, visit.y, sample, work.rays);
        work.add(finiteOrZero(value, &work.nonFiniteSamples), scene_.camera(), sample);
    }
    if (tais_.settings().contributionFilter) filterMaximumContribution(work.values);  // line 21
    temporary_.addFinishedTo(maps_, tais_.settings().worldFloorShare);  // lines 22–24
    rows_.store(visit.x, &maps_);
}

}  // namespace rr::tais
