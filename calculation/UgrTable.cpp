#include "calculation/UgrTable.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>

#include "shaders/shared/Constants.h"
#include "util/Error.h"

namespace candela {

namespace {

using gpu::kPi;
constexpr double kRad = kPi / 180.0;

// ---------------------------------------------------------------------------------------------
// The standard's tables. The numbers are facts from CIE 190:2010 (Tables 4 and 5) and CIE
// 117:1995 (Table 4.1), as transcribed in eulumdat-ugr (github.com/123VincentB/eulumdat-ugr, MIT
// licence, src/eulumdat_ugr/background.py and guth.py); Candela had no copy of the standards.
// Uncertain, as the transcription stands:
//  - F_GL: its notes say CIE 190 Table 4 lists 10 room sizes, yet it gives 13 room indices;
//    which (if any) were interpolated is not stated.
//  - F_T: 50/50/20's F_T,CW is .365 for 2H x 4H and .364 for 4H x 2H (same room index k = 1.33;
//    every other set gives both rooms the same factors).
//  - Guth: T/R 2.7, H/R 0.6 reads 7.50, out of line with its neighbours (7.08 and 7.12 below it);
//    kept as published, as the catalogue programs keep it.

/// The room sizes, X and Y in units of H, rows of X = 2, 4, 8 and 12 H.
constexpr UgrRoomSize kRooms[kUgrRoomCount] = {
    {2, 2},  {2, 3},  {2, 4}, {2, 6},  {2, 8}, {2, 12},  //
    {4, 2},  {4, 3},  {4, 4}, {4, 6},  {4, 8}, {4, 12},  //
    {8, 4},  {8, 6},  {8, 8}, {8, 12},                   //
    {12, 4}, {12, 6}, {12, 8}};

/// CIE 190 Table 4: the room index k and F_GL1..4, the weights of the flux below 41.4, 60, 75.5
/// and 90 degrees in the direct flux on the floor.
struct FloorFactors {
    double k;
    std::array<double, 4> f;
};
constexpr FloorFactors kFloor[] = {
    {1.00, {0.690, 0.109, 0.085, -0.016}}, {1.20, {0.578, 0.200, 0.127, -0.018}},
    {1.33, {0.528, 0.218, 0.170, -0.017}}, {1.50, {0.485, 0.215, 0.222, -0.012}},
    {1.60, {0.466, 0.207, 0.249, -0.006}}, {1.71, {0.448, 0.198, 0.272, 0.005}},
    {2.00, {0.338, 0.257, 0.351, -0.018}}, {2.40, {0.296, 0.203, 0.449, -0.006}},
    {2.67, {0.280, 0.165, 0.499, 0.006}},  {3.00, {0.264, 0.125, 0.541, 0.027}},
    {3.43, {0.248, 0.058, 0.628, 0.032}},  {4.00, {0.239, -0.012, 0.690, 0.058}},
    {4.80, {0.232, -0.084, 0.740, 0.098}},
};

/// CIE 190 Table 5: F_T,FW, F_T,WW-1, F_T,CW per reflectance set and room (kRooms' order).
using Transfer = std::array<std::array<double, 3>, kUgrRoomCount>;
constexpr std::array<Transfer, kUgrReflectanceCount> kTransfer = {{
    // 70/50/20
    {{{.220, .422, .646},
      {.199, .376, .571},
      {.187, .351, .531},
      {.174, .322, .488},
      {.167, .307, .466},
      {.160, .290, .443},
      {.187, .351, .531},
      {.158, .295, .439},
      {.142, .265, .389},
      {.124, .230, .335},
      {.115, .211, .307},
      {.105, .190, .279},
      {.115, .211, .307},
      {.094, .175, .247},
      {.083, .155, .215},
      {.071, .133, .183},
      {.105, .190, .279},
      {.083, .153, .216},
      {.071, .133, .183}}},
    // 70/30/20
    {{{.188, .217, .553},
      {.173, .196, .497},
      {.164, .184, .465},
      {.154, .171, .432},
      {.149, .164, .415},
      {.143, .156, .397},
      {.164, .184, .465},
      {.142, .159, .393},
      {.129, .144, .351},
      {.114, .127, .307},
      {.106, .117, .283},
      {.098, .106, .259},
      {.106, .117, .283},
      {.088, .098, .231},
      {.078, .088, .203},
      {.067, .076, .174},
      {.098, .106, .259},
      {.078, .086, .204},
      {.067, .076, .174}}},
    // 50/50/20
    {{{.198, .380, .445},
      {.178, .338, .393},
      {.166, .314, .365},
      {.154, .287, .335},
      {.147, .273, .320},
      {.141, .257, .304},
      {.166, .314, .364},
      {.140, .263, .301},
      {.125, .235, .267},
      {.108, .204, .230},
      {.100, .187, .211},
      {.091, .167, .191},
      {.100, .187, .211},
      {.081, .154, .169},
      {.071, .137, .147},
      {.061, .117, .125},
      {.091, .167, .191},
      {.071, .134, .148},
      {.061, .117, .125}}},
    // 50/30/20
    {{{.172, .198, .386},
      {.157, .179, .346},
      {.148, .167, .324},
      {.138, .155, .301},
      {.133, .147, .288},
      {.128, .140, .276},
      {.148, .167, .324},
      {.126, .143, .272},
      {.114, .129, .244},
      {.100, .113, .212},
      {.093, .104, .196},
      {.085, .094, .179},
      {.093, .104, .196},
      {.076, .087, .158},
      {.067, .078, .140},
      {.058, .067, .120},
      {.085, .094, .179},
      {.068, .077, .140},
      {.058, .067, .120}}},
    // 30/30/20
    {{{.157, .181, .227},
      {.141, .162, .203},
      {.132, .151, .190},
      {.123, .139, .176},
      {.118, .132, .169},
      {.113, .124, .161},
      {.132, .151, .190},
      {.112, .128, .159},
      {.100, .115, .142},
      {.087, .101, .124},
      {.081, .092, .114},
      {.074, .083, .104},
      {.081, .092, .114},
      {.066, .077, .092},
      {.058, .069, .081},
      {.049, .059, .069},
      {.074, .083, .104},
      {.058, .067, .081},
      {.049, .059, .069}}},
}};

/// CIE 117 Table 4.1, Guth's position index: rows T/R = 0, 0.1, .., 3.0; columns H/R = 0, 0.1,
/// .., 1.9; 0 where the table has no entry.
constexpr int kGuthRows = 31, kGuthColumns = 20;
constexpr double kGuth[kGuthRows][kGuthColumns] = {
    {1.00, 1.26, 1.53, 1.90,  2.35,  2.86,  3.50,  4.20,  5.00, 6.00,
     7.00, 8.10, 9.25, 10.35, 11.70, 13.15, 14.70, 16.20, 0,    0},
    {1.05, 1.22, 1.46, 1.80,  2.20,  2.75,  3.40,  4.10,  4.80, 5.80,
     6.80, 8.00, 9.10, 10.30, 11.60, 13.00, 14.60, 16.10, 0,    0},
    {1.12, 1.30, 1.50, 1.80, 2.20,  2.66,  3.18,  3.88,  4.60, 5.50,
     6.50, 7.60, 8.75, 9.85, 11.20, 12.70, 14.00, 15.70, 0,    0},
    {1.22, 1.38, 1.60, 1.97, 2.25,  2.70,  3.25,  3.90,  4.60, 5.45,
     6.45, 7.40, 8.40, 9.50, 10.85, 12.10, 13.70, 15.00, 0,    0},
    {1.32, 1.47, 1.70, 1.96, 2.35,  2.80,  3.30,  3.90,  4.60,  5.40,
     6.40, 7.30, 8.30, 9.40, 10.60, 11.90, 13.20, 14.60, 16.00, 0},
    {1.43, 1.60, 1.82, 2.10, 2.48,  2.91,  3.40,  3.98,  4.70,  5.50,
     6.40, 7.30, 8.30, 9.40, 10.50, 11.75, 13.00, 14.40, 15.70, 0},
    {1.55, 1.72, 1.98, 2.30, 2.65,  3.10,  3.60,  4.10,  4.80,  5.50,
     6.40, 7.35, 8.40, 9.40, 10.50, 11.70, 13.00, 14.10, 15.40, 0},
    {1.70, 1.88, 2.12, 2.48, 2.87,  3.30,  3.78,  4.30,  4.88,  5.60,
     6.50, 7.40, 8.50, 9.50, 10.50, 11.70, 12.85, 14.00, 15.20, 0},
    {1.82, 2.00, 2.32, 2.70, 3.08,  3.50,  3.92,  4.50,  5.10,  5.75,
     6.60, 7.50, 8.60, 9.50, 10.60, 11.75, 12.80, 14.00, 15.10, 0},
    {1.96, 2.20, 2.54, 2.90, 3.30,  3.70,  4.20,  4.75,  5.30,  6.00,
     6.75, 7.70, 8.70, 9.65, 10.75, 11.80, 12.90, 14.00, 15.00, 16.00},
    {2.11, 2.40, 2.75, 3.10, 3.50,  3.91,  4.40,  5.00,  5.60,  6.20,
     7.00, 7.90, 8.80, 9.75, 10.80, 11.90, 12.95, 14.00, 15.00, 16.00},
    {2.30, 2.55, 2.92, 3.30, 3.72,  4.20,  4.70,  5.25,  5.80,  6.55,
     7.20, 8.15, 9.00, 9.90, 10.95, 12.00, 13.00, 14.00, 15.00, 16.00},
    {2.40, 2.75, 3.12, 3.50,  3.90,  4.35,  4.85,  5.50,  6.05,  6.70,
     7.50, 8.30, 9.20, 10.00, 11.02, 12.10, 13.10, 14.00, 15.00, 16.00},
    {2.55, 2.90, 3.30, 3.70,  4.20,  4.65,  5.20,  5.70,  6.30,  7.00,
     7.70, 8.55, 9.35, 10.20, 11.20, 12.25, 13.20, 14.00, 15.00, 16.00},
    {2.70, 3.10, 3.50, 3.90,  4.35,  4.85,  5.35,  5.85,  6.50,  7.25,
     8.00, 8.70, 9.50, 10.40, 11.40, 12.40, 13.25, 14.05, 15.00, 16.00},
    {2.85, 3.15, 3.65, 4.10,  4.55,  5.00,  5.50,  6.20,  6.80,  7.50,
     8.20, 8.85, 9.70, 10.55, 11.50, 12.50, 13.30, 14.05, 15.02, 16.00},
    {2.95, 3.40, 3.80, 4.25,  4.75,  5.20,  5.75,  6.30,  7.00,  7.65,
     8.40, 9.00, 9.80, 10.80, 11.75, 12.60, 13.40, 14.20, 15.10, 16.00},
    {3.10, 3.55, 4.00,  4.50,  4.90,  5.40,  5.95,  6.50,  7.20,  7.80,
     8.50, 9.20, 10.00, 10.85, 11.85, 12.75, 13.45, 14.20, 15.10, 16.00},
    {3.25, 3.70, 4.20,  4.65,  5.10,  5.60,  6.10,  6.75,  7.40,  8.00,
     8.65, 9.35, 10.10, 11.00, 11.90, 12.80, 13.50, 14.20, 15.10, 16.00},
    {3.43, 3.86, 4.30,  4.75,  5.20,  5.70,  6.30,  6.90,  7.50,  8.17,
     8.80, 9.50, 10.20, 11.00, 12.00, 12.82, 13.55, 14.20, 15.10, 16.00},
    {3.50, 4.00, 4.50,  4.90,  5.35,  5.80,  6.40,  7.10,  7.70,  8.30,
     8.90, 9.60, 10.40, 11.10, 12.00, 12.85, 13.60, 14.30, 15.10, 16.00},
    {3.60, 4.17, 4.65,  5.05,  5.50,  6.00,  6.60,  7.20,  7.82,  8.45,
     9.00, 9.75, 10.50, 11.20, 12.10, 12.90, 13.70, 14.35, 15.10, 16.00},
    {3.75, 4.25, 4.72,  5.20,  5.60,  6.10,  6.70,  7.35,  8.00,  8.55,
     9.15, 9.85, 10.60, 11.30, 12.10, 12.90, 13.70, 14.40, 15.15, 16.00},
    {3.85, 4.35, 4.80,  5.25,  5.70,  6.22,  6.80,  7.40,  8.10,  8.65,
     9.30, 9.90, 10.70, 11.40, 12.20, 12.95, 13.70, 14.40, 15.20, 16.00},
    {3.95, 4.40,  4.90,  5.35,  5.80,  6.30,  6.90,  7.50,  8.20,  8.80,
     9.40, 10.00, 10.80, 11.50, 12.25, 13.00, 13.75, 14.45, 15.20, 16.00},
    {4.00, 4.50,  4.96,  5.40,  5.85,  6.40,  6.95,  7.55,  8.25,  8.85,
     9.50, 10.05, 10.85, 11.55, 12.30, 13.00, 13.80, 14.50, 15.25, 16.00},
    {4.07, 4.55,  5.05,  5.47,  5.95,  6.46,  7.00,  7.65,  8.35,  8.95,
     9.55, 10.10, 10.90, 11.60, 12.32, 13.00, 13.80, 14.50, 15.25, 16.00},
    {4.10, 4.60,  5.10,  5.53,  6.00,  6.50,  7.50,  7.70,  8.40,  9.00,
     9.60, 10.16, 10.92, 11.63, 12.35, 13.00, 13.80, 14.50, 15.25, 16.00},
    {4.15, 4.62,  5.15,  5.56,  6.05,  6.55,  7.08,  7.73,  8.45,  9.05,
     9.65, 10.20, 10.95, 11.65, 12.35, 13.00, 13.80, 14.50, 15.25, 16.00},
    {4.20, 4.65,  5.17,  5.60,  6.07,  6.57,  7.12,  7.75,  8.50,  9.10,
     9.70, 10.23, 10.95, 11.65, 12.35, 13.00, 13.80, 14.50, 15.25, 16.00},
    {4.22, 4.67,  5.20,  5.65,  6.12,  6.60,  7.15,  7.80,  8.55,  9.12,
     9.70, 10.23, 10.95, 11.65, 12.35, 13.00, 13.80, 14.50, 15.25, 16.00},
};

/// CIE 190's zone limits 41.4 and 75.5 degrees fall inside the 10-degree zones 40-50 and 70-80:
/// the standard takes 0.130 and 0.547 of those zones (as transcribed; the solid-angle fractions
/// (cos 40 - cos 41.4) / (cos 40 - cos 50) = 0.129 and (cos 70 - cos 75.5) / (cos 70 - cos 80) =
/// 0.544 are what a uniform intensity would give).
constexpr double kPartOfZone40To50 = 0.130, kPartOfZone70To80 = 0.547;

/// A value of the file's keywords as a number (EULUMDAT header fields); `fallback` when absent.
double keywordNumber(const PhotometricData& d, const char* key, double fallback) {
    std::string text = d.keyword({key});
    double v = 0.0;
    auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), v);
    return error == std::errc() && end != text.data() && std::isfinite(v) ? v : fallback;
}

std::string formatted(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

std::string millimetres(double metres) {
    return formatted(metres * 1e3);
}

/// The unit direction (C, gamma) in the photometric frame: +x C0, +y C90, +z gamma 0.
glm::dvec3 direction(double cDeg, double gammaDeg) {
    double c = cDeg * kRad, g = gammaDeg * kRad;
    return {std::sin(g) * std::cos(c), std::sin(g) * std::sin(c), std::cos(g)};
}

/// The mean of I(C, gamma) over C at `gammaDeg`: the trapezoid rule over a type C table's own
/// planes (exact for the interpolant, which is linear in C between them), else 720 samples.
double meanOverC(const PhotometricData& d, double gammaDeg) {
    if (d.goniometer == Goniometer::C && d.horizontal.size() >= 2) {
        double sum = 0.0;
        double previous = d.intensity(direction(d.horizontal[0], gammaDeg));
        for (size_t h = 1; h < d.horizontal.size(); ++h) {
            double next = d.intensity(direction(d.horizontal[h], gammaDeg));
            sum += 0.5 * (previous + next) * (d.horizontal[h] - d.horizontal[h - 1]);
            previous = next;
        }
        return sum / (d.horizontal.back() - d.horizontal.front());
    }
    constexpr int kSamples = 720;
    double sum = 0.0;
    for (int k = 0; k < kSamples; ++k)
        sum += d.intensity(direction(360.0 * k / kSamples, gammaDeg));
    return sum / kSamples;
}

std::array<double, 4> floorFactors(double k) {
    for (const FloorFactors& f : kFloor)
        if (std::abs(f.k - k) < 0.006) return f.f;
    throw std::logic_error("UGR table: no F_GL for room index " + std::to_string(k));
}

/// Phi, the factor that takes the file's candela to Phi's, the light output ratio and whose
/// flux it is.
struct FluxBasis {
    double flux = 0.0, scale = 1.0, lightOutputRatio = 1.0;
    std::string note;
};

FluxBasis fluxBasis(const PhotometricData& d) {
    FluxBasis b;
    double table = d.fluxFromTable();
    bool absolute = !d.keyword({"absolute photometry"}).empty() || !(d.lampFlux > 0.0);
    if (!d.lampSetFlux.empty() && d.lampFlux > 0.0) {
        // EULUMDAT: cd/klm of the lamp sets' sum; catalogue tables take the first set's flux.
        b.flux = d.lampSetFlux[0];
        b.scale = b.flux / d.lampFlux;
        b.note = d.lampSetFlux.size() == 1
                     ? "lamp set 1"
                     : "lamp set 1 of " + std::to_string(d.lampSetFlux.size()) +
                           ", as DIALux and Relux take it";
        if (absolute) b.note += ", absolute photometry: the luminaire's flux";
        if (!(b.flux > 0.0))
            throw InputError(d.path +
                             ": lamp set 1 has no luminous flux (0 lm); a UGR table is computed at "
                             "the first lamp set's flux");
    } else if (d.lampFlux > 0.0) {
        b.flux = d.lampFlux;
        b.note = "lamps";
    } else {
        b.flux = table;
        b.note = "absolute photometry: the luminaire's flux from its table";
    }
    if (d.declaresLightOutputRatio && d.lightOutputRatio > 0.0)
        b.lightOutputRatio = d.lightOutputRatio;
    else
        b.lightOutputRatio = d.lampFlux > 0.0 ? table / d.lampFlux : 1.0;
    if (!(b.flux > 0.0) || !(table > 0.0))
        throw InputError(d.path + ": no luminous flux (the intensity table is all 0 cd)");
    return b;
}

}  // namespace

const std::array<UgrRoomSize, kUgrRoomCount> kUgrRoomSizes = std::to_array(kRooms);
const std::array<UgrReflectances, kUgrReflectanceCount> kUgrReflectances = {
    {{70, 50, 20}, {70, 30, 20}, {50, 50, 20}, {50, 30, 20}, {30, 30, 20}}};

double guthTablePositionIndex(double tOverR, double hOverR) {
    double x = tOverR * 10.0, y = hOverR * 10.0;
    constexpr double kEdge = 1e-9;  // on a grid line, the next row or column has no weight
    if (!(x >= 0.0 && y >= 0.0) || x > kGuthRows - 1 + kEdge || y > kGuthColumns - 1 + kEdge)
        return 0.0;
    int i = std::min(int(x), kGuthRows - 2), j = std::min(int(y), kGuthColumns - 2);
    double u = std::clamp(x - i, 0.0, 1.0), v = std::clamp(y - j, 0.0, 1.0);
    double sum = 0.0;
    for (int di = 0; di < 2; ++di)
        for (int dj = 0; dj < 2; ++dj) {
            double w = (di ? u : 1.0 - u) * (dj ? v : 1.0 - v);
            if (w <= kEdge) continue;
            double p = kGuth[i + di][j + dj];
            if (p <= 0.0) return 0.0;
            sum += w * p;
        }
    return sum;
}

// ---------------------------------------------------------------------------------------------
// The luminous area

double UgrLuminousArea::bottom() const {
    return projected(0.0, 0.0);
}

double UgrLuminousArea::projected(double cDeg, double gammaDeg) const {
    glm::dvec3 u = direction(cDeg, gammaDeg);
    double s = std::sin(gammaDeg * kRad), c = std::cos(gammaDeg * kRad);
    double cosC = std::cos(cDeg * kRad), sinC = std::sin(cDeg * kRad);
    // The faces seen from this side: C0 or C180, C90 or C270.
    double h0 = cosC >= 0.0 ? heights[0] : heights[2], h90 = sinC >= 0.0 ? heights[1] : heights[3];
    switch (shape) {
        case Shape::Box:
            // The C0 and C180 faces span the C90 axis, the C90 and C270 faces the C0 axis.
            return alongC0 * alongC90 * c +
                   s * (std::abs(cosC) * alongC90 * h0 + std::abs(sinC) * alongC0 * h90);
        case Shape::Round: {
            double a = 0.5 * alongC0, b = 0.5 * alongC90;
            // The ellipse's width across the line of sight, times the side's height (blended
            // between the faces, so a cylinder of one height shows width x height).
            double width = 2.0 * std::sqrt(a * a * sinC * sinC + b * b * cosC * cosC);
            return kPi * a * b * c + s * width * (cosC * cosC * h0 + sinC * sinC * h90);
        }
        case Shape::Ellipsoid: {
            // The shadow of an ellipsoid with semi-axes a, b, e along x, y, z on the plane
            // normal to u: pi sqrt((b e ux)^2 + (a e uy)^2 + (a b uz)^2).
            double a = 0.5 * alongC0, b = 0.5 * alongC90, e = 0.5 * heights[0];
            return kPi * std::sqrt(b * b * e * e * u.x * u.x + a * a * e * e * u.y * u.y +
                                   a * a * b * b * u.z * u.z);
        }
        case Shape::CylinderAlongC0:
        case Shape::CylinderAlongC90: {
            bool x = shape == Shape::CylinderAlongC0;
            double length = x ? alongC0 : alongC90, diameter = x ? alongC90 : alongC0;
            double along = std::abs(x ? u.x : u.y);  // cosine of the angle to the axis
            return length * diameter * std::sqrt(std::max(0.0, 1.0 - along * along)) +
                   0.25 * kPi * diameter * diameter * along;
        }
    }
    return 0.0;
}

UgrLuminousArea ugrLuminousArea(const PhotometricData& d) {
    const std::string why =
        ": the UGR table needs the luminaire's luminance, its intensity over its luminous area";
    UgrLuminousArea a;
    if (d.format == "EULUMDAT") {
        // The size from the parsed opening (LdtParse::opening: the file's length along
        // C90-C270, so the faces seen from C0 and C180 are length x height, which Relux's printed
        // luminances of a linear luminaire with luminous sides bear out), with each face's own
        // height (fields 18-21), which the opening reduces to the largest.
        const double mm = 1e-3;
        const LuminousOpening& o = d.opening;
        const char* faces[4] = {"luminous area height C0 (mm)", "luminous area height C90 (mm)",
                                "luminous area height C180 (mm)", "luminous area height C270 (mm)"};
        for (int k = 0; k < 4; ++k) a.heights[k] = keywordNumber(d, faces[k], 0.0) * mm;
        if (!(o.width > 0.0))
            throw InputError(d.path + ": no luminous area (EULUMDAT field 16, its length, is " +
                             millimetres(o.width) + " mm, and field 17, its width, " +
                             millimetres(o.length) + " mm)" + why);
        bool round = o.shape != LuminousOpening::Shape::Rectangle;
        a.shape = round ? UgrLuminousArea::Shape::Round : UgrLuminousArea::Shape::Box;
        a.alongC0 = o.length;
        a.alongC90 = o.width;
        a.note = round ? "EULUMDAT fields 16-21, round (width 0)"
                       : "EULUMDAT fields 16-21, length along C90-C270 as DIALux and Relux read it";
        return a;
    }
    const LuminousOpening& o = d.opening;
    using S = LuminousOpening::Shape;
    a.alongC0 = o.length;
    a.alongC90 = o.width;
    a.heights.fill(o.height);
    a.note = "the file's luminous opening, length along C0-C180";
    switch (o.shape) {
        case S::Point:
            throw InputError(d.path +
                             ": no luminous area (a point source: the opening's width, length "
                             "and height are 0)" +
                             why);
        case S::Rectangle:
            a.shape = UgrLuminousArea::Shape::Box;
            break;
        case S::Ellipse:
        case S::Cylinder:
            if (o.shape == S::Cylinder && o.axis != LuminousOpening::Axis::Z) {
                a.shape = o.axis == LuminousOpening::Axis::X
                              ? UgrLuminousArea::Shape::CylinderAlongC0
                              : UgrLuminousArea::Shape::CylinderAlongC90;
                a.heights.fill(0.0);
            } else {
                a.shape = UgrLuminousArea::Shape::Round;
            }
            break;
        case S::Sphere:
            a.shape = UgrLuminousArea::Shape::Ellipsoid;
            break;
    }
    if (!(a.bottom() > 0.0))
        throw InputError(d.path + ": no luminous area (the opening is " + millimetres(o.length) +
                         " x " + millimetres(o.width) + " mm, without area seen from below)" + why);
    return a;
}

// ---------------------------------------------------------------------------------------------
// The table

namespace {

/// Sum of L^2 omega / p^2 over the luminaires of room `size` in the field of view (see the
/// header), `crosswise` or endwise; `counted` gets their number.
double glareSum(const PhotometricData& d, const UgrLuminousArea& area, double scale,
                UgrRoomSize size, const UgrTableOptions& o, bool crosswise, int& counted) {
    const double h = o.height, spacing = o.spacing * h;
    const int across = int(std::lround(size.x / o.spacing)) / 2;  // columns each side
    const int along = int(std::lround(size.y / o.spacing));
    double sum = 0.0;
    counted = 0;
    for (int i = 0; i < across; ++i) {
        for (int j = 0; j < along; ++j) {
            const double t = (i + 0.5) * spacing, r = (j + 0.5) * spacing;
            if (t / r > 3.0) continue;
            const double gamma = std::atan(std::hypot(t, r) / h) / kRad;
            if (gamma > 85.0) continue;
            const double p = guthTablePositionIndex(t / r, h / r);
            if (!(p > 0.0)) continue;
            const double r2 = t * t + r * r + h * h;
            const double offset = std::atan2(t, r) / kRad;
            for (double side : {1.0, -1.0}) {  // the luminaires left and right of the axis
                double c = crosswise ? side * offset : 90.0 - side * offset;
                if (c < 0.0) c += 360.0;
                double intensity = d.intensity(direction(c, gamma)) * scale;
                double ap = area.projected(c, gamma);
                // L^2 omega = (I / Ap)^2 Ap / r^2.
                sum += intensity * intensity / (ap * r2 * p * p);
                ++counted;
            }
        }
    }
    return sum;
}

}  // namespace

UgrTable computeUgrTable(const PhotometricData& d, const UgrTableOptions& options) {
    double perH = 1.0 / options.spacing;
    if (!(options.spacing > 0.0) || std::abs(perH - std::round(perH)) > 1e-6 || perH > 20.5)
        throw InputError("luminaire spacing " + formatted(options.spacing) +
                         " H: expected 1 / n of H (1, 0.5, 0.25, .., 0.05), so that each standard "
                         "room holds whole rows of luminaires");
    if (!(options.height > 0.0) || !std::isfinite(options.height))
        throw InputError("UGR table: H must be a positive length in metres");
    UgrTable t;
    t.path = d.path;
    t.options = options;
    t.area = ugrLuminousArea(d);
    FluxBasis basis = fluxBasis(d);
    t.flux = basis.flux;
    t.fluxNote = basis.note;
    t.lightOutputRatio = basis.lightOutputRatio;

    // Zonal fluxes at the 10-degree zones' midpoints 5, 15, .., 175 degrees (CIE 190): the mean
    // intensity over C times the zone's solid angle, scaled so that they sum to the light output
    // ratio (fractions of the lamp flux). The zone's exact solid angle 2 pi (cos a - cos b) and
    // the standard's 2 pi sin(g) 10 deg differ by a factor the scaling removes.
    std::array<double, 18> zone{};
    double total = 0.0;
    for (int m = 0; m < 18; ++m) {
        double a = 10.0 * m * kRad, b = 10.0 * (m + 1) * kRad;
        zone[m] = meanOverC(d, 10.0 * m + 5.0) * 2.0 * kPi * (std::cos(a) - std::cos(b));
        total += zone[m];
    }
    if (!(total > 0.0))
        throw InputError(d.path + ": no light in the intensity table's zones (all 0 cd)");
    for (double& z : zone) z *= t.lightOutputRatio / total;
    for (int m = 0; m < 18; ++m) (m < 9 ? t.rDLO : t.rULO) += zone[m];
    auto below = [&](int zones) {
        double s = 0.0;
        for (int m = 0; m < zones; ++m) s += zone[m];
        return s;
    };
    t.cumulative = {below(4) + kPartOfZone40To50 * zone[4], below(6),
                    below(7) + kPartOfZone70To80 * zone[7], below(9)};

    const double h = options.height;
    for (int room = 0; room < kUgrRoomCount; ++room) {
        UgrRoomResult r;
        r.size = kRooms[room];
        const double x = r.size.x, y = r.size.y;
        r.roomIndex = x * y / (x + y);
        r.fGL = floorFactors(r.roomIndex);
        r.luminaires = int(std::lround(x * perH)) * int(std::lround(y * perH));
        for (int k = 0; k < 4; ++k) r.fDF += t.cumulative[k] * r.fGL[k];
        r.fDW = t.rDLO - r.fDF;
        r.fDC = t.rULO;
        const double wallArea = 2.0 * h * (x * h + y * h);  // A_w, m2
        r.wallFlux = t.flux * r.luminaires / wallArea;
        r.sum[0] = glareSum(d, t.area, basis.scale, r.size, options, true, r.counted[0]);
        r.sum[1] = glareSum(d, t.area, basis.scale, r.size, options, false, r.counted[1]);
        for (int s = 0; s < kUgrReflectanceCount; ++s) {
            r.fT[s] = kTransfer[s][room];
            r.fUWID[s] = r.fDF * r.fT[s][0] + r.fDW * r.fT[s][1] + r.fDC * r.fT[s][2];
            r.background[s] = r.wallFlux * r.fUWID[s] / kPi;
            auto ugr = [&](double sum) {
                return sum > 0.0 && r.background[s] > 0.0
                           ? 8.0 * std::log10(0.25 / r.background[s] * sum)
                           : std::numeric_limits<double>::quiet_NaN();
            };
            r.crosswise[s] = ugr(r.sum[0]);
            r.endwise[s] = ugr(r.sum[1]);
        }
        t.rooms.push_back(r);
    }
    return t;
}

}  // namespace candela
