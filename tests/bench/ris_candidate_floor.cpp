// `make bench`: the floor under a RIS light candidate on RIS fig. 4 (issue 40). The paper's
// variance model fitted on that scene (results/ris/analysis.md) says robust RIS beats light
// sampling by ×1.3 at equal time only if a candidate costs at most 22 ns. This measures what
// an environment-map candidate costs when stripped to its memory traffic, outside the
// renderer's framework, at the first hits of camera rays (dragon and ground, one thread,
// M = 16 candidates per point, the median of 5 passes):
//  - `texel_draw`: the renderer's TexelSampler alone, its draws batched in steps as
//    EnvironmentMap::sampleMany batches them (a texel: no direction, no ĝ, no reservoir);
//  - `alias_candidate`: the cheapest design we know: a Walker–Vose alias table over the
//    probe's texels whose records carry the texel centre's direction and ĝ/p's light factor,
//    all draws of a point prefetched before any is used, one PCG stream per point, then ĝ for
//    the Lambert dragon and a streaming reservoir. It omits what an unbiased candidate also
//    needs: the point within the texel, the light's choice, the decision-indexed random
//    numbers (so it is an optimistic floor);
//  - `polygon_candidate`: the renderer's polygon lights (Arvo's sampler, the view of the
//    fan cached per point), with ĝ and the reservoir: a fifth of fig. 4's candidates.
// One JSON object on stdout, nanoseconds per candidate. Not a test (tests never time).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "io/rgb_image_io.h"
#include "loader/asset_resolver.h"
#include "math/frame.h"
#include "sampling/hash.h"
#include "sampling/texel_sampler.h"
#include "scene/lights/env_layout.h"
#include "support/scene_testing.h"

namespace rr::test {
namespace {

using Clock = std::chrono::steady_clock;
constexpr int kCandidates = 16, kPasses = 5, kPoints = 20000;
constexpr float kProbeScale = 0.4f;  // ris_fig4_dragon_env.json's map scale
const float kLambert = Rgb(0.7f, 0.6f, 0.45f).luminance() / 3.14159265f;  // the dragon's Fs

struct Point {
    Vec3 position, normal;
};

// PCG32 (O'Neill 2014): one stream per shading point.
struct Pcg32 {
    uint64_t state;
    float next() {
        const uint32_t bits = pcgOutput(state);
        state = pcgStep(state);
        return toUnitFloat(bits);
    }
};

// First hits of rays from the camera through the scene file's view (rendering space has the
// camera at its origin).
std::vector<Point> shadingPoints(const Scene& scene) {
    const Frame view(normalize(Vec3(0, 0.65f, 0) - Vec3(0.4f, 2.1f, 3.5f)));
    std::vector<Point> points;
    Pcg32 random{1};
    while (points.size() < kPoints) {
        const Vec3 d(0.56f * (random.next() - 0.5f), 0.42f * (random.next() - 0.5f), 1);
        SurfaceHit hit;
        if (scene.intersect(Ray{Vec3(0.0f), normalize(view.toWorld(d)), 1e30f, 0}, &hit))
            points.push_back({hit.position, hit.shadingNormal});
    }
    return points;
}

// The probe as the scene lights it: texel weights ∝ luminance · dω/(ds dt), values, and each
// texel centre's direction (turned 180° about +Y) and dω/(ds dt).
struct Probe {
    int width = 0, height = 0;
    std::vector<float> weight, jacobian;
    std::vector<Rgb> radiance;
    std::vector<Vec3> direction;
};

Probe readProbe() {
    const auto file = AssetResolver::standard(TEST_SCENES_DIR).resolve("envmaps/galileo_probe.hdr");
    if (!file)
        throw std::runtime_error("envmaps/galileo_probe.hdr is not on the asset search path");
    const RgbImage image = readRgbImage(*file);
    Probe probe{image.width, image.height, {}, {}, {}, {}};
    const ProbeLayout layout;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            Vec3 w(0.0f);
            float jacobian = 0;
            const Vec2 st((x + 0.5f) / image.width, (y + 0.5f) / image.height);
            if (!layout.direction(st, &w, &jacobian)) jacobian = 0;
            const Rgb value = image.pixels[size_t(y) * image.width + x] * kProbeScale;
            probe.radiance.push_back(value);
            probe.jacobian.push_back(jacobian);
            probe.weight.push_back(value.luminance() * jacobian);
            probe.direction.push_back(Vec3(-w.x, w.y, -w.z));
        }
    return probe;
}

// Walker–Vose alias table whose records carry what a candidate reads of its texel.
class AliasProbe {
  public:
    explicit AliasProbe(const Probe& probe) : entries_(probe.weight.size()) {
        const size_t n = entries_.size();
        double total = 0;
        for (float w : probe.weight)
            total += w;
        std::vector<double> scaled(n);
        std::vector<uint32_t> small, large;
        for (size_t i = 0; i < n; ++i) {
            scaled[i] = probe.weight[i] / total * double(n);
            (scaled[i] < 1 ? small : large).push_back(uint32_t(i));
        }
        while (!small.empty() && !large.empty()) {
            const uint32_t s = small.back(), l = large.back();
            small.pop_back();
            entries_[s] = {float(scaled[s]), l};
            scaled[l] -= 1 - scaled[s];
            if (scaled[l] < 1) {
                large.pop_back();
                small.push_back(l);
            }
        }
        for (uint32_t i : large)
            entries_[i] = {1, i};
        for (uint32_t i : small)
            entries_[i] = {1, i};
        for (size_t i = 0; i < n; ++i) {
            // p per solid angle = (w_i / Σw) · n / jacobian_i; the record keeps L / p.
            const double density = probe.weight[i] / total * double(n);
            const float lightOverPdf =
                density > 0 ? float(probe.radiance[i].luminance() * probe.jacobian[i] / density)
                            : 0;
            records_.push_back({probe.direction[i], lightOverPdf});
        }
    }
    struct Record {
        Vec3 direction;
        float lightOverPdf;
    };
    uint32_t column(float u) const {
        return std::min(uint32_t(u * float(entries_.size())), uint32_t(entries_.size() - 1));
    }
    const void* entryAddress(uint32_t i) const { return &entries_[i]; }
    uint32_t resolve(uint32_t i, float u) const {
        return u < entries_[i].probability ? i : entries_[i].alias;
    }
    const Record& record(uint32_t i) const { return records_[i]; }

  private:
    struct Entry {
        float probability;
        uint32_t alias;
    };
    std::vector<Entry> entries_;
    std::vector<Record> records_;
};

// Nanoseconds per candidate of one pass of `perPoint` over all points, median over passes.
template <typename PerPoint>
double nanosecondsPerCandidate(const std::vector<Point>& points, PerPoint perPoint) {
    std::vector<double> passes;
    double sink = 0;
    for (int pass = 0; pass < kPasses; ++pass) {
        const Clock::time_point start = Clock::now();
        for (size_t k = 0; k < points.size(); ++k)
            sink += perPoint(points[k], Pcg32{mixKey(k, uint64_t(pass))});
        passes.push_back(std::chrono::duration<double, std::nano>(Clock::now() - start).count() /
                         double(points.size() * kCandidates));
    }
    std::nth_element(passes.begin(), passes.begin() + kPasses / 2, passes.end());
    if (sink == -1)  // keeps the work observable
        std::puts("");
    return passes[kPasses / 2];
}

// A streaming reservoir over candidates' weights: returns Σw plus the kept direction's x.
struct Reservoir {
    float total = 0;
    Vec3 kept = Vec3(0.0f);
    void add(float weight, const Vec3& direction, float u) {
        total += weight;
        kept = u * total < weight ? direction : kept;
    }
    double result() const { return double(total) + kept.x; }
};

double texelDraws(const std::vector<Point>& points, const TexelSampler& texels) {
    return nanosecondsPerCandidate(points, [&](const Point&, Pcg32 random) {
        std::array<TexelSampler::Ticket, kCandidates> tickets;
        for (TexelSampler::Ticket& t : tickets) {
            const float ux = random.next();
            texels.begin(Vec2(ux, random.next()), &t);
        }
        for (TexelSampler::Ticket& t : tickets)
            texels.locate(&t);
        double sum = 0;
        for (const TexelSampler::Ticket& t : tickets) {
            TexelSampler::Draw draw;
            if (texels.finish(t, &draw)) sum += draw.density;
        }
        return sum;
    });
}

double aliasCandidates(const std::vector<Point>& points, const AliasProbe& probe) {
    return nanosecondsPerCandidate(points, [&](const Point& point, Pcg32 random) {
        std::array<uint32_t, kCandidates> texel;
        for (uint32_t& i : texel) {
            i = probe.column(random.next());
            __builtin_prefetch(probe.entryAddress(i));
        }
        for (uint32_t& i : texel) {
            i = probe.resolve(i, random.next());
            __builtin_prefetch(&probe.record(i));
        }
        Reservoir reservoir;
        for (uint32_t i : texel) {
            const AliasProbe::Record& r = probe.record(i);
            const float cosine = std::max(0.0f, dot(point.normal, r.direction));
            reservoir.add(kLambert * cosine * r.lightOverPdf, r.direction, random.next());
        }
        return reservoir.result();
    });
}

double polygonCandidates(const std::vector<Point>& points, const Scene& scene) {
    std::vector<const Light*> polygons;
    for (const Light* light : scene.lights())
        if (!light->isInfinite()) polygons.push_back(light);
    return nanosecondsPerCandidate(points, [&](const Point& point, Pcg32 random) {
        Reservoir reservoir;
        for (int m = 0; m < kCandidates; ++m) {
            const Light& light = *polygons[size_t(random.next() * float(polygons.size()))];
            const float u0 = random.next();
            LightSample s;
            if (!light.sample(LightReference(point.position, point.normal), Vec2(u0, random.next()),
                              0, &s))
                continue;
            const float cosine = std::max(0.0f, dot(point.normal, s.direction));
            reservoir.add(kLambert * cosine * s.radiance.luminance() / s.pdf, s.direction,
                          random.next());
        }
        return reservoir.result();
    });
}

}  // namespace
}  // namespace rr::test

int main() {
    using namespace rr;
    using namespace rr::test;
    const LoadedScene loaded = loadSceneFile("ris_fig4_dragon_env.json");
    const std::vector<Point> points = shadingPoints(*loaded.scene);
    const Probe probe = readProbe();
    const TexelSampler texels(probe.weight, probe.radiance, probe.width, probe.height);
    const AliasProbe alias(probe);
    std::printf(
        "{\"candidates_per_point\": %d, \"texel_draw\": %.1f, \"alias_candidate\": %.1f, "
        "\"polygon_candidate\": %.1f}\n",
        kCandidates, texelDraws(points, texels), aliasCandidates(points, alias),
        polygonCandidates(points, *loaded.scene));
}
