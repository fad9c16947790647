// TAIS's per-pixel hook (Algorithm 1): for each pixel of a band, in the scan order the schedule
// gives, start from the normalised sum of the rendered neighbours' maps (fig. 3), render the
// pixel's samples with those maps fixed while collecting them in temporary maps (lines 3–20),
// optionally clamp them (eq. 4, line 21), and store the pixel's maps plus its finished
// temporary maps for the pixels after it (lines 22–24).
#pragma once

#include <vector>

#include "render/render_schedule.h"
#include "techniques/tais/pixel_maps.h"
#include "techniques/tais/scan.h"
#include "techniques/tais/tais_integrator.h"
#include "techniques/tais/temporary_map.h"

namespace rr::tais {

class TaisPixels final : public PixelRenderer {
  public:
    TaisPixels(const Scene& scene, const TaisIntegrator& tais, const Sampler& sampler);

    void render(const PixelVisit& visit, PixelWork& work) override;

  private:
    // One sample of pixel (x, y) with the pixel's maps; added to the temporary maps.
    Rgb renderSample(int x, int y, const PixelSample& sample, RayCounters& rays);

    const Scene& scene_;
    const TaisIntegrator& tais_;
    const Sampler& sampler_;
    MapRows<PixelMaps> rows_;
    PixelMaps maps_;  // the pixel's maps while it renders
    TemporaryMaps temporary_;
    int firstRow_ = -1;  // the image row of the unit's first visit
    int row_ = 0;        // the current row, counted from firstRow_
};

}  // namespace rr::tais
