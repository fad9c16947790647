#include "scene/lights/environment_map.h"

#include <algorithm>
#include <vector>

namespace rr {

namespace {

// The mean of dω/(ds dt) over a texel (a 4 × 4 midpoint rule): the texel's solid angle over its
// area. The sampling weight must follow the solid angle, not the Jacobian at the centre: at the
// probe's rim the Jacobian falls from its value at the inner edge of a texel to zero across
// it, and a texel weighted by its centre value alone would give radiance/pdf tens of times the
// mean over its inner part (heavy-tailed estimates).
float meanJacobian(const EnvLayout& layout, int col, int row, int width, int height) {
    constexpr int kSub = 4;
    float sum = 0;
    for (int a = 0; a < kSub; ++a)
        for (int b = 0; b < kSub; ++b)
            sum += layout.jacobian({(float(col) + (float(a) + 0.5f) / kSub) / float(width),
                                    (float(row) + (float(b) + 0.5f) / kSub) / float(height)});
    return sum / (kSub * kSub);
}

}  // namespace

EnvironmentMap::EnvironmentMap(RgbImage image, std::unique_ptr<EnvLayout> layout, const Rgb& scale,
                               const Frame& toWorld)
    : image_(std::move(image)), layout_(std::move(layout)), toWorld_(toWorld) {
    const int width = image_.width, height = image_.height;
    std::vector<float> weights(image_.pixels.size());
    double integral[3] = {0, 0, 0};
    const double texelArea = 1.0 / (double(width) * height);
    for (int row = 0; row < height; ++row)
        for (int col = 0; col < width; ++col) {
            const size_t i = size_t(row) * width + col;
            const Vec2 centre((float(col) + 0.5f) / float(width),
                              (float(row) + 0.5f) / float(height));
            Rgb& p = image_.pixels[i];
            // A texel whose centre has no solid angle is masked: the probe's texels outside
            // the unit disc (u² + v² > 1), which hold the copyright notice, not radiance.
            if (!(layout_->jacobian(centre) > 0)) {
                p = Rgb(0.0f);
                continue;
            }
            p = Rgb(std::max(p.r, 0.0f), std::max(p.g, 0.0f), std::max(p.b, 0.0f)) * scale;
            const float jacobian = meanJacobian(*layout_, col, row, width, height);
            weights[i] = p.luminance() * jacobian;
            for (int c = 0; c < 3; ++c)
                integral[c] += double(p[c]) * jacobian * texelArea;
        }
    distribution_ = Distribution2D(weights, width, height);
    radianceIntegral_ = Rgb(float(integral[0]), float(integral[1]), float(integral[2]));
}

int EnvironmentMap::texelIndex(Vec2 st) const {
    const int col = std::clamp(static_cast<int>(st.x * float(image_.width)), 0, image_.width - 1);
    const int row = std::clamp(static_cast<int>(st.y * float(image_.height)), 0, image_.height - 1);
    return row * image_.width + col;
}

bool EnvironmentMap::sample(const Vec3& reference, Vec2 u, float, LightSample* out) const {
    float imagePdf;
    const Vec2 st = distribution_.sample(u, &imagePdf);
    Vec3 local;
    float jacobian;
    // A point of a probe's rim texel may lie outside the disc: no direction, no sample (the
    // density below is then that of a distribution of total mass slightly below 1, which
    // keeps the estimator unbiased).
    if (imagePdf == 0 || !layout_->direction(st, &local, &jacobian)) return false;
    out->direction = normalize(toWorld_.toWorld(local));
    // Twice the diameter: outside the bounding sphere from any point inside it.
    out->position = reference + out->direction * (4.0f * radius_);
    out->normal = Vec3(0.0f);
    out->errorScale = 0;
    // Radiance and density of the direction itself, exactly as escaped rays and MIS see them
    // (the texel is found again from the direction, so the three always agree).
    out->radiance = escapedRadiance(out->direction);
    out->pdf = directionPdf(out->direction);
    out->isDelta = false;
    return out->pdf > 0 && !out->radiance.isBlack();
}

Rgb EnvironmentMap::escapedRadiance(const Vec3& w) const {
    return image_.pixels[size_t(texelIndex(layout_->imagePoint(toWorld_.toLocal(w))))];
}

float EnvironmentMap::directionPdf(const Vec3& w) const {
    const Vec2 st = layout_->imagePoint(toWorld_.toLocal(w));
    const float jacobian = layout_->jacobian(st);
    return jacobian > 0 ? distribution_.pdf(st) / jacobian : 0.0f;
}

bool EnvironmentMap::invertSample(const Vec3&, const Vec3& direction, const Vec3&, Vec2* u) const {
    // The frame is orthonormal: toLocal undoes toWorld (sample()'s normalisation only removes
    // rounding). The image point is found exactly as directionPdf finds it, so invertSample
    // succeeds exactly where the density of the direction is positive.
    const Vec2 st = layout_->imagePoint(toWorld_.toLocal(direction));
    if (!(layout_->jacobian(st) > 0) || !(distribution_.pdf(st) > 0)) return false;
    *u = distribution_.invert(st);
    return true;
}

}  // namespace rr
