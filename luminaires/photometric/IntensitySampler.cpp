#include "luminaires/photometric/IntensitySampler.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>

#include "shaders/shared/Constants.h"

namespace candela {

namespace {

constexpr double kDeg = gpu::kPi / 180.0;
constexpr double kTwoPi = 2.0 * gpu::kPi;

/// The coordinate along which solid angle is uniform: cos(gamma) for type C (falling with the
/// angle), sin(V) for type B (rising).
double areaCoordinate(bool typeC, double angle) {
    return typeC ? -std::cos(angle) : std::sin(angle);
}

}  // namespace

IntensitySampler::IntensitySampler(const PhotometricData& data) {
    mTypeC = data.goniometer == Goniometer::C;
    const size_t nv = data.vertical.size(), nh = data.horizontal.size();
    if (nv < 2 || nh < 2 || data.candela.size() != nv * nh) return;
    for (double v : data.vertical) mV.push_back(v * kDeg);
    for (double h : data.horizontal) mH.push_back(h * kDeg);
    mCdf.assign((nv - 1) * (nh - 1) + 1, 0.0);
    mDensity.assign((nv - 1) * (nh - 1), 0.0);
    std::vector<double> solid(mDensity.size(), 0.0);
    for (size_t h = 0; h + 1 < nh; ++h)
        for (size_t v = 0; v + 1 < nv; ++v) {
            size_t cell = h * (nv - 1) + v;
            auto at = [&](size_t hh, size_t vv) { return data.candela[hh * nv + vv]; };
            double peak = std::max({at(h, v), at(h, v + 1), at(h + 1, v), at(h + 1, v + 1)});
            double omega = (areaCoordinate(mTypeC, mV[v + 1]) - areaCoordinate(mTypeC, mV[v])) *
                           (mH[h + 1] - mH[h]);
            solid[cell] = omega;
            double w = omega > 0.0 && std::isfinite(peak) ? peak * omega : 0.0;
            mCdf[cell + 1] = mCdf[cell] + w;
        }
    mTotal = mCdf.back();
    if (!(mTotal > 0.0) || !std::isfinite(mTotal)) {
        mTotal = 0.0;
        return;
    }
    for (size_t cell = 0; cell < mDensity.size(); ++cell)
        mDensity[cell] =
            solid[cell] > 0.0 ? (mCdf[cell + 1] - mCdf[cell]) / (mTotal * solid[cell]) : 0.0;
}

std::shared_ptr<const IntensitySampler> IntensitySampler::of(
    const std::shared_ptr<const PhotometricData>& data) {
    static std::mutex mutex;
    // Keyed by the table; the weak pointer tells a live table from a new one at a reused address.
    static std::map<const PhotometricData*, std::pair<std::weak_ptr<const PhotometricData>,
                                                      std::shared_ptr<const IntensitySampler>>>
        cache;
    if (!data) return nullptr;
    std::lock_guard<std::mutex> lock(mutex);
    auto it = cache.find(data.get());
    if (it != cache.end() && it->second.first.lock() == data) return it->second.second;
    for (auto i = cache.begin(); i != cache.end();)
        i = i->second.first.expired() ? cache.erase(i) : std::next(i);
    auto sampler = std::make_shared<const IntensitySampler>(*data);
    cache[data.get()] = {data, sampler};
    return sampler;
}

glm::dvec3 IntensitySampler::sample(double pick, const glm::dvec2& u) const {
    if (!valid()) return glm::dvec3(0.0, 0.0, 1.0);
    const size_t nv = mV.size();
    double target = pick * mTotal;
    size_t cell =
        size_t(std::upper_bound(mCdf.begin() + 1, mCdf.end(), target) - (mCdf.begin() + 1));
    cell = std::min(cell, mDensity.size() - 1);
    while (cell > 0 && !(mCdf[cell + 1] > mCdf[cell])) --cell;  // never an empty cell
    size_t h = cell / (nv - 1), v = cell % (nv - 1);
    double a0 = areaCoordinate(mTypeC, mV[v]), a1 = areaCoordinate(mTypeC, mV[v + 1]);
    double a = a0 + u.x * (a1 - a0);
    double az = mH[h] + u.y * (mH[h + 1] - mH[h]);
    if (mTypeC) {
        double cosG = std::clamp(-a, -1.0, 1.0), sinG = std::sqrt(std::max(0.0, 1.0 - cosG * cosG));
        return {sinG * std::cos(az), sinG * std::sin(az), cosG};
    }
    // Type B: V the latitude toward +y, H the azimuth from +z toward +x.
    double sinV = std::clamp(a, -1.0, 1.0), cosV = std::sqrt(std::max(0.0, 1.0 - sinV * sinV));
    return {cosV * std::sin(az), sinV, cosV * std::cos(az)};
}

std::vector<double> IntensitySampler::normalisedCdf() const {
    std::vector<double> out = mCdf;
    for (double& c : out) c = valid() ? c / mTotal : 0.0;
    return out;
}

bool IntensitySampler::locate(const glm::dvec3& d, size_t& v, size_t& h) const {
    double va, ha;
    if (mTypeC) {
        va = std::acos(std::clamp(d.z, -1.0, 1.0));
        ha = std::atan2(d.y, d.x);
        if (ha < 0.0) ha += kTwoPi;
    } else {
        va = std::asin(std::clamp(d.y, -1.0, 1.0));
        ha = std::atan2(d.x, d.z);
    }
    if (va < mV.front() || va > mV.back() || ha < mH.front() || ha > mH.back()) return false;
    v = std::min(size_t(std::upper_bound(mV.begin(), mV.end(), va) - mV.begin()), mV.size() - 1) -
        1;
    h = std::min(size_t(std::upper_bound(mH.begin(), mH.end(), ha) - mH.begin()), mH.size() - 1) -
        1;
    return true;
}

double IntensitySampler::pdf(const glm::dvec3& d) const {
    size_t v, h;
    if (!valid() || !locate(d, v, h)) return 0.0;
    return mDensity[h * (mV.size() - 1) + v];
}

}  // namespace candela
