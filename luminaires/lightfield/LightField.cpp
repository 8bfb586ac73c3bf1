// The light-field model of Lu et al. 2015: precomputed tables, the basis and kernel, restricted
// boxes and their summed-area integrals, box sampling, power and Granier's table. Loading and
// saving manifests is in LightFieldIo.cpp.
#include "luminaires/lightfield/LightField.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <thread>

#include "util/Threads.h"

namespace candela {

double bspline2(double x) {
    x = std::abs(x);
    if (x < 0.5) return 0.75 - x * x;
    if (x < 1.5) return 0.5 * (1.5 - x) * (1.5 - x);
    return 0.0;
}

namespace {

constexpr double kGauss4X[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                0.8611363115940526};
constexpr double kGauss4W[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                0.3478548451374538};
/// Relative energy below which a summed-area difference is rounding noise (doubles keep ~1e-16;
/// 1e-12 leaves room for tables of 8192^2 pixels).
constexpr double kEnergyFloor = 1e-12;

/// Search over the knots 0..n of a non-decreasing piecewise linear function for the piece
/// [k, k+1] with value(k) <= target < value(k+1) (the last rising piece when target is at the
/// top). Secant guesses on the knot index, falling back to bisection when a guess does not halve
/// the bracket: the "modified secant" inversion of Sec. 5, which stops as soon as the bracket is
/// one linear piece. Returns k, or -1 when the function does not rise at all.
template <class Fn>
int findPiece(int n, double target, const Fn& value) {
    int lo = 0, hi = n;
    double vlo = value(lo), vhi = value(hi);
    if (!(vhi > vlo)) return -1;
    if (target >= vhi) {
        // Top end: the last piece that rises.
        for (int k = n - 1; k >= 0; --k)
            if (value(k + 1) > value(k)) return k;
        return -1;
    }
    bool bisect = false;
    while (hi - lo > 1) {
        int mid;
        if (bisect) {
            mid = lo + (hi - lo) / 2;
        } else {
            double f = (target - vlo) / (vhi - vlo);
            mid = lo + int(f * double(hi - lo));
            mid = std::clamp(mid, lo + 1, hi - 1);
        }
        int before = hi - lo;
        double v = value(mid);
        if (v > target) {
            hi = mid;
            vhi = v;
        } else {
            lo = mid;
            vlo = v;
        }
        bisect = (hi - lo) * 2 > before;  // the guess did not halve the bracket
    }
    // lo..hi is one piece with vlo <= target < vhi.
    return lo;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Precomputation (Sec. 3.1)

namespace {

/// Image m's tables (Sec. 3.1): its summed-area table, marginal CDF and median (Sec. 6.2).
void precomputeImage(const LightFieldData& lf, size_t m, LightFieldTables& t) {
    glm::dvec2 px = lf.pixelSize();
    double area = px.x * px.y;
    size_t w = size_t(lf.width), h = size_t(lf.height);
    const std::vector<float>& c = lf.images[m].luminance;
    t.sat.assign((w + 1) * (h + 1), 0.0);
    for (size_t j = 0; j < h; ++j) {
        double row = 0.0;
        for (size_t i = 0; i < w; ++i) {
            row += double(c[j * w + i]) * area;
            t.sat[(j + 1) * (w + 1) + i + 1] = t.sat[j * (w + 1) + i + 1] + row;
        }
    }
    t.total = t.sat.back();
    t.marginalCdf.assign(w + 1, 0.0);
    for (size_t i = 0; i <= w; ++i)
        t.marginalCdf[i] = t.total > 0.0 ? t.sat[h * (w + 1) + i] / t.total : double(i) / double(w);
    // Sec. 6.2: s_m with cdf_m(s) = 0.5 and cdf_m(t | s) = 0.5.
    t.median = 0.5 * (lf.imageMin + lf.imageMax);
    if (!(t.total > 0.0)) return;
    int ci = findPiece(int(w), 0.5, [&](int k) { return t.marginalCdf[size_t(k)]; });
    if (ci < 0) return;
    double a = t.marginalCdf[size_t(ci)], b = t.marginalCdf[size_t(ci) + 1];
    t.median.x = lf.imageMin.x + (double(ci) + (0.5 - a) / (b - a)) * px.x;
    std::vector<double> col(h + 1);
    for (size_t j = 0; j <= h; ++j) col[j] = t.conditionalCdf(size_t(ci), j, w, h);
    int rj = findPiece(int(h), 0.5, [&](int k) { return col[size_t(k)]; });
    if (rj >= 0)
        t.median.y =
            lf.imageMin.y +
            (double(rj) + (0.5 - col[size_t(rj)]) / (col[size_t(rj) + 1] - col[size_t(rj)])) * px.y;
}

}  // namespace

void LightFieldData::precompute() {
    auto start = std::chrono::steady_clock::now();
    tables.assign(images.size(), {});
    // The images are independent: shared among the cores, each worker taking the next image.
    // Most of the time is the first touch of each table's memory (half a megabyte of doubles
    // for 256^2 pixels), which the cores then share too.
    size_t workers =
        std::min<size_t>(std::clamp(std::thread::hardware_concurrency(), 1u, 8u), images.size());
    std::atomic<size_t> next{0};
    std::mutex failedMutex;
    std::exception_ptr failed;
    auto work = [&] {
        try {
            for (size_t m; (m = next++) < images.size();) precomputeImage(*this, m, tables[m]);
        } catch (...) {  // std::bad_alloc: rethrown on the calling thread
            std::lock_guard<std::mutex> lock(failedMutex);
            failed = std::current_exception();
            next = images.size();
        }
    };
    runInParallel(int(workers), work);
    if (failed) std::rethrow_exception(failed);
    precomputeMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// ---------------------------------------------------------------------------------------------
// Geometry

glm::dvec2 LightFieldData::node(int m) const {
    return origin + glm::dvec2(double(m % count.x) * spacing.x, double(m / count.x) * spacing.y);
}

void LightFieldData::support(int m, glm::dvec2& uMin, glm::dvec2& uMax) const {
    glm::dvec2 c = node(m);
    uMin = c - 1.5 * spacing;
    uMax = c + 1.5 * spacing;
}

double LightFieldData::basis(int m, const glm::dvec2& u) const {
    glm::dvec2 d = (u - node(m)) / spacing;
    return bspline2(d.x) * bspline2(d.y);
}

double LightFieldData::psi(int m, const glm::dvec2& u, const glm::dvec2& s) const {
    double phi = basis(m, u);
    if (model == Model::Canned || phi == 0.0) return phi;
    // "goesele": Psi = Phi delta^2 cos^4(theta), theta the ray's angle with the planes' normal.
    glm::dvec2 d = s - u;
    double c2 = delta * delta / (delta * delta + glm::dot(d, d));
    return phi * delta * delta * c2 * c2;
}

glm::dvec2 LightFieldData::pixelSize() const {
    return (imageMax - imageMin) / glm::dvec2(double(width), double(height));
}

double LightFieldData::lum(int m, const glm::dvec2& s) const {
    glm::dvec2 f = (s - imageMin) / pixelSize();
    if (!(f.x >= 0.0 && f.y >= 0.0 && f.x < double(width) && f.y < double(height))) return 0.0;
    return double(images[size_t(m)].luminance[size_t(int(f.y)) * size_t(width) + size_t(int(f.x))]);
}

glm::dvec3 LightFieldData::colour(int m, const glm::dvec2& s) const {
    if (!rgb) return glm::dvec3(1.0);
    glm::dvec2 f = (s - imageMin) / pixelSize();
    if (!(f.x >= 0.0 && f.y >= 0.0 && f.x < double(width) && f.y < double(height)))
        return glm::dvec3(1.0);
    return glm::dvec3(
        images[size_t(m)].colour[size_t(int(f.y)) * size_t(width) + size_t(int(f.x))]);
}

glm::dvec3 LightFieldData::radiance(const glm::dvec2& u, const glm::dvec2& s) const {
    glm::dvec3 sum(0.0);
    // Only the (up to) 3 x 3 basis functions whose support holds u contribute.
    glm::dvec2 g = (u - origin) / spacing;
    int i0 = std::max(0, int(std::ceil(g.x - 1.5))),
        i1 = std::min(count.x - 1, int(std::floor(g.x + 1.5)));
    int j0 = std::max(0, int(std::ceil(g.y - 1.5))),
        j1 = std::min(count.y - 1, int(std::floor(g.y + 1.5)));
    for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
            int m = j * count.x + i;
            double c = lum(m, s);
            if (c > 0.0) sum += c * psi(m, u, s) * colour(m, s);
        }
    return sum;
}

bool LightFieldData::restrictedBox(int m, const glm::dvec3& q, glm::dvec2& sMin,
                                   glm::dvec2& sMax) const {
    if (!(q.z > delta)) return false;
    glm::dvec2 uMin, uMax;
    support(m, uMin, uMax);
    // The line from q through u meets S at s = u + (q - u) delta / q.z (seed 000 Eq. 7 with the
    // U-plane term the printed equation drops); s grows with u, so the box maps to a box.
    double f = delta / q.z;
    glm::dvec2 p(q.x, q.y);
    sMin = glm::max(uMin + (p - uMin) * f, imageMin);
    sMax = glm::min(uMax + (p - uMax) * f, imageMax);
    return sMax.x > sMin.x && sMax.y > sMin.y;
}

namespace {

/// Integral of C over [s0, x] x [s0, y] from the summed-area table: bilinear within a pixel,
/// which is exact for a piecewise constant image.
double satAt(const LightFieldData& lf, const LightFieldTables& t, glm::dvec2 s) {
    glm::dvec2 f = glm::clamp((s - lf.imageMin) / lf.pixelSize(), glm::dvec2(0.0),
                              glm::dvec2(double(lf.width), double(lf.height)));
    int i = std::min(int(f.x), lf.width - 1), j = std::min(int(f.y), lf.height - 1);
    double fx = f.x - i, fy = f.y - j;
    size_t w1 = size_t(lf.width) + 1;
    double s00 = t.sat[size_t(j) * w1 + size_t(i)], s10 = t.sat[size_t(j) * w1 + size_t(i) + 1];
    double s01 = t.sat[size_t(j + 1) * w1 + size_t(i)],
           s11 = t.sat[size_t(j + 1) * w1 + size_t(i) + 1];
    return s00 + fx * (s10 - s00) + fy * (s01 - s00) + fx * fy * (s11 - s10 - s01 + s00);
}

}  // namespace

namespace {

/// Pixels [i0, i1) x [j0, j1) that a box on S covers (clamped to the image).
struct PixelSpan {
    int i0, i1, j0, j1;
    int columns() const { return i1 - i0; }
    int rows() const { return j1 - j0; }
};
PixelSpan spanOf(const LightFieldData& lf, glm::dvec2 a, glm::dvec2 b) {
    glm::dvec2 px = lf.pixelSize();
    PixelSpan s;
    s.i0 = std::clamp(int(std::floor((a.x - lf.imageMin.x) / px.x)), 0, lf.width - 1);
    s.i1 = std::clamp(int(std::ceil((b.x - lf.imageMin.x) / px.x)), s.i0 + 1, lf.width);
    s.j0 = std::clamp(int(std::floor((a.y - lf.imageMin.y) / px.y)), 0, lf.height - 1);
    s.j1 = std::clamp(int(std::ceil((b.y - lf.imageMin.y) / px.y)), s.j0 + 1, lf.height);
    return s;
}

/// Boxes of at most this many pixels per side are integrated and sampled pixel by pixel: the
/// summed-area table's differences of large partial sums lose a small box's energy to rounding
/// (a receiver 1e-9 m beyond S has boxes 1e-8 of a pixel wide: the table gave 0).
constexpr int kDirectPixels = 4;

/// Overlap of [lo, hi] with pixel k of size `size` starting at `origin`.
double overlap(double lo, double hi, double origin, double size, int k) {
    return std::max(0.0, std::min(hi, origin + (k + 1) * size) - std::max(lo, origin + k * size));
}

}  // namespace

double LightFieldData::boxIntegral(int m, glm::dvec2 a, glm::dvec2 b) const {
    if (!(b.x > a.x && b.y > a.y)) return 0.0;
    a = glm::max(a, imageMin);
    b = glm::min(b, imageMax);
    if (!(b.x > a.x && b.y > a.y)) return 0.0;
    PixelSpan span = spanOf(*this, a, b);
    if (span.columns() <= kDirectPixels && span.rows() <= kDirectPixels) {
        glm::dvec2 px = pixelSize();
        double sum = 0.0;
        for (int j = span.j0; j < span.j1; ++j) {
            double h = overlap(a.y, b.y, imageMin.y, px.y, j);
            for (int i = span.i0; i < span.i1; ++i)
                sum += double(images[size_t(m)].luminance[size_t(j) * size_t(width) + size_t(i)]) *
                       h * overlap(a.x, b.x, imageMin.x, px.x, i);
        }
        return sum;
    }
    const LightFieldTables& t = tables[size_t(m)];
    double v = satAt(*this, t, b) - satAt(*this, t, {a.x, b.y}) - satAt(*this, t, {b.x, a.y}) +
               satAt(*this, t, a);
    // Below 1e-12 of the image's energy the difference is the table's rounding, not energy.
    return v > kEnergyFloor * t.total ? v : 0.0;
}

bool LightFieldData::sampleBox(int m, const glm::dvec2& a, const glm::dvec2& b, glm::dvec2 xi,
                               glm::dvec2& s) const {
    const LightFieldTables& t = tables[size_t(m)];
    glm::dvec2 px = pixelSize();
    PixelSpan span = spanOf(*this, a, b);
    if (span.columns() <= kDirectPixels && span.rows() <= kDirectPixels) {
        // Small boxes pixel by pixel: a column by its energy, x uniform within it (the density is
        // constant along a pixel row), then a row of that column by its energy, y uniform in it.
        const std::vector<float>& image = images[size_t(m)].luminance;
        auto energy = [&](int i, int j) {
            return double(image[size_t(j) * size_t(width) + size_t(i)]) *
                   overlap(a.x, b.x, imageMin.x, px.x, i) * overlap(a.y, b.y, imageMin.y, px.y, j);
        };
        double column[kDirectPixels] = {}, total = 0.0;
        for (int i = span.i0; i < span.i1; ++i) {
            for (int j = span.j0; j < span.j1; ++j) column[i - span.i0] += energy(i, j);
            total += column[i - span.i0];
        }
        if (!(total > 0.0)) return false;
        double target = std::clamp(xi.x, 0.0, 1.0) * total;
        int i = span.i0;
        for (; i + 1 < span.i1 && target > column[i - span.i0]; ++i) target -= column[i - span.i0];
        if (!(column[i - span.i0] > 0.0)) return false;
        double x0 = std::max(a.x, imageMin.x + i * px.x),
               x1 = std::min(b.x, imageMin.x + (i + 1) * px.x);
        s.x =
            std::clamp(x0 + std::clamp(target / column[i - span.i0], 0.0, 1.0) * (x1 - x0), x0, x1);
        double targetY = std::clamp(xi.y, 0.0, 1.0) * column[i - span.i0];
        int j = span.j0;
        for (; j + 1 < span.j1 && targetY > energy(i, j); ++j) targetY -= energy(i, j);
        double e = energy(i, j);
        if (!(e > 0.0)) return false;
        double y0 = std::max(a.y, imageMin.y + j * px.y),
               y1 = std::min(b.y, imageMin.y + (j + 1) * px.y);
        s.y = std::clamp(y0 + std::clamp(targetY / e, 0.0, 1.0) * (y1 - y0), y0, y1);
        return true;
    }
    // Knots of the restricted marginal G(x) = F(x, b.y) - F(x, a.y): the box's ends and the pixel
    // column edges between them (Eq. 8, cdf_m(s | p), built from the SAT rather than the global
    // marginal so that the density is exactly C_m / A_m, Eq. 10).
    int c0 = std::clamp(int(std::floor((a.x - imageMin.x) / px.x)), 0, width - 1);
    int c1 = std::clamp(int(std::ceil((b.x - imageMin.x) / px.x)), c0 + 1, width);
    auto knotX = [&](int k) { return std::clamp(imageMin.x + double(c0 + k) * px.x, a.x, b.x); };
    auto G = [&](int k) {
        double x = knotX(k);
        return satAt(*this, t, {x, b.y}) - satAt(*this, t, {x, a.y});
    };
    int nx = c1 - c0;
    double g0 = G(0), g1 = G(nx);
    if (!(g1 - g0 > kEnergyFloor * t.total)) return false;
    double target = g0 + std::clamp(xi.x, 0.0, 1.0) * (g1 - g0);
    int kx = findPiece(nx, target, G);
    if (kx < 0) return false;
    double ga = G(kx), gb = G(kx + 1), xa = knotX(kx), xb = knotX(kx + 1);
    s.x = std::clamp(xa + (target - ga) / (gb - ga) * (xb - xa), xa, xb);
    int column = c0 + kx;

    // Conditional in t within that pixel column (Eq. 8, cdf_m(t | s, p)).
    int r0 = std::clamp(int(std::floor((a.y - imageMin.y) / px.y)), 0, height - 1);
    int r1 = std::clamp(int(std::ceil((b.y - imageMin.y) / px.y)), r0 + 1, height);
    double colL = imageMin.x + double(column) * px.x, colR = colL + px.x;
    auto knotY = [&](int k) { return std::clamp(imageMin.y + double(r0 + k) * px.y, a.y, b.y); };
    auto H = [&](int k) {
        double y = knotY(k);
        return satAt(*this, t, {colR, y}) - satAt(*this, t, {colL, y});
    };
    int ny = r1 - r0;
    double h0 = H(0), h1 = H(ny);
    if (!(h1 - h0 > kEnergyFloor * t.total)) return false;
    double targetY = h0 + std::clamp(xi.y, 0.0, 1.0) * (h1 - h0);
    int ky = findPiece(ny, targetY, H);
    if (ky < 0) return false;
    double ha = H(ky), hb = H(ky + 1), ya = knotY(ky), yb = knotY(ky + 1);
    s.y = std::clamp(ya + (targetY - ha) / (hb - ha) * (yb - ya), ya, yb);
    // Keep s inside the chosen pixel column even where x fell on its edge.
    s.x = std::clamp(s.x, std::max(colL, a.x), std::min(colR, b.x));
    return true;
}

// ---------------------------------------------------------------------------------------------
// Power

glm::dvec3 LightFieldData::cachedPower() const {
    std::call_once(mPowerOnce, [&] { mPower = power(); });
    return mPower;
}

namespace {

/// Psi of the basis function centred on 0 for the ray from u on U to the offset o on S (Eq. 1).
double psiAt(const LightFieldData& lf, glm::dvec2 u, glm::dvec2 o) {
    double d2 = lf.delta * lf.delta;
    double phi = bspline2(u.x / lf.spacing.x) * bspline2(u.y / lf.spacing.y);
    if (lf.model == LightFieldData::Model::Goesele) {
        glm::dvec2 d = o - u;
        double c2 = d2 / (d2 + glm::dot(d, d));
        phi *= d2 * c2 * c2;
    }
    return phi;
}

/// Integral over the cell [lo, hi] of U of Psi(u->o) delta^2 / |u - o|^4: 4 x 4 Gauss-Legendre,
/// the cell split while it is large next to its distance from o plus delta: in four, or, more
/// than twice as long as wide, across its long side only (quartering would double the cells
/// near the peak at every level: fuzzing found a basis spacing of 5.02 x 0.02 m whose power took
/// minutes). Square cells, as in every real file, are quartered.
double kernelCell(const LightFieldData& lf, glm::dvec2 lo, glm::dvec2 hi, glm::dvec2 o, int depth) {
    double d2 = lf.delta * lf.delta;
    glm::dvec2 size = hi - lo;
    glm::dvec2 nearest = glm::clamp(o, lo, hi);
    double dist = glm::length(nearest - o);
    if (depth < 8 && std::max(size.x, size.y) > 0.5 * (dist + lf.delta)) {
        glm::dvec2 mid = 0.5 * (lo + hi);
        if (size.x > 2.0 * size.y)
            return kernelCell(lf, lo, {mid.x, hi.y}, o, depth + 1) +
                   kernelCell(lf, {mid.x, lo.y}, hi, o, depth + 1);
        if (size.y > 2.0 * size.x)
            return kernelCell(lf, lo, {hi.x, mid.y}, o, depth + 1) +
                   kernelCell(lf, {lo.x, mid.y}, hi, o, depth + 1);
        return kernelCell(lf, lo, mid, o, depth + 1) +
               kernelCell(lf, {mid.x, lo.y}, {hi.x, mid.y}, o, depth + 1) +
               kernelCell(lf, {lo.x, mid.y}, {mid.x, hi.y}, o, depth + 1) +
               kernelCell(lf, mid, hi, o, depth + 1);
    }
    double sum = 0.0;
    for (int b = 0; b < 4; ++b)
        for (int a = 0; a < 4; ++a) {
            glm::dvec2 u = lo + 0.5 * (glm::dvec2(kGauss4X[a], kGauss4X[b]) + 1.0) * size;
            glm::dvec2 d = u - o;
            double r2 = glm::dot(d, d) + d2;
            sum += kGauss4W[a] * kGauss4W[b] * psiAt(lf, u, o) * d2 / (r2 * r2);
        }
    return sum * 0.25 * size.x * size.y;
}

/// G(o) of LightFieldData::power, over the support's 3 x 3 knot cells.
double kernelAt(const LightFieldData& lf, glm::dvec2 o) {
    double sum = 0.0;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            glm::dvec2 lo = glm::dvec2(-1.5 + i, -1.5 + j) * lf.spacing;
            sum += kernelCell(lf, lo, lo + lf.spacing, o, 0);
        }
    return sum;
}

/// G tabulated over the offsets s - node that occur (n points from oMin, step st), read
/// bilinearly. Entries are computed when a lookup first needs them: the offsets of one image
/// fill only a patch of the table's bounding range, and where the basis spacing is large next to
/// the image (fuzzing found 1.02 m around an image of 8 cm, delta 3 cm) the patches of all images
/// cover 1 % of it, while each entry costs a refined quadrature. Not thread-safe (power() runs
/// once, on one thread).
class KernelTable {
  public:
    explicit KernelTable(const LightFieldData& lf) : mLf(lf) {
        // Offsets s - node over all pixels and nodes.
        glm::dvec2 nodeMin = lf.origin, nodeMax = lf.origin + glm::dvec2(lf.count - 1) * lf.spacing;
        oMin = lf.imageMin - nodeMax;
        glm::dvec2 oMax = lf.imageMax - nodeMin;
        double step = std::min({lf.delta, lf.spacing.x, lf.spacing.y}) / 6.0;
        // Clamped as doubles: an image 3e7 m across (fuzzing) needs 9e9 points, beyond int.
        glm::dvec2 points = glm::ceil((oMax - oMin) / step) + 1.0;
        n = glm::ivec2(std::isfinite(points.x) ? std::clamp(points.x, 2.0, 400.0) : 400.0,
                       std::isfinite(points.y) ? std::clamp(points.y, 2.0, 400.0) : 400.0);
        st = (oMax - oMin) / glm::dvec2(n - 1);
        // A range lost to rounding (fuzzing: a basis origin of 1e308 m next to an image of 8 cm,
        // where oMax - oMin is 0) gets a positive step, so lookups clamp to its ends instead of
        // dividing by 0.
        for (int a = 0; a < 2; ++a)
            if (!(st[a] > 0.0) || !std::isfinite(st[a])) st[a] = step > 0.0 ? step : 1.0;
        table.assign(size_t(n.x) * size_t(n.y), std::numeric_limits<double>::quiet_NaN());
    }

    double lookup(glm::dvec2 o) {
        glm::dvec2 f = (o - oMin) / st;
        for (int a = 0; a < 2; ++a)
            if (std::isnan(f[a])) f[a] = 0.0;  // infinities clamp to an end below
        f = glm::clamp(f, glm::dvec2(0.0), glm::dvec2(n - 1) - 1e-9);
        int i = int(f.x), j = int(f.y);
        double fx = f.x - i, fy = f.y - j;
        return (1 - fy) * ((1 - fx) * entry(i, j) + fx * entry(i + 1, j)) +
               fy * ((1 - fx) * entry(i, j + 1) + fx * entry(i + 1, j + 1));
    }

  private:
    double entry(int i, int j) {
        double& e = table[size_t(j) * size_t(n.x) + size_t(i)];
        if (std::isnan(e)) {  // G itself is finite: NaN marks an entry not computed yet
            e = kernelAt(mLf, oMin + glm::dvec2(i, j) * st);
        }
        return e;
    }

    const LightFieldData& mLf;
    glm::dvec2 oMin{0.0}, st{0.0};
    glm::ivec2 n{0};
    std::vector<double> table;
};

}  // namespace

glm::dvec3 LightFieldData::power() const {
    // Flux = sum_m sum_pixels C_m(pixel) int_pixel G_m(s) ds with
    // G_m(s) = int_U Psi_m(u->s) delta^2 / |u - s|^4 du (L cos(theta_u) cos(theta_s) / r^2, both
    // cosines delta / r). G_m(s) = G(s - node_m) for all m, so G is tabulated once over the
    // offsets that occur and read bilinearly; each table entry is a Gauss-Legendre quadrature over
    // the support's 3 x 3 knot cells, refined near the kernel's peak (width delta).
    KernelTable kernel(*this);
    glm::dvec2 px = pixelSize();
    double g = 0.5773502691896258;  // 2 x 2 Gauss points per pixel
    glm::dvec3 flux(0.0);
    for (int m = 0; m < imageCount(); ++m) {
        glm::dvec2 c = node(m);
        const LightFieldImage& img = images[size_t(m)];
        for (int j = 0; j < height; ++j)
            for (int i = 0; i < width; ++i) {
                double v = img.luminance[size_t(j) * size_t(width) + size_t(i)];
                if (v <= 0.0) continue;
                glm::dvec2 centre = imageMin + (glm::dvec2(i, j) + 0.5) * px;
                double sum = 0.0;
                for (int b = -1; b <= 1; b += 2)
                    for (int a = -1; a <= 1; a += 2)
                        sum += kernel.lookup(centre + 0.5 * px * glm::dvec2(a * g, b * g) - c);
                double e = v * 0.25 * sum * px.x * px.y;
                flux += e * (rgb ? glm::dvec3(img.colour[size_t(j) * size_t(width) + size_t(i)])
                                 : glm::dvec3(1.0));
            }
    }
    return flux;
}

namespace {

/// Antiderivative of the uniform quadratic B-spline (support [-1.5, 1.5]): 0 below, 1 above.
double bsplineIntegral(double x) {
    if (x <= -1.5) return 0.0;
    if (x >= 1.5) return 1.0;
    if (x < -0.5) return (x + 1.5) * (x + 1.5) * (x + 1.5) / 6.0;
    if (x < 0.5) return 1.0 / 6.0 + 0.75 * (x + 0.5) - (x * x * x + 0.125) / 3.0;
    return 1.0 - (1.5 - x) * (1.5 - x) * (1.5 - x) / 6.0;
}

}  // namespace

const GranierTable& LightFieldData::granierTable() const {
    std::call_once(mGranierOnce, [&] {
        // W_m(c) = int C_m(s) Phi_m(s - c + node_m) ds, the exact far field of image m for the
        // box centred on c, and U_m(c) = (1/9) int over the support centred on c of C_m, what
        // Granier et al.'s spot light has there; both separable in x and y, so per image
        // W = Ix C Iy^T with Ix[k][i] the integral of the B-spline over pixel column i for the
        // k-th centre (its antiderivative, exact), and likewise the box for U.
        GranierTable& g = mGranier;
        g.size = kGranierTableSize;
        glm::dvec2 margin = 1.5 * spacing;
        g.min = imageMin - margin;
        g.max = imageMax + margin;
        glm::dvec2 px = pixelSize();
        glm::dvec2 step = (g.max - g.min) / double(g.size - 1);
        auto weights = [&](int axis, int pixels, bool box) {  // box: unused (B-spline weights)
            std::vector<double> w(size_t(g.size) * size_t(pixels));
            for (int k = 0; k < g.size; ++k) {
                double c = g.min[axis] + k * step[axis], h = spacing[axis];
                for (int i = 0; i < pixels; ++i) {
                    double a = (imageMin[axis] + i * px[axis] - c) / h,
                           b = (imageMin[axis] + (i + 1) * px[axis] - c) / h;
                    double v = box ? std::max(0.0, std::min(b, 1.5) - std::max(a, -1.5)) / 3.0
                                   : bsplineIntegral(b) - bsplineIntegral(a);
                    w[size_t(k) * size_t(pixels) + size_t(i)] = v * h;
                }
            }
            return w;
        };
        std::vector<double> bx = weights(0, width, false), by = weights(1, height, false);
        g.weighted.assign(size_t(imageCount()) * size_t(g.size) * size_t(g.size), 0.f);
        std::vector<double> rows(size_t(height) * size_t(g.size));
        for (int m = 0; m < imageCount(); ++m) {
            const std::vector<float>& c = images[size_t(m)].luminance;
            // Rows first: R[j][k] = sum_i C[j][i] Ix[k][i]; then W[l][k] = sum_j R[j][k] Iy[l][j].
            for (int j = 0; j < height; ++j)
                for (int k = 0; k < g.size; ++k) {
                    double sum = 0.0;
                    const float* row = &c[size_t(j) * size_t(width)];
                    const double* w = &bx[size_t(k) * size_t(width)];
                    for (int i = 0; i < width; ++i) sum += double(row[i]) * w[i];
                    rows[size_t(j) * size_t(g.size) + size_t(k)] = sum;
                }
            for (int l = 0; l < g.size; ++l)
                for (int k = 0; k < g.size; ++k) {
                    double w = 0.0;
                    for (int j = 0; j < height; ++j)
                        w += rows[size_t(j) * size_t(g.size) + size_t(k)] *
                             by[size_t(l) * size_t(height) + size_t(j)];
                    g.weighted[(size_t(m) * size_t(g.size) + size_t(l)) * size_t(g.size) +
                               size_t(k)] = float(std::max(0.0, w));
                }
        }
    });
    return mGranier;
}

double GranierTable::at(int m, glm::dvec2 centre) const {
    glm::dvec2 f = (centre - min) / (max - min) * double(size - 1);
    if (!(f.x >= 0.0 && f.y >= 0.0 && f.x <= size - 1 && f.y <= size - 1)) return 0.0;
    f = glm::min(f, glm::dvec2(size - 1) - 1e-9);
    int i = int(f.x), j = int(f.y);
    double fx = f.x - i, fy = f.y - j;
    const float* r0 = &weighted[(size_t(m) * size_t(size) + size_t(j)) * size_t(size) + size_t(i)];
    const float* r1 = r0 + size;
    return (1 - fy) * ((1 - fx) * r0[0] + fx * r0[1]) + fy * ((1 - fx) * r1[0] + fx * r1[1]);
}

}  // namespace candela
