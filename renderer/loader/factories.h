// One factory per category, each building objects from their JSON description (Tungsten's
// pattern). Adding a type = writing the class + one entry in the category's table.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "config/json_reader.h"
#include "config/type_table.h"
#include "loader/asset_resolver.h"
#include "math/transform.h"
#include "render/technique_registry.h"
#include "scene/light.h"
#include "scene/material.h"
#include "scene/medium.h"
#include "scene/shape.h"

namespace rr {

// Materials made of other materials (mix, checker) refer to them by name or embed them: the
// loader resolves such a reference (`reference`, found at JSON pointer `pointer`) to a material
// that the scene owns.
using MaterialReferences =
    std::function<const Material*(const Json& reference, const std::string& pointer)>;

// Material parameters may be textures; image textures are found through `assets`.
std::unique_ptr<Material> makeMaterial(ObjectReader& json, const AssetResolver& assets,
                                       const MaterialReferences& references);

// A participating medium: {"sigma_a", "sigma_s", "phase"} (configs/README.md, "Media").
std::unique_ptr<Medium> makeMedium(ObjectReader& json);

// Shapes are built in rendering space: `transform` (the shape's placement in the scene file,
// then the file's move into rendering space, loader/camera_reader.h) is applied to their
// defining points.
std::unique_ptr<Shape> makeShape(ObjectReader& json, const Transform& transform,
                                 const AssetResolver& assets);

// Environment maps are found through `assets`; point and spot lights are placed by
// `worldToRender` (loader/camera_reader.h).
std::unique_ptr<Light> makeLight(ObjectReader& json, const AssetResolver& assets,
                                 const Transform& worldToRender);

// Each category's types and their key tables (key_table.h), and the tables of the objects
// inside them.
using MaterialTypes = TypeTable<Material, const AssetResolver&, const MaterialReferences&>;
const MaterialTypes& materialTypes();
std::vector<const KeyTable*> materialPartKeys();  // a Lafortune lobe
const TypeTable<Shape, const Transform&, const AssetResolver&>& shapeTypes();
using LightTypes = TypeTable<Light, const AssetResolver&, const Transform&>;
const LightTypes& lightTypes();
const KeyTable& mediumKeys();
const TypeTable<PhaseFunction>& phaseTypes();
std::vector<const KeyTable*> transformKeys();  // a transform, a rotation

// Every integrator and direct-lighting estimator type: the core ones and the techniques'.
const TechniqueRegistry& techniqueRegistry();

// The "transform" object: scale, then rotations in order, then translation; or a 4×4 matrix.
Transform readTransform(ObjectReader& parent, const std::string& key);

}  // namespace rr
