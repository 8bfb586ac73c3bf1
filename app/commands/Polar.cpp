// `candela polar`: the polar candela diagram of an IES or EULUMDAT file (C0-C180 and C90-C270,
// gamma 0 at the bottom) as a PNG drawn by gnuplot, and its intensities as a table.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "app/commands/Commands.h"
#include "app/commands/Gnuplot.h"
#include "formats/Photometry.h"
#include "report/PolarDiagram.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

namespace {

namespace fs = std::filesystem;

/// gnuplot data block $polar: one block per plane, theta (degrees, 0 at the bottom, + to the
/// right) and cd, the two separated by two blank lines (gnuplot's `index`).
std::string plotData(const PolarCurves& c) {
    std::ostringstream out;
    out << "$polar << EOD\n";
    auto block = [&](const std::vector<double>& left, const std::vector<double>& right) {
        for (size_t k = c.gamma.size(); k-- > 0;) out << -c.gamma[k] << " " << left[k] << "\n";
        for (size_t k = 0; k < c.gamma.size(); ++k) out << c.gamma[k] << " " << right[k] << "\n";
        out << "\n\n";
    };
    block(c.c180, c.c0);
    block(c.c270, c.c90);
    out << "EOD\n";
    return out.str();
}

/// gnuplot ttics list: theta every 30 degrees, each labelled with gamma = |theta|.
std::string ticsList() {
    std::string out;
    for (int theta = -150; theta <= 180; theta += 30)
        out += (out.empty() ? "" : ", ") + std::string("'") + std::to_string(std::abs(theta)) +
               "' " + std::to_string(theta);
    return out;
}

/// Single quotes are the only character gnuplot's single-quoted strings cannot hold.
std::string singleQuoted(const std::string& s) {
    std::string out = "'";
    for (char ch : s) out += ch == '\'' ? std::string("''") : std::string(1, ch);
    return out + "'";
}

void plotPng(const PhotometricData& data, const PolarCurves& curves, const std::string& out) {
    if (!gnuplotAvailable())
        throw RuntimeError("gnuplot not found (install gnuplot-nox: scripts/setup.sh)");
    std::vector<double> rings = polarRings(curves.peak);
    std::string title = (data.name.empty() ? fs::path(data.path).filename().string() : data.name) +
                        ": luminous intensity [cd]";
    // The image comes back on gnuplot's standard output, then is written like every output.
    std::ostringstream gp;
    gp << plotData(curves) << "set terminal pngcairo size 720,720 noenhanced\n"
       << "set title " << singleQuoted(title)
       << " . \"\\n\" . 'left half C180 / C270, right half C0 / C90, "
          "gamma from the aim'\n"
       << "set polar\nset angles degrees\n"
       << "set theta bottom counterclockwise  # gamma 0 at the bottom; C0 and C90 on the right\n"
       << "set size square\nunset border\nunset xtics\nunset ytics\nunset raxis\n"
       << "set rrange [0:" << rings.back() << "]\n"
       << "set rtics " << rings.front() << " format '%g' scale 0 font ',8'\n"
       << "set rlabel 'cd'\n"
       << "set ttics (" << ticsList() << ") font ',9'  # labelled in gamma on both halves\n"
       << "set grid polar 30 lt 1 lc rgb '#c8c8c8' lw 0.5\n"
       << "set key outside bottom center horizontal\n"
       << "plot $polar index 0 using 1:2 with lines lw 2.5 lc rgb '#e07b00' title 'C0-C180', "
          "$polar index 1 using 1:2 with lines lw 2.5 lc rgb '#2c7fd0' dt 2 title 'C90-C270'\n";
    std::string png = gnuplotOutput(gp.str(), {}, out);
    writeFileAtomically(out, png, "cannot write the plot");
}

}  // namespace

int cmdPolar(const Args& args) {
    std::string path, out;
    double step = 0.0;
    CommandLine cli("polar");
    cli.argument("FILE", path, "the photometry file: .ies, .ldt or TM-33 .xml");
    cli.output("--out", out, "F.png", "also draw the polar diagram as a PNG (needs gnuplot)");
    cli.option("--step", "DEG",
               "the table's gamma step, degrees, 1..90 (default: the file's own "
               "vertical angles for type C photometry, else 5)",
               [&step](const std::string& v) { step = parseInt("--step", v, 1, 90); });
    cli.strictPhotometry();
    if (!cli.parse(args)) return 0;
    if (!out.empty() && fs::path(out).extension() != ".png")
        throw InputError(out + ": unsupported output extension \"" +
                         fs::path(out).extension().string() + "\" (use .png)");
    PhotometricData data = loadPhotometry(path);
    ProtectedInputs inputs({data.path, data.tiltPath});
    checkNotAnInput(out, "--out");

    // Table at the file's own vertical angles (type C) or every `step` degrees.
    std::vector<double> gamma;
    if (step == 0.0 && data.goniometer == Goniometer::C) {
        for (double g : data.vertical)
            if (g >= 0.0 && g <= 180.0) gamma.push_back(g);
    }
    if (gamma.empty()) {
        double s = step > 0.0 ? step : 5.0;
        for (int k = 0; k * s <= 180.0 + 1e-9; ++k) gamma.push_back(k * s);
    }
    PolarCurves table = polarCurves(data, gamma);
    std::printf("%s (%s, type %s), peak %.6g cd\n", path.c_str(), data.format.c_str(),
                data.goniometer == Goniometer::C ? "C" : "B", data.maxIntensity());
    std::printf("luminous intensity [cd]; gamma [deg] from the aim\n");
    std::printf("%9s %12s %12s %12s %12s\n", "gamma", "C0", "C180", "C90", "C270");
    for (size_t k = 0; k < table.gamma.size(); ++k)
        std::printf("%9.3g %12.6g %12.6g %12.6g %12.6g\n", table.gamma[k], table.c0[k],
                    table.c180[k], table.c90[k], table.c270[k]);
    if (!out.empty()) {
        plotPng(data, polarCurves(data, 0.5), out);
        std::printf("wrote %s\n", out.c_str());
    }
    return 0;
}

}  // namespace candela
