#include "support/histograms.h"

#include <algorithm>
#include <cmath>

namespace rr::test {

namespace {

constexpr int kSubdivisions = 16;
constexpr int kEdgeSubdivisions = 96;

// Nodes in [0, 1] and weights (summing to 1) of a one-dimensional rule.
struct QuadratureRule {
    std::vector<double> nodes, weights;
};

// The n-point Gauss–Legendre rule, exact for polynomials of degree 2n − 1: a smooth but
// peaked density (a cos^50 lobe across a cell) is integrated to ~1e-10, where the midpoint
// rule errs by ~1e-3 — which, with 10⁶ samples, is several standard deviations of a cell
// holding most of them. Nodes by Newton's method on the Legendre polynomial P_n (three-term
// recurrence), from the usual Chebyshev-like initial guesses.
QuadratureRule gaussLegendre(int n) {
    QuadratureRule rule{std::vector<double>(n), std::vector<double>(n)};
    for (int i = 0; i < n; ++i) {
        double x = std::cos(M_PI * (i + 0.75) / (n + 0.5)), derivative = 0;
        for (int iteration = 0; iteration < 100; ++iteration) {
            double p0 = 1, p1 = x;  // P_0, P_1
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            derivative = n * (x * p1 - p0) / (x * x - 1);  // P_n'(x)
            const double step = p1 / derivative;
            x -= step;
            if (std::abs(step) < 1e-15) break;
        }
        rule.nodes[i] = 0.5 * (1 - x);                                  // [−1, 1] → [0, 1]
        rule.weights[i] = 1 / ((1 - x * x) * derivative * derivative);  // 2/(…) halved
    }
    return rule;
}

// The midpoint rule on n sub-intervals: robust where the density is discontinuous.
QuadratureRule midpoint(int n) {
    QuadratureRule rule{std::vector<double>(n), std::vector<double>(n, 1.0 / n)};
    for (int i = 0; i < n; ++i)
        rule.nodes[i] = (i + 0.5) / n;
    return rule;
}

const QuadratureRule& smoothRule() {
    static const QuadratureRule rule = gaussLegendre(kSubdivisions);
    return rule;
}
const QuadratureRule& edgeRule() {
    static const QuadratureRule rule = midpoint(kEdgeSubdivisions);
    return rule;
}

// Mean of density(row, col, fraction, fraction) over one cell by the product rule;
// *mixed tells whether it was zero at some nodes and not at others.
double cellMean(const std::function<double(int, int, double, double)>& density, int row, int col,
                const QuadratureRule& rule, bool* mixed) {
    const int n = int(rule.nodes.size());
    double sum = 0;
    int zeros = 0;
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            const double d = density(row, col, rule.nodes[a], rule.nodes[b]);
            sum += rule.weights[a] * rule.weights[b] * d;
            zeros += d == 0;
        }
    if (mixed) *mixed = zeros > 0 && zeros < n * n;
    return sum;
}

// Expected counts of a rows × cols grid (row-major) plus an outside cell that expects nothing;
// `scale` turns a cell's mean density into its count. Edge cells are integrated finely.
std::vector<double> integrateCells(int rows, int cols, bool wrapColumns,
                                   const std::function<double(int, int, double, double)>& density,
                                   double scale) {
    std::vector<double> mean(size_t(rows) * cols);
    std::vector<char> mixed(mean.size());
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            bool m;
            mean[size_t(r) * cols + c] = cellMean(density, r, c, smoothRule(), &m);
            mixed[size_t(r) * cols + c] = m;
        }
    std::vector<double> out(mean.size() + 1, 0.0);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            const size_t i = size_t(r) * cols + c;
            bool edge = mixed[i];
            for (int dr = -1; dr <= 1 && !edge; ++dr)
                for (int dc = -1; dc <= 1 && !edge; ++dc) {
                    int rr = r + dr, cc = c + dc;
                    if (wrapColumns) cc = (cc + cols) % cols;
                    if (rr < 0 || rr >= rows || cc < 0 || cc >= cols) continue;
                    edge = (mean[i] == 0) != (mean[size_t(rr) * cols + cc] == 0);
                }
            out[i] = scale * (edge ? cellMean(density, r, c, edgeRule(), nullptr) : mean[i]);
        }
    return out;
}

}  // namespace

DirectionHistogram::DirectionHistogram(int zCells, int phiCells, double zMin)
    : zCells_(zCells), phiCells_(phiCells), zMin_(zMin), counts_(size_t(zCells) * phiCells + 1) {}

size_t DirectionHistogram::cellOf(const Vec3& w) const {
    const double len = std::sqrt(double(w.x) * w.x + double(w.y) * w.y + double(w.z) * w.z);
    const double z = w.z / len;
    if (z < zMin_ || !std::isfinite(z)) return counts_.size() - 1;
    double phi = std::atan2(double(w.y), double(w.x));
    if (phi < 0) phi += 2 * M_PI;
    const int iz = std::min(int((z - zMin_) / (1.0 - zMin_) * zCells_), zCells_ - 1);
    const int ip = std::min(int(phi / (2 * M_PI) * phiCells_), phiCells_ - 1);
    return size_t(iz) * phiCells_ + ip;
}

void DirectionHistogram::add(const Vec3& w, double weight) {
    counts_[cellOf(w)] += weight;
}

Vec3 DirectionHistogram::direction(double zCell, double phiCell) const {
    const double z = zMin_ + zCell * (1.0 - zMin_) / zCells_;
    const double phi = phiCell * 2 * M_PI / phiCells_;
    const double r = std::sqrt(std::max(0.0, 1 - z * z));
    return Vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
}

std::vector<double> DirectionHistogram::expected(const std::function<double(const Vec3&)>& pdf,
                                                 double samples) const {
    const double cellArea = (1.0 - zMin_) / zCells_ * (2 * M_PI / phiCells_);  // dω = dz dφ
    return integrateCells(
        zCells_, phiCells_, /*wrapColumns=*/true,
        [&](int iz, int ip, double fz, double fp) { return pdf(direction(iz + fz, ip + fp)); },
        cellArea * samples);
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
                                             double samples) const {
    const double dx = (x1_ - x0_) / xCells_, dy = (y1_ - y0_) / yCells_;
    return integrateCells(
        yCells_, xCells_, /*wrapColumns=*/false,
        [&](int iy, int ix, double fy, double fx) {
            return pdf(Vec2(float(x0_ + (ix + fx) * dx), float(y0_ + (iy + fy) * dy)));
        },
        dx * dy * samples);
}

}  // namespace rr::test
