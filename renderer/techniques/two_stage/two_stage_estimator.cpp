#include "techniques/two_stage/two_stage_estimator.h"

#include <algorithm>
#include <cmath>

#include "config/config_error.h"
#include "scene/lights/environment_map.h"
#include "techniques/two_stage/hierarchical_warp.h"
#include "techniques/two_stage/partition.h"
#include "techniques/two_stage/two_stage_decisions.h"

namespace rr::two_stage {

namespace {

// The map-frame direction at texel-space point (x, y) of a lat-long map.
Vec3 mapDirection(const EnvironmentMap& map, const LatLongLayout& layout, double x, double y) {
    Vec3 w;
    float jacobian;
    layout.direction({float(x / map.width()), float(y / map.height())}, &w, &jacobian);
    return w;
}

// f = luminance(fr·|cos θ|) at the map's grid points, seen from a shading point; the grid
// points' directions from the tabulated factors of their row and column.
class SurfaceFactor final : public ProductFactor {
  public:
    SurfaceFactor(const ShadingPoint& point, const EnvironmentMap& map,
                  const std::vector<LatLongLayout::RowFactor>& rows,
                  const std::vector<LatLongLayout::ColumnFactor>& columns)
        : point_(point), map_(map), rows_(rows), columns_(columns) {}
    double at(int x, int y) const override {
        const Vec3 local = LatLongLayout::fromFactors(rows_[size_t(y)], columns_[size_t(x)]);
        return double(point_.scattering(map_.toWorld().toWorld(local)).luminance());
    }

  private:
    const ShadingPoint& point_;
    const EnvironmentMap& map_;
    const std::vector<LatLongLayout::RowFactor>& rows_;
    const std::vector<LatLongLayout::ColumnFactor>& columns_;
};

// The map's texel-space position of world direction `w`.
void mapPosition(const EnvironmentMap& map, const Vec3& w, double* x, double* y) {
    const Vec2 st = map.layout().imagePoint(map.toWorld().toLocal(w));
    *x = double(st.x) * map.width();
    *y = double(st.y) * map.height();
}

int nearestGrid(double v) {
    return static_cast<int>(std::lround(v));
}

}  // namespace

double SampleMoments::standardDeviation() const {
    if (count < 2) return 0;
    const double mean = sum / count;
    return std::sqrt(std::max(0.0, (sumSquares - mean * sum) / (count - 1)));
}

nlohmann::json TwoStageEstimator::parameters() const {
    nlohmann::json p = readParameters();
    p["samples"] = settings_.samples;
    p["splits"] = settings_.splitsFor(settings_.samples);
    p["peaks"] = settings_.peaks == PeakSource::Analytic ? "analytic" : "bsdf";
    return p;
}

uint32_t TwoStageEstimator::peakSamples(uint32_t samples) const {
    return settings_.peaks == PeakSource::BsdfSamples ? std::max(1u, samples / 4) : 0;
}

uint32_t TwoStageEstimator::decisionRepeats() const {
    return std::max(settings_.samples, peakSamples(settings_.samples));
}

void TwoStageEstimator::prepare(const Scene& scene, const std::string& pointer) {
    const auto lights = scene.lights();
    const EnvironmentMap* map =
        lights.size() == 1 ? dynamic_cast<const EnvironmentMap*>(lights[0]) : nullptr;
    if (!map)
        throw ConfigError(pointer + "/type",
                          "two_stage samples an environment map: the scene's lights must be "
                          "exactly one environment map (\"file\"), it has " +
                              std::to_string(lights.size()) + " light(s) of other kinds");
    if (!dynamic_cast<const LatLongLayout*>(&map->layout()))
        throw ConfigError(pointer + "/type",
                          "two_stage works on a latitude-longitude map: give the probe's light "
                          "\"latlong_width\" to resample it at load");
    if (settings_.peaks == PeakSource::Analytic) {
        peakSources_ = LobePeakSources(scene.materials());
        for (const auto& material : scene.materials())
            if (!peakSources_.of(*material))
                throw ConfigError(pointer + "/peaks",
                                  "\"analytic\" splits at the materials' own lobe peaks, and a "
                                  "material of the scene does not give its peaks: use \"bsdf\", "
                                  "which finds peaks by sampling the BSDF");
    }
    attach(*map);
}

void TwoStageEstimator::attach(const EnvironmentMap& map) {
    map_ = &map;
    layout_ = &dynamic_cast<const LatLongLayout&>(map.layout());
    table_ = SummedAreaTable(map);
    // The same image points as mapDirection() at grid points.
    rowFactors_.resize(size_t(map.height()) + 1);
    for (size_t y = 0; y < rowFactors_.size(); ++y)
        rowFactors_[y] = LatLongLayout::rowFactor(float(double(y) / map.height()));
    columnFactors_.resize(size_t(map.width()) + 1);
    for (size_t x = 0; x < columnFactors_.size(); ++x)
        columnFactors_[x] = LatLongLayout::columnFactor(float(double(x) / map.width()));
}

bool TwoStageEstimator::partitionAt(ShadingPoint& point, uint32_t samples,
                                    Partition* partition) const {
    ScatteringShape shape;
    const bool analytic = settings_.peaks == PeakSource::Analytic;
    if (!point.scatteringShape(analytic ? &peakSources_ : nullptr, &shape)) return false;
    const int height = map_->height();
    double xn, yn;
    mapPosition(*map_, shape.normal, &xn, &yn);
    PartitionRequest request;
    // The root (Fig. 3): the rows of the hemisphere around the normal, every row for
    // materials that also transmit.
    request.rootY0 = shape.transmits ? 0 : std::max(0, int(std::floor(yn - height / 2.0)));
    request.rootY1 = shape.transmits ? height : std::min(height, int(std::ceil(yn + height / 2.0)));
    request.normalX = nearestGrid(xn);
    request.normalY = nearestGrid(yn);
    request.splits = settings_.splitsFor(samples);
    if (analytic)
        for (int i = 0; i < shape.peaks.count; ++i) {
            double x, y;
            mapPosition(*map_, shape.peaks.directions[size_t(i)], &x, &y);
            request.addPeak(nearestGrid(x), nearestGrid(y));
        }
    const SurfaceFactor f(point, *map_, rowFactors_, columnFactors_);
    partition->build(table_, request, f);
    const uint32_t searches = peakSamples(samples);
    for (uint32_t k = 0; k < searches; ++k) {
        Vec3 wi;
        float pdf;
        if (!point.sampleScattering(point.decide1D(kPeakLobe, k, searches),
                                    point.decide2D(kPeakDirection, k, searches), &wi, &pdf))
            continue;
        double x, y;
        mapPosition(*map_, wi, &x, &y);
        partition->offerPeak(nearestGrid(x), nearestGrid(y));
    }
    partition->finish();
    return true;
}

bool TwoStageEstimator::warpDirection(const Partition& partition, double s, double t,
                                      Vec3* direction, int* col, int* row, double* pdf) const {
    WarpedPoint p;
    if (!warp(partition, table_, s, t, &p)) return false;
    const int width = map_->width(), height = map_->height();
    *col = std::clamp(static_cast<int>(p.x), 0, width - 1);
    *row = std::clamp(static_cast<int>(p.y), 0, height - 1);
    // The density per unit image area over dω/(ds dt): the appendix's last line divides
    // (with the printed multiplication a constant L·f would not give 1/4π).
    const double jacobian = layout_->jacobian({float(p.x / width), float(p.y / height)});
    if (!(jacobian > 0)) return false;
    *pdf = p.density / jacobian;
    *direction = normalize(map_->toWorld().toWorld(mapDirection(*map_, *layout_, p.x, p.y)));
    return std::isfinite(*pdf);
}

double TwoStageEstimator::pdf(const Partition& partition, const Vec3& direction) const {
    double x, y;
    mapPosition(*map_, direction, &x, &y);
    const double jacobian =
        layout_->jacobian({float(x / map_->width()), float(y / map_->height())});
    if (!(jacobian > 0)) return 0;
    return densityAt(partition, table_, x, y) / jacobian;
}

void TwoStageEstimator::estimate(ShadingPoint& point, uint32_t samples,
                                 SampleMoments* moments) const {
    // Per thread, reused: no allocation once the first shading points have grown it.
    thread_local Partition partition;
    if (!partitionAt(point, samples, &partition)) return;
    for (uint32_t i = 0; i < samples; ++i) {
        const Rgb value = sample(point, partition, i, samples);
        if (moments) moments->add(value.luminance());
        // Eq. (2): (1/N) Σ Le·fr·|cos θ|·V / p.
        if (!value.isBlack()) point.add(value / float(samples));
    }
}

Rgb TwoStageEstimator::sample(ShadingPoint& point, const Partition& partition, uint32_t i,
                              uint32_t samples) const {
    const Vec2 u = point.decide2D(Decision::LightPoint, i, samples);
    Vec3 wi;
    int col, row;
    double pdf;
    if (!warpDirection(partition, u.x, u.y, &wi, &col, &row, &pdf)) return Rgb(0.0f);
    const Rgb& le = map_->texel(col, row);
    if (le.isBlack()) return Rgb(0.0f);
    const Rgb f = point.scattering(wi);
    if (f.isBlack()) return Rgb(0.0f);
    LightSample ls;
    map_->aim(point.position(), wi, &ls);
    float survival;
    const Rgb tr = point.visibility(ls, true, &survival);
    if (tr.isBlack()) return Rgb(0.0f);
    return point.contribution(f, le, tr, 1.0f, float(pdf));
}

}  // namespace rr::two_stage
