// How an environment image covers the sphere of directions. Image coordinates (s, t) ∈ [0,1]²
// run to the right and downwards: texel (col, row) covers [col, col+1)/width × [row, row+1)/
// height, row 0 being the top scanline as stored in the file. Directions are in the map's own
// frame, before the light's rotation. Both layouts share one convention: the image centre is
// the direction +Z, +Y is up, and a viewer facing +Z sees the map as the image shows it, not
// mirrored (image right is −X, the viewer's right in a right-handed frame).
#pragma once

#include <memory>
#include <string>

#include "math/vector.h"

namespace rr {

class EnvLayout {
  public:
    virtual ~EnvLayout() = default;

    // The unit direction at image point `st` and the Jacobian dω/(ds dt) there; false when
    // the point is outside the layout's domain (the probe's corners).
    virtual bool direction(Vec2 st, Vec3* w, float* jacobian) const = 0;
    // The image point of a unit direction (the inverse of direction()).
    virtual Vec2 imagePoint(const Vec3& w) const = 0;
    // dω/(ds dt) at `st`; zero outside the domain.
    virtual float jacobian(Vec2 st) const = 0;
};

// Latitude-longitude (equirectangular): t = θ/π with θ the angle from +Y (row 0 is the +Y
// pole), s = φ/(2π) with the direction (sin θ sin φ, cos θ, −sin θ cos φ): the image centre
// (s = ½) looks along +Z, s = ¾ along −X, the left and right edges along −Z.
// dω = sin θ dθ dφ = 2π² sin(πt) ds dt.
class LatLongLayout final : public EnvLayout {
  public:
    // The direction factors into a term of the row and a term of the column, so a grid of
    // directions can be tabulated by rows and columns (two-stage sampling's corner
    // evaluations): direction() is fromFactors(rowFactor(t), columnFactor(s)).
    struct RowFactor {
        float sinTheta, cosTheta;
    };
    struct ColumnFactor {
        float sinPhi, cosPhi;
    };
    static RowFactor rowFactor(float t);
    static ColumnFactor columnFactor(float s);
    static Vec3 fromFactors(RowFactor r, ColumnFactor c) {
        return Vec3(r.sinTheta * c.sinPhi, r.cosTheta, -r.sinTheta * c.cosPhi);
    }

    bool direction(Vec2 st, Vec3* w, float* jacobian) const override;
    Vec2 imagePoint(const Vec3& w) const override;
    float jacobian(Vec2 st) const override;
};

// Debevec's angular map ("light probe" format): u = 2s − 1, v = 1 − 2t over the unit disc
// u² + v² ≤ 1; the direction at angle θ = π·ρ (ρ = √(u² + v²)) from the centre direction +Z,
// towards (−u, v) in the XY plane: w = (−sin θ · u/ρ, sin θ · v/ρ, cos θ). The gallery's
// formula, (u, v) = (Dx, Dy) · acos(Dz) / (π √(Dx² + Dy²)), puts the centre at +Z while its
// prose says the centre is −Z, forward for a viewer with +X to the right: taken literally it
// mirrors the room (Galileo's bright nave windows, right of the image centre, would light the
// scene from the viewer's left), and no rotation undoes a mirror. We keep the prose's
// handedness with the centre at +Z (the prose's convention turned 180° about +Y). The rim ρ = 1
// is the single direction −Z. dω = π sin(πρ)/ρ du dv = 4π sin(πρ)/ρ ds dt (du = 2 ds,
// dv = 2 dt), which integrates to 4π over the disc and vanishes at the rim.
class ProbeLayout final : public EnvLayout {
  public:
    bool direction(Vec2 st, Vec3* w, float* jacobian) const override;
    Vec2 imagePoint(const Vec3& w) const override;
    float jacobian(Vec2 st) const override;
};

// "latlong" or "probe"; nullptr for another name.
std::unique_ptr<EnvLayout> makeEnvLayout(const std::string& name);

}  // namespace rr
