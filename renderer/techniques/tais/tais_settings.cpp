#include "techniques/tais/tais_settings.h"

namespace rr::tais {

namespace {

// Table 1's names, in MapKind order.
constexpr std::string_view kNames[kMapKinds] = {
    "time",
    "lens",
    "scatter_distance",
    "bifurcation",
    "light_selection",
    "point_on_light",
    "scatter_direction",
};

}  // namespace

std::string_view mapName(MapKind kind) {
    return kNames[static_cast<int>(kind)];
}

bool parseMapName(std::string_view name, MapKind* out) {
    for (int k = 0; k < kMapKinds; ++k)
        if (kNames[k] == name) {
            *out = static_cast<MapKind>(k);
            return true;
        }
    return false;
}

}  // namespace rr::tais
