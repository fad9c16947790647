#include "loader/factories.h"
#include "loader/type_table.h"
#include "scene/materials/dielectric.h"
#include "scene/materials/lambert.h"
#include "scene/materials/mirror.h"

namespace rr {

std::unique_ptr<Material> makeMaterial(ObjectReader& json, const AssetResolver& assets) {
    static const TypeTable<Material, const AssetResolver&> table{
        {"lambert",
         [](ObjectReader& j, const AssetResolver&) {
             return std::make_unique<Lambert>(j.getRgb("albedo", Rgb(0.8f), Range::unit()));
         }},
        {"mirror",
         [](ObjectReader& j, const AssetResolver&) {
             return std::make_unique<Mirror>(j.getRgb("reflectance", Rgb(1.0f), Range::unit()));
         }},
        {"dielectric",
         [](ObjectReader& j, const AssetResolver&) {
             const float ior = j.getFloat("ior", 1.5f, Range::positive());
             const Rgb r = j.getRgb("reflectance", Rgb(1.0f), Range::unit());
             const Rgb t = j.getRgb("transmittance", Rgb(1.0f), Range::unit());
             return std::make_unique<Dielectric>(ior, r, t);
         }},
    };
    return buildByType(json, "material", table, assets);
}

}  // namespace rr
