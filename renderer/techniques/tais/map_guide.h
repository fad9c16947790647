// The decisions of one TAIS path sample (Cline et al. 2008, Algorithm 1, lines 6–17), as a
// guide for the path walk: StandardSampling (integrators/standard_sampling.h, which documents
// each member) with the members whose decisions a map steers hidden. Which decision each map
// steers:
//  - time and lens: the camera's; scatter distance: the camera ray's free flight (vertex 0);
//  - point on light: next-event estimation at the first scattering vertex (vertex 0), the one
//    a pixel's neighbours share most; light selection: there, and at the next vertices when
//    lightSelectionVertices > 1, each vertex from its own entries;
//  - bifurcation: reflect or transmit at every vertex v < bifurcationVertices;
//  - scatter direction: the first (and second) surface vertex whose material has no specular
//    lobe (media vertices sample their phase function as usual).
// Preimage maps warp the decision's coordinates and divide the sample by p_map (eq. 3). World
// maps choose with probability α from the map and otherwise by standard sampling, with the
// mixture density of eq. (2) in the sample's weight and in every MIS weight that involves the
// decision, so the estimator stays unbiased. By default they draw from the map's credited part
// only, with α scaled by that part's share of the decision's mass
// (TaisSettings::alphaFollowsEvidence; fixed before the pixel's samples, as the maps are). A
// point-on-light map warps only lights that can invert their sampling (scene/invertible_light.h),
// since MIS must find the map density of a point that BSDF sampling hit; other lights are
// sampled as usual.
//
// The guide remembers where each decision fell; splat() then adds the sample to the pixel's
// temporary maps (line 19) at those coordinates.
#pragma once

#include <array>
#include <span>

#include "integrators/standard_sampling.h"
#include "scene/invertible_light.h"
#include "techniques/tais/pixel_maps.h"
#include "techniques/tais/tais_settings.h"

namespace rr::tais {

class MapGuide : public StandardSampling {
  public:
    // `invertible[i]`: scene light i's inverse of its sampling, or nullptr when it has none.
    MapGuide(const Scene& scene, const PixelSample& sample, const PixelMaps& maps,
             const TaisSettings& settings, std::span<const InvertibleLight* const> invertible)
        : StandardSampling(scene, sample),
          maps_(maps),
          settings_(settings),
          invertible_(invertible) {}
    // The guide keeps a reference to the sample: a temporary would dangle.
    MapGuide(const Scene& scene, const PixelSample&& sample, const PixelMaps& maps,
             const TaisSettings& settings,
             std::span<const InvertibleLight* const> invertible) = delete;

    // The camera ray through pixel (x, y), its time and lens coordinates warped by their maps;
    // *weight = 1 / (p_time · p_lens).
    Ray cameraRay(int x, int y, float* weight);

    float flightCoordinate(uint32_t vertex, const Rgb& radiance, float* warpPdf);
    bool sampleLight(uint32_t vertex, uint32_t repeat, uint32_t count,
                     const LightStandIns* standIns, const LightReference& reference, float time,
                     LightSample* ls, float* pdf, const Light** chosen);
    // Not StandardSampling's batch, which would bypass the maps: one draw at a time.
    void sampleLights(uint32_t vertex, std::span<const uint32_t> repeats, uint32_t count,
                      const LightStandIns* standIns, const LightReference& reference, float time,
                      LightDraw* out) = delete;
    void lightContribution(uint32_t vertex, const Rgb& contribution);
    float lightPdf(uint32_t vertex, const AreaLight& light, const LightReference& reference,
                   const SurfaceHit& hit) const;
    float lightPdf(uint32_t vertex, const Light& light, const LightReference& reference,
                   const Vec3& w) const;
    bool sampleBsdf(uint32_t vertex, const Material& material, const ShadingContext& ctx,
                    const Frame& frame, const Vec3& wo, const Rgb& radiance, BsdfSample* bs);
    float bsdfPdf(uint32_t vertex, const Material& material, const ShadingContext& ctx,
                  const Frame& frame, const Vec3& wo, const Vec3& wi) const;

    // Algorithm 1, line 19: the sample's value L(x) added to the temporary maps at the
    // coordinates of its decisions, credited as settings.credit says.
    void splat(const Rgb& value, TemporaryMaps& maps) const;

    // The most decisions one path records: bifurcation and light-selection vertices (one light
    // sample per vertex: TaisIntegrator's next-event estimator takes one), a point on a light,
    // and the time, lens, scatter-distance and two scatter-direction maps.
    static constexpr int kMaxBifurcationVertices = 32;
    static constexpr int kMaxLightSelectionVertices = 8;
    static constexpr int kMaxRecords = kMaxBifurcationVertices + kMaxLightSelectionVertices + 6;

  private:
    // Where one decision fell. `amount` is the path's radiance before the decision (the
    // value credited is what came after it), or for a light sample its own contribution.
    struct Record {
        MapKind kind;
        int cell;  // discrete maps: the entry; scatter direction: the bounce
        Vec2 coordinates;
        Rgb amount;
        bool isContribution;
    };
    // A record's storage, left uninitialised: a guide lives for one sample and record() writes
    // every field before anything reads it, so zeroing all the slots (1.4 KiB) per sample,
    // which a plain array of Records does, is waste.
    union RecordSlot {
        RecordSlot() {}
        Record record;
    };
    void record(MapKind kind, int cell, Vec2 coordinates, const Rgb& amount,
                bool isContribution = false);

    bool steersSelection(uint32_t vertex) const {
        return maps_.lightSelection && int(vertex) < settings_.lightSelectionVertices;
    }
    bool steersPointOnLight(uint32_t vertex) const { return vertex == 0 && maps_.pointOnLight; }
    bool guidesLights(uint32_t vertex) const {
        return steersSelection(vertex) || steersPointOnLight(vertex);
    }
    // This light's inverse when its point at `vertex` is warped (steered there, and
    // invertible); nullptr otherwise.
    const InvertibleLight* warpsPointOn(const Light& light, uint32_t vertex) const {
        return steersPointOnLight(vertex) ? invertible_[size_t(light.index())] : nullptr;
    }
    // Eq. (2) for one decision of a world map: the part of the map drawn from and α. With the
    // evidence weighting (the default), the credited part, and α times that part's share of
    // the decision's mass (`partMass` of `wholeMass`): the uncredited, even share is left to
    // standard sampling. Otherwise the whole map and α (partMass = wholeMass).
    MapPart mapPart() const;
    float alphaFor(double partMass, double wholeMass) const;
    // The map's share a · p_map(cell) of the scatter-direction mixture (0 when a = 0, where
    // the credited part may be empty).
    float directionMapTerm(const InvertedMap2D& map, float a, Vec2 cell) const;
    // The light choice at `vertex`: its slice of the map (from cell `first`), the mass of the
    // part drawn from, and α.
    struct SelectionMix {
        int first;
        double mass;
        float alpha;
    };
    SelectionMix selectionMix(uint32_t vertex) const;
    // Eq. (2) for the light-selection map at `vertex`: α q_v(light) + (1 − α) p_selector(light).
    float selectionPmf(const Light& light, const Vec3& reference, uint32_t vertex) const;
    // The point-on-light map's density at the coordinates of `point` (1 when not warped).
    float pointOnLightPdf(const Light& light, const LightReference& reference,
                          const Vec3& direction, const Vec3& point, uint32_t vertex) const;
    const InvertedMap2D* directionMap() const {
        return bounce_ < int(maps_.scatterDirection.size()) ? &maps_.scatterDirection[bounce_]
                                                            : nullptr;
    }
    bool sampleBifurcation(uint32_t vertex, const Material& material, const ShadingContext& ctx,
                           const Vec3& wo, const Rgb& radiance, BsdfSample* bs);
    bool sampleDirection(uint32_t vertex, const InvertedMap2D& map, const Material& material,
                         const ShadingContext& ctx, const Frame& frame, const Vec3& wo,
                         const Rgb& radiance, BsdfSample* bs);

    const PixelMaps& maps_;
    const TaisSettings& settings_;
    std::span<const InvertibleLight* const> invertible_;

    int bounce_ = 0;  // non-specular surface vertices so far
    std::array<RecordSlot, kMaxRecords> records_;
    int recordCount_ = 0;
    int lightRecords_ = 0;  // records of the current light sample, awaiting its contribution
};

}  // namespace rr::tais
