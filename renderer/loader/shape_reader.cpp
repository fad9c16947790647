#include "loader/shape_reader.h"

#include <cmath>

#include "loader/factories.h"

namespace rr {

void readShape(ObjectReader& j, MaterialCatalog& materials, SceneBuilder& builder,
               const AssetResolver& assets, const CameraReading& view) {
    const CameraSettings& camera = view.camera;
    Transform transform = readTransform(j, "transform");

    Rgb emission(0.0f);
    bool twoSided = false;
    if (const Json* e = j.rawOptional("emission")) {
        ObjectReader ej(*e, j.pointerTo("emission"));
        emission = ej.getRgb("radiance");
        twoSided = ej.getBool("two_sided", false);
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
        ObjectReader mj(*m, j.pointerTo("motion"));
        motion = mj.getVec3("translate");
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
