#include "app/commands/BenchUtil.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/commands/Gnuplot.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

std::string machineDescription() {
    std::ifstream in("/proc/cpuinfo");
    std::string line, model = "unknown CPU";
    int cores = 0;
    while (std::getline(in, line)) {
        if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
            model = line.substr(line.find(':') + 2);
            ++cores;
        }
    }
    return model + ", " + std::to_string(std::max(cores, 1)) + " cores";
}

std::vector<int> parseList(const std::string& text, const std::string& flag) {
    std::vector<int> out;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) out.push_back(parseInt(flag, item, 1, kMaxSampleCount));
    if (out.empty()) throw InputError(flag + ": expected a comma-separated list of sample counts");
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
    return {std::move(technique),
            spp,
            shadeMs,
            std::sqrt(std::max(0.0, raw * raw - refNoise * refNoise)),
            meanDeltaE(display, refDisplay),
            raw};
}

BenchRow rowAt(const std::vector<BenchRow>& rows, const std::string& technique, int spp) {
    for (const BenchRow& r : rows)
        if (r.technique == technique && r.spp == spp) return r;
    BenchRow none;
    none.technique = technique;
    none.spp = spp;
    none.shadeMs = none.rmse = none.deltaE = none.rawRmse = std::nan("");
    return none;
}

double atError(const std::vector<BenchRow>& rows, const std::string& technique, double error,
               bool time) {
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
    std::ostringstream csv;
    csv << "technique,spp,gpu_ms,rel_rmse,mean_delta_e,rel_rmse_raw,repeats,rel_rmse_spread\n";
    for (const BenchRow& r : rows)
        csv << r.technique << "," << r.spp << "," << r.shadeMs << "," << r.rmse << "," << r.deltaE
            << "," << r.rawRmse << "," << r.repeats << "," << r.rmseSpread << "\n";
    writeFileAtomically(path, csv.str());
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
    return "plot for [t in '" + techniques + "'] 'bench.csv' using (strcol(1) eq t ? $" +
           std::to_string(xColumn) + " : 1/0):" + std::to_string(yColumn) +
           " with linespoints pointsize 1.5 title t\n";
}

bool runGnuplot(const std::string& dir, const std::string& output) {
    // Named without the folder: a bench writes into a staging folder and moves its files into
    // --out at the end (BenchFolder).
    std::string path = (std::filesystem::path(dir) / output).string();
    if (!gnuplotAvailable()) {
        std::printf("gnuplot not found: plot.gp, beside the results, plots the CSV\n");
        return false;
    }
    try {
        writeFileAtomically(path, gnuplotOutput("load 'plot.gp'\n", dir, path),
                            "cannot write the plot");
    } catch (const RuntimeError& e) {
        std::printf("the plot %s was not made (%s); plot.gp, beside the results, plots the CSV\n",
                    output.c_str(), e.what());
        return false;
    }
    std::printf("plotted %s\n", output.c_str());
    return true;
}

}  // namespace candela
