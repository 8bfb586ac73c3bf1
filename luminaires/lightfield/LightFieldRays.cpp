#include "luminaires/lightfield/LightFieldRays.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include "util/Error.h"
#include "util/Threads.h"

namespace candela {

namespace {

// 4-point Gauss-Legendre on [-1, 1].
constexpr double kGaussX[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                               0.8611363115940526};
constexpr double kGaussW[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                               0.3478548451374538};

/// One axis of a product quadrature of the quadratic B-spline of spacing h (support +-1.5 h):
/// positions (metres) and weights (weight times the B-spline, metres). Each knot interval is cut
/// into `pieces` so the kernel (width delta) is resolved; the spline is exact on every piece.
struct AxisRule {
    std::vector<double> x, w;
    AxisRule(double h, int pieces) {
        for (int knot = 0; knot < 3; ++knot)
            for (int p = 0; p < pieces; ++p) {
                double a = -1.5 + knot + double(p) / pieces, b = a + 1.0 / pieces;  // units of h
                for (int g = 0; g < 4; ++g) {
                    double t = 0.5 * (a + b) + 0.5 * (b - a) * kGaussX[g];
                    x.push_back(t * h);
                    w.push_back(0.5 * (b - a) * h * kGaussW[g] * bspline2(t));
                }
            }
    }
};

/// H(d) = int Phi(v) k(d - v) dv, with Phi the basis function centred on 0 and
/// k(r) = delta^2 / (delta^2 + |r|^2)^2 = cos(theta_u) cos(theta_s) / r^2 between U and S (1/m2).
/// G_m(s) = H(s - node_m). H is even in both components, so a quarter plane is tabulated
/// (bilinear lookups; the step is 1/16 of the kernel's or the basis' width, which keeps the
/// interpolation error of this smooth, peaked function below about 0.2 %).
class KernelTable {
  public:
    explicit KernelTable(const LightFieldLayout& l) {
        glm::dvec2 nodeMin = l.origin, nodeMax = l.origin + glm::dvec2(l.count - 1) * l.spacing;
        glm::dvec2 reach = glm::max(glm::abs(l.imageMax - nodeMin), glm::abs(l.imageMin - nodeMax));
        double width = std::min({l.delta, l.spacing.x, l.spacing.y});
        constexpr int kMaxSide = 1024;
        // Clamped as doubles, so a huge reach cannot overflow the conversion to int.
        glm::dvec2 points = glm::ceil(reach / (width / 16.0)) + 2.0;
        auto side = [&](double v) {
            return std::isfinite(v) ? int(std::clamp(v, 3.0, double(kMaxSide))) : kMaxSide;
        };
        mN = glm::ivec2(side(points.x), side(points.y));
        mStep = reach / glm::dvec2(mN - 2);
        auto pieces = [&](double h) { return std::clamp(int(std::ceil(2.0 * h / l.delta)), 1, 8); };
        AxisRule rx(l.spacing.x, pieces(l.spacing.x)), ry(l.spacing.y, pieces(l.spacing.y));
        double d2 = l.delta * l.delta;
        mTable.assign(size_t(mN.x) * size_t(mN.y), 0.0);
        auto rows = [&](int first, int stride) {
            for (int j = first; j < mN.y; j += stride)
                for (int i = 0; i < mN.x; ++i) {
                    glm::dvec2 d = glm::dvec2(i, j) * mStep;
                    double sum = 0.0;
                    for (size_t b = 0; b < ry.x.size(); ++b) {
                        double dy = d.y - ry.x[b], row = 0.0;
                        for (size_t a = 0; a < rx.x.size(); ++a) {
                            double dx = d.x - rx.x[a];
                            double r2 = d2 + dx * dx + dy * dy;
                            row += rx.w[a] / (r2 * r2);
                        }
                        sum += ry.w[b] * row;
                    }
                    mTable[size_t(j) * size_t(mN.x) + size_t(i)] = sum * d2;
                }
        };
        int threads = std::clamp(int(std::thread::hardware_concurrency()), 1, 8);
        runSlices(threads, [&](int t) { rows(t, threads); });
    }

    double operator()(glm::dvec2 d) const {
        glm::dvec2 f = glm::min(glm::abs(d) / mStep, glm::dvec2(mN - 1) - 1e-9);
        int i = int(f.x), j = int(f.y);
        double fx = f.x - i, fy = f.y - j;
        const double* r0 = &mTable[size_t(j) * size_t(mN.x) + size_t(i)];
        const double* r1 = r0 + mN.x;
        return (1.0 - fy) * ((1.0 - fx) * r0[0] + fx * r0[1]) +
               fy * ((1.0 - fx) * r1[0] + fx * r1[1]);
    }

  private:
    glm::ivec2 mN{0};
    glm::dvec2 mStep{0.0};       ///< metres
    std::vector<double> mTable;  ///< H, sr (the basis-weighted solid angle of U seen from S).
};

/// The quadratic B-splines of one axis that reach grid coordinate g (units of the spacing from
/// node 0): up to three nodes within 1.5 spacings, their weights and the weights' sum (1 where the
/// basis is a partition of unity, less near the grid's ends).
struct BasisWeights {
    int n = 0;
    int node[4] = {0, 0, 0, 0};
    double weight[4] = {0.0, 0.0, 0.0, 0.0};
    double sum = 0.0;
    BasisWeights(double g, int count) {
        if (!(g > -1.5 && g < count + 0.5)) return;  // also NaN
        int first = std::max(0, int(std::ceil(g - 1.5)));
        int last = std::min(count - 1, int(std::floor(g + 1.5)));
        for (int i = first; i <= last && n < 4; ++i) {
            double b = bspline2(g - i);
            if (b <= 0.0) continue;
            node[n] = i;
            weight[n++] = b;
            sum += b;
        }
    }
};

/// Rotation taking unit vector a onto +z (Rodrigues; the half-turn about x for a = -z).
glm::dmat3 rotationToZ(glm::dvec3 a) {
    a = glm::normalize(a);
    glm::dvec3 z(0.0, 0.0, 1.0);
    double c = glm::dot(a, z);
    if (c < -1.0 + 1e-12) return glm::dmat3(1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, -1.0);
    glm::dvec3 v = glm::cross(a, z);
    // Column-major: K is the cross-product matrix of v, R = I + K + K^2 / (1 + c).
    glm::dmat3 k(0.0, v.z, -v.y, -v.z, 0.0, v.x, v.y, -v.x, 0.0);
    return glm::dmat3(1.0) + k + k * k * (1.0 / (1.0 + c));
}

/// Smallest value v with sum of weights of values <= v at least q * total.
double weightedQuantile(std::vector<std::pair<double, double>>& vw, double q) {
    std::sort(vw.begin(), vw.end());
    double total = 0.0;
    for (const auto& p : vw) total += p.second;
    double target = q * total, acc = 0.0;
    for (const auto& p : vw) {
        acc += p.second;
        if (acc >= target) return p.first;
    }
    return vw.empty() ? 0.0 : vw.back().first;
}

/// Rounds up to two significant digits (a readable delta).
double roundUp2(double x) {
    double e = std::pow(10.0, std::floor(std::log10(x)) - 1.0);
    return std::ceil(x / e - 1e-9) * e;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Layout

namespace {

/// Forward rays in the local frame: start points, crossings of U, slopes (dx/dz, dy/dz), flux.
struct ForwardRays {
    std::vector<glm::dvec2> start, u, slope;  ///< metres, metres, no unit
    std::vector<double> flux;                 ///< lm or W
};

/// Mean direction, rotation and the U plane (options permitting) into c.
void chooseFrame(const std::vector<EmittedRay>& rays, const LayoutOptions& o, LayoutChoice& c) {
    auto bad = [&](const std::string& msg) { throw InputError(o.what + ": " + msg); };
    double total = 0.0;
    for (const EmittedRay& r : rays) {
        c.meanDirection += r.flux * r.direction;
        total += r.flux;
    }
    if (!(total > 0.0)) bad("the rays carry no flux");
    c.meanDirection /= total;
    if (o.axis == SourceAxis::MainAxis) {
        // Below 0.1 the mean direction is noise around a source without a main axis.
        if (glm::length(c.meanDirection) < 0.1)
            c.axisFallback = true;
        else
            c.frame.rotation = rotationToZ(c.meanDirection);
    } else if (o.axis == SourceAxis::Custom) {
        if (!(glm::length(o.customAxis) > 0.0)) bad("the emission axis is a zero vector");
        c.frame.rotation = rotationToZ(o.customAxis);
    }
    double zU = o.uPlaneZ;
    if (std::isnan(zU)) {
        zU = -std::numeric_limits<double>::infinity();
        for (const EmittedRay& r : rays)
            if (r.flux > 0.0) zU = std::max(zU, (c.frame.rotation * r.position).z);
    }
    c.frame.uPlaneZ = zU;
}

ForwardRays forwardRays(const std::vector<EmittedRay>& rays, const RayFrame& frame) {
    ForwardRays f;
    for (const EmittedRay& r : rays) {
        glm::dvec3 p = frame.point(r.position), d = frame.direction(r.direction);
        if (!(d.z > 0.0) || !(r.flux > 0.0)) continue;
        glm::dvec2 cross = glm::dvec2(p) - p.z / d.z * glm::dvec2(d);
        if (!std::isfinite(cross.x) || !std::isfinite(cross.y)) continue;
        f.start.push_back(glm::dvec2(p));
        f.u.push_back(cross);
        f.slope.push_back(glm::dvec2(d) / d.z);
        f.flux.push_back(r.flux);
    }
    return f;
}

/// Half-widths of the box on U where the basis must sum to one, metres.
glm::dvec2 chooseUBox(const ForwardRays& f, const LayoutOptions& o) {
    double level = 1.0 - (1.0 - o.coverage) / 2.0;  // per axis, both sides
    std::vector<std::pair<double, double>> vw(f.u.size());
    // The source's own footprint (start points), the larger of its two half-widths.
    double footprint = 0.0;
    for (int axis = 0; axis < 2; ++axis) {
        for (size_t k = 0; k < vw.size(); ++k) vw[k] = {std::abs(f.start[k][axis]), f.flux[k]};
        footprint = std::max(footprint, weightedQuantile(vw, level));
    }
    glm::dvec2 half = o.uHalfWidth;
    for (int axis = 0; axis < 2; ++axis) {
        if (half[axis] > 0.0) continue;
        for (size_t k = 0; k < vw.size(); ++k) vw[k] = {std::abs(f.u[k][axis]), f.flux[k]};
        half[axis] = weightedQuantile(vw, level);
        // At most twice the source's footprint: a source emitting sideways from deep below U (a
        // recording sphere) would otherwise spread U over metres for a sliver of flux.
        if (footprint > 0.0) half[axis] = std::min(half[axis], 2.0 * footprint);
    }
    // A point-like source still needs a basis of some size: at least 1e-3 of the other axis
    // and 1 micrometre.
    double largest = std::max({half.x, half.y, 1e-6});
    return glm::max(half, glm::dvec2(1e-3 * largest));
}

/// The image extent on S covering `coverage` of the flux that the basis keeps: each ray weighted
/// by sum_m Phi_m(u) (all rays alike if the basis keeps none).
void chooseSBox(const ForwardRays& f, double coverage, LightFieldLayout& l) {
    std::vector<double> kept(f.u.size());
    double keptTotal = 0.0;
    for (size_t k = 0; k < kept.size(); ++k) {
        glm::dvec2 g = (f.u[k] - l.origin) / l.spacing;
        kept[k] = f.flux[k] * BasisWeights(g.x, l.count.x).sum * BasisWeights(g.y, l.count.y).sum;
        keptTotal += kept[k];
    }
    if (!(keptTotal > 0.0)) kept = f.flux;
    double tail = (1.0 - coverage) / 4.0;  // per side of each axis
    double scale = std::max({l.spacing.x, l.spacing.y, l.delta});
    std::vector<std::pair<double, double>> vw(kept.size());
    for (int axis = 0; axis < 2; ++axis) {
        for (size_t k = 0; k < vw.size(); ++k)
            vw[k] = {f.u[k][axis] + l.delta * f.slope[k][axis], kept[k]};
        double lo = weightedQuantile(vw, tail), hi = weightedQuantile(vw, 1.0 - tail);
        // 1 % margins, and never an empty extent (a collimated point source).
        double pad = std::max(0.01 * (hi - lo), 1e-3 * scale);
        l.imageMin[axis] = lo - pad;
        l.imageMax[axis] = hi + pad;
    }
}

}  // namespace

LayoutChoice chooseLayout(const std::vector<EmittedRay>& rays, const LayoutOptions& o) {
    auto bad = [&](const std::string& msg) { throw InputError(o.what + ": " + msg); };
    if (o.count.x < 3 || o.count.y < 3) bad("the basis needs at least 3x3 functions");
    if (o.resolution.x < 1 || o.resolution.y < 1) bad("images need at least one pixel");
    if (!(o.coverage > 0.5 && o.coverage < 1.0)) bad("coverage must be in (0.5, 1)");
    LayoutChoice c;
    chooseFrame(rays, o, c);
    ForwardRays f = forwardRays(rays, c.frame);
    if (f.u.empty()) bad("no ray goes forward (+z in the luminaire's frame); try another --axis");
    c.uHalfWidth = chooseUBox(f, o);

    LightFieldLayout& l = c.layout;
    l.count = o.count;
    l.resolution = o.resolution;
    // The basis sums to one on [node_0 + h/2, node_{W-1} - h/2], (W - 2) h wide.
    l.spacing = 2.0 * c.uHalfWidth / glm::dvec2(o.count - 2);
    l.origin = -0.5 * glm::dvec2(o.count - 1) * l.spacing;
    l.delta = o.delta > 0.0 ? o.delta : roundUp2(std::max(c.uHalfWidth.x, c.uHalfWidth.y));
    chooseSBox(f, o.coverage, l);
    return c;
}

// ---------------------------------------------------------------------------------------------
// Accumulation

LightFieldAccumulator::LightFieldAccumulator(const LightFieldLayout& layout, Estimator estimator)
    : mLayout(layout), mEstimator(estimator) {
    mPixel = (layout.imageMax - layout.imageMin) / glm::dvec2(layout.resolution);
    mPixels = size_t(layout.resolution.x) * size_t(layout.resolution.y);
    mSums.assign(mPixels * size_t(layout.count.x) * size_t(layout.count.y), 0.0);
}

void LightFieldAccumulator::add(const EmittedRay& ray) {
    const LightFieldLayout& l = mLayout;
    const glm::dvec3& p = ray.position;
    const glm::dvec3& d = ray.direction;
    double f = ray.flux;
    ++mReport.rays;
    mReport.totalFlux += f;
    if (!(d.z > 0.0)) {
        ++mReport.backwardRays;
        mReport.backwardFlux += f;
        return;
    }
    glm::dvec2 u = glm::dvec2(p) - p.z / d.z * glm::dvec2(d);
    glm::dvec2 s = u + l.delta / d.z * glm::dvec2(d);
    glm::dvec2 g = (u - l.origin) / l.spacing;
    BasisWeights bx(g.x, l.count.x), by(g.y, l.count.y);
    double covered = bx.sum * by.sum;
    if (!(covered > 0.0)) {
        ++mReport.outsideBasisRays;
        mReport.outsideBasisFlux += f;
        return;
    }
    glm::dvec2 px = (s - l.imageMin) / mPixel;
    if (!(px.x >= 0.0 && px.x < l.resolution.x && px.y >= 0.0 && px.y < l.resolution.y)) {
        ++mReport.outsideImageRays;
        mReport.outsideImageFlux += f;
        return;
    }
    size_t pixel = size_t(std::min(int(px.y), l.resolution.y - 1)) * size_t(l.resolution.x) +
                   size_t(std::min(int(px.x), l.resolution.x - 1));
    mReport.keptFlux += f * covered;
    mReport.outsideBasisFlux += f * (1.0 - covered);
    double weight = f;
    if (mEstimator == Estimator::PerRay) {
        double c2 = d.z * d.z;  // cos^2(theta), d being a unit vector
        weight *= l.delta * l.delta / (c2 * c2) / (mPixel.x * mPixel.y * l.spacing.x * l.spacing.y);
    }
    for (int b = 0; b < by.n; ++b)
        for (int a = 0; a < bx.n; ++a) {
            size_t m = size_t(by.node[b]) * size_t(l.count.x) + size_t(bx.node[a]);
            mSums[m * mPixels + pixel] += weight * bx.weight[a] * by.weight[b];
        }
}

void LightFieldAccumulator::add(const std::vector<EmittedRay>& rays, const RayFrame& frame,
                                const std::function<void(double)>& progress) {
    size_t every = std::max<size_t>(rays.size() / 20, 1);
    for (size_t k = 0; k < rays.size(); ++k) {
        const EmittedRay& r = rays[k];
        add(EmittedRay{frame.point(r.position), frame.direction(r.direction), r.flux});
        if (progress && (k + 1) % every == 0) progress(double(k + 1) / double(rays.size()));
    }
}

std::shared_ptr<LightFieldData> LightFieldAccumulator::build(const std::string& unit) {
    const LightFieldLayout& l = mLayout;
    KernelTable kernel(l);
    // G_m(P) = int_P H(s - node_m) ds by n x n Gauss-Legendre points per pixel, n growing with the
    // pixel's size against the kernel's width so the pixel integral stays resolved.
    double width = std::min({l.delta, l.spacing.x, l.spacing.y});
    int n = std::clamp(int(std::ceil(2.0 * std::max(mPixel.x, mPixel.y) / width)), 2, 4);
    std::vector<double> gx, gw;
    if (n == 2)
        gx = {-0.5773502691896258, 0.5773502691896258}, gw = {1.0, 1.0};
    else if (n == 3)
        gx = {-0.7745966692414834, 0.0, 0.7745966692414834}, gw = {5.0 / 9, 8.0 / 9, 5.0 / 9};
    else
        gx.assign(kGaussX, kGaussX + 4), gw.assign(kGaussW, kGaussW + 4);

    auto lf = std::make_shared<LightFieldData>();
    lf->model = LightFieldData::Model::Canned;
    lf->delta = l.delta;
    lf->count = l.count;
    lf->spacing = l.spacing;
    lf->origin = l.origin;
    lf->imageMin = l.imageMin;
    lf->imageMax = l.imageMax;
    lf->width = l.resolution.x;
    lf->height = l.resolution.y;
    lf->rgb = false;
    lf->unit = unit;
    lf->images.resize(size_t(l.count.x) * size_t(l.count.y));
    double area = mPixel.x * mPixel.y;
    mReport.modelFlux = 0.0;
    for (size_t m = 0; m < lf->images.size(); ++m) {
        glm::dvec2 node =
            l.origin +
            glm::dvec2(double(m % size_t(l.count.x)), double(m / size_t(l.count.x))) * l.spacing;
        std::vector<float>& image = lf->images[m].luminance;
        image.assign(mPixels, 0.0f);
        for (size_t k = 0; k < mPixels; ++k) {
            double sum = mSums[m * mPixels + k];
            if (sum == 0.0) continue;
            glm::dvec2 centre = l.imageMin + (glm::dvec2(double(k % size_t(l.resolution.x)),
                                                         double(k / size_t(l.resolution.x))) +
                                              0.5) *
                                                 mPixel;
            double g = 0.0;
            for (size_t b = 0; b < gx.size(); ++b)
                for (size_t a = 0; a < gx.size(); ++a)
                    g += gw[a] * gw[b] *
                         kernel(centre + 0.5 * mPixel * glm::dvec2(gx[a], gx[b]) - node);
            g *= 0.25 * area;  // G_m(P), m2 sr
            double c = mEstimator == Estimator::FluxConserving ? sum / g : sum;
            image[k] = float(c);
            mReport.modelFlux += double(image[k]) * g;
        }
    }
    lf->validate("projected light field");
    lf->precompute();
    return lf;
}

std::shared_ptr<LightFieldData> projectRays(const std::vector<EmittedRay>& rays,
                                            const LayoutChoice& choice, const std::string& unit,
                                            ProjectionReport& report, Estimator estimator,
                                            const std::function<void(double)>& progress) {
    auto start = std::chrono::steady_clock::now();
    LightFieldAccumulator acc(choice.layout, estimator);
    acc.add(rays, choice.frame, progress);
    auto lf = acc.build(unit);
    report = acc.report();
    report.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return lf;
}

std::vector<EmittedRay> raysFromTm25(const Tm25RayFile& file, bool scaleToHeader,
                                     Tm25FluxInfo& info) {
    const Tm25Header& h = file.header;
    info.photometric = h.flags.luminousFlux;
    info.headerTotal = info.photometric ? h.luminousFlux : h.radiantFlux;
    info.raySum = info.photometric ? file.rayLuminousFlux() : file.rayRadiantFlux();
    info.unit = info.photometric ? "cd/m2" : "W/(m2 sr)";
    info.scale = 1.0;
    // Within float rounding of the header (the LED's sum agrees to 1e-7), keep the rays as they
    // are.
    if (scaleToHeader && std::isfinite(info.headerTotal) && info.headerTotal > 0.0 &&
        info.raySum > 0.0 && std::abs(info.headerTotal / info.raySum - 1.0) > 1e-5)
        info.scale = info.headerTotal / info.raySum;
    std::vector<EmittedRay> rays(file.rays.size());
    for (size_t k = 0; k < rays.size(); ++k) {
        const Tm25Ray& r = file.rays[k];
        rays[k] = {r.position, r.direction,
                   info.scale * (info.photometric ? r.luminousFlux : r.radiantFlux)};
    }
    return rays;
}

}  // namespace candela
