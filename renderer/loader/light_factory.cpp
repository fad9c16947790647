#include "loader/factories.h"
#include "loader/type_table.h"
#include "scene/lights/constant_environment.h"
#include "scene/lights/point_light.h"

namespace rr {

std::unique_ptr<Light> makeLight(ObjectReader& json, const AssetResolver& assets) {
    static const TypeTable<Light, const AssetResolver&> table{
        {"point",
         [](ObjectReader& j, const AssetResolver&) {
             return std::make_unique<PointLight>(j.getVec3("position"), j.getRgb("intensity"));
         }},
        {"environment",
         [](ObjectReader& j, const AssetResolver&) {
             return std::make_unique<ConstantEnvironment>(j.getRgb("radiance"));
         }},
    };
    return buildByType(json, "light", table, assets);
}

}  // namespace rr
