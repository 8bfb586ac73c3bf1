#include "app/commands/BenchUtil.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "util/Error.h"

namespace candela {

double luma(const float* c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

/// sqrt(sum (x - r)^2 / sum r^2) over pixel luminances.
double relRmse(const std::vector<float>& x, const std::vector<float>& r) {
    double num = 0.0, den = 0.0;
    for (size_t i = 0; i + 2 < r.size(); i += 3) {
        double d = luma(&x[i]) - luma(&r[i]);
        num += d * d;
        den += luma(&r[i]) * luma(&r[i]);
    }
    return den > 0.0 ? std::sqrt(num / den) : 0.0;
}

/// sRGB8 to CIELAB (D65).
glm::dvec3 lab(const unsigned char* c) {
    auto lin = [](double v) {
        v /= 255.0;
        return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
    };
    double r = lin(c[0]), g = lin(c[1]), b = lin(c[2]);
    double X = (0.4124 * r + 0.3576 * g + 0.1805 * b) / 0.95047;
    double Y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
    double Z = (0.0193 * r + 0.1192 * g + 0.9505 * b) / 1.08883;
    auto f = [](double t) { return t > 216.0 / 24389.0 ? std::cbrt(t) : (24389.0 / 27.0 * t + 16.0) / 116.0; };
    return {116.0 * f(Y) - 16.0, 500.0 * (f(X) - f(Y)), 200.0 * (f(Y) - f(Z))};
}

double meanDeltaE(const std::vector<unsigned char>& x, const std::vector<unsigned char>& r) {
    double sum = 0.0;
    size_t n = r.size() / 3;
    for (size_t i = 0; i < n; ++i) sum += glm::length(lab(&x[3 * i]) - lab(&r[3 * i]));
    return n ? sum / double(n) : 0.0;
}

std::vector<int> parseList(const std::string& text) {
    std::vector<int> out;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) out.push_back(parseInt("--spp", item, 1, 1 << 20));
    if (out.empty()) throw InputError("--spp: expected a comma-separated list of sample counts");
    return out;
}

std::string formatRatio(double ratio) {
    if (!std::isfinite(ratio)) return "n/a";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1fx", ratio);
    return buf;
}

BenchRow benchRow(std::string technique, int spp, double shadeMs, const std::vector<float>& linear,
                  const std::vector<unsigned char>& display, const std::vector<float>& refLinear,
                  const std::vector<unsigned char>& refDisplay, double refNoise) {
    double raw = relRmse(linear, refLinear);
    return {std::move(technique), spp, shadeMs, std::sqrt(std::max(0.0, raw * raw - refNoise * refNoise)),
            meanDeltaE(display, refDisplay), raw};
}

double atError(const std::vector<BenchRow>& rows, const std::string& technique, double error, bool time) {
    std::vector<const BenchRow*> c;
    for (const BenchRow& r : rows)
        if (r.technique == technique) c.push_back(&r);
    for (size_t i = 0; i + 1 < c.size(); ++i) {
        const BenchRow &a = *c[i], &b = *c[i + 1];
        if ((a.rmse - error) * (b.rmse - error) > 0.0) continue;
        double xa = std::log(time ? a.shadeMs : a.spp), xb = std::log(time ? b.shadeMs : b.spp);
        double t = (std::log(error) - std::log(a.rmse)) / (std::log(b.rmse) - std::log(a.rmse));
        return std::exp(xa + t * (xb - xa));
    }
    return std::nan("");
}

void writeBenchCsv(const std::string& path, const std::vector<BenchRow>& rows) {
    std::ofstream csv(path);
    csv << "technique,spp,gpu_ms,rel_rmse,mean_delta_e,rel_rmse_raw,repeats,rel_rmse_spread\n";
    for (const BenchRow& r : rows)
        csv << r.technique << "," << r.spp << "," << r.shadeMs << "," << r.rmse << "," << r.deltaE << ","
            << r.rawRmse << "," << r.repeats << "," << r.rmseSpread << "\n";
}

BenchRow meanRow(const std::vector<BenchRow>& repeats) {
    BenchRow mean;
    if (repeats.empty()) return mean;
    mean.technique = repeats.front().technique;
    mean.spp = repeats.front().spp;
    mean.repeats = int(repeats.size());
    double mse = 0.0, rawMse = 0.0, sum = 0.0;
    for (const BenchRow& r : repeats) {
        mean.shadeMs += r.shadeMs;
        mean.deltaE += r.deltaE;
        mse += r.rmse * r.rmse;
        rawMse += r.rawRmse * r.rawRmse;
        sum += r.rmse;
    }
    double n = double(repeats.size());
    mean.shadeMs /= n;
    mean.deltaE /= n;
    mean.rmse = std::sqrt(mse / n);
    mean.rawRmse = std::sqrt(rawMse / n);
    mean.rmseSpread = n > 1 ? std::sqrt(std::max(0.0, (mse - sum * sum / n) / (n - 1))) : 0.0;
    return mean;
}

std::string sweepPlot(const std::string& techniques, int xColumn, int yColumn) {
    return "plot for [t in '" + techniques + "'] 'bench.csv' using (strcol(1) eq t ? $" + std::to_string(xColumn) +
           " : 1/0):" + std::to_string(yColumn) + " with linespoints pointsize 1.5 title t\n";
}

bool runGnuplot(const std::string& dir, const std::string& output) {
    std::string cmd = "cd '" + dir + "' && gnuplot plot.gp > '" + output + "' 2>/dev/null";
    if (std::system("command -v gnuplot >/dev/null 2>&1") == 0 && std::system(cmd.c_str()) == 0) {
        std::printf("wrote %s/%s\n", dir.c_str(), output.c_str());
        return true;
    }
    std::printf("gnuplot not found: %s/plot.gp is there to plot the CSV\n", dir.c_str());
    return false;
}

}  // namespace candela
