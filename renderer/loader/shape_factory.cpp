#include <cmath>

#include "config/type_table.h"
#include "io/mesh_io.h"
#include "loader/asset_files.h"
#include "loader/factories.h"
#include "scene/shapes/disk.h"
#include "scene/shapes/polygon.h"
#include "scene/shapes/quad.h"
#include "scene/shapes/sphere.h"
#include "scene/shapes/triangle_mesh.h"

namespace rr {

namespace {

float similarityScale(ObjectReader& j, const Transform& t, const char* shape) {
    float scale = 1;
    if (!t.isSimilarity(&scale))
        j.fail("transform",
               std::string("a ") + shape + " takes only rotation, uniform scale and translation");
    return scale;
}

std::unique_ptr<Shape> makeSphere(ObjectReader& j, const Transform& t, const AssetResolver&) {
    const Vec3d center = j.getPoint("center", Vec3d{});
    const float radius = j.getFloat("radius", Range::positive());
    const float scale = similarityScale(j, t, "sphere");
    // The transform's rotation turns the sphere's own axes (the poles of its uv).
    Frame orientation;
    orientation.s = normalize(t.vector(Vec3(1, 0, 0)));
    orientation.t = normalize(t.vector(Vec3(0, 1, 0)));
    orientation.n = normalize(t.vector(Vec3(0, 0, 1)));
    return std::make_unique<Sphere>(t.point(center), radius * scale, orientation);
}

std::unique_ptr<Shape> makeQuad(ObjectReader& j, const Transform& t, const AssetResolver&) {
    const Vec3 corner = t.point(j.getPoint("corner"));
    const Vec3 edgeU = t.vector(j.getVec3("edge_u"));
    const Vec3 edgeV = t.vector(j.getVec3("edge_v"));
    const float area = length(cross(edgeU, edgeV));
    if (!(area > 1e-12f * (lengthSquared(edgeU) + lengthSquared(edgeV))) || !(area > 0))
        j.fail("edge_v", "edges are parallel or zero: the quad has zero area");
    return std::make_unique<Quad>(corner, edgeU, edgeV);
}

std::unique_ptr<Shape> makeDisk(ObjectReader& j, const Transform& t, const AssetResolver&) {
    const Vec3d center = j.getPoint("center", Vec3d{});
    const Vec3 normal = j.getVec3("normal", Vec3(0, 0, 1));
    const float radius = j.getFloat("radius", Range::positive());
    if (!(length(normal) > 0)) j.fail("normal", "expected a non-zero vector");
    const float scale = similarityScale(j, t, "disk");
    return std::make_unique<Disk>(t.point(center), normalize(t.normal(normal)), radius * scale);
}

std::unique_ptr<Shape> makePolygon(ObjectReader& j, const Transform& t, const AssetResolver&) {
    std::vector<Vec3> vertices;
    for (const Vec3d& v : j.getPointArray("vertices", 3))
        vertices.push_back(t.point(v));
    if (const auto problem = checkConvexPolygon(vertices)) {
        if (problem->vertex < 0) j.fail("vertices", problem->message);
        throw ConfigError(j.pointerTo("vertices") + "/" + std::to_string(problem->vertex),
                          "vertex " + std::to_string(problem->vertex) + " " + problem->message);
    }
    // As an emitter: "solid_angle" (Arvo 1995) or "area" (cheaper, a worse density).
    const std::string sampling = j.getChoice("sampling", {"solid_angle", "area"}, "solid_angle");
    return std::make_unique<Polygon>(
        vertices, sampling == "area" ? PolygonSampling::Area : PolygonSampling::SolidAngle);
}

std::unique_ptr<Shape> makeMesh(ObjectReader& j, const Transform& t, const AssetResolver& assets) {
    const std::filesystem::path path = readAssetPath(j, "file", assets, "mesh");
    const std::string normals = j.getChoice("normals", {"geometric", "smooth"}, "geometric");
    MeshData data;
    try {
        data = loadMesh(path);
    } catch (const std::exception& e) {
        j.fail("file", e.what());
    }
    for (Vec3& p : data.positions) {
        p = t.point(Vec3d{p.x, p.y, p.z});
        if (!isFinite(p)) j.fail("transform", "moves the mesh's vertices beyond float range");
    }
    if (normals == "smooth") data.normals = TriangleMesh::smoothNormals(data);
    return std::make_unique<TriangleMesh>(std::move(data));
}

}  // namespace

std::unique_ptr<Shape> makeShape(ObjectReader& json, const Transform& transform,
                                 const AssetResolver& assets) {
    static const TypeTable<Shape, const Transform&, const AssetResolver&> table{
        {"sphere", makeSphere},   {"quad", makeQuad}, {"disk", makeDisk},
        {"polygon", makePolygon}, {"mesh", makeMesh},
    };
    return buildByType(json, "shape", table, transform, assets);
}

Transform readTransform(ObjectReader& parent, const std::string& key) {
    const Json* value = parent.rawOptional(key);
    if (!value) return Transform();
    ObjectReader j(*value, parent.pointerTo(key));
    Transform t;
    if (j.has("matrix")) {
        const auto m = j.getNumbers("matrix", 16);
        // Affine only: the bottom row (acting on column vectors) must be [0, 0, 0, 1].
        for (int i = 12; i < 16; ++i)
            if (m[i] != (i == 15 ? 1.0 : 0.0))
                throw ConfigError(j.pointerTo("matrix") + "/" + std::to_string(i),
                                  "the bottom row of the matrix must be [0, 0, 0, 1] (projective "
                                  "transforms are not supported)");
        t = Transform::fromRowMajor(m.data());
    } else {
        if (j.has("scale")) {
            const Json& s = j.raw("scale");
            t = s.is_number() ? Transform::scale(Vec3(j.getFloat("scale", Range::positive())))
                              : Transform::scale(j.getVec3("scale"));
        }
        if (const Json* rotations = j.rawOptional("rotate")) {
            const std::string at = j.pointerTo("rotate");
            auto addRotation = [&](const Json& r, const std::string& pointer) {
                ObjectReader rj(r, pointer);
                const Vec3 axis = rj.getVec3("axis");
                if (!(length(axis) > 0)) rj.fail("axis", "expected a non-zero vector");
                t = t.then(Transform::rotate(axis, rj.getNumber("angle")));
                rj.finish();
            };
            if (rotations->is_array()) {
                for (size_t i = 0; i < rotations->size(); ++i)
                    addRotation((*rotations)[i], at + "/" + std::to_string(i));
            } else {
                addRotation(*rotations, at);
            }
        }
        t = t.then(Transform::translate(j.getPoint("translate", Vec3d{})));
    }
    if (!t.isInvertible()) parent.fail(key, "the transform is singular");
    j.finish();
    return t;
}

}  // namespace rr
