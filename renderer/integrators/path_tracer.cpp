#include "integrators/path_tracer.h"

#include "config/config_error.h"
#include "integrators/light_sample_estimator.h"
#include "integrators/path_walk.h"

namespace rr {

std::unique_ptr<PathTracer> PathTracer::withoutNextEventEstimation(const PathSettings& settings) {
    return std::unique_ptr<PathTracer>(
        new PathTracer("path", settings, std::make_unique<ScatteringOnlyEstimator>()));
}

void PathSettings::addTo(nlohmann::json* parameters) const {
    (*parameters)["max_depth"] = maxDepth;
    (*parameters)["rr_depth"] = rrDepth;
    if (rrSurvival > 0)
        (*parameters)["rr_survival"] = rrSurvival;
    else
        (*parameters)["rr_threshold"] = rrThreshold;
}

nlohmann::json PathTracer::parameters() const {
    nlohmann::json p = {{"type", name()}};
    settings_.addTo(&p);
    if (nee_->lightSamples() > 0) p["estimator"] = nee_->parameters();
    return p;
}

void PathTracer::prepare(const Scene& scene) {
    if (scene.hasMedia() && !nee_->worksInMedia())
        throw ConfigError("/integrator/estimator/type",
                          "estimator '" + nee_->name() +
                              "' samples directions and cannot render participating media");
    nee_->prepare(scene, "/integrator/estimator");
}

Rgb PathTracer::estimate(const Scene& scene, int x, int y, const PixelSample& sample,
                         RayCounters& rays) const {
    StandardSampling standard(scene, sample);
    return tracePath(scene, standard, x, y, settings_, *nee_, rays, records_.slot(x, y));
}

}  // namespace rr
