#include "luminaires/environment/EnvironmentSampling.h"

#include <algorithm>
#include <cmath>

#include "luminaires/Random.h"
#include "shaders/shared/Constants.h"
#include "shaders/shared/CubeFaces.h"
#include "shaders/shared/GpuTypes.h"

namespace candela {

namespace {

using gpu::kPi;

/// Floor of a cube texel's luminance as a fraction of its face's mean (see CubeMapDistribution),
/// and the share of the largest luminance a cube texel touches in its sampling weight: with it,
/// L(w) / (mu_f pdf_L(w|f)) is bounded (L <= max <= weight / (kMaxShare Omega)), so a sun thinner
/// than the supersampling cannot give rare huge samples. One definition for C++ and GLSL.
constexpr double kFaceFloor = gpu::kEnvFaceFloor;
constexpr double kMaxShare = gpu::kEnvMaxShare;

/// Face f's frame from the table shared with GLSL (its components are exact in float).
constexpr CubeFaceFrame sharedFrame(int f) {
    return {glm::dvec3(gpu::kCubeFaceCentre[f]), glm::dvec3(gpu::kCubeFaceRight[f]),
            glm::dvec3(gpu::kCubeFaceDown[f])};
}

constexpr CubeFaceFrame kFaces[6] = {sharedFrame(0), sharedFrame(1), sharedFrame(2),
                                     sharedFrame(3), sharedFrame(4), sharedFrame(5)};

double clamp01(double u) {
    return u > 0.0 ? (u < 1.0 ? u : std::nextafter(1.0, 0.0)) : 0.0;
}

/// Signed solid angle of [0, a] x [0, b] on the plane at distance 1.
double cornerSolidAngle(double a, double b) {
    return std::atan2(a * b, std::sqrt(1.0 + a * a + b * b));
}

glm::dvec3 faceDirection(int face, double a, double b) {
    const CubeFaceFrame& f = kFaces[face];
    return glm::normalize(f.centre + a * f.right + b * f.down);
}

/// Largest luminance of the lat-long texels that texel (c, r) of face f (of n^2) may touch.
double touchedMaximum(const EnvironmentMap& map, int f, int c, int r, int n) {
    const int w = map.width(), h = map.height(), kEdge = gpu::kEnvTouchedSteps;
    double a0 = -1.0 + 2.0 * c / n, a1 = -1.0 + 2.0 * (c + 1) / n;
    double b0 = -1.0 + 2.0 * r / n, b1 = -1.0 + 2.0 * (r + 1) / n;
    double uc = map.uvOf(faceDirection(f, 0.5 * (a0 + a1), 0.5 * (b0 + b1))).x;
    double duMin = 0.0, duMax = 0.0, vMin = 1.0, vMax = 0.0;
    for (int e = 0; e < 4; ++e)
        for (int i = 0; i <= kEdge; ++i) {
            double t = double(i) / kEdge;
            double a = e < 2 ? a0 + t * (a1 - a0) : (e == 2 ? a0 : a1);
            double b = e < 2 ? (e == 0 ? b0 : b1) : b0 + t * (b1 - b0);
            glm::dvec2 uv = map.uvOf(faceDirection(f, a, b));
            double du = uv.x - uc;
            du -= std::round(du);  // into [-1/2, 1/2]
            duMin = std::min(duMin, du);
            duMax = std::max(duMax, du);
            vMin = std::min(vMin, uv.y);
            vMax = std::max(vMax, uv.y);
        }
    bool pole = (f == 2 || f == 3) && a0 <= 0.0 && a1 >= 0.0 && b0 <= 0.0 && b1 >= 0.0;
    if (pole) (f == 2 ? vMin : vMax) = f == 2 ? 0.0 : 1.0;
    int y0 = std::max(0, int(std::floor(vMin * h))),
        y1 = std::min(h - 1, int(std::floor(vMax * h)));
    bool allColumns = pole || duMax - duMin > 0.25;
    int x0 = int(std::floor((uc + duMin) * w)), x1 = int(std::floor((uc + duMax) * w));
    if (allColumns) x0 = 0, x1 = w - 1;
    double best = 0.0;
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x)
            best = std::max(best, map.texelLuminance(((x % w) + w) % w, y));
    return best;
}

}  // namespace

const CubeFaceFrame& cubeFaceFrame(int face) {
    return kFaces[face];
}

int cubeFaceOf(const glm::dvec3& w, glm::dvec2& ab) {
    double ax = std::abs(w.x), ay = std::abs(w.y), az = std::abs(w.z);
    if (!(ax + ay + az > 0.0) || !std::isfinite(ax + ay + az)) return -1;
    int face;
    double major;
    if (ax >= ay && ax >= az) {
        face = w.x > 0.0 ? 0 : 1;
        major = ax;
    } else if (ay >= az) {
        face = w.y > 0.0 ? 2 : 3;
        major = ay;
    } else {
        face = w.z > 0.0 ? 4 : 5;
        major = az;
    }
    glm::dvec3 d = w / major;
    ab = {std::clamp(glm::dot(d, kFaces[face].right), -1.0, 1.0),
          std::clamp(glm::dot(d, kFaces[face].down), -1.0, 1.0)};
    return face;
}

// ---------------------------------------------------------------------------------------------
// Tabulated CDFs

void Cdf1D::build(const double* weights, int n) {
    cdf.assign(size_t(n) + 1, 0.0);
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        sum += weights[i];
        cdf[size_t(i) + 1] = sum;
    }
    total = sum;
    if (sum > 0.0)
        for (double& c : cdf) c /= sum;
    cdf[size_t(n)] = sum > 0.0 ? 1.0 : 0.0;
}

int Cdf1D::sample(double u, double& fraction) const {
    int n = int(cdf.size()) - 1;
    u = clamp01(u);
    // First index whose cdf exceeds u, minus one: cdf[i] <= u < cdf[i+1], a non-empty piece.
    int i = int(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin()) - 1;
    i = std::clamp(i, 0, n - 1);
    double width = cdf[size_t(i) + 1] - cdf[size_t(i)];
    fraction = width > 0.0 ? std::clamp((u - cdf[size_t(i)]) / width, 0.0, 1.0) : 0.5;
    return i;
}

// ---------------------------------------------------------------------------------------------
// Cube map

CubeMapDistribution::CubeMapDistribution(const EnvironmentMap& map, int faceSize) : mN(faceSize) {
    const int n = mN;
    mSolidAngle.resize(size_t(n) * size_t(n));
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) {
            double a0 = -1.0 + 2.0 * c / n, a1 = -1.0 + 2.0 * (c + 1) / n;
            double b0 = -1.0 + 2.0 * r / n, b1 = -1.0 + 2.0 * (r + 1) / n;
            mSolidAngle[size_t(r) * size_t(n) + size_t(c)] =
                cornerSolidAngle(a1, b1) - cornerSolidAngle(a0, b1) - cornerSolidAngle(a1, b0) +
                cornerSolidAngle(a0, b0);
        }
    // k x k subsamples per texel, k >= 2 W / (pi N): the subsample pitch (2 / (N k) rad at a
    // face's centre) is at most half the lat-long pitch at the equator (2 pi / W).
    int k = std::clamp(int(std::ceil(2.0 * map.width() / (kPi * n))), 1, 8);
    for (int f = 0; f < 6; ++f) {
        Face& face = mFaces[size_t(f)];
        face.luminance.assign(size_t(n) * size_t(n), 0.0);
        for (int r = 0; r < n; ++r)
            for (int c = 0; c < n; ++c) {
                double sum = 0.0;
                for (int j = 0; j < k; ++j)
                    for (int i = 0; i < k; ++i) {
                        double a = -1.0 + 2.0 * (c + (i + 0.5) / k) / n;
                        double b = -1.0 + 2.0 * (r + (j + 0.5) / k) / n;
                        sum += luminanceOf(map.radiance(faceDirection(f, a, b)));
                    }
                face.luminance[size_t(r) * size_t(n) + size_t(c)] = sum / double(k * k);
            }
        for (int j = 0; j < 4; ++j)
            mCorners[size_t(f)][size_t(j)] =
                faceDirection(f, (j & 1) ? 1.0 : -1.0, (j & 2) ? 1.0 : -1.0);
    }
    // The largest lat-long luminance a texel touches: over the (u, v) box of 17 points per edge,
    // and the whole column range (to the pole) on a texel containing a pole.
    std::vector<double> maxLum(6 * size_t(n) * size_t(n));
    for (int f = 0; f < 6; ++f)
        for (int r = 0; r < n; ++r)
            for (int c = 0; c < n; ++c)
                maxLum[(size_t(f) * n + r) * n + c] = touchedMaximum(map, f, c, r, n);
    std::vector<double> column(static_cast<size_t>(n));
    std::vector<double> colSums(static_cast<size_t>(n));
    for (Face& face : mFaces) {
        double energy = 0.0;
        for (size_t i = 0; i < face.luminance.size(); ++i)
            energy += face.luminance[i] * mSolidAngle[i];
        double floor = kFaceFloor * energy / (4.0 * kPi / 6.0);  // 1e-3 x the face's mean
        face.weight.resize(face.luminance.size());
        size_t f = size_t(&face - &mFaces[0]);
        for (size_t i = 0; i < face.luminance.size(); ++i)
            face.weight[i] =
                (face.luminance[i] + kMaxShare * maxLum[f * n * n + i] + floor) * mSolidAngle[i];
        face.rows.resize(size_t(n));
        for (int c = 0; c < n; ++c) {
            for (int r = 0; r < n; ++r)
                column[size_t(r)] = face.weight[size_t(r) * size_t(n) + size_t(c)];
            face.rows[size_t(c)].build(column.data(), n);
            colSums[size_t(c)] = face.rows[size_t(c)].total;
        }
        face.columns.build(colSums.data(), n);
    }
}

double CubeMapDistribution::texelLuminance(int face, int col, int row) const {
    return mFaces[size_t(face)].luminance[size_t(row) * size_t(mN) + size_t(col)];
}
double CubeMapDistribution::texelWeight(int face, int col, int row) const {
    return mFaces[size_t(face)].weight[size_t(row) * size_t(mN) + size_t(col)];
}
double CubeMapDistribution::texelSolidAngle(int col, int row) const {
    return mSolidAngle[size_t(row) * size_t(mN) + size_t(col)];
}

DirectionSample CubeMapDistribution::sampleFace(int f, const glm::dvec2& u) const {
    DirectionSample s;
    const Face& face = mFaces[size_t(f)];
    if (!(face.columns.total > 0.0)) return s;
    double fx, fy;
    int c = face.columns.sample(u.x, fx);
    int r = face.rows[size_t(c)].sample(u.y, fy);
    double a = -1.0 + 2.0 * (c + fx) / mN, b = -1.0 + 2.0 * (r + fy) / mN;
    double p = face.columns.probability(c) * face.rows[size_t(c)].probability(r);
    double texelArea = 4.0 / (double(mN) * double(mN));
    double q = 1.0 + a * a + b * b;
    s.w = faceDirection(f, a, b);
    // Area density p / texelArea on the face plane; dA = q^(3/2) dw at unit distance.
    s.pdf = p / texelArea * q * std::sqrt(q);
    return s;
}

double CubeMapDistribution::pdfFace(int f, const glm::dvec3& w) const {
    glm::dvec2 ab;
    if (cubeFaceOf(w, ab) != f) return 0.0;
    const Face& face = mFaces[size_t(f)];
    if (!(face.columns.total > 0.0)) return 0.0;
    int c = std::clamp(int((ab.x + 1.0) * 0.5 * mN), 0, mN - 1);
    int r = std::clamp(int((ab.y + 1.0) * 0.5 * mN), 0, mN - 1);
    double p = face.weight[size_t(r) * size_t(mN) + size_t(c)] / face.columns.total;
    double q = 1.0 + ab.x * ab.x + ab.y * ab.y;
    return p / (4.0 / (double(mN) * double(mN))) * q * std::sqrt(q);
}

glm::dvec2 CubeMapDistribution::invertFace(int f, const glm::dvec3& w) const {
    glm::dvec2 ab;
    cubeFaceOf(w, ab);
    const Face& face = mFaces[size_t(f)];
    double x = (ab.x + 1.0) * 0.5 * mN, y = (ab.y + 1.0) * 0.5 * mN;
    int c = std::clamp(int(x), 0, mN - 1), r = std::clamp(int(y), 0, mN - 1);
    double u1 = face.columns.cdf[size_t(c)] + (x - c) * face.columns.probability(c);
    const Cdf1D& rows = face.rows[size_t(c)];
    double u2 = rows.cdf[size_t(r)] + (y - r) * rows.probability(r);
    return {u1, u2};
}

std::array<double, 6> CubeMapDistribution::balance(const glm::dvec3& n) const {
    std::array<double, 6> mu{};
    double sum = 0.0;
    for (int f = 0; f < 6; ++f) {
        double form = 0.0;  // F_f(n) of Eq. (3), the pseudo form factor
        for (const glm::dvec3& c : mCorners[size_t(f)]) form += std::max(0.0, glm::dot(n, c));
        mu[size_t(f)] = form * faceImportance(f);
        sum += mu[size_t(f)];
    }
    for (double& m : mu) m = sum > 0.0 ? m / sum : 0.0;
    return mu;
}

DirectionSample CubeMapDistribution::sample(const std::array<double, 6>& mu,
                                            const glm::dvec3& u) const {
    double acc = 0.0;
    double u0 = clamp01(u.x);
    for (int f = 0; f < 6; ++f) {
        double m = mu[size_t(f)];
        if (m > 0.0 && (u0 < acc + m || f == 5)) {
            DirectionSample s = sampleFace(f, {u.y, u.z});
            s.pdf *= m;
            return s;
        }
        acc += m;
    }
    // Rounding left u0 beyond the last non-empty face: take the last one.
    for (int f = 5; f >= 0; --f)
        if (mu[size_t(f)] > 0.0) {
            DirectionSample s = sampleFace(f, {u.y, u.z});
            s.pdf *= mu[size_t(f)];
            return s;
        }
    return {};
}

double CubeMapDistribution::pdf(const std::array<double, 6>& mu, const glm::dvec3& w) const {
    glm::dvec2 ab;
    int f = cubeFaceOf(w, ab);
    if (f < 0 || !(mu[size_t(f)] > 0.0)) return 0.0;
    return mu[size_t(f)] * pdfFace(f, w);
}

glm::dvec3 CubeMapDistribution::invert(const std::array<double, 6>& mu, const glm::dvec3& w) const {
    glm::dvec2 ab;
    int f = cubeFaceOf(w, ab);
    if (f < 0) return glm::dvec3(0.0);
    double acc = 0.0;
    for (int g = 0; g < f; ++g) acc += mu[size_t(g)];
    glm::dvec2 uv = invertFace(f, w);
    return {acc + 0.5 * mu[size_t(f)], uv.x, uv.y};
}

// ---------------------------------------------------------------------------------------------
// Global lat-long CDF

LatLongDistribution::LatLongDistribution(const EnvironmentMap& map) : mMap(&map) {
    int w = map.width(), h = map.height();
    std::vector<double> rowWeights(static_cast<size_t>(h)), lum(static_cast<size_t>(w));
    mColumns.resize(size_t(h));
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) lum[size_t(x)] = map.texelLuminance(x, y);
        mColumns[size_t(y)].build(lum.data(), w);
        rowWeights[size_t(y)] = mColumns[size_t(y)].total * map.rowSolidAngle(y);
    }
    mRows.build(rowWeights.data(), h);
}

DirectionSample LatLongDistribution::sample(const glm::dvec2& u) const {
    DirectionSample s;
    if (empty()) return s;
    const EnvironmentMap& map = *mMap;
    double fy, fx;
    int y = mRows.sample(u.x, fy);
    int x = mColumns[size_t(y)].sample(u.y, fx);
    double h = map.height();
    double c0 = std::cos(kPi * y / h), c1 = std::cos(kPi * (y + 1) / h);
    double cosTheta = std::clamp(c0 - fy * (c0 - c1), -1.0, 1.0);
    double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
    double phi = 2.0 * kPi * (x + fx) / map.width() + map.rotation();
    s.w = {sinTheta * std::cos(phi), cosTheta, sinTheta * std::sin(phi)};
    double p = mRows.probability(y) * mColumns[size_t(y)].probability(x);
    s.pdf = p / map.rowSolidAngle(y);
    return s;
}

double LatLongDistribution::pdf(const glm::dvec3& w) const {
    if (empty()) return 0.0;
    glm::ivec2 t = mMap->texelOf(w);
    double p = mRows.probability(t.y) * mColumns[size_t(t.y)].probability(t.x);
    return p / mMap->rowSolidAngle(t.y);
}

glm::dvec2 LatLongDistribution::invert(const glm::dvec3& w) const {
    const EnvironmentMap& map = *mMap;
    glm::dvec2 uv = map.uvOf(w);
    glm::ivec2 t = map.texelOf(w);
    double h = map.height();
    double c0 = std::cos(kPi * t.y / h), c1 = std::cos(kPi * (t.y + 1) / h);
    double fy = std::clamp((c0 - glm::normalize(w).y) / (c0 - c1), 0.0, 1.0);
    double fx = std::clamp(uv.x * map.width() - t.x, 0.0, 1.0);
    const Cdf1D& cols = mColumns[size_t(t.y)];
    return {mRows.cdf[size_t(t.y)] + fy * mRows.probability(t.y),
            cols.cdf[size_t(t.x)] + fx * cols.probability(t.x)};
}

// ---------------------------------------------------------------------------------------------
// Havran et al. 2005

std::vector<glm::dvec2> relaxedHalton(int count, int iterations) {
    auto radicalInverse = [](int i, int base) {
        double inv = 1.0 / base, f = inv, r = 0.0;
        for (; i > 0; i /= base, f *= inv) r += f * (i % base);
        return r;
    };
    std::vector<glm::dvec2> pts(size_t(std::max(count, 0)));
    for (int i = 0; i < count; ++i)
        pts[size_t(i)] = {radicalInverse(i + 1, 2), radicalInverse(i + 1, 3)};
    const int g = 256;
    std::vector<glm::dvec2> sum(pts.size());
    std::vector<int> hits(pts.size());
    for (int it = 0; it < iterations && count > 1; ++it) {
        std::fill(sum.begin(), sum.end(), glm::dvec2(0.0));
        std::fill(hits.begin(), hits.end(), 0);
        for (int y = 0; y < g; ++y)
            for (int x = 0; x < g; ++x) {
                glm::dvec2 q((x + 0.5) / g, (y + 0.5) / g);
                size_t best = 0;
                double bestD = 1e300;
                for (size_t k = 0; k < pts.size(); ++k) {
                    glm::dvec2 d = pts[k] - q;
                    double dd = glm::dot(d, d);
                    if (dd < bestD) bestD = dd, best = k;
                }
                sum[best] += q;
                ++hits[best];
            }
        for (size_t k = 0; k < pts.size(); ++k)
            if (hits[k] > 0) pts[k] = sum[k] / double(hits[k]);
    }
    return pts;
}

HavranLights::HavranLights(int count) : mPoints(relaxedHalton(std::max(count, 1))) {}

const std::vector<HavranLights::Light>& HavranLights::rawLights() const {
    static const std::vector<Light> kNone;
    return mHistory.empty() ? kNone : mHistory.front();
}

void HavranLights::update(const EnvironmentMap& map) {
    LatLongDistribution global(map);
    std::vector<Light> frame(mPoints.size());
    for (size_t k = 0; k < mPoints.size(); ++k) {
        DirectionSample s = global.sample(mPoints[k]);
        if (s.pdf > 0.0) frame[k].direction = s.w;
    }
    if (!global.empty()) {
        // Spherical Voronoi cells: each texel's RGB radiance x solid angle goes to the nearest
        // light.
        for (int y = 0; y < map.height(); ++y) {
            double omega = map.rowSolidAngle(y);
            for (int x = 0; x < map.width(); ++x) {
                glm::dvec3 L = map.texel(x, y);
                if (!(L.x + L.y + L.z > 0.0)) continue;
                glm::dvec3 d = map.direction((x + 0.5) / map.width(), (y + 0.5) / map.height());
                size_t best = 0;
                double bestDot = -2.0;
                for (size_t k = 0; k < frame.size(); ++k) {
                    double c = glm::dot(d, frame[k].direction);
                    if (c > bestDot) bestDot = c, best = k;
                }
                frame[best].power += L * omega;
            }
        }
    }
    mHistory.push_front(std::move(frame));
    if (mHistory.size() > 4) mHistory.pop_back();
    // The causal FIR filter over the frames kept, renormalised over those present.
    mLights.assign(mPoints.size(), Light{});
    double norm = 0.0;
    for (size_t i = 0; i < mHistory.size(); ++i) norm += kTaps[i];
    std::vector<double> lum(mPoints.size());
    for (size_t k = 0; k < mPoints.size(); ++k) {
        glm::dvec3 dir(0.0), power(0.0);
        for (size_t i = 0; i < mHistory.size(); ++i) {
            dir += kTaps[i] * mHistory[i][k].direction;
            power += kTaps[i] * mHistory[i][k].power;
        }
        double len = glm::length(dir);
        mLights[k].direction = len > 0.0 ? dir / len : mHistory.front()[k].direction;
        mLights[k].power = power / norm;
        lum[k] = luminanceOf(mLights[k].power);
    }
    mChoice.build(lum.data(), int(lum.size()));
}

int HavranLights::sample(double u) const {
    if (!(mChoice.total > 0.0)) return -1;
    double fraction;
    return mChoice.sample(u, fraction);
}

double HavranLights::probability(int light) const {
    if (!(mChoice.total > 0.0) || light < 0 || light >= int(mLights.size())) return 0.0;
    return mChoice.probability(light);
}

// ---------------------------------------------------------------------------------------------
// The shared per-frame data

EnvironmentLighting::EnvironmentLighting(std::shared_ptr<const EnvironmentMap> map, int faceSize,
                                         int havranLights)
    : mMap(std::move(map)),
      mCube(*mMap, faceSize > 0 ? faceSize : defaultFaceSize(*mMap)),
      mGlobal(*mMap),
      mHavran(havranLights) {
    mHavran.update(*mMap);
}

glm::ivec2 SampleChart::faceCell(int face) {
    static const glm::ivec2 kCells[6] = {{2, 1}, {0, 1}, {1, 0}, {1, 2}, {3, 1}, {1, 1}};
    return kCells[face];
}

SampleChart sampleChart(const EnvironmentMap& map, const CubeMapDistribution& cube,
                        const glm::dvec3& normal, int spp, bool balanced, uint64_t seed,
                        int facePixels) {
    SampleChart chart;
    const int P = std::max(8, facePixels);
    chart.facePixels = P;
    chart.width = 4 * P;
    chart.height = 3 * P;
    chart.rgb.assign(size_t(chart.width) * size_t(chart.height) * 3, 40);  // the empty cells
    double len = glm::length(normal);
    glm::dvec3 n = len > 0.0 && std::isfinite(len) ? normal / len : glm::dvec3(0, 1, 0);
    if (balanced)
        chart.mu = cube.balance(n);
    else
        chart.mu.fill(1.0 / 6.0);

    // The map: Reinhard against its mean luminance, dimmed so that the samples stand out.
    double mean = map.totalLuminancePower() / (4.0 * kPi);
    auto pixelOf = [&](int face, const glm::dvec2& ab) {
        glm::ivec2 cell = SampleChart::faceCell(face);
        int x = std::clamp(int((ab.x + 1.0) * 0.5 * P), 0, P - 1),
            y = std::clamp(int((ab.y + 1.0) * 0.5 * P), 0, P - 1);
        return glm::ivec2(cell.x * P + x, cell.y * P + y);
    };
    auto put = [&](glm::ivec2 px, glm::dvec3 c) {
        if (px.x < 0 || px.y < 0 || px.x >= chart.width || px.y >= chart.height) return;
        unsigned char* o = &chart.rgb[(size_t(px.y) * size_t(chart.width) + size_t(px.x)) * 3];
        for (int k = 0; k < 3; ++k)
            o[k] = (unsigned char)std::clamp(c[k] * 255.0 + 0.5, 0.0, 255.0);
    };
    for (int f = 0; f < 6; ++f) {
        const CubeFaceFrame& fr = cubeFaceFrame(f);
        double dim = chart.mu[size_t(f)] > 0.0 ? 0.55 : 0.2;
        for (int y = 0; y < P; ++y)
            for (int x = 0; x < P; ++x) {
                double a = 2.0 * (x + 0.5) / P - 1.0, b = 2.0 * (y + 0.5) / P - 1.0;
                glm::dvec3 L = map.radiance(fr.centre + a * fr.right + b * fr.down);
                glm::dvec3 shown = mean > 0.0 ? L / (glm::dvec3(mean) + L) : glm::dvec3(0.0);
                put(pixelOf(f, {a, b}), glm::pow(shown, glm::dvec3(1.0 / 2.2)) * dim);
            }
    }
    // The normal, where it leaves the cube.
    glm::dvec2 nab;
    int nf = cubeFaceOf(n, nab);
    if (nf >= 0) {
        glm::ivec2 c = pixelOf(nf, nab);
        for (int d = -5; d <= 5; ++d)
            put(c + glm::ivec2(d, 0), glm::dvec3(1.0)), put(c + glm::ivec2(0, d), glm::dvec3(1.0));
    }
    // The samples, drawn as the estimators draw them: ceil(N_f) per face (the last one weighted
    // by frac(N_f)).
    Random rng(seed);
    for (int f = 0; f < 6; ++f) {
        double nf = chart.mu[size_t(f)] * spp;
        if (!(nf > 0.0) || !(cube.faceImportance(f) > 0.0)) continue;
        int count = int(std::ceil(nf));
        for (int k = 0; k < count; ++k) {
            DirectionSample smp = cube.sampleFace(f, {rng.uniform(), rng.uniform()});
            if (!(smp.pdf > 0.0)) continue;
            ++chart.drawn[size_t(f)];
            bool effective = glm::dot(n, smp.w) > 0.0;
            chart.effective[size_t(f)] += effective;
            glm::dvec2 ab;
            int face = cubeFaceOf(smp.w, ab);
            glm::ivec2 c = pixelOf(face, ab), lo = SampleChart::faceCell(face) * P,
                       hi = lo + glm::ivec2(P - 1);
            glm::dvec3 colour = effective ? glm::dvec3(0.2, 1.0, 0.3) : glm::dvec3(1.0, 0.2, 0.2);
            for (int dy = -1; dy <= 1; ++dy)  // a 3 x 3 dot, kept inside its face's cell
                for (int dx = -1; dx <= 1; ++dx)
                    put(glm::clamp(c + glm::ivec2(dx, dy), lo, hi), colour);
        }
    }
    return chart;
}

}  // namespace candela
