#include "techniques/tais/map_guide.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace rr::tais {

namespace {

// The brightness |L| a map accumulates: the mean of the channels' magnitudes, so that a red, a
// green and a blue light of equal power count equally.
double brightness(const Rgb& c) {
    return (std::abs(double(c.r)) + std::abs(double(c.g)) + std::abs(double(c.b))) / 3.0;
}

// u ∈ [a, b) rescaled to [0, 1): the rest of a coordinate that made a discrete choice.
float rescale(float u, float a, float b) {
    return std::min((u - a) / (b - a), kOneMinusEpsilon);
}

}  // namespace

void MapGuide::record(MapKind kind, int cell, Vec2 coordinates, const Rgb& amount,
                      bool isContribution) {
    if (recordCount_ == kMaxRecords) throw std::logic_error("TAIS: too many decisions recorded");
    std::construct_at(&records_[recordCount_++].record,
                      Record{kind, cell, coordinates, amount, isContribution});
}

Ray MapGuide::cameraRay(int x, int y, float* weight) {
    const Camera& camera = scene().camera();
    CameraSample c = drawCameraSample(camera, sample());
    float w = 1;
    if (camera.isThinLens() && maps_.lens) {
        float p;
        c.lens = maps_.lens->warp(c.lens, &p);
        w /= p;
        record(MapKind::Lens, 0, c.lens, Rgb(0.0f));
    }
    if (camera.hasShutterInterval() && maps_.time) {
        float p;
        c.time = maps_.time->warp(c.time, &p);
        w /= p;
        record(MapKind::Time, 0, Vec2(c.time, 0.0f), Rgb(0.0f));
    }
    *weight = w;
    return rr::cameraRay(camera, x, y, c);
}

float MapGuide::flightCoordinate(uint32_t vertex, const Rgb& radiance, float* warpPdf) {
    const float u = sample().get1D(Decision::MediumDistance, vertex);
    if (vertex != 0 || !maps_.scatterDistance) {
        *warpPdf = 1;
        return u;
    }
    const float warped = maps_.scatterDistance->warp(u, warpPdf);
    record(MapKind::ScatterDistance, 0, Vec2(warped, 0.0f), radiance);
    return warped;
}

MapPart MapGuide::mapPart() const {
    return settings_.alphaFollowsEvidence ? MapPart::Credited : MapPart::Whole;
}

float MapGuide::alphaFor(double partMass, double wholeMass) const {
    return float(settings_.alpha * (partMass / wholeMass));
}

MapGuide::SelectionMix MapGuide::selectionMix(uint32_t vertex) const {
    const InvertedMap1D& map = *maps_.lightSelection;
    const int first = lightSelectionCell(int(vertex), 0, maps_.lights);
    const double mass = map.sliceTotal(first, maps_.lights, mapPart());
    return {first, mass, alphaFor(mass, map.sliceTotal(first, maps_.lights))};
}

float MapGuide::selectionPmf(const Light& light, const Vec3& reference, uint32_t vertex) const {
    const float standard = scene().lightSelector().pmf(light, reference);
    if (!steersSelection(vertex)) return standard;
    const SelectionMix mix = selectionMix(vertex);
    const double q =
        mix.alpha > 0
            ? maps_.lightSelection->weight(mix.first + light.index(), mapPart()) / mix.mass
            : 0.0;
    return mix.alpha * float(q) + (1 - mix.alpha) * standard;
}

float MapGuide::pointOnLightPdf(const Light& light, const LightReference& reference,
                                const Vec3& direction, const Vec3& point, uint32_t vertex) const {
    const InvertibleLight* inverse = warpsPointOn(light, vertex);
    Vec2 u;
    if (!inverse || !inverse->invertSample(reference, direction, point, &u)) return 1;
    return maps_.pointOnLight->pdf(u);
}

bool MapGuide::sampleLight(uint32_t vertex, uint32_t repeat, uint32_t count,
                           const LightStandIns* standIns, const LightReference& reference,
                           float time, LightSample* ls, float* pdf, const Light** chosen) {
    lightRecords_ = 0;
    if (!guidesLights(vertex))
        return StandardSampling::sampleLight(vertex, repeat, count, standIns, reference, time, ls,
                                             pdf, chosen);
    const LightSelector& selector = scene().lightSelector();
    const float uSelect = sample().get1D({Decision::LightSelect, vertex, repeat, count});
    Vec2 uPoint = sample().get2D({Decision::LightPoint, vertex, repeat, count});
    const Light* light;
    float selectPmf;
    if (steersSelection(vertex)) {
        // Eq. (2): the map's entries of this vertex with probability α, the scene's selector
        // otherwise.
        const SelectionMix mix = selectionMix(vertex);
        const float a = mix.alpha;
        float unused;
        light = uSelect < a ? scene().lights()[size_t(
                                  maps_.lightSelection->sampleCellIn(
                                      mix.first, maps_.lights, rescale(uSelect, 0, a), mapPart()) -
                                  mix.first)]
                            : selector.select(rescale(uSelect, a, 1), reference.point, &unused);
        if (!light) return false;
        selectPmf = selectionPmf(*light, reference.point, vertex);
        record(MapKind::LightSelection, mix.first + light->index(), Vec2(0.0f, 0.0f), Rgb(0.0f),
               true);
        ++lightRecords_;
    } else {
        light = selector.select(uSelect, reference.point, &selectPmf);
        if (!light) return false;
    }
    float warp = 1;
    if (warpsPointOn(*light, vertex)) {
        uPoint = maps_.pointOnLight->warp(uPoint, &warp);
        record(MapKind::PointOnLight, 0, uPoint, Rgb(0.0f), true);
        ++lightRecords_;
    }
    // The warp is a density on the coordinates: it composes with either sampler's.
    if (!sampleLightOrStandIn(*light, standIns, reference, uPoint, time, ls)) return false;
    *pdf = selectPmf * ls->pdf * warp;  // eq. (3) for the point
    *chosen = light;
    return true;
}

void MapGuide::lightContribution(uint32_t /*vertex*/, const Rgb& contribution) {
    // The records of the light sample just drawn at this vertex (none when standard sampling
    // drew it): the next-event estimator adds each sample's contribution right after drawing
    // it, one sample per vertex.
    for (int i = recordCount_ - lightRecords_; i < recordCount_; ++i)
        records_[i].record.amount = contribution;
    lightRecords_ = 0;
}

float MapGuide::lightPdf(uint32_t vertex, const AreaLight& light, const LightReference& reference,
                         const SurfaceHit& hit) const {
    if (!guidesLights(vertex)) return StandardSampling::lightPdf(vertex, light, reference, hit);
    const Vec3 direction = normalize(hit.position - reference.point);
    return selectionPmf(light, reference.point, vertex) * light.pdf(reference.point, hit) *
           pointOnLightPdf(light, reference, direction, hit.position, vertex);
}

float MapGuide::lightPdf(uint32_t vertex, const Light& light, const LightReference& reference,
                         const Vec3& w) const {
    if (!guidesLights(vertex)) return StandardSampling::lightPdf(vertex, light, reference, w);
    return selectionPmf(light, reference.point, vertex) * light.directionPdf(reference, w) *
           pointOnLightPdf(light, reference, w, reference.point + w, vertex);
}

bool MapGuide::sampleBsdf(uint32_t vertex, const Material& material, const ShadingContext& ctx,
                          const Frame& frame, const Vec3& wo, const Rgb& radiance, BsdfSample* bs) {
    const uint8_t lobes = material.lobes();
    if (maps_.bifurcation && (lobes & kReflection) && (lobes & kTransmission) &&
        int(vertex) < settings_.bifurcationVertices)
        return sampleBifurcation(vertex, material, ctx, wo, radiance, bs);
    const InvertedMap2D* map = (lobes & kSpecular) ? nullptr : directionMap();
    if (!(lobes & kSpecular)) ++bounce_;
    if (!map) return StandardSampling::sampleBsdf(vertex, material, ctx, frame, wo, radiance, bs);
    return sampleDirection(vertex, *map, material, ctx, frame, wo, radiance, bs);
}

bool MapGuide::sampleBifurcation(uint32_t vertex, const Material& material,
                                 const ShadingContext& ctx, const Vec3& wo, const Rgb& radiance,
                                 BsdfSample* bs) {
    // Eq. (2) over {reflect, transmit}: the map's conditional probability of reflecting at
    // this vertex, mixed with the material's own (Fresnel) choice.
    const InvertedMap1D& map = *maps_.bifurcation;
    const int reflectCell = bifurcationCell(int(vertex), true);
    const int transmitCell = bifurcationCell(int(vertex), false);
    const double reflectMass = map.weight(reflectCell, mapPart());
    const double mass = reflectMass + map.weight(transmitCell, mapPart());
    const float a = alphaFor(mass, map.weight(reflectCell) + map.weight(transmitCell));
    const float q = a > 0 ? float(reflectMass / mass) : 0.0f;
    const float fresnel = material.reflectionChoice(ctx, wo);
    const float reflectProbability = a * q + (1 - a) * fresnel;
    const float u = sample().get1D(Decision::BsdfLobe, vertex);
    const bool reflect = u < reflectProbability;
    // A branch the material cannot take carries no light: the path ends with value 0.
    if (reflect ? !(fresnel > 0) : !(fresnel < 1)) return false;
    // The material's own lobe coordinate for the chosen branch (it reflects iff uLobe < F).
    const float uLobe =
        reflect
            ? std::min(fresnel * rescale(u, 0, reflectProbability), std::nextafter(fresnel, 0.0f))
            : std::min(fresnel + (1 - fresnel) * rescale(u, reflectProbability, 1),
                       kOneMinusEpsilon);
    if (!material.sample(ctx, wo, uLobe, sample().get2D(Decision::BsdfDirection, vertex), bs))
        return false;
    const float chosen = reflect ? reflectProbability : 1 - reflectProbability;
    bs->weight *= bs->pdf / chosen;
    bs->pdf = chosen;
    record(MapKind::Bifurcation, bifurcationCell(int(vertex), reflect), Vec2(0.0f, 0.0f), radiance);
    return true;
}

float MapGuide::directionMapTerm(const InvertedMap2D& map, float a, Vec2 cell) const {
    return a > 0 ? a * directionPdfFromMap(map.pdf(cell, mapPart())) : 0.0f;
}

bool MapGuide::sampleDirection(uint32_t vertex, const InvertedMap2D& map, const Material& material,
                               const ShadingContext& ctx, const Frame& frame, const Vec3& wo,
                               const Rgb& radiance, BsdfSample* bs) {
    const float a = alphaFor(map.total(mapPart()), map.total());
    const float u = sample().get1D(Decision::BsdfLobe, vertex);
    const Vec2 uDirection = sample().get2D(Decision::BsdfDirection, vertex);
    Vec2 cell;
    if (u < a) {
        // From the map: a world direction, evaluated through the material.
        float mapPdf;
        cell = map.warp(uDirection, &mapPdf, mapPart());
        const Vec3 wi = frame.toLocal(mapToDirection(cell));
        const Rgb f = material.eval(ctx, wo, wi);
        if (f.isBlack()) return false;  // the sample's value is 0 from here on
        const float pdf = a * directionPdfFromMap(mapPdf) + (1 - a) * material.pdf(ctx, wo, wi);
        bs->wi = wi;
        bs->weight = f * (1.0f / pdf);
        bs->pdf = pdf;
        bs->eta = 1;
        bs->lobe = uint8_t((wi.z * wo.z > 0 ? kReflection : kTransmission) | kDiffuse);
    } else {
        if (!material.sample(ctx, wo, rescale(u, a, 1), uDirection, bs)) return false;
        cell = directionToMap(frame.toWorld(bs->wi));
        const float pdf = directionMapTerm(map, a, cell) + (1 - a) * bs->pdf;
        bs->weight *= bs->pdf / pdf;
        bs->pdf = pdf;
    }
    record(MapKind::ScatterDirection, bounce_ - 1, cell, radiance);
    return true;
}

float MapGuide::bsdfPdf(uint32_t /*vertex*/, const Material& material, const ShadingContext& ctx,
                        const Frame& frame, const Vec3& wo, const Vec3& wi) const {
    const float pdf = material.pdf(ctx, wo, wi);
    const InvertedMap2D* map = (material.lobes() & kSpecular) ? nullptr : directionMap();
    if (!map) return pdf;
    const float a = alphaFor(map->total(mapPart()), map->total());
    return directionMapTerm(*map, a, directionToMap(frame.toWorld(wi))) + (1 - a) * pdf;
}

void MapGuide::splat(const Rgb& value, TemporaryMaps& maps) const {
    for (int i = 0; i < recordCount_; ++i) {
        const Record& r = records_[i].record;
        const double v = settings_.credit == Credit::Path ? brightness(value)
                         : r.isContribution               ? brightness(r.amount)
                                                          : brightness(value - r.amount);
        if (!(v > 0)) continue;
        switch (r.kind) {
            case MapKind::Time:
                maps.time->splat(r.coordinates.x, v);
                break;
            case MapKind::Lens:
                maps.lens->splat(r.coordinates, v);
                break;
            case MapKind::ScatterDistance:
                maps.scatterDistance->splat(r.coordinates.x, v);
                break;
            case MapKind::Bifurcation:
                maps.bifurcation->add(r.cell, v);
                break;
            case MapKind::LightSelection:
                maps.lightSelection->add(r.cell, v);
                break;
            case MapKind::PointOnLight:
                maps.pointOnLight->splat(r.coordinates, v);
                break;
            case MapKind::ScatterDirection:
                maps.scatterDirection[size_t(r.cell)].splat(r.coordinates, v);
                break;
            case MapKind::Count:
                break;
        }
    }
}

}  // namespace rr::tais
