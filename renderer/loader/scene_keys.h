// The catalogue of every key a scene file takes (config/key_table.h): the tables the loader's
// readers and the registered integrators and estimators read through, gathered for
// `renderer keys` (from which configs/README.md's key tables and the scene schema are
// generated) and for estimandOf.
#pragma once

#include "config/key_table.h"

namespace rr {

const KeyCatalogue& sceneKeys();

// The keys of the scene document's top level.
const KeyTable& sceneRootKeys();

}  // namespace rr
