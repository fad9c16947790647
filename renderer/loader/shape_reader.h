// One entry of the scene's "shapes": the keys every shape shares (transform, material,
// emission, interior medium, motion) around the type-specific geometry of the shape factory.
#pragma once

#include "config/json_reader.h"
#include "loader/asset_resolver.h"
#include "loader/camera_reader.h"
#include "loader/material_catalog.h"
#include "scene/scene.h"

namespace rr {

// Builds the shape described by `json` in rendering space and adds it to `builder`. Motion needs
// the camera's shutter: a moving shape is frozen at the shutter instant when the shutter does
// not open.
void readShape(ObjectReader& json, MaterialCatalog& materials, SceneBuilder& builder,
               const AssetResolver& assets, const CameraReading& view);

// The keys every shape takes, and the tables of its "emission" and "motion" objects.
const KeyTable& shapeCommonKeys();
std::vector<const KeyTable*> shapePartKeys();

}  // namespace rr
