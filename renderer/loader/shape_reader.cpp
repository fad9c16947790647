#include "loader/shape_reader.h"

#include <cmath>

#include "loader/factories.h"

namespace rr {

namespace {

const KeyTable kShapeKeys{
    "shape",
    "",
    {key("type").string().means("the shape's type"),
     key("material")
         .custom("a material name or object",
                 {{"anyOf", {{{"type", "string"}}, {{"$ref", "#/$defs/material"}}}}})
         .defaultSays("required unless the shape emits or has an `interior_medium`")
         .means("an emitter without a material reflects nothing; a medium boundary without one "
                "is index-matched: rays pass through it, only the medium changes"),
     key("emission").object("emission").optional().means("makes the shape a diffuse area light"),
     key("transform")
         .object("transform")
         .optional()
         .means("applied to the shape's defining points"),
     key("motion").object("motion").optional().means(
         "linear motion over scene time [0, 1] (Embree motion blur)"),
     key("interior_medium")
         .object("medium")
         .optional()
         .means("fills the shape's inside (the side opposite its normal; closed shapes with "
                "outward normals)")}};

const KeyTable kEmissionKeys{
    "emission",
    "a diffuse area light on the shape",
    {key("radiance").colour().means("emitted radiance"),
     key("two_sided")
         .boolean()
         .byDefault(false)
         .means("emit on both sides; one-sided emitters emit on the side of their normal")}};

const KeyTable kMotionKeys{
    "motion",
    "linear motion",
    {key("translate").vector().means("the displacement from scene time 0 to 1")}};

}  // namespace

const KeyTable& shapeCommonKeys() {
    return kShapeKeys;
}

std::vector<const KeyTable*> shapePartKeys() {
    return {&kEmissionKeys, &kMotionKeys};
}

void readShape(ObjectReader& j, MaterialCatalog& materials, SceneBuilder& builder,
               const AssetResolver& assets, const CameraReading& view) {
    j.addKeys(kShapeKeys);
    const CameraSettings& camera = view.camera;
    Transform transform = readTransform(j, "transform");

    Rgb emission(0.0f);
    bool twoSided = false;
    if (const Json* e = j.rawOptional("emission")) {
        ObjectReader ej(*e, j.pointerTo("emission"), kEmissionKeys);
        emission = ej.colour("radiance");
        twoSided = ej.boolean("two_sided");
        ej.finish();
    }
    const Medium* interior = nullptr;
    if (const Json* m = j.rawOptional("interior_medium")) {
        ObjectReader mj(*m, j.pointerTo("interior_medium"));
        interior = builder.addMedium(makeMedium(mj));
    }
    const Material* material = nullptr;
    if (j.has("material"))
        material = materials.resolve(j);
    else if (emission.isBlack() && !interior)
        j.fail("material",
               "missing required key (only emitters and medium boundaries may omit a material)");

    Vec3 motion(0.0f);
    if (const Json* m = j.rawOptional("motion")) {
        ObjectReader mj(*m, j.pointerTo("motion"), kMotionKeys);
        motion = mj.vector("translate");
        mj.finish();
    }
    // Without a shutter interval a moving shape is frozen where it is at the shutter instant,
    // so the scene pays nothing for motion blur.
    const bool shutterOpenInterval = camera.shutterClose > camera.shutterOpen;
    if (!shutterOpenInterval) {
        const Vec3 frozen = motion * camera.shutterOpen;
        transform = transform.then(Transform::translate({frozen.x, frozen.y, frozen.z}));
    }
    transform = transform.then(view.worldToRender);

    // The geometry is read last: the factory's finish() then rejects unknown keys for the
    // whole shape object, including the common keys read above.
    std::unique_ptr<Shape> shape = makeShape(j, transform, assets);
    if (!(shape->area() > 0) || !std::isfinite(shape->area()))
        j.fail("type", "the shape has zero or non-finite area");
    if (shutterOpenInterval) shape->setMotion(motion);
    shape->setInteriorMedium(interior);
    builder.addShape(std::move(shape), material, emission, twoSided);
}

}  // namespace rr
