#include "loader/factories.h"
#include "loader/type_table.h"
#include "scene/lights/point_light.h"

namespace rr {

std::unique_ptr<Light> makeLight(ObjectReader& json) {
    static const TypeTable<Light> table{
        {"point",
         [](ObjectReader& j) {
             return std::make_unique<PointLight>(j.getVec3("position"), j.getRgb("intensity"));
         }},
    };
    return buildByType(json, "light", table);
}

}  // namespace rr
