// Mesh import (PLY by io/ply_reader, OBJ through Assimp) and triangle geometry in renders.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/mesh_io.h"
#include "loader/asset_resolver.h"
#include "scene/shapes/triangle_mesh.h"
#include "support/chi2.h"
#include "support/scene_testing.h"
#include "support/scratch.h"

namespace rr::test {
namespace {

namespace fs = std::filesystem;

// A unit cube as ASCII PLY (12 triangles, outward right-hand winding) and as OBJ with quads,
// written by the test so it needs no asset.
fs::path writeCube(const std::string& format) {
    const fs::path dir = scratchDirectory(format);
    const float v[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                           {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                             {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}};
    const fs::path file = dir / ("cube." + format);
    std::ofstream out(file);
    if (format == "ply") {
        out << "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
               "property float z\nelement face 12\nproperty list uchar int vertex_indices\n"
               "end_header\n";
        for (auto& p : v)
            out << p[0] << " " << p[1] << " " << p[2] << "\n";
        for (auto& q : quads)
            out << "3 " << q[0] << " " << q[1] << " " << q[2] << "\n3 " << q[0] << " " << q[2]
                << " " << q[3] << "\n";
    } else {
        for (auto& p : v)
            out << "v " << p[0] << " " << p[1] << " " << p[2] << "\n";
        for (auto& q : quads)
            out << "f " << q[0] + 1 << " " << q[1] + 1 << " " << q[2] + 1 << " " << q[3] + 1
                << "\n";
    }
    return file;
}

class CubeMesh : public ::testing::TestWithParam<std::string> {};

TEST_P(CubeMesh, LoadsTwelveOutwardTriangles) {
    const MeshData mesh = loadMesh(writeCube(GetParam()));
    ASSERT_EQ(mesh.indices.size(), 36u);
    EXPECT_EQ(mesh.positions.size(), 8u);  // shared vertices are joined
    for (size_t t = 0; t < 12; ++t) {
        const Vec3 a = mesh.positions[mesh.indices[3 * t]],
                   b = mesh.positions[mesh.indices[3 * t + 1]],
                   c = mesh.positions[mesh.indices[3 * t + 2]];
        const Vec3 n = cross(b - a, c - a);
        EXPECT_GT(dot(n, (a + b + c) / 3.0f), 0) << "triangle " << t << " faces inward";
    }
    for (const Vec3& n : TriangleMesh::smoothNormals(mesh))
        EXPECT_NEAR(length(n), 1.0f, 1e-5f);
}

// A convex diffuse object under a uniform emitter renders ρL wherever it is seen: the mesh
// version of the analytic sphere test, through Embree's triangle path.
TEST_P(CubeMesh, ConvexMeshUnderUniformEmitterRendersAlbedoTimesL) {
    const std::string file = writeCube(GetParam()).string();
    for (const char* integrator : {"path", "path_mis"}) {
        const LoadedScene scene =
            loadSceneText(std::string(R"({
            "render": {"resolution": [16, 16], "max_depth": -1, "rr_depth": 1},
            "integrator": {"type": ")") +
                          integrator + R"("},
            "camera": {"position": [2.5, 2, 3], "look_at": [0, 0, 0], "fov": 18},
            "shapes": [
              {"type": "sphere", "radius": 20, "emission": {"radiance": 2, "two_sided": true}},
              {"type": "mesh", "file": ")" +
                          file + R"(", "material": {"type": "lambert", "albedo": 0.4},
               "transform": {"rotate": {"axis": [1, 2, 3], "angle": 10}}}]})");
        const TestRender r = renderScene(scene, 64);
        const Estimate e = imageMean(r.film, 0);
        const double z = zThreshold(sidakAlpha(0.01, 4));
        EXPECT_LE(std::abs(e.mean - 0.8), z * e.standardError + 1e-5)
            << integrator << ": " << e.mean << " ± " << e.standardError;
    }
}

INSTANTIATE_TEST_SUITE_P(Formats, CubeMesh, ::testing::Values("ply", "obj"),
                         [](const auto& param) { return param.param; });

// The Stanford meshes, when the asset search path has them (../shared/assets in CI): counts
// and bounding boxes as verified in that directory's README.
TEST(StanfordMeshes, MatchTheirVerifiedStatistics) {
    struct Expected {
        const char* file;
        size_t triangles;
        Vec3 lo, hi;
    };
    const Expected meshes[] = {{"meshes/dragon_vrip_res4.ply",
                                11102,
                                {-0.107585f, 0.052844f, -0.049836f},
                                {0.095236f, 0.196343f, 0.040826f}},
                               {"meshes/stanford-bunny.obj",
                                69451,
                                {-0.09469f, 0.032987f, -0.061874f},
                                {0.061009f, 0.187321f, 0.0588f}}};
    const AssetResolver assets = AssetResolver::standard(TEST_SCENES_DIR);
    int found = 0;
    for (const Expected& m : meshes) {
        const auto path = assets.resolve(m.file);
        if (!path) continue;
        ++found;
        const MeshData mesh = loadMesh(*path);
        EXPECT_EQ(mesh.indices.size() / 3, m.triangles) << m.file;
        Vec3 lo(1e30f), hi(-1e30f);
        for (uint32_t i : mesh.indices) {
            lo = min(lo, mesh.positions[i]);
            hi = max(hi, mesh.positions[i]);
        }
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(lo[k], m.lo[k], 1e-5f) << m.file;
            EXPECT_NEAR(hi[k], m.hi[k], 1e-5f) << m.file;
        }
    }
    if (found == 0)
        GTEST_SKIP() << "no Stanford mesh on the asset search path " << assets.describe();
}

TEST(MeshErrors, UnreadableFileIsAnError) {
    const fs::path file = scratchDirectory() / "broken.ply";
    std::ofstream(file) << "ply\nformat ascii 1.0\nelement vertex 3\nend_header\n1 2\n";
    EXPECT_THROW(loadMesh(file), std::runtime_error);
}

}  // namespace
}  // namespace rr::test
