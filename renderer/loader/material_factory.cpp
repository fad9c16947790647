#include "loader/factories.h"
#include "loader/type_table.h"
#include "scene/materials/dielectric.h"
#include "scene/materials/lambert.h"
#include "scene/materials/mirror.h"

namespace rr {

std::unique_ptr<Material> makeMaterial(ObjectReader& json) {
    static const TypeTable<Material> table{
        {"lambert",
         [](ObjectReader& j) {
             return std::make_unique<Lambert>(j.getRgb("albedo", Rgb(0.8f), Range::unit()));
         }},
        {"mirror",
         [](ObjectReader& j) {
             return std::make_unique<Mirror>(j.getRgb("reflectance", Rgb(1.0f), Range::unit()));
         }},
        {"dielectric",
         [](ObjectReader& j) {
             const float ior = j.getFloat("ior", 1.5f, Range::positive());
             const Rgb r = j.getRgb("reflectance", Rgb(1.0f), Range::unit());
             const Rgb t = j.getRgb("transmittance", Rgb(1.0f), Range::unit());
             return std::make_unique<Dielectric>(ior, r, t);
         }},
    };
    return buildByType(json, "material", table);
}

}  // namespace rr
