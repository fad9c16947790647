#include "loader/scene_keys.h"

#include "loader/camera_reader.h"
#include "loader/factories.h"
#include "loader/render_settings_reader.h"
#include "loader/shape_reader.h"
#include "loader/texture_factory.h"

namespace rr {

namespace {

KeyCatalogue buildCatalogue() {
    KeyCatalogue c;
    c.root = &sceneRootKeys();
    c.tables = {&sceneRootKeys(), &renderKeys(),      &cameraKeys(),
                &mediumKeys(),    &shapeCommonKeys(), &typeKeyTable()};
    for (const std::vector<const KeyTable*>& more :
         {shapePartKeys(), transformKeys(), materialPartKeys()})
        c.tables.insert(c.tables.end(), more.begin(), more.end());
    auto add = [&](const std::string& name, const std::string& meaning, const KeyTable* common,
                   std::vector<std::pair<std::string, const KeyTable*>> types,
                   const std::string& defaultType = "") {
        for (const auto& entry : types)
            c.tables.push_back(entry.second);
        c.categories.push_back({name, meaning, common, std::move(types), defaultType});
    };
    const TechniqueRegistry& registry = techniqueRegistry();
    c.tables.insert(c.tables.end(), registry.objectKeys().begin(), registry.objectKeys().end());
    add("integrator", "how the image is estimated", &typeKeyTable(), registry.integratorKeys(),
        "path_mis");
    add("estimator", "a direct-lighting estimator", &typeKeyTable(), registry.estimatorKeys());
    add("filter", "a reconstruction filter", &typeKeyTable(), filterTypeKeys());
    add("shape", "a shape", &shapeCommonKeys(), typeKeys(shapeTypes()));
    add("material", "a material", &typeKeyTable(), typeKeys(materialTypes()));
    add("texture", "a texture", &typeKeyTable(), textureTypeKeys());
    add("light", "a light that is not a shape", &typeKeyTable(), typeKeys(lightTypes()));
    add("phase", "a phase function", &typeKeyTable(), typeKeys(phaseTypes()));
    return c;
}

// Removes from `value`, an object read by `table` (and the type table its category picks),
// every key declared estimand-neutral, recursing into the objects it holds.
void eraseNeutral(const KeyCatalogue& c, const KeyTable& table, Json& value);

void eraseNeutralIn(const KeyCatalogue& c, const KeySpec& spec, Json& value) {
    auto oneOf = [&](Json& object) {
        const KeyCatalogue::Category* category = c.category(spec.refers);
        if (!category || !object.is_object()) return;
        if (category->common) eraseNeutral(c, *category->common, object);
        if (const KeyTable* t = c.typeTable(*category, object)) eraseNeutral(c, *t, object);
    };
    switch (spec.kind) {
        case KeyKind::Object:
            if (const KeyTable* t = c.table(spec.refers)) eraseNeutral(c, *t, value);
            break;
        case KeyKind::OneOf:
            oneOf(value);
            break;
        case KeyKind::ListOf:
            if (value.is_array())
                for (Json& element : value)
                    oneOf(element);
            break;
        case KeyKind::MapOf:
            if (value.is_object())
                for (auto& [name, element] : value.items())
                    oneOf(element);
            break;
        default:
            break;
    }
}

void eraseNeutral(const KeyCatalogue& c, const KeyTable& table, Json& value) {
    if (!value.is_object()) return;
    for (const KeySpec& spec : table.keys) {
        const auto it = value.find(spec.name);
        if (it == value.end()) continue;
        if (spec.estimandNeutral)
            value.erase(it);
        else
            eraseNeutralIn(c, spec, *it);
    }
}

}  // namespace

const KeyTable& sceneRootKeys() {
    static const KeyTable keys{
        "scene",
        "one scene document",
        {key("description")
             .string()
             .optional()
             .estimandNeutral()
             .means("free text: what the scene is and the choices made recreating it"),
         key("render").object("render").optional().means(
             "image size, samples, sampler, filter, path length"),
         key("integrator")
             .oneOf("integrator")
             .defaultSays(R"(`{"type": "path_mis"}`)")
             .means("how the image is estimated (kept in the estimand: `direct` and `path` "
                    "estimate different images)"),
         key("camera").object("camera").means("the camera"),
         key("medium").object("medium").optional().means(
             "a participating medium filling the scene outside shapes with their own"),
         key("materials").mapOf("material").optional().means("named materials"),
         key("shapes").listOf("shape").means("the geometry"),
         key("lights").listOf("light").optional().means("lights that are not shapes")}};
    return keys;
}

const KeyCatalogue& sceneKeys() {
    static const KeyCatalogue catalogue = buildCatalogue();
    return catalogue;
}

Json estimandOf(const Json& document) {
    Json estimand = document;
    const KeyCatalogue& c = sceneKeys();
    eraseNeutral(c, *c.root, estimand);
    return estimand;
}

}  // namespace rr
