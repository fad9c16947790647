// The scene's named material table ("materials") and inline materials. Named materials are
// built on first reference, so that mix and checker materials may refer to any entry of the
// table whatever its order, and every entry is built once; a chain of references that returns
// to a material being built is an error.
#pragma once

#include <map>
#include <string>

#include "config/json_reader.h"
#include "loader/asset_resolver.h"
#include "scene/scene.h"

namespace rr {

class MaterialCatalog {
  public:
    // `table`: the "materials" object at `pointer` (nullptr when the scene has none). Every
    // entry is built and checked, referenced or not.
    MaterialCatalog(const Json* table, const std::string& pointer, SceneBuilder& builder,
                    const AssetResolver& assets);

    // A material reference at `pointer`: a name from the table or an inline object.
    const Material* resolve(const Json& reference, const std::string& pointer);
    // A shape's "material".
    const Material* resolve(ObjectReader& shape) {
        return resolve(shape.raw("material"), shape.pointerTo("material"));
    }

  private:
    const Material* named(const std::string& name, const std::string& referrer);
    const Material* build(const Json& description, const std::string& pointer);

    const Json* table_;
    std::string pointer_;
    SceneBuilder& builder_;
    const AssetResolver& assets_;
    std::map<std::string, const Material*> named_;  // nullptr while being built
};

}  // namespace rr
