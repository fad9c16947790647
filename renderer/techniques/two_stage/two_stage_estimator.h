// Two-stage importance sampling of an environment map (Cline, Egbert, Talbot & Cardon 2006), a
// direct-lighting estimator (integrators/direct_lighting_estimator.h) usable by `direct` and at
// every vertex of `path_mis`. Per shading point: stage 1 partitions the lat-long map into a BSP
// tree approximating Le·f (partition.h), stage 2 warps N sample points through it
// (hierarchical_warp.h), and eq. (2) averages Le·fr·|cos θ|·V / p_ω over them, without MIS:
// unbiased because p_ω is tracked exactly and is non-zero wherever Le·f is (the partition's
// floor).
//
// The scene's lights must be one environment map in the latitude-longitude layout (a probe is
// resampled at load with the light's `latlong_width`); the estimate covers all of its light
// (FoundEmission::Excluded). Surfaces only. Analytic peaks (the default) need every material of
// the scene to give its lobe peaks (scene/lobe_peaks.h); `bsdf` peaks need nothing of them.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "integrators/direct_lighting_estimator.h"
#include "scene/lights/env_layout.h"
#include "scene/lobe_peaks.h"
#include "techniques/two_stage/partition.h"
#include "techniques/two_stage/summed_area_table.h"

namespace rr {
class EnvironmentMap;
}  // namespace rr

namespace rr::two_stage {

enum class PeakSource : uint8_t {
    Analytic,     // the materials' own peaks (mirror, retro-reflection, lobe axes, cone)
    BsdfSamples,  // N/4 BSDF samples, each a peak where f beats its leaf's corners (§2.2)
};

struct TwoStageSettings {
    uint32_t samples = 1;  // N per shading point
    // Refinement splits per shading point; none given: as many as samples (the paper's rule).
    std::optional<uint32_t> splits;
    PeakSource peaks = PeakSource::Analytic;

    uint32_t splitsFor(uint32_t sampleCount) const { return splits.value_or(sampleCount); }
};

// The moments of one estimate's per-sample values (the luminance of Le·fr·|cos θ|·V / p, zero
// for samples that found no light), for §5's allocation of samples to pixels.
struct SampleMoments {
    double sum = 0, sumSquares = 0;
    uint32_t count = 0;

    void add(double v) {
        sum += v;
        sumSquares += v * v;
        ++count;
    }
    // The samples' standard deviation (n − 1 in the denominator); 0 below two samples.
    double standardDeviation() const;
};

class TwoStageEstimator final : public DirectLightingEstimator {
  public:
    explicit TwoStageEstimator(const TwoStageSettings& settings) : settings_(settings) {}

    std::string name() const override { return "two_stage"; }
    nlohmann::json parameters() const override;
    uint32_t lightSamples() const override { return settings_.samples; }
    FoundEmission foundEmission() const override { return FoundEmission::Excluded; }
    uint32_t decisionRepeats() const override;
    bool worksInMedia() const override { return false; }
    // Checks the scene's lights and, for analytic peaks, that its materials give theirs
    // (scene/lobe_peaks.h), and attaches the map.
    void prepare(const Scene& scene, const std::string& pointer) override;
    // Builds the summed-area table of `map` (lat-long layout), which must outlive the
    // estimator.
    void attach(const EnvironmentMap& map);
    void estimate(ShadingPoint& point) const override {
        estimate(point, settings_.samples, nullptr);
    }
    // With a sample count of the caller's (§5's variable allocation; as many splits unless the
    // settings give them), adding each sample's value to *moments when not null.
    void estimate(ShadingPoint& point, uint32_t samples, SampleMoments* moments) const;

    // What estimate() does before its samples: stage 1 at `point`, into `partition`. False
    // where the point has no surface scattering.
    bool partitionAt(ShadingPoint& point, Partition* partition) const {
        return partitionAt(point, settings_.samples, partition);
    }
    bool partitionAt(ShadingPoint& point, uint32_t samples, Partition* partition) const;
    // A direction warped through `partition` from (s, t): world direction, its texel and its
    // density per steradian. False when the warp yields none.
    bool warpDirection(const Partition& partition, double s, double t, Vec3* direction, int* col,
                       int* row, double* pdf) const;
    // The density per steradian of world direction `direction` under `partition`.
    double pdf(const Partition& partition, const Vec3& direction) const;

    const SummedAreaTable& table() const { return table_; }
    const EnvironmentMap& map() const { return *map_; }

    const TwoStageSettings& settings() const { return settings_; }

  private:
    uint32_t peakSamples(uint32_t samples) const;
    // Sample i of `samples`: Le·fr·|cos θ|·V / p of a direction warped through `partition`.
    Rgb sample(ShadingPoint& point, const Partition& partition, uint32_t i, uint32_t samples) const;

    TwoStageSettings settings_;
    const EnvironmentMap* map_ = nullptr;
    const LatLongLayout* layout_ = nullptr;  // the map's (final: calls need no indirection)
    SummedAreaTable table_;
    LobePeakSources peakSources_;  // analytic peaks: the scene's materials' (prepare)
    // The direction factors of the map's grid lines (height + 1 rows, width + 1 columns):
    // stage 1 evaluates f at grid points, which then need no trigonometry.
    std::vector<LatLongLayout::RowFactor> rowFactors_;
    std::vector<LatLongLayout::ColumnFactor> columnFactors_;
};

}  // namespace rr::two_stage
