// Table-driven adaptive importance sampling (Cline, Adams & Egbert 2008): `path_mis` whose
// decisions are steered by per-pixel importance maps learned from the pixels rendered before
// (map_guide.h says which map steers which decision).
//
// Rendering (Algorithm 1 and §3.3): rows are scanned back and forth; each pixel starts from the
// average of its rendered neighbours' maps (normalised, fig. 3), renders all its samples while
// collecting them in temporary maps, optionally clamps them (eq. 4, biased), and stores its
// maps plus the finished temporary maps for the pixels after it. The maps are fixed while a
// pixel renders, so each pixel's estimate is unbiased.
//
// Parallelism: the scan makes every pixel depend on the one before it, so the image is cut into
// bands of `bandRows` rows (render/scan_bands.h). Bands depend only on the settings, never on
// the thread count, so the image is bit-identical for any number of threads. A band that started
// from uniform maps would learn from scratch in its first rows; instead it first scans
// `bandWarmupRows` (4 by default) rows of the band above with independent sample indices and
// discards their values. Both are measured against one serial scan (bandRows ≥ height) in
// results/tables/tais.md.
#pragma once

#include <array>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "integrators/light_sample_estimator.h"
#include "render/technique_registry.h"
#include "scene/invertible_light.h"
#include "techniques/tais/tais_settings.h"

namespace rr::tais {

class TaisIntegrator final : public Integrator {
  public:
    // `mapPointers[k]`: where the config asked for map k (for errors); empty in auto mode.
    TaisIntegrator(const TaisSettings& settings, std::array<std::string, kMapKinds> mapPointers);

    std::string name() const override { return "tais"; }
    LightTransport transport() const override { return LightTransport::Paths; }
    nlohmann::json parameters() const override;
    // Resolves `auto` to the maps whose decisions the scene has; rejects a map asked for
    // whose decision the scene lacks.
    void prepare(const Scene& scene) override;

    // Bands of settings.bandRows rows in scan order, one TaisPixels hook per band.
    std::unique_ptr<RenderSchedule> schedule(const ScheduleInputs& inputs) const;

    const TaisSettings& settings() const { return settings_; }
    // Per scene light: its inverse of its sampling (point-on-light maps), or nullptr.
    std::span<const InvertibleLight* const> invertibleLights() const { return invertible_; }
    // Next-event estimation: light sampling and the guided BSDF sample combined by MIS.
    const DirectLightingEstimator& nextEventEstimator() const { return nee_; }

  private:
    TaisSettings settings_;
    std::array<std::string, kMapKinds> mapPointers_;
    std::vector<const InvertibleLight*> invertible_;
    LightSampleEstimator nee_{1, /*multipleImportance=*/true};
};

// Whether the scene makes the decision a map steers (no time map without motion blur, …).
bool sceneHasDecision(const Scene& scene, MapKind kind);

// Registers the `tais` integrator (configs/README.md documents its keys).
void registerTechnique(TechniqueRegistry& registry);

}  // namespace rr::tais
