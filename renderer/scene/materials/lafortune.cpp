#include "scene/materials/lafortune.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sampling/warps.h"
#include "scene/materials/cosine_lobe.h"

namespace rr {

namespace {

constexpr int kTableSize = 129;   // entries over the axis' cos θ ∈ [−1, 1]
constexpr int kQuadrature = 512;  // midpoint rule in s = cos^(n+1) α

// ∫₀^{2π} max(0, a + b·cos φ) dφ for b ≥ 0: the integrand is positive for |φ| < φ0 with
// cos φ0 = −a/b.
double clampedOverAzimuth(double a, double b) {
    if (a >= b) return 2 * M_PI * a;
    if (a <= -b) return 0;
    const double phi0 = std::acos(-a / b);
    return 2 * (a * phi0 + b * std::sin(phi0));
}

// ∫ cos^n α·max(0, cos θ) dω over the lobe (cos α > 0) whose axis has cos θ = z. In lobe
// coordinates cos θ = cos α·z + sin α·cos φ·√(1 − z²); with s = cos^(n+1) α the measure
// cos^n α dω becomes ds dφ / (n + 1), and the φ-integral is closed-form.
double clippedLobeIntegral(double exponent, double z) {
    const double sinAxis = std::sqrt(std::max(0.0, 1 - z * z));
    double sum = 0;
    for (int i = 0; i < kQuadrature; ++i) {
        const double s = (i + 0.5) / kQuadrature;
        const double cosAlpha = std::pow(s, 1 / (exponent + 1));
        const double sinAlpha = std::sqrt(std::max(0.0, 1 - cosAlpha * cosAlpha));
        sum += clampedOverAzimuth(cosAlpha * z, sinAlpha * sinAxis);
    }
    return sum / kQuadrature / (exponent + 1);
}

// Rows: Cx = Cy, Cz and n of one lobe for the red, green and blue channels (pbrt-v1,
// materials/skin.cpp).
struct SkinLobe {
    float cxy[3], cz[3], exponent[3];
};
constexpr SkinLobe kSkinLobes[3] = {
    {{-1.131747f, -1.016939f, -0.966018f},
     {-1.209182f, -1.462488f, -1.222419f},
     {6.421658f, 3.699932f, 3.524889f}},
    {{-0.546570f, -0.643533f, -0.638934f},
     {0.380123f, 0.410559f, 0.437367f},
     {3.685044f, 4.266495f, 4.539742f}},
    {{-0.998888f, -1.020153f, -1.027479f},
     {0.857998f, 0.703913f, 0.573625f},
     {64.208486f, 63.919687f, 43.809866f}},
};

// sum += albedo·s per channel, in double: |a|^n may be large where the albedo is small. A
// black channel adds nothing even when s is infinite.
void accumulate(double sum[3], const Rgb& albedo, double s) {
    for (int c = 0; c < 3; ++c)
        if (albedo[c] != 0) sum[c] += albedo[c] * s;
}

}  // namespace

Rgb Lafortune::skinDiffuse() {
    return Rgb(0.428425f, 0.301341f, 0.331054f);
}

std::vector<LafortuneLobe> Lafortune::skinLobes() {
    std::vector<LafortuneLobe> lobes;
    for (const SkinLobe& lobe : kSkinLobes)
        for (int channel = 0; channel < 3; ++channel) {
            Rgb albedo(0.0f);
            (channel == 0 ? albedo.r : channel == 1 ? albedo.g : albedo.b) = 1;
            const float cxy = lobe.cxy[channel];
            lobes.push_back({Vec3(cxy, cxy, lobe.cz[channel]), lobe.exponent[channel], albedo});
        }
    return lobes;
}

Lafortune::Lafortune(TexturePtr<Rgb> diffuse, const std::vector<LafortuneLobe>& lobes)
    : diffuse_(std::move(diffuse)) {
    if (lobes.size() > size_t(kMaxLobes))
        throw std::invalid_argument("Lafortune: at most " + std::to_string(kMaxLobes) + " lobes");
    for (const LafortuneLobe& params : lobes) {
        Lobe lobe{params, std::vector<float>(kTableSize)};
        for (int k = 0; k < kTableSize; ++k)
            lobe.clippedIntegral[k] =
                float(clippedLobeIntegral(params.exponent, -1.0 + 2.0 * k / (kTableSize - 1)));
        lobes_.push_back(std::move(lobe));
    }
}

Lafortune::Oriented Lafortune::orient(const Lobe& lobe, const Vec3& wo) {
    const Vec3& c = lobe.params.c;
    const double ax = double(c.x) * wo.x, ay = double(c.y) * wo.y, az = double(c.z) * wo.z;
    const double length = std::sqrt(ax * ax + ay * ay + az * az);
    if (!(length > 0)) return {Vec3(0, 0, 1), 0.0};
    const Vec3 axis(float(ax / length), float(ay / length), float(az / length));
    return {axis, std::pow(length, double(lobe.params.exponent))};
}

double Lafortune::clippedIntegral(const Lobe& lobe, double axisCos) {
    const double t = std::clamp((axisCos + 1) * 0.5, 0.0, 1.0) * (kTableSize - 1);
    const int k = std::min(int(t), kTableSize - 2);
    const double f = t - k;
    return (1 - f) * lobe.clippedIntegral[k] + f * lobe.clippedIntegral[k + 1];
}

Rgb Lafortune::lobeAlbedo(const Vec3& wo) const {
    double albedo[3] = {0, 0, 0};
    for (const Lobe& lobe : lobes_) {
        const Oriented o = orient(lobe, wo);
        const double axisCos = wo.z < 0 ? -o.axis.z : o.axis.z;
        accumulate(albedo, lobe.params.albedo, o.scale * clippedIntegral(lobe, axisCos));
    }
    return Rgb(float(albedo[0]), float(albedo[1]), float(albedo[2]));
}

Rgb Lafortune::maxLobeAlbedo(Vec3* where) const {
    // The model depends on wo through wo.x², wo.y² and wo.z: one quadrant of azimuths suffices.
    float best[3] = {0, 0, 0}, largest = -1;
    for (int theta = 0; theta <= 90; ++theta)
        for (int phi = 0; phi <= 90; phi += 10) {
            const double t = theta * M_PI / 180, p = phi * M_PI / 180;
            const Vec3 wo(float(std::sin(t) * std::cos(p)), float(std::sin(t) * std::sin(p)),
                          float(std::cos(t)));
            const Rgb albedo = lobeAlbedo(wo);
            for (int c = 0; c < 3; ++c)
                if (std::isnan(albedo[c]) || albedo[c] > best[c])
                    best[c] = albedo[c];  // NaN sticks
            if (albedo.maxComponent() > largest) {
                largest = albedo.maxComponent();
                if (where) *where = wo;
            }
        }
    return Rgb(best[0], best[1], best[2]);
}

Lafortune::View Lafortune::view(const ShadingContext& ctx, const Vec3& wo) const {
    View v;
    v.diffuse = diffuse_->eval(ctx);
    v.diffuseWeight = v.total = v.diffuse.luminance();
    for (size_t i = 0; i < lobes_.size(); ++i) {
        const Lobe& lobe = lobes_[i];
        v.lobe[i] = orient(lobe, wo);
        const double luminance = lobe.params.albedo.luminance();
        const double axisCos = wo.z < 0 ? -v.lobe[i].axis.z : v.lobe[i].axis.z;  // wo's side
        // (A black lobe weighs nothing even where |a|^n overflows.)
        v.weight[i] =
            luminance == 0 ? 0 : luminance * v.lobe[i].scale * clippedIntegral(lobe, axisCos);
        v.total += v.weight[i];
    }
    return v;
}

void Lafortune::evaluate(const View& v, const Vec3& wi, Rgb* f, float* pdf) const {
    const double cosI = std::abs(wi.z);
    double value[3] = {v.diffuse.r * M_1_PI, v.diffuse.g * M_1_PI, v.diffuse.b * M_1_PI};
    double density = v.diffuseWeight * cosI * M_1_PI;
    for (size_t i = 0; i < lobes_.size(); ++i) {
        // max(0, a·wi)^n = |a|^n·cos^n α, α the angle between wi and the axis.
        const double exponent = lobes_[i].params.exponent;
        const double power = cosinePower(oneMinusCosine(wi, v.lobe[i].axis), exponent);
        accumulate(value, lobes_[i].params.albedo, v.lobe[i].scale * power);
        density += v.weight[i] * (exponent + 1) / (2 * M_PI) * power;
    }
    *f = Rgb(float(value[0] * cosI), float(value[1] * cosI), float(value[2] * cosI));
    *pdf = v.total > 0 ? float(density / v.total) : 0.0f;
}

Rgb Lafortune::eval(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z * wi.z <= 0) return Rgb(0.0f);  // two-sided: both on the same side
    Rgb f;
    float density;
    evaluate(view(ctx, wo), wi, &f, &density);
    return f;
}

float Lafortune::pdf(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z * wi.z <= 0) return 0;
    Rgb f;
    float density;
    evaluate(view(ctx, wo), wi, &f, &density);
    return density;
}

bool Lafortune::sample(const ShadingContext& ctx, const Vec3& wo, float uLobe, Vec2 uDirection,
                       BsdfSample* out) const {
    if (wo.z == 0) return false;
    const View v = view(ctx, wo);
    if (!(v.total > 0)) return false;  // black

    // The component whose cumulative weight interval contains uLobe·total; the last lobe
    // with a weight absorbs rounding at the top end.
    double target = uLobe * v.total - v.diffuseWeight;
    Vec3 wi;
    uint8_t lobeType = kReflection | kGlossy;
    if (target < 0) {
        wi = squareToCosineHemisphere(uDirection);
        if (wo.z < 0) wi.z = -wi.z;
        lobeType = kReflection | kDiffuse;
    } else {
        int chosen = -1;
        for (size_t i = 0; i < lobes_.size() && target >= 0; ++i)
            if (v.weight[i] > 0) {
                chosen = int(i);
                target -= v.weight[i];
            }
        if (chosen < 0) return false;
        wi = sampleCosinePower(uDirection, lobes_[chosen].params.exponent, v.lobe[chosen].axis);
    }
    if (wi.z * wo.z <= 0) return false;  // the lobe's part below the surface, or the horizon
    out->wi = wi;
    evaluate(v, wi, &out->weight, &out->pdf);
    if (!(out->pdf > 0)) return false;  // a lobe direction whose density underflowed
    out->weight = out->weight / out->pdf;
    out->lobe = lobeType;
    return true;
}

void Lafortune::peaks(const ShadingContext&, const Vec3& wo, LobePeaks* out) const {
    for (const Lobe& lobe : lobes_) {
        const Oriented o = orient(lobe, wo);
        if (!(o.scale > 0) || o.axis.z * wo.z <= 0) continue;  // lobes pointing into the surface
        const auto end = out->directions.begin() + out->count;
        if (std::find(out->directions.begin(), end, o.axis) == end) out->add(o.axis);
    }
}

}  // namespace rr
