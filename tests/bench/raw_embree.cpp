// `make bench`: raw Embree's ray throughput on the bench dragon, the yardstick for the
// renderer's. dragon_bench.json's geometry (the dragon, 202,520 triangles, and its quads: the
// ground and the light) as triangles in one Embree scene of the renderer's build quality,
// traced with rtcIntersect1 / rtcOccluded1 on 2 threads:
//  - camera rays through jittered pixel positions of the scene's camera;
//  - bounce rays from the camera rays' hits, cosine-distributed about the geometric normal;
//  - shadow rays from those hits to uniform points on the scene's emitting quad.
// Rays are made before the clock starts; each kind is traced kPasses times and the median
// pass is reported, as one JSON object on stdout: {"camera", "bounce", "shadow"} in Mrays/s.
// Not a test (tests never time).
#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

#include "io/mesh_io.h"
#include "loader/asset_resolver.h"
#include "math/frame.h"
#include "sampling/hash.h"
#include "sampling/warps.h"
#include "support/scene_testing.h"

namespace rr::test {
namespace {

constexpr int kThreads = 2, kPasses = 5, kRaysPerHit = 4;

struct Quad {
    Vec3 corner, u, v;
    bool emits;
};

// The scene file's quads, read from its JSON (the built Scene keeps no quads as such).
std::vector<Quad> quadsOf(const std::filesystem::path& sceneFile) {
    const nlohmann::json scene = nlohmann::json::parse(std::ifstream(sceneFile));
    auto vec = [](const nlohmann::json& a) { return Vec3(a[0], a[1], a[2]); };
    std::vector<Quad> quads;
    for (const nlohmann::json& shape : scene.at("shapes"))
        if (shape.at("type") == "quad")
            quads.push_back({vec(shape.at("corner")), vec(shape.at("edge_u")),
                             vec(shape.at("edge_v")), shape.contains("emission")});
    return quads;
}

struct BenchRay {
    Vec3 origin, direction;
    float tMax;
};

float uniform(uint64_t key, uint64_t index) {
    return toUnitFloat(pcgOutput(mixKey(key, index)));
}

RTCScene buildScene(RTCDevice device, const MeshData& dragon, const std::vector<Quad>& quads) {
    RTCScene scene = rtcNewScene(device);
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    const size_t vertices = dragon.positions.size() + 4 * quads.size(),
                 triangles = dragon.indices.size() / 3 + 2 * quads.size();
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertices));
    auto* t = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangles));
    size_t n = 0;
    auto addVertex = [&](const Vec3& p) {
        v[3 * n] = p.x, v[3 * n + 1] = p.y, v[3 * n + 2] = p.z;
        ++n;
    };
    for (const Vec3& p : dragon.positions)
        addVertex(p);
    t = std::copy(dragon.indices.begin(), dragon.indices.end(), t);
    for (const Quad& quad : quads) {
        const unsigned q = unsigned(n);
        for (const Vec3& p : {quad.corner, quad.corner + quad.u, quad.corner + quad.u + quad.v,
                              quad.corner + quad.v})
            addVertex(p);
        const unsigned corners[6] = {q, q + 1, q + 2, q, q + 2, q + 3};
        t = std::copy(corners, corners + 6, t);
    }
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    rtcCommitScene(scene);
    return scene;
}

RTCRayHit toRayHit(const BenchRay& r) {
    RTCRayHit rh{};
    rh.ray.org_x = r.origin.x, rh.ray.org_y = r.origin.y, rh.ray.org_z = r.origin.z;
    rh.ray.dir_x = r.direction.x, rh.ray.dir_y = r.direction.y, rh.ray.dir_z = r.direction.z;
    rh.ray.tnear = 0;
    rh.ray.tfar = r.tMax;
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

// The hits of the camera rays: the points bounce and shadow rays leave from.
struct Hit {
    Vec3 point, normal;  // normal faces the camera ray's origin
};

std::vector<Hit> firstHits(RTCScene scene, const std::vector<BenchRay>& rays) {
    std::vector<Hit> hits;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (const BenchRay& r : rays) {
        RTCRayHit rh = toRayHit(r);
        rtcIntersect1(scene, &context, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
        Vec3 n = normalize(Vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
        if (dot(n, r.direction) > 0) n = -n;
        hits.push_back({r.origin + r.direction * rh.ray.tfar + n * 1e-4f, n});
    }
    return hits;
}

// Mrays/s of tracing `rays` on kThreads threads: the median of kPasses passes.
double throughput(RTCScene scene, const std::vector<BenchRay>& rays, bool shadow) {
    tbb::task_arena arena(kThreads);
    std::vector<double> seconds;
    for (int pass = 0; pass < kPasses; ++pass) {
        const auto start = std::chrono::steady_clock::now();
        arena.execute([&] {
            tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 1024), [&](auto range) {
                RTCIntersectContext context;
                rtcInitIntersectContext(&context);
                for (size_t i = range.begin(); i < range.end(); ++i) {
                    RTCRayHit rh = toRayHit(rays[i]);
                    if (shadow)
                        rtcOccluded1(scene, &context, &rh.ray);
                    else
                        rtcIntersect1(scene, &context, &rh);
                }
            });
        });
        seconds.push_back(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    std::nth_element(seconds.begin(), seconds.begin() + kPasses / 2, seconds.end());
    return double(rays.size()) / seconds[kPasses / 2] * 1e-6;
}

int run() {
    const LoadedScene loaded = loadSceneFile("dragon_bench.json");
    const Camera& camera = loaded.scene->camera();
    const auto mesh =
        AssetResolver::standard(TEST_SCENES_DIR).resolve("meshes/dragon_vrip_res2.ply");
    if (!mesh) throw std::runtime_error("meshes/dragon_vrip_res2.ply not found");
    const MeshData dragon = loadMesh(*mesh);

    const std::vector<Quad> quads =
        quadsOf(std::filesystem::path(TEST_SCENES_DIR) / "dragon_bench.json");
    const auto light =
        std::find_if(quads.begin(), quads.end(), [](const Quad& q) { return q.emits; });
    if (light == quads.end()) throw std::runtime_error("dragon_bench.json has no emitting quad");

    RTCDevice device = rtcNewDevice(nullptr);
    RTCScene scene = buildScene(device, dragon, quads);

    const int width = loaded.render.width, height = loaded.render.height;
    std::vector<BenchRay> cameraRays;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const uint64_t key = hashKeys(uint64_t(x), uint64_t(y));
            const Ray r = camera.generateRay(Vec2(x + uniform(key, 0), y + uniform(key, 1)),
                                             Vec2(0.5f, 0.5f), 0);
            // The bench's scene is in the file's coordinates; the camera in rendering space.
            cameraRays.push_back(
                {r.origin + toFloat(loaded.scene->renderOrigin()), r.direction, r.tMax});
        }
    const std::vector<Hit> hits = firstHits(scene, cameraRays);
    std::vector<BenchRay> bounceRays, shadowRays;
    for (size_t i = 0; i < hits.size(); ++i)
        for (int k = 0; k < kRaysPerHit; ++k) {
            const uint64_t key = hashKeys(i, uint64_t(k), 7);
            const Vec3 local = squareToCosineHemisphere(Vec2(uniform(key, 0), uniform(key, 1)));
            bounceRays.push_back({hits[i].point, Frame(hits[i].normal).toWorld(local),
                                  std::numeric_limits<float>::infinity()});
            const Vec3 target =
                light->corner + light->u * uniform(key, 2) + light->v * uniform(key, 3);
            const Vec3 toLight = target - hits[i].point;
            const float distance = length(toLight);
            shadowRays.push_back({hits[i].point, toLight / distance, distance * 0.999f});
        }

    const double cameraRate = throughput(scene, cameraRays, false);
    const double bounceRate = throughput(scene, bounceRays, false);
    const double shadowRate = throughput(scene, shadowRays, true);
    std::printf("{\"camera\": %.2f, \"bounce\": %.2f, \"shadow\": %.2f, \"threads\": %d}\n",
                cameraRate, bounceRate, shadowRate, kThreads);
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
    return 0;
}

}  // namespace
}  // namespace rr::test

int main() {
    try {
        return rr::test::run();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
