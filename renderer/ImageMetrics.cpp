#include "renderer/ImageMetrics.h"

#include <algorithm>
#include <cmath>

namespace candela {

double luma(const float* c) {
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

double relRmse(const std::vector<float>& x, const std::vector<float>& r) {
    return relRmse(x, r, {});
}

double relRmse(const std::vector<float>& x, const std::vector<float>& r,
               const std::vector<unsigned char>& skip) {
    double num = 0.0, den = 0.0;
    for (size_t i = 0; i + 2 < r.size() && i + 2 < x.size(); i += 3) {
        if (i / 3 < skip.size() && skip[i / 3]) continue;
        double d = luma(&x[i]) - luma(&r[i]);
        num += d * d;
        den += luma(&r[i]) * luma(&r[i]);
    }
    return den > 0.0 ? std::sqrt(num / den) : 0.0;
}

double meanLuminance(const std::vector<float>& rgb) {
    double sum = 0.0;
    size_t n = rgb.size() / 3;
    for (size_t i = 0; i < n; ++i) sum += luma(&rgb[3 * i]);
    return n ? sum / double(n) : 0.0;
}

glm::dvec3 lab(const unsigned char* c) {
    auto lin = [](double v) {
        v /= 255.0;
        return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
    };
    double r = lin(c[0]), g = lin(c[1]), b = lin(c[2]);
    double X = (0.4124 * r + 0.3576 * g + 0.1805 * b) / 0.95047;
    double Y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
    double Z = (0.0193 * r + 0.1192 * g + 0.9505 * b) / 1.08883;
    auto f = [](double t) {
        return t > 216.0 / 24389.0 ? std::cbrt(t) : (24389.0 / 27.0 * t + 16.0) / 116.0;
    };
    return {116.0 * f(Y) - 16.0, 500.0 * (f(X) - f(Y)), 200.0 * (f(Y) - f(Z))};
}

double meanDeltaE(const std::vector<unsigned char>& x, const std::vector<unsigned char>& r) {
    double sum = 0.0;
    size_t n = std::min(x.size(), r.size()) / 3;
    for (size_t i = 0; i < n; ++i) sum += glm::length(lab(&x[3 * i]) - lab(&r[3 * i]));
    return n ? sum / double(n) : 0.0;
}

std::vector<unsigned char> toneMapSrgb8(const std::vector<float>& rgb, double average,
                                        double exposure, bool reinhard) {
    double avg = std::max(average, 1e-8);
    std::vector<unsigned char> out(rgb.size());
    for (size_t i = 0; i < rgb.size(); ++i) {
        double c = std::isfinite(rgb[i]) ? std::max(0.0, double(rgb[i])) : 0.0;
        double m = reinhard ? 0.18 * exposure * c / avg : 0.0;
        double mapped = reinhard ? m / (1.0 + m) : 1.0 - std::exp(-exposure * c / avg);
        mapped = std::clamp(mapped, 0.0, 1.0);
        double s =
            mapped <= 0.0031308 ? 12.92 * mapped : 1.055 * std::pow(mapped, 1.0 / 2.4) - 0.055;
        out[i] = static_cast<unsigned char>(std::lround(std::clamp(s, 0.0, 1.0) * 255.0));
    }
    return out;
}

}  // namespace candela
