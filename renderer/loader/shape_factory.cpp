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

const KeyTable kSphereKeys{
    "shape/sphere",
    "analytic sphere (exact hits and normals, normal outward); uv = (φ/2π, θ/π) about its own z "
    "axis; similarity transforms only; as a light, sampled by the cone it subtends",
    {key("center").vector().byDefault({0, 0, 0}).means("centre"),
     key("radius").number(Range::positive()).means("radius")}};

const KeyTable kQuadKeys{
    "shape/quad",
    "the parallelogram corner + s·edge_u + t·edge_v, s, t ∈ [0, 1]; normal = edge_u × edge_v; "
    "uv = (s, t); zero area is an error",
    {key("corner").vector().means("one corner"), key("edge_u").vector().means("the edge along u"),
     key("edge_v").vector().means("the edge along v")}};

const KeyTable kDiskKeys{
    "shape/disk",
    "a disk; uv = (r/radius, φ/2π); similarity transforms only",
    {key("center").vector().byDefault({0, 0, 0}).means("centre"),
     key("normal").vector().byDefault({0, 0, 1}).means("the side it faces (non-zero)"),
     key("radius").number(Range::positive()).means("radius")}};

const KeyTable kPolygonKeys{
    "shape/polygon",
    "a convex planar polygon, normal by the right-hand rule on the vertex order (checked at "
    "load: see Shapes); as a light, sampled by solid angle (Arvo 1995) or by area",
    {key("vertices").points(3).means("[[x, y, z], …], at least 3, convex and planar"),
     key("sampling")
         .choice({"solid_angle", "area"})
         .byDefault("solid_angle")
         .means("as an emitter: uniform in the subtended solid angle (by area below 10⁻⁴ sr), "
                "or always by area (worse density, cheaper: resampling's source density)")}};

const KeyTable kMeshKeys{
    "shape/mesh",
    "triangles from a PLY (the renderer's own strict reader) or OBJ (Assimp) file; equal "
    "vertices joined, degenerate triangles dropped; emits sampled uniformly by area",
    {key("file").string().means("PLY or OBJ, found on the asset search path"),
     key("normals")
         .choice({"geometric", "smooth"})
         .byDefault("geometric")
         .means("shading normals: each triangle's own, or area-weighted vertex normals")}};

const KeyTable kTransformKeys{
    "transform",
    "scale, then rotations in list order, then translation; or a 4×4 matrix",
    {key("matrix").numbers(16).optional().means(
         "row-major, acting on column vectors; affine: the bottom row [0, 0, 0, 1] (not with "
         "scale, rotate, translate)"),
     key("scale")
         .custom("number > 0 or [sx, sy, sz]", {{"anyOf",
                                                 {{{"type", "number"}, {"exclusiveMinimum", 0}},
                                                  {{"type", "array"},
                                                   {"items", {{"type", "number"}}},
                                                   {"minItems", 3},
                                                   {"maxItems", 3}}}}})
         .optional()
         .means("uniform or per-axis scale"),
     key("rotate")
         .custom("a rotation object or a list of them",
                 {{"anyOf",
                   {{{"$ref", "#/$defs/rotation"}},
                    {{"type", "array"}, {"items", {{"$ref", "#/$defs/rotation"}}}}}}})
         .optional()
         .means("rotations, applied in list order"),
     key("translate").vector().byDefault({0, 0, 0}).means("translation")}};

const KeyTable kRotationKeys{
    "rotation",
    "a rotation about an axis through the origin",
    {key("axis").vector().means("non-zero axis"), key("angle").number().means("degrees")}};

float similarityScale(ObjectReader& j, const Transform& t, const char* shape) {
    float scale = 1;
    if (!t.isSimilarity(&scale))
        j.fail("transform",
               std::string("a ") + shape + " takes only rotation, uniform scale and translation");
    return scale;
}

std::unique_ptr<Shape> makeSphere(ObjectReader& j, const Transform& t, const AssetResolver&) {
    const Vec3d center = j.point("center");
    const float radius = j.real("radius");
    const float scale = similarityScale(j, t, "sphere");
    // The transform's rotation turns the sphere's own axes (the poles of its uv).
    Frame orientation;
    orientation.s = normalize(t.vector(Vec3(1, 0, 0)));
    orientation.t = normalize(t.vector(Vec3(0, 1, 0)));
    orientation.n = normalize(t.vector(Vec3(0, 0, 1)));
    return std::make_unique<Sphere>(t.point(center), radius * scale, orientation);
}

std::unique_ptr<Shape> makeQuad(ObjectReader& j, const Transform& t, const AssetResolver&) {
    const Vec3 corner = t.point(j.point("corner"));
    const Vec3 edgeU = t.vector(j.vector("edge_u"));
    const Vec3 edgeV = t.vector(j.vector("edge_v"));
    const float area = length(cross(edgeU, edgeV));
    if (!(area > 1e-12f * (lengthSquared(edgeU) + lengthSquared(edgeV))) || !(area > 0))
        j.fail("edge_v", "edges are parallel or zero: the quad has zero area");
    return std::make_unique<Quad>(corner, edgeU, edgeV);
}

std::unique_ptr<Shape> makeDisk(ObjectReader& j, const Transform& t, const AssetResolver&) {
    const Vec3d center = j.point("center");
    const Vec3 normal = j.vector("normal");
    const float radius = j.real("radius");
    if (!(length(normal) > 0)) j.fail("normal", "expected a non-zero vector");
    const float scale = similarityScale(j, t, "disk");
    return std::make_unique<Disk>(t.point(center), normalize(t.normal(normal)), radius * scale);
}

std::unique_ptr<Shape> makePolygon(ObjectReader& j, const Transform& t, const AssetResolver&) {
    std::vector<Vec3> vertices;
    for (const Vec3d& v : j.points("vertices"))
        vertices.push_back(t.point(v));
    if (const auto problem = checkConvexPolygon(vertices)) {
        if (problem->vertex < 0) j.fail("vertices", problem->message);
        throw ConfigError(j.pointerTo("vertices") + "/" + std::to_string(problem->vertex),
                          "vertex " + std::to_string(problem->vertex) + " " + problem->message);
    }
    const std::string sampling = j.choice("sampling");
    return std::make_unique<Polygon>(
        vertices, sampling == "area" ? PolygonSampling::Area : PolygonSampling::SolidAngle);
}

std::unique_ptr<Shape> makeMesh(ObjectReader& j, const Transform& t, const AssetResolver& assets) {
    const std::filesystem::path path = readAssetPath(j, "file", assets, "mesh");
    const std::string normals = j.choice("normals");
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
    return buildByType(json, "shape", shapeTypes(), transform, assets);
}

const TypeTable<Shape, const Transform&, const AssetResolver&>& shapeTypes() {
    static const TypeTable<Shape, const Transform&, const AssetResolver&> table{
        {"sphere", {makeSphere, &kSphereKeys}}, {"quad", {makeQuad, &kQuadKeys}},
        {"disk", {makeDisk, &kDiskKeys}},       {"polygon", {makePolygon, &kPolygonKeys}},
        {"mesh", {makeMesh, &kMeshKeys}},
    };
    return table;
}

std::vector<const KeyTable*> transformKeys() {
    return {&kTransformKeys, &kRotationKeys};
}

Transform readTransform(ObjectReader& parent, const std::string& key) {
    const Json* value = parent.rawOptional(key);
    if (!value) return Transform();
    ObjectReader j(*value, parent.pointerTo(key), kTransformKeys);
    Transform t;
    if (j.has("matrix")) {
        const auto m = j.numbers("matrix");
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
                ObjectReader rj(r, pointer, kRotationKeys);
                const Vec3 axis = rj.vector("axis");
                if (!(length(axis) > 0)) rj.fail("axis", "expected a non-zero vector");
                t = t.then(Transform::rotate(axis, rj.number("angle")));
                rj.finish();
            };
            if (rotations->is_array()) {
                for (size_t i = 0; i < rotations->size(); ++i)
                    addRotation((*rotations)[i], at + "/" + std::to_string(i));
            } else {
                addRotation(*rotations, at);
            }
        }
        t = t.then(Transform::translate(j.point("translate")));
    }
    if (!t.isInvertible()) parent.fail(key, "the transform is singular");
    j.finish();
    return t;
}

}  // namespace rr
