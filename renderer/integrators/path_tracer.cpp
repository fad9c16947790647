#include "integrators/path_tracer.h"

#include "config/config_error.h"

namespace rr {

nlohmann::json PathTracerBase::parameters() const {
    nlohmann::json p = {{"type", name()}};
    settings_.addTo(&p);
    if (nee_->lightSamples() > 0) p["estimator"] = nee_->parameters();
    return p;
}

void PathTracerBase::prepare(const Scene& scene) {
    if (scene.hasMedia() && !nee_->worksInMedia())
        throw ConfigError("/integrator/estimator/type",
                          "estimator '" + nee_->name() +
                              "' samples directions and cannot render participating media");
    nee_->prepare(scene, "/integrator/estimator");
}

template class PathTracer<StandardSampling>;

}  // namespace rr
