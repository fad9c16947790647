#include "support/histograms.h"

#include <algorithm>
#include <cmath>

namespace rr::test {

DirectionHistogram::DirectionHistogram(int zCells, int phiCells, double zMin)
    : zCells_(zCells), phiCells_(phiCells), zMin_(zMin), counts_(size_t(zCells) * phiCells + 1) {}

void DirectionHistogram::add(const Vec3& w) {
    const double len = std::sqrt(double(w.x) * w.x + double(w.y) * w.y + double(w.z) * w.z);
    const double z = w.z / len;
    if (z < zMin_ || !std::isfinite(z)) {
        counts_.back() += 1;
        return;
    }
    double phi = std::atan2(double(w.y), double(w.x));
    if (phi < 0) phi += 2 * M_PI;
    const int iz = std::min(int((z - zMin_) / (1.0 - zMin_) * zCells_), zCells_ - 1);
    const int ip = std::min(int(phi / (2 * M_PI) * phiCells_), phiCells_ - 1);
    counts_[size_t(iz) * phiCells_ + ip] += 1;
}

std::vector<double> DirectionHistogram::expected(const std::function<double(const Vec3&)>& pdf,
                                                 double samples, int subdivisions) const {
    std::vector<double> out(counts_.size(), 0.0);
    const double dz = (1.0 - zMin_) / zCells_, dphi = 2 * M_PI / phiCells_;
    const double subArea = (dz / subdivisions) * (dphi / subdivisions);
    for (int iz = 0; iz < zCells_; ++iz)
        for (int ip = 0; ip < phiCells_; ++ip) {
            double mass = 0;
            for (int a = 0; a < subdivisions; ++a)
                for (int b = 0; b < subdivisions; ++b) {
                    const double z = zMin_ + (iz + (a + 0.5) / subdivisions) * dz;
                    const double phi = (ip + (b + 0.5) / subdivisions) * dphi;
                    const double r = std::sqrt(std::max(0.0, 1 - z * z));
                    mass += pdf(Vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)));
                }
            out[size_t(iz) * phiCells_ + ip] = mass * subArea * samples;
        }
    return out;  // the outside cell expects nothing: the domain must contain the support
}

PlaneHistogram::PlaneHistogram(int xCells, int yCells, double x0, double x1, double y0, double y1)
    : xCells_(xCells),
      yCells_(yCells),
      x0_(x0),
      x1_(x1),
      y0_(y0),
      y1_(y1),
      counts_(size_t(xCells) * yCells + 1) {}

void PlaneHistogram::add(const Vec2& p) {
    const double fx = (p.x - x0_) / (x1_ - x0_), fy = (p.y - y0_) / (y1_ - y0_);
    if (!(fx >= 0 && fx <= 1 && fy >= 0 && fy <= 1)) {
        counts_.back() += 1;
        return;
    }
    const int ix = std::min(int(fx * xCells_), xCells_ - 1);
    const int iy = std::min(int(fy * yCells_), yCells_ - 1);
    counts_[size_t(iy) * xCells_ + ix] += 1;
}

std::vector<double> PlaneHistogram::expected(const std::function<double(const Vec2&)>& pdf,
                                             double samples, int subdivisions) const {
    std::vector<double> out(counts_.size(), 0.0);
    const double dx = (x1_ - x0_) / xCells_, dy = (y1_ - y0_) / yCells_;
    const double subArea = (dx / subdivisions) * (dy / subdivisions);
    for (int iy = 0; iy < yCells_; ++iy)
        for (int ix = 0; ix < xCells_; ++ix) {
            double mass = 0;
            for (int a = 0; a < subdivisions; ++a)
                for (int b = 0; b < subdivisions; ++b)
                    mass += pdf(Vec2(float(x0_ + (ix + (a + 0.5) / subdivisions) * dx),
                                     float(y0_ + (iy + (b + 0.5) / subdivisions) * dy)));
            out[size_t(iy) * xCells_ + ix] = mass * subArea * samples;
        }
    return out;  // the outside cell expects nothing: the domain covers the whole support
}

}  // namespace rr::test
