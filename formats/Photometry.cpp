#include "formats/Photometry.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <sstream>

#include "shaders/shared/Constants.h"
#include "util/Error.h"
#include "util/FileInput.h"
#include "util/TextEncoding.h"

// Shared part of the far-field photometry: the luminous opening, bilinear evaluation of the
// table, its exact flux, symmetry unfolding and the dispatch by extension. The parsers live in
// IesFile.cpp (IES LM-63) and LdtFile.cpp (EULUMDAT).

namespace candela {

namespace {

using gpu::kPi;
constexpr double kDegToRad = kPi / 180.0;
/// Two angles closer than this (degrees) are the same angle when unfolding symmetries.
constexpr double kAngleEps = 1e-9;
/// Sides of the polygon that stands for an ellipse or a circle.
constexpr int kEllipseSides = 16;

/// Cell of a strictly ascending grid containing x: a[i] <= x <= a[i+1], with x = a[i] + t (a[i+1]
/// - a[i]). False when x lies outside [a.front(), a.back()] or the grid has fewer than 2 nodes.
bool locate(const std::vector<double>& a, double x, size_t& i, double& t) {
    if (a.size() < 2 || !(x >= a.front()) || !(x <= a.back())) return false;
    auto it = std::upper_bound(a.begin(), a.end(), x);
    i = it == a.end() ? a.size() - 2 : size_t(it - a.begin()) - 1;
    i = std::min(i, a.size() - 2);
    double span = a[i + 1] - a[i];
    t = span > 0.0 ? std::clamp((x - a[i]) / span, 0.0, 1.0) : 0.0;
    return true;
}

/// Linear interpolation of rows given at ascending angles `g` (clamped to the end rows outside).
void sampleRow(const std::vector<double>& g, const std::vector<double>& rows, size_t rowLength,
               double s, double* out) {
    size_t k = 0;
    double t = 0.0;
    if (g.size() == 1 || s <= g.front()) {
        k = 0;
    } else if (s >= g.back()) {
        k = g.size() - 1;
    } else {
        locate(g, s, k, t);
    }
    for (size_t v = 0; v < rowLength; ++v) {
        double a = rows[k * rowLength + v];
        double b = t > 0.0 ? rows[(k + 1) * rowLength + v] : a;
        out[v] = a + t * (b - a);
    }
}

/// Integrals over [x0, x1] (radians) of the two linear hat weights (x1 - x)/dx and (x - x0)/dx
/// times sin x (type C, x = gamma) or cos x (type B, x = V), in closed form:
///   int (x1 - x)/dx sin x = cos x0 - (sin x1 - sin x0)/dx,
///   int (x - x0)/dx sin x = (sin x1 - sin x0)/dx - cos x1,
///   int (x1 - x)/dx cos x = (cos x0 - cos x1)/dx - sin x0,
///   int (x - x0)/dx cos x = sin x1 - (cos x0 - cos x1)/dx.
void hatMoments(bool sine, double x0, double x1, double& w0, double& w1) {
    double dx = x1 - x0;
    if (sine) {
        double ds = (std::sin(x1) - std::sin(x0)) / dx;
        w0 = std::cos(x0) - ds;
        w1 = ds - std::cos(x1);
    } else {
        double dc = (std::cos(x0) - std::cos(x1)) / dx;
        w0 = dc - std::sin(x0);
        w1 = std::sin(x1) - dc;
    }
}

std::string lowerExtension(const std::string& path) {
    size_t slash = path.find_last_of("/\\");
    size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string ext = path.substr(dot);
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Shared helpers

namespace photometry_detail {

std::vector<std::string> splitLines(const std::string& text) {
    std::vector<std::string> lines;
    std::string cur;
    for (size_t i = 0; i < text.size(); ++i) {
        char c = text[i];
        if (c == '\n' || c == '\r') {
            lines.push_back(cur);
            cur.clear();
            if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
        } else {
            cur.push_back(c);
        }
    }
    if (!cur.empty()) lines.push_back(cur);
    return lines;
}

void fail(const std::string& path, int line, const std::string& expected,
          const std::string& found) {
    throw InputError(toValidUtf8(path + ":" + std::to_string(line) + ": expected " + expected +
                                 ", found " + found));
}

void allow(PhotometricData& data, const PhotometryOptions& options, const std::string& lines,
           const std::string& what, const std::string& assumed) {
    std::string where = toValidUtf8(data.path + ":" + lines + ": ");
    if (options.strict) throw InputError(where + toValidUtf8(what) + " (refused by --strict)");
    data.warnings.push_back(where + toValidUtf8(what + "; " + assumed));
}

std::vector<std::string> readLines(const std::string& bytes, PhotometricData& data,
                                   const PhotometryOptions& options) {
    DecodedText text = decodeText(bytes, data.path);
    if (text.encoding != DecodedText::Encoding::Utf8) {
        bool utf16 = text.encoding != DecodedText::Encoding::Windows1252;
        std::string what = std::string("text in ") + encodingName(text.encoding);
        if (utf16)
            what += text.byteOrderMark ? " with a byte-order mark" : " without a byte-order mark";
        else
            what += ", not UTF-8";
        allow(data, options, text.firstLine, what, "transcoded to UTF-8");
    }
    // Line endings: the first kind seen, and the first line ending in another kind.
    const char* names[] = {"LF", "CRLF", "CR"};
    int first = -1, other = -1, line = 1, otherLine = 0;
    const std::string& t = text.utf8;
    for (size_t i = 0; i < t.size(); ++i) {
        int kind = -1;
        if (t[i] == '\n')
            kind = 0;
        else if (t[i] == '\r')
            kind = i + 1 < t.size() && t[i + 1] == '\n' ? 1 : 2;
        if (kind < 0) continue;
        if (kind == 1) ++i;
        if (first < 0)
            first = kind;
        else if (kind != first && other < 0)
            other = kind, otherLine = line;
        ++line;
    }
    if (other >= 0)
        allow(data, options, otherLine,
              std::string("mixed line endings (") + names[first] + " before this line, " +
                  names[other] + " here)",
              "each read as the end of a line");
    std::vector<std::string> lines = splitLines(t);
    auto blank = [](const std::string& s) {
        return std::all_of(s.begin(), s.end(),
                           [](char c) { return std::isspace(static_cast<unsigned char>(c)); });
    };
    size_t end = lines.size();
    while (end > 0 && blank(lines[end - 1])) --end;
    if (end > 0 && end < lines.size()) {  // an all-blank file is left to the parser's message
        size_t n = lines.size() - end;
        std::string where = std::to_string(end + 1);
        if (n > 1) where += '-' + std::to_string(lines.size());
        allow(data, options, where,
              std::to_string(n) + " trailing blank line" + (n == 1 ? "" : "s"), "ignored");
        lines.resize(end);
    }
    return lines;
}

void checkCandela(const std::string& path, int line, double candela, const std::string& what) {
    if (!(candela <= kMaxCandela))
        fail(
            path, line,
            what + " of at most " + formatNumber(kMaxCandela) + " cd (no luminaire is that bright)",
            std::isfinite(candela) ? formatNumber(candela) + " cd" : std::string("an overflow"));
}

bool parseNumber(const std::string& token, double& value) {
    if (token.empty()) return false;
    const char* begin = token.c_str();
    char* end = nullptr;
    errno = 0;
    double v = std::strtod(begin, &end);
    if (end == begin || *end != '\0') return false;
    // strtod accepts "nan", "inf" and hexadecimal; none of them is a photometric number.
    if (!std::isfinite(v)) return false;
    for (char c : token)
        if (c == 'x' || c == 'X') return false;
    value = v;
    return true;
}

std::string formatNumber(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

namespace {

/// A full turn of type C planes wrapped periodically, so the piece between the last plane and 360
/// (or between 0 and the first plane) interpolates towards the other end.
void wrapFullTurn(std::vector<double>& g, std::vector<double>& rows, size_t nv) {
    double first = g.front(), last = g.back();
    std::vector<double> firstRow(rows.begin(), rows.begin() + std::ptrdiff_t(nv));
    std::vector<double> lastRow(rows.end() - std::ptrdiff_t(nv), rows.end());
    // C = 360 is the C = 0 plane: a file's own 360 row is replaced by its 0 row so the unfolded
    // table is continuous (Photometry.h: first and last rows equal).
    if (last >= 360.0 - kAngleEps && first <= kAngleEps)
        std::copy(firstRow.begin(), firstRow.end(), rows.end() - std::ptrdiff_t(nv));
    if (last < 360.0 - kAngleEps) {
        g.push_back(first + 360.0);
        rows.insert(rows.end(), firstRow.begin(), firstRow.end());
    }
    if (first > kAngleEps) {
        g.insert(g.begin(), last - 360.0);
        rows.insert(rows.begin(), lastRow.begin(), lastRow.end());
    }
}

/// The unfolded table: one row per distinct target angle, each sampled from the given planes g
/// (rows of nv values) at the angle that `fold` maps it to.
void resample(PhotometricData& data, const std::vector<double>& g, const std::vector<double>& rows,
              const std::function<double(double)>& fold, std::vector<double> targets) {
    const size_t nv = data.vertical.size();
    std::sort(targets.begin(), targets.end());
    std::vector<double> unique;
    for (double t : targets)
        if (unique.empty() || t - unique.back() > kAngleEps) unique.push_back(t);
    data.horizontal = unique;
    data.candela.assign(unique.size() * nv, 0.0);
    for (size_t h = 0; h < unique.size(); ++h)
        sampleRow(g, rows, nv, fold(unique[h]), data.candela.data() + h * nv);
}

}  // namespace

PhotometricSymmetry symmetryOfRange(Goniometer goniometer, const std::vector<double>& given,
                                    const std::string& path, int line) {
    using Sym = PhotometricSymmetry;
    auto near = [](double a, double b) { return std::abs(a - b) < 1e-6; };
    double f = given.front(), last = given.back();
    if (given.size() == 1) return Sym::Axial;
    if (goniometer == Goniometer::C) {
        if (near(f, 0.0) && near(last, 90.0)) return Sym::Quadrant;
        if (near(f, 0.0) && near(last, 180.0)) return Sym::PlaneC0C180;
        if (near(f, 90.0) && near(last, 270.0)) return Sym::PlaneC90C270;
        if (near(f, 0.0) && last > 180.0) return Sym::None;
        fail(path, line,
             "type C horizontal angles 0 (axial), 0..90, 0..180, 90..270 or 0..(more than 180, up "
             "to 360)",
             formatNumber(f) + ".." + formatNumber(last));
    }
    if (near(f, 0.0)) return Sym::PlaneC90C270;  // type B mirrored about H = 0
    if (f < 0.0) return Sym::None;
    fail(path, line, "type B horizontal angles starting at 0 (symmetric) or below 0",
         formatNumber(f) + ".." + formatNumber(last));
}

double tiltFactorAtZero(const PhotometricData& d) {
    const auto& a = d.tiltAngles;
    const auto& f = d.tiltFactors;
    if (a.empty()) return 1.0;
    if (0.0 <= a.front()) return f.front();
    if (0.0 >= a.back()) return f.back();
    size_t k = size_t(std::upper_bound(a.begin(), a.end(), 0.0) - a.begin()) - 1;
    double t = (0.0 - a[k]) / (a[k + 1] - a[k]);
    return f[k] + t * (f[k + 1] - f[k]);
}

void unfold(PhotometricData& data, const std::vector<double>& given,
            const std::vector<double>& givenCandela) {
    const size_t nv = data.vertical.size();
    using Sym = PhotometricSymmetry;
    const bool typeC = data.goniometer == Goniometer::C;
    std::vector<double> g = given, rows = givenCandela;
    std::function<double(double)> fold;
    std::vector<double> targets;
    auto addImages = [&](std::initializer_list<double> images, double source) {
        for (double t : images) {
            double lo = typeC ? 0.0 : -180.0, hi = typeC ? 360.0 : 180.0;
            if (t >= lo - kAngleEps && t <= hi + kAngleEps && std::abs(fold(t) - source) < 1e-6)
                targets.push_back(std::clamp(t, lo, hi));
        }
    };

    if (data.symmetry == Sym::Axial || g.size() == 1) {
        // One plane stands for every azimuth.
        g.resize(1);
        rows.resize(nv);
        fold = [&](double) { return g[0]; };
        targets = typeC ? std::vector<double>{0.0, 360.0} : std::vector<double>{-180.0, 180.0};
    } else if (!typeC) {
        if (data.symmetry == Sym::PlaneC90C270) {
            // Type B mirrored about H = 0 (x -> -x): H in [0, last] covers [-last, last].
            fold = [](double t) { return std::abs(t); };
            for (double a : given) addImages({a, -a}, a);
        } else {
            fold = [](double t) { return t; };
            for (double a : given) addImages({a}, a);
        }
    } else {
        switch (data.symmetry) {
            case Sym::Quadrant:
                fold = [](double t) {
                    double m = std::fmod(t, 180.0);
                    return m <= 90.0 ? m : 180.0 - m;
                };
                for (double a : given) addImages({a, 180.0 - a, 180.0 + a, 360.0 - a}, a);
                break;
            case Sym::PlaneC0C180:
                fold = [](double t) { return t <= 180.0 ? t : 360.0 - t; };
                for (double a : given) addImages({a, 360.0 - a}, a);
                break;
            case Sym::PlaneC90C270:
                fold = [](double t) { return t < 90.0 ? 180.0 - t : (t > 270.0 ? 540.0 - t : t); };
                for (double a : given) addImages({a, 180.0 - a, 540.0 - a}, a);
                break;
            default:
                wrapFullTurn(g, rows, nv);
                fold = [](double t) { return t; };
                for (double a : given) addImages({a, a - 360.0, a + 360.0}, a);
                break;
        }
        if (data.symmetry != Sym::Axial) {
            targets.push_back(0.0);
            targets.push_back(360.0);
        }
    }
    resample(data, g, rows, fold, targets);
}

}  // namespace photometry_detail

// ---------------------------------------------------------------------------------------------
// Luminous opening

std::vector<glm::dvec2> LuminousOpening::polygon() const {
    std::vector<glm::dvec2> p;
    const double a = 0.5 * length, b = 0.5 * width;
    bool rectangle = shape == Shape::Rectangle || (shape == Shape::Cylinder && axis != Axis::Z);
    bool ellipse = shape == Shape::Ellipse || shape == Shape::Sphere ||
                   (shape == Shape::Cylinder && axis == Axis::Z);
    if (shape == Shape::Point || !(a > 0.0 || b > 0.0)) return p;
    if (rectangle) {
        // Counter-clockwise seen from +z: the usual orientation of the (x, y) plane.
        p = {{-a, -b}, {a, -b}, {a, b}, {-a, b}};
    } else if (ellipse) {
        for (int k = 0; k < kEllipseSides; ++k) {
            double phi = 2.0 * kPi * double(k) / double(kEllipseSides);
            p.push_back({a * std::cos(phi), b * std::sin(phi)});
        }
    }
    return p;
}

double LuminousOpening::area() const {
    // Shoelace formula over polygon(); positive for the counter-clockwise order.
    std::vector<glm::dvec2> p = polygon();
    double twice = 0.0;
    for (size_t k = 0; k < p.size(); ++k) {
        const glm::dvec2& u = p[k];
        const glm::dvec2& w = p[(k + 1) % p.size()];
        twice += u.x * w.y - w.x * u.y;
    }
    return 0.5 * std::abs(twice);
}

// ---------------------------------------------------------------------------------------------
// Evaluation and flux

double PhotometricData::intensity(const glm::dvec3& dir) const {
    double len = glm::length(dir);
    if (!(len > 0.0) || !std::isfinite(len) || vertical.size() < 2 || horizontal.size() < 2 ||
        candela.size() != vertical.size() * horizontal.size())
        return 0.0;
    glm::dvec3 d = dir / len;
    double vAngle, hAngle;
    if (goniometer == Goniometer::C) {
        vAngle = std::acos(std::clamp(d.z, -1.0, 1.0)) / kDegToRad;
        hAngle = std::atan2(d.y, d.x) / kDegToRad;
        if (hAngle < 0.0) hAngle += 360.0;
        if (hAngle >= 360.0) hAngle = 0.0;
    } else {
        hAngle = std::atan2(d.x, d.z) / kDegToRad;
        vAngle = std::asin(std::clamp(d.y, -1.0, 1.0)) / kDegToRad;
    }
    size_t iv, ih;
    double tv, th;
    if (!locate(vertical, vAngle, iv, tv) || !locate(horizontal, hAngle, ih, th)) return 0.0;
    const size_t nv = vertical.size();
    auto at = [&](size_t h, size_t v) { return candela[h * nv + v]; };
    double lo = at(ih, iv) + tv * (at(ih, iv + 1) - at(ih, iv));
    double hi = at(ih + 1, iv) + tv * (at(ih + 1, iv + 1) - at(ih + 1, iv));
    return std::max(0.0, lo + th * (hi - lo));
}

double PhotometricData::fluxFromTable() const {
    const size_t nv = vertical.size(), nh = horizontal.size();
    if (nv < 2 || nh < 2 || candela.size() != nv * nh) return 0.0;
    // Flux = int int I(v, h) w(v) dv dh with w = sin(gamma) (type C, polar axis z) or cos(V)
    // (type B, V the latitude about the y axis). On a cell the interpolant is bilinear, so the
    // h integral of each hat weight is dh/2 and the v integral is hatMoments() in closed form.
    const bool sine = goniometer == Goniometer::C;
    std::vector<double> w0(nv - 1), w1(nv - 1);
    for (size_t v = 0; v + 1 < nv; ++v)
        hatMoments(sine, vertical[v] * kDegToRad, vertical[v + 1] * kDegToRad, w0[v], w1[v]);
    double flux = 0.0;
    for (size_t h = 0; h + 1 < nh; ++h) {
        double halfDh = 0.5 * (horizontal[h + 1] - horizontal[h]) * kDegToRad;
        const double* a = candela.data() + h * nv;
        const double* b = candela.data() + (h + 1) * nv;
        double cell = 0.0;
        for (size_t v = 0; v + 1 < nv; ++v)
            cell += (a[v] + b[v]) * w0[v] + (a[v + 1] + b[v + 1]) * w1[v];
        flux += halfDh * cell;
    }
    return flux;
}

double PhotometricData::declaredFlux() const {
    return lampFlux > 0.0 && lightOutputRatio > 0.0 ? lampFlux * lightOutputRatio : 0.0;
}

std::string PhotometricData::keyword(std::initializer_list<const char*> keys) const {
    for (const char* k : keys)
        for (const auto& [key, value] : keywords)
            if (key == k && !value.empty()) return value;
    return {};
}

double PhotometricData::maxIntensity() const {
    double m = 0.0;
    for (double c : candela) m = std::max(m, c);
    return m;
}

// ---------------------------------------------------------------------------------------------
// Dispatch

namespace {
PhotometryOptions& defaults() {
    static PhotometryOptions options;
    return options;
}
}  // namespace

bool isPhotometryExtension(const std::string& lowerExtension) {
    return lowerExtension == ".ies" || lowerExtension == ".ldt" || lowerExtension == ".xml" ||
           lowerExtension == ".iesxml";
}

const PhotometryOptions& defaultPhotometryOptions() {
    return defaults();
}
void setDefaultPhotometryOptions(const PhotometryOptions& options) {
    defaults() = options;
}

PhotometricData loadPhotometry(const std::string& path, const PhotometryOptions& options) {
    std::string ext = lowerExtension(path);
    std::string shown = toValidUtf8(path);
    if (!isPhotometryExtension(ext))
        throw InputError(shown +
                         ": expected a photometry file ending in .ies, .ldt, .xml or .iesxml "
                         "(TM-33), found '" +
                         toValidUtf8(ext) + "'");
    std::string text = readInputFile(path, "photometry", kMaxPhotometryBytes);
    if (ext == ".ies") return parseIes(text, path, options);
    if (ext == ".ldt") return parseEulumdat(text, path, options);
    return parseTm33(text, path, options);
}

}  // namespace candela
