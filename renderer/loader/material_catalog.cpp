#include "loader/material_catalog.h"

#include "loader/factories.h"

namespace rr {

MaterialCatalog::MaterialCatalog(const Json* table, const std::string& pointer,
                                 SceneBuilder& builder, const AssetResolver& assets)
    : table_(table), pointer_(pointer), builder_(builder), assets_(assets) {
    if (!table) return;
    if (!table->is_object()) throw ConfigError(pointer, "expected an object of materials");
    for (const auto& item : table->items())
        named(item.key(), pointer);
}

const Material* MaterialCatalog::resolve(const Json& reference, const std::string& pointer) {
    if (reference.is_object()) return build(reference, pointer);
    if (!reference.is_string()) throw ConfigError(pointer, "expected a material name or object");
    return named(reference.get<std::string>(), pointer);
}

const Material* MaterialCatalog::named(const std::string& name, const std::string& referrer) {
    if (const auto it = named_.find(name); it != named_.end()) {
        if (!it->second)
            throw ConfigError(referrer, "material \"" + name + "\" refers back to itself");
        return it->second;
    }
    if (!table_ || !table_->contains(name))
        throw ConfigError(referrer, "no material named \"" + name + "\" in /materials");
    named_[name] = nullptr;  // being built
    const Material* material = build(table_->at(name), pointer_ + "/" + escapePointerToken(name));
    named_[name] = material;
    return material;
}

const Material* MaterialCatalog::build(const Json& description, const std::string& pointer) {
    ObjectReader m(description, pointer);
    const MaterialReferences references = [this](const Json& ref, const std::string& at) {
        return resolve(ref, at);
    };
    return builder_.addMaterial(makeMaterial(m, assets_, references));
}

}  // namespace rr
