#include "scene/lights/environment_map.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
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

// The side of the stand-in's blocks: the largest common divisor of the map's sides that leaves
// at least 64 blocks across the shorter one (100 × 100 blocks of 10 × 10 texels for a
// 1000 × 1000 probe, 128 × 64 of 8 × 8 for a 1024 × 512 lat-long map): tables of ~0.3 MB that
// stay in a core's cache. Maps whose sides share no such divisor keep their texels.
int proxyBlockSide(int width, int height) {
    const int common = std::gcd(width, height), limit = std::min(width, height) / 64;
    for (int side = std::min(common, limit); side > 1; --side)
        if (common % side == 0) return side;
    return 1;
}

}  // namespace

EnvironmentMap::EnvironmentMap(RgbImage image, std::unique_ptr<EnvLayout> layout, const Rgb& scale,
                               const Frame& toWorld, EnvSampling sampling)
    : image_(std::move(image)), layout_(std::move(layout)), toWorld_(toWorld), sampling_(sampling) {
    const int width = image_.width, height = image_.height;
    std::vector<float> weights(image_.pixels.size()), jacobians(image_.pixels.size());
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
            jacobians[i] = jacobian;
            weights[i] = p.luminance() * jacobian;
            for (int c = 0; c < 3; ++c)
                integral[c] += double(p[c]) * jacobian * texelArea;
        }
    radianceIntegral_ = Rgb(float(integral[0]), float(integral[1]), float(integral[2]));
    // The map's own sampling tables, only when light samples follow the map.
    if (sampling_ != EnvSampling::Luminance) return;
    texels_ = TexelSampler(weights, image_.pixels, width, height);
    buildProxy(weights, jacobians);
}

void EnvironmentMap::buildProxy(const std::vector<float>& weights,
                                const std::vector<float>& jacobians) {
    const int block = proxyBlockSide(image_.width, image_.height);
    if (block == 1) return;
    const int columns = image_.width / block, rows = image_.height / block;
    std::vector<float> cellWeights(size_t(columns) * rows);
    proxy_.radiance.assign(cellWeights.size(), Rgb(0.0f));
    for (int row = 0; row < rows; ++row)
        for (int col = 0; col < columns; ++col) {
            double weight = 0, solidAngle = 0, radiance[3] = {0, 0, 0};
            for (int y = row * block; y < (row + 1) * block; ++y)
                for (int x = col * block; x < (col + 1) * block; ++x) {
                    const size_t i = size_t(y) * image_.width + x;
                    weight += weights[i];
                    solidAngle += jacobians[i];
                    for (int c = 0; c < 3; ++c)
                        radiance[c] += double(image_.pixels[i][c]) * jacobians[i];
                }
            const size_t cell = size_t(row) * columns + col;
            cellWeights[cell] = float(weight);
            if (solidAngle > 0)
                proxy_.radiance[cell] =
                    Rgb(float(radiance[0] / solidAngle), float(radiance[1] / solidAngle),
                        float(radiance[2] / solidAngle));
        }
    proxy_.distribution = Distribution2D(cellWeights, columns, rows);
    proxy_.block = block;
}

int EnvironmentMap::texelIndex(Vec2 st) const {
    const int col = std::clamp(static_cast<int>(st.x * float(image_.width)), 0, image_.width - 1);
    const int row = std::clamp(static_cast<int>(st.y * float(image_.height)), 0, image_.height - 1);
    return row * image_.width + col;
}

void EnvironmentMap::setDirection(const Vec3& reference, const Vec3& local,
                                  LightSample* out) const {
    aim(reference, normalize(toWorld_.toWorld(local)), out);
}

void EnvironmentMap::aim(const Vec3& reference, const Vec3& direction, LightSample* out) const {
    out->direction = direction;
    // Twice the diameter: outside the bounding sphere from any point inside it.
    out->position = reference + direction * (4.0f * radius_);
    out->normal = Vec3(0.0f);
    out->errorScale = 0;
    out->isDelta = false;
}

bool EnvironmentMap::sample(const LightReference& reference, Vec2 u, float,
                            LightSample* out) const {
    if (sampling_ != EnvSampling::Luminance) {
        Vec3 w;
        if (!sampleEnvDirection(sampling_, reference, u, &w, &out->pdf)) return false;
        aim(reference.point, w, out);
        out->radiance = escapedRadiance(w);
        return !out->radiance.isBlack();
    }
    TexelSampler::Ticket ticket;
    texels_.begin(u, &ticket);
    texels_.locate(&ticket);
    return sampleFromTexel(reference, ticket, out);
}

bool EnvironmentMap::sampleFromTexel(const LightReference& reference,
                                     const TexelSampler::Ticket& ticket, LightSample* out) const {
    TexelSampler::Draw draw;
    Vec3 local;
    float jacobian;
    // A point of a probe's rim texel may lie outside the disc: no direction, no sample (the
    // density below is then that of a distribution of total mass slightly below 1, which
    // keeps the estimator unbiased).
    if (!texels_.finish(ticket, &draw) || !layout_->direction(draw.point, &local, &jacobian) ||
        !(jacobian > 0))
        return false;
    setDirection(reference.point, local, out);
    out->radiance = draw.value;
    out->pdf = draw.density / jacobian;
    return std::isfinite(out->pdf) && !out->radiance.isBlack();
}

void EnvironmentMap::sampleMany(const LightReference& reference, std::span<const Vec2> u,
                                float time, LightSample* out, bool* drawn) const {
    if (sampling_ != EnvSampling::Luminance)
        return Light::sampleMany(reference, u, time, out, drawn);
    constexpr size_t kChunk = 16;
    std::array<TexelSampler::Ticket, kChunk> tickets;
    for (size_t first = 0; first < u.size(); first += kChunk) {
        const size_t count = std::min(kChunk, u.size() - first);
        for (size_t i = 0; i < count; ++i)
            texels_.begin(u[first + i], &tickets[i]);
        for (size_t i = 0; i < count; ++i)
            texels_.locate(&tickets[i]);
        for (size_t i = 0; i < count; ++i)
            drawn[first + i] = sampleFromTexel(reference, tickets[i], &out[first + i]);
    }
}

bool EnvironmentMap::sampleStandIn(const LightReference& reference, Vec2 u, float time,
                                   LightSample* out) const {
    if (proxy_.block == 1) return sample(reference, u, time, out);
    float imagePdf;
    int cell;
    const Vec2 st = proxy_.distribution.sample(u, &imagePdf, &cell);
    Vec3 local;
    float jacobian;
    if (imagePdf == 0 || !layout_->direction(st, &local, &jacobian) || !(jacobian > 0))
        return false;
    setDirection(reference.point, local, out);
    out->radiance = proxy_.radiance[size_t(cell)];
    // The density of the point's direction itself (the layout's Jacobian there, not a texel's
    // mean): the stand-in's pdf is exact, only its radiance approximates.
    out->pdf = imagePdf / jacobian;
    return std::isfinite(out->pdf) && !out->radiance.isBlack();
}

Rgb EnvironmentMap::escapedRadiance(const Vec3& w) const {
    return image_.pixels[size_t(texelIndex(layout_->imagePoint(toWorld_.toLocal(w))))];
}

float EnvironmentMap::imageDensity(Vec2 st) const {
    const int texel = texelIndex(st);
    return texels_.density(texel % image_.width, texel / image_.width);
}

float EnvironmentMap::directionPdf(const LightReference& reference, const Vec3& w) const {
    if (sampling_ != EnvSampling::Luminance) return envDirectionPdf(sampling_, reference, w);
    const Vec2 st = layout_->imagePoint(toWorld_.toLocal(w));
    const float jacobian = layout_->jacobian(st);
    return jacobian > 0 ? imageDensity(st) / jacobian : 0.0f;
}

bool EnvironmentMap::invertSample(const LightReference& reference, const Vec3& direction,
                                  const Vec3&, Vec2* u) const {
    if (sampling_ != EnvSampling::Luminance)
        return invertEnvDirection(sampling_, reference, direction, u);
    // The frame is orthonormal: toLocal undoes toWorld (sample()'s normalisation only removes
    // rounding). The image point is found exactly as directionPdf finds it, so invertSample
    // succeeds exactly where the density of the direction is positive.
    const Vec2 st = layout_->imagePoint(toWorld_.toLocal(direction));
    if (!(layout_->jacobian(st) > 0) || !(imageDensity(st) > 0)) return false;
    *u = texels_.invert(st);
    return true;
}

}  // namespace rr
