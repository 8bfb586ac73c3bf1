// EULUMDAT photometric data files (.ldt).
//
// Field order (Stockmar 1990, "EULUMDAT - ein Leuchtendatenformat fuer den europaeischen
// Beleuchtungsplaner", and its published field list), one field per line:
//   1 company, 2 Ityp, 3 Isym, 4 Mc, 5 Dc, 6 Ng, 7 Dg, 8 measurement report, 9 luminaire name,
//   10 luminaire number, 11 file name, 12 date/user, 13-15 luminaire length/diameter, width
//   (0: round), height (mm), 16-17 luminous area length/diameter, width (0: round) (mm),
//   18-21 luminous area height at C0, C90, C180, C270 (mm), 22 DFF (%), 23 LORL (%),
//   24 conversion factor for luminous intensities, 25 tilt of luminaire during measurement,
//   26 number n of lamp sets, then per set 26a number of lamps, 26b type, 26c total luminous flux
//   (lm), 26d colour temperature, 26e colour rendering, 26f wattage (W);
//   then 10 direct ratios, Mc C angles, Ng gamma angles and the intensities (cd/klm) of the
//   C planes that Isym requires, Ng values per plane:
//   Isym 0: all Mc planes; 1: one plane; 2: C0..C180 (Mc/2 + 1); 3: C90..C270 (Mc/2 + 1, from
//   the C90 plane); 4: C0..C90 (Mc/4 + 1).
// The header fields are read line by line (text fields may be empty); from the direct ratios on
// the numbers are read as white-space separated tokens, so files that put several on one line
// also load. Decimal commas ("1,5") are accepted in numbers.
//
// Decisions (documented for `candela info` and the tests):
// - Absolute candela = value * conversion factor * (sum of the lamp sets' total flux) / 1000.
//   The conversion factor is multiplied (its name: "conversion factor for luminous
//   intensities"); a factor of 0 is read as "unused" and taken as 1. All files seen use 1.
// - A negative number of lamps marks absolute photometry (the DIAL / Lighting Analysts
//   convention for EULUMDAT: the "lamp" flux is then the luminaire flux and LORL 100 %); the
//   count is used as its absolute value and the keyword "absolute photometry" is set. The
//   intensities are still cd/klm of the given flux, so the conversion is the same.
// - Luminous area: the file's length along C90-C270 (the luminaire's long axis), its width along
//   C0-C180 (see LdtParse::opening); its height the largest of the four luminous-area heights.
// Leniencies (Photometry.h; each a warning, or an error with PhotometryOptions::strict): empty
// lamp type, colour temperature, colour rendering index or wattage (0 W); empty DFF, conversion
// factor (1) or tilt (0); empty direct ratios (recognised when the ten lines after the lamp sets
// hold one number or nothing each); a repeated last C plane (C360 after C0, or the last angle
// twice: Mc counts it, it is dropped, and for Isym 0 its intensities too); decimal commas; a
// conversion factor of 0 (read as 1); LORL 0 (no declared luminaire flux); values after the
// intensities (ignored).

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

#include "formats/Photometry.h"
#include "util/Error.h"

namespace candela {

using photometry_detail::allow;
using photometry_detail::fail;
using photometry_detail::formatNumber;
using photometry_detail::kMaxCount;
using photometry_detail::parseNumber;

namespace {

std::string trim(const std::string& s) {
    size_t b = 0, e = s.size();
    while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
    while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
    return s.substr(b, e - b);
}

std::string showToken(const std::string& s) {
    std::string shown = s.size() > 40 ? s.substr(0, 40) + "..." : s;
    for (char& c :
         shown)  // control characters as '?'; the text is UTF-8 (fail() repairs a cut sequence)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) c = '?';
    return "'" + shown + "'";
}

/// A number with an optional decimal comma ("1,5" -> 1.5).
bool parseLdtNumber(std::string s, double& v) {
    if (s.find(',') != std::string::npos && s.find('.') == std::string::npos)
        std::replace(s.begin(), s.end(), ',', '.');
    return parseNumber(s, v);
}

class LdtReader {
  public:
    LdtReader(std::vector<std::string> lines, std::string path)
        : mPath(std::move(path)), mLines(std::move(lines)) {}

    const std::string& path() const { return mPath; }
    int lineCount() const { return int(mLines.size()); }

    /// Text of line `n` (1-based), trimmed.
    std::string text(int n, const std::string& what) const {
        if (n > int(mLines.size()))
            fail(mPath, std::max(1, int(mLines.size())), what + " on line " + std::to_string(n),
                 "the end of the file after " + std::to_string(mLines.size()) + " line(s)");
        return trim(mLines[size_t(n - 1)]);
    }

    double number(int n, const std::string& what) {
        std::string s = text(n, what);
        double v;
        if (!parse(s, n, v))
            fail(mPath, n, what + " (a number)", s.empty() ? "an empty line" : showToken(s));
        return v;
    }

    /// True when line `n` exists and is empty (white space only).
    bool empty(int n) const {
        return n >= 1 && n <= int(mLines.size()) && trim(mLines[size_t(n - 1)]).empty();
    }
    /// True when line `n` exists and holds at most one word.
    bool atMostOneWord(int n) const {
        if (n < 1 || n > int(mLines.size())) return false;
        std::string s = trim(mLines[size_t(n - 1)]);
        return std::none_of(s.begin(), s.end(), [](char c) {
            return std::isspace(static_cast<unsigned char>(c)) || c == ';';
        });
    }

    /// First line where a number had a decimal comma (0: none).
    int decimalCommaLine() const { return mCommaLine; }

    int integer(int n, const std::string& what, int lo, int hi) {
        double v = number(n, what);
        if (!(std::abs(v - std::round(v)) < 1e-6) || v < lo || v > hi)
            fail(mPath, n,
                 what + " (an integer from " + std::to_string(lo) + " to " + std::to_string(hi) +
                     ")",
                 formatNumber(v));
        return int(std::lround(v));
    }

    /// Switches to token reading from line `n` (1-based) on.
    void startTokens(int n) {
        for (size_t l = size_t(std::max(n, 1) - 1); l < mLines.size(); ++l) {
            std::string s = mLines[l];
            std::replace(s.begin(), s.end(), ';', ' ');
            std::istringstream words(s);
            std::string w;
            while (words >> w) mTokens.push_back({w, int(l) + 1});
        }
        mLastLine = mTokens.empty() ? std::max(1, int(mLines.size())) : mTokens.back().second;
    }
    int tokenLine() const { return mPos < mTokens.size() ? mTokens[mPos].second : mLastLine; }
    int lineOfToken(size_t index) const {
        return index < mTokens.size() ? mTokens[index].second : mLastLine;
    }
    size_t position() const { return mPos; }

    std::vector<double> numbers(size_t n, const std::string& what) {
        size_t take = std::min(n, mTokens.size() - mPos);
        std::vector<double> out;
        out.reserve(take);
        for (size_t k = 0; k < take; ++k) {
            const auto& [s, line] = mTokens[mPos++];
            double v;
            if (!parse(s, line, v))
                fail(mPath, line,
                     "a finite number (" + what + ", value " + std::to_string(k + 1) + " of " +
                         std::to_string(n) + ")",
                     showToken(s));
            out.push_back(v);
        }
        if (take < n)
            fail(mPath, mLastLine, std::to_string(n) + " " + what,
                 "only " + std::to_string(take) + " before the data ended at line " +
                     std::to_string(mLastLine));
        return out;
    }
    /// Tokens not read yet.
    size_t remaining() const { return mTokens.size() - mPos; }
    /// The next token's text (call only when remaining() > 0).
    const std::string& peek() const { return mTokens[mPos].first; }

  private:
    /// parseLdtNumber, noting the first decimal comma.
    bool parse(const std::string& s, int line, double& v) {
        if (!parseLdtNumber(s, v)) return false;
        if (mCommaLine == 0 && s.find(',') != std::string::npos) mCommaLine = line;
        return true;
    }

    std::string mPath;
    std::vector<std::string> mLines;
    std::vector<std::pair<std::string, int>> mTokens;
    size_t mPos = 0;
    int mLastLine = 1;
    int mCommaLine = 0;
};

void checkAscending(const std::vector<double>& a, double lo, double hi, bool hiOpen,
                    const std::string& path, int line, const std::string& what) {
    for (size_t k = 0; k < a.size(); ++k) {
        if (a[k] < lo || a[k] > hi || (hiOpen && a[k] >= hi))
            fail(path, line,
                 what + " from " + formatNumber(lo) +
                     (hiOpen ? " up to (not including) " : " to ") + formatNumber(hi) + " degrees",
                 formatNumber(a[k]));
        if (k > 0 && !(a[k] > a[k - 1]))
            fail(path, line, what + " in strictly ascending order",
                 formatNumber(a[k]) + " after " + formatNumber(a[k - 1]));
    }
}

/// One parse: the reader, the result, the options, and what the header fields say.
struct LdtParse {
    LdtReader in;
    PhotometricData& d;
    const PhotometryOptions& options;
    int isym = 0, mc = 0, ng = 0, sets = 0;
    double size[9] = {};  ///< Luminaire and luminous-area sizes, mm (fields 13-21).
    double conversion = 1.0;
    double totalFlux = 0.0;  ///< Sum of the lamp sets' flux, lm.

    void keep(const std::string& key, const std::string& value) {
        d.keywords.emplace_back(key, value);
    }

    /// A text field that a complete file fills; empty is allowed (a warning).
    std::string optionalText(int n, const std::string& what) {
        std::string s = in.text(n, what);
        if (s.empty()) allow(d, options, n, "empty " + what, "left unknown");
        return s;
    }
    /// A number field that some exporters leave empty: `fallback` with a warning saying `assumed`.
    double optionalNumber(int n, const std::string& what, double fallback,
                          const std::string& assumed) {
        if (!in.empty(n)) return in.number(n, what);
        allow(d, options, n, "empty " + what, assumed);
        return fallback;
    }

    void header();
    void lampSets();
    void directRatios();
    /// The last C plane when it repeats one (counted in Mc, its data dropped).
    struct RepeatedPlane {
        bool present = false;
        bool ofC0 = false;  ///< C360 after C0; else the last angle twice.
        int line = 0;       ///< Where its angle is.
        double angle = 0.0;
    };
    std::vector<double> cPlaneAngles(RepeatedPlane& repeat);
    std::vector<double> storedPlanes(const std::vector<double>& cAngles, int cLine);
    std::vector<double> intensityValues(const std::vector<double>& given,
                                        const RepeatedPlane& repeat, bool repeatedData);
    void dropRepeatedPlane(std::vector<double>& cd, const std::vector<double>& given,
                           const RepeatedPlane& repeat, bool repeatedData);
    void intensities();
    void opening();
};

/// Fields 1-25.
void LdtParse::header() {
    const std::string& path = d.path;
    keep("company", in.text(1, "company identification"));
    int ityp = in.integer(2, "type indicator Ityp", 0, 3);
    isym = in.integer(3, "symmetry indicator Isym", 0, 4);
    mc = in.integer(4, "number of C planes Mc", 1, kMaxCount);
    double dc = in.number(5, "distance between C planes Dc");
    ng = in.integer(6, "number of intensities per C plane Ng", 1, kMaxCount);
    double dg = in.number(7, "distance between intensities Dg");
    keep("Ityp", std::to_string(ityp));
    keep("Isym", std::to_string(isym));
    keep("Mc", std::to_string(mc));
    keep("Dc", formatNumber(dc));
    keep("Ng", std::to_string(ng));
    keep("Dg", formatNumber(dg));
    keep("measurement report", in.text(8, "measurement report number"));
    d.name = in.text(9, "luminaire name");
    keep("luminaire name", d.name);
    keep("luminaire number", in.text(10, "luminaire number"));
    keep("file name", in.text(11, "file name"));
    keep("date/user", in.text(12, "date/user"));
    const char* sizes[] = {"luminaire length/diameter (mm)", "luminaire width (mm)",
                           "luminaire height (mm)",          "luminous area length/diameter (mm)",
                           "luminous area width (mm)",       "luminous area height C0 (mm)",
                           "luminous area height C90 (mm)",  "luminous area height C180 (mm)",
                           "luminous area height C270 (mm)"};
    for (int k = 0; k < 9; ++k) {
        size[k] = in.number(13 + k, sizes[k]);
        if (size[k] < 0.0)
            fail(path, 13 + k, std::string(sizes[k]) + " >= 0", formatNumber(size[k]));
        if (k >= 3 && !(size[k] <= kMaxOpening * 1e3))
            fail(path, 13 + k,
                 std::string(sizes[k]) + " of at most " + formatNumber(kMaxOpening * 1e3) + " mm",
                 formatNumber(size[k]));
        keep(sizes[k], formatNumber(size[k]));
    }
    double dff = optionalNumber(22, "downward flux fraction DFF (%)", 0.0, "left unknown");
    double lorl = in.number(23, "light output ratio LORL (%)");
    if (lorl < 0.0) fail(path, 23, "a light output ratio LORL >= 0 %", formatNumber(lorl));
    if (lorl == 0.0)
        allow(d, options, 23, "light output ratio LORL 0 %",
              "no declared luminaire flux (the intensities are still cd/klm of the lamp flux)");
    conversion =
        optionalNumber(24, "conversion factor for luminous intensities", 1.0, "taken as 1");
    if (conversion < 0.0) fail(path, 24, "a conversion factor >= 0", formatNumber(conversion));
    if (conversion == 0.0) {
        allow(d, options, 24, "conversion factor 0", "taken as 1");
        conversion = 1.0;
    }
    double tilt =
        optionalNumber(25, "tilt of the luminaire during measurement (degrees)", 0.0, "taken as 0");
    keep("DFF %", formatNumber(dff));
    keep("LORL %", formatNumber(lorl));
    keep("conversion factor", formatNumber(conversion));
    keep("tilt", formatNumber(tilt));
    d.lightOutputRatio = lorl / 100.0;
    d.declaresLightOutputRatio = true;
}

/// Field 26 and the lamp sets 26a-26f.
void LdtParse::lampSets() {
    const std::string& path = d.path;
    sets = in.integer(26, "number of lamp sets n", 1, kMaxCount);
    double watts = 0.0;
    bool absolute = false;
    for (int s = 0; s < sets; ++s) {
        int base = 27 + 6 * s;
        std::string set = "lamp set " + std::to_string(s + 1);
        int lamps = in.integer(base, "number of lamps in " + set, -kMaxCount, kMaxCount);
        if (lamps < 0) absolute = true;
        std::string type = optionalText(base + 1, "lamp type of " + set);
        double flux = in.number(base + 2, "total luminous flux (lm) of " + set);
        if (flux < 0.0) fail(path, base + 2, "a total luminous flux >= 0 lm", formatNumber(flux));
        std::string cct = optionalText(base + 3, "colour temperature of " + set);
        std::string cri = optionalText(base + 4, "colour rendering index of " + set);
        double wattage = optionalNumber(base + 5, "wattage of " + set, 0.0, "taken as 0 W");
        totalFlux += flux;
        d.lampSetFlux.push_back(flux);
        watts += wattage;
        if (!(totalFlux <= kMaxLumens) || !std::isfinite(watts))
            fail(path, base + 2,
                 "lamp flux (at most " + formatNumber(kMaxLumens) + " lm in all) and wattage",
                 "an overflow in their sums");
        keep(set, std::to_string(std::abs(lamps)) + " x " + type + ", " + formatNumber(flux) +
                      " lm, " + cct + ", CRI " + cri + ", " + formatNumber(wattage) + " W");
    }
    if (absolute) keep("absolute photometry", "negative number of lamps");
    if (!(totalFlux > 0.0))
        fail(path, 27 + 2, "a positive total lamp flux (sum over the lamp sets)",
             formatNumber(totalFlux));
    if (!(totalFlux * d.lightOutputRatio <= kMaxLumens))
        fail(path, 23,
             "a declared luminaire flux (lamp flux x LORL) of at most " + formatNumber(kMaxLumens) +
                 " lm",
             formatNumber(totalFlux) + " lm x " + formatNumber(d.lightOutputRatio));
    d.lampFlux = totalFlux;
    d.inputWatts = watts;
}

/// Field 27, the ten direct ratios; starts token reading after them. When the ten lines after
/// the lamp sets hold at most one number each and some are empty, the empty ones are empty
/// ratios; otherwise the ratios are the next ten numbers wherever they are.
void LdtParse::directRatios() {
    const int first = 27 + 6 * sets;
    bool lineWise = true;
    int empties = 0, firstEmpty = 0, lastEmpty = 0;
    for (int n = first; n < first + 10 && lineWise; ++n) {
        lineWise = in.atMostOneWord(n);
        if (lineWise && in.empty(n)) {
            ++empties;
            if (firstEmpty == 0) firstEmpty = n;
            lastEmpty = n;
        }
    }
    std::string shown;
    if (lineWise && empties > 0) {
        for (int k = 0; k < 10; ++k) {
            int n = first + k;
            if (k > 0) shown += ' ';
            shown += in.empty(n)
                         ? std::string("?")
                         : formatNumber(in.number(n, "direct ratio " + std::to_string(k + 1)));
        }
        std::string lines = std::to_string(firstEmpty);
        if (lastEmpty > firstEmpty) lines += '-' + std::to_string(lastEmpty);
        allow(d, options, lines,
              empties == 10 ? "the ten direct ratios are empty"
                            : std::to_string(empties) + " of the ten direct ratios are empty",
              "left unknown (Candela does not use them)");
        in.startTokens(first + 10);
    } else {
        in.startTokens(first);
        for (double r : in.numbers(10, "direct ratios")) {
            if (!shown.empty()) shown += ' ';
            shown += formatNumber(r);
        }
    }
    keep("direct ratios", shown);
}

/// Field 28, the C angles; a repeated last plane (C360 after C0, or the last angle twice) is
/// dropped from them and from Mc, and described in `repeat`.
std::vector<double> LdtParse::cPlaneAngles(RepeatedPlane& repeat) {
    int cLine = in.tokenLine();
    size_t cStart = in.position();
    std::vector<double> cAngles = in.numbers(size_t(mc), "C angles");
    // A repeated last plane: C360 after C0 (the same plane), or the last angle twice.
    bool repeatsC0 =
        mc >= 2 && std::abs(cAngles.back() - 360.0) < 1e-6 && std::abs(cAngles.front()) < 1e-6;
    bool repeated = repeatsC0 || (mc >= 2 && cAngles.back() == cAngles[size_t(mc - 2)]);
    int repeatLine = in.lineOfToken(cStart + size_t(mc) - 1);
    double repeatedAngle = cAngles.back();
    if (repeated) {
        cAngles.pop_back();
        --mc;
    }
    checkAscending(cAngles, 0.0, 360.0, true, d.path, cLine, "C angles");
    repeat = {repeated, repeatsC0, repeatLine, repeatedAngle};
    return cAngles;
}

/// The C planes Isym stores, checked against the C angles read from line `cLine`.
std::vector<double> LdtParse::storedPlanes(const std::vector<double>& cAngles, int cLine) {
    const std::string& path = d.path;
    using Sym = PhotometricSymmetry;
    const Sym symmetries[] = {Sym::None, Sym::Axial, Sym::PlaneC0C180, Sym::PlaneC90C270,
                              Sym::Quadrant};
    d.symmetry = symmetries[isym];
    size_t firstPlane = 0, planes = size_t(mc);
    double expectFirst = 0.0, expectLast = -1.0;
    if ((isym == 2 || isym == 3) && mc % 2 != 0)
        fail(path, 4, "an even number of C planes Mc for Isym " + std::to_string(isym),
             std::to_string(mc));
    if (isym == 4 && mc % 4 != 0)
        fail(path, 4, "a number of C planes Mc divisible by 4 for Isym 4", std::to_string(mc));
    if (isym == 1) planes = 1;
    if (isym == 2) planes = size_t(mc / 2 + 1), expectLast = 180.0;
    if (isym == 4) planes = size_t(mc / 4 + 1), expectLast = 90.0;
    if (isym == 3) {
        planes = size_t(mc / 2 + 1), expectFirst = 90.0, expectLast = 270.0;
        auto it = std::find_if(cAngles.begin(), cAngles.end(),
                               [](double c) { return std::abs(c - 90.0) < 1e-6; });
        if (it == cAngles.end())
            fail(path, cLine, "a C90 plane among the C angles (Isym 3 data start there)", "none");
        firstPlane = size_t(it - cAngles.begin());
    }
    if (firstPlane + planes > cAngles.size())
        fail(path, cLine,
             std::to_string(planes) + " C planes from C" + formatNumber(cAngles[firstPlane]),
             "only " + std::to_string(cAngles.size() - firstPlane));
    std::vector<double> given(cAngles.begin() + std::ptrdiff_t(firstPlane),
                              cAngles.begin() + std::ptrdiff_t(firstPlane + planes));
    if (isym >= 2 && (std::abs(given.front() - expectFirst) > 1e-6 ||
                      std::abs(given.back() - expectLast) > 1e-6))
        fail(path, cLine,
             "C planes " + formatNumber(expectFirst) + ".." + formatNumber(expectLast) +
                 " for Isym " + std::to_string(isym),
             formatNumber(given.front()) + ".." + formatNumber(given.back()));
    return given;
}

/// Field 30, the intensities (cd/klm, unscaled) of the planes `given`, followed by the repeated
/// plane's when `repeatedData`; each checked once scaled by the lamp flux.
std::vector<double> LdtParse::intensityValues(const std::vector<double>& given,
                                              const RepeatedPlane& repeat, bool repeatedData) {
    const std::string& path = d.path;
    size_t planes = given.size();
    size_t values = planes * size_t(ng);
    size_t start = in.position();
    std::vector<double> cd = in.numbers(values + (repeatedData ? size_t(ng) : 0),
                                        "intensities (cd/klm, " + std::to_string(planes) +
                                            " C planes x " + std::to_string(ng) + " gamma angles)");
    double scale = conversion * totalFlux / 1000.0;
    for (size_t k = 0; k < cd.size(); ++k) {
        int line = in.lineOfToken(start + k);
        if (cd[k] < 0.0)
            fail(path, line,
                 "non-negative intensities (C" +
                     formatNumber(k < values ? given[k / size_t(ng)] : repeat.angle) + ", gamma " +
                     formatNumber(d.vertical[k % size_t(ng)]) + ")",
                 formatNumber(cd[k]));
        photometry_detail::checkCandela(path, line, cd[k] * scale,
                                        "intensities (cd/klm x lamp flux)");
    }
    return cd;
}

/// Drops the repeated plane's intensities (read when `repeatedData`) with a warning saying how
/// far they differ from the plane they repeat.
void LdtParse::dropRepeatedPlane(std::vector<double>& cd, const std::vector<double>& given,
                                 const RepeatedPlane& repeat, bool repeatedData) {
    size_t planes = given.size();
    size_t values = planes * size_t(ng);
    std::string assumed = "dropped";
    if (repeatedData) {
        // Compare with the plane it repeats: C0 (the first) or the one before it (the last kept).
        size_t same = repeat.ofC0 ? 0 : planes - 1;
        double worst = 0.0;
        for (size_t v = 0; v < size_t(ng); ++v)
            worst = std::max(worst, std::abs(cd[values + v] - cd[same * size_t(ng) + v]));
        if (worst > 0.0)
            assumed += " (its intensities differ from C" + formatNumber(given[same]) +
                       "'s by up to " + formatNumber(worst) + " cd/klm)";
        cd.resize(values);
    }
    allow(d, options, repeat.line,
          std::string("C") + formatNumber(repeat.angle) + " repeats the " +
              (repeat.ofC0 ? std::string("C0 plane") : "plane before it") +
              " (counted in Mc = " + std::to_string(mc + 1) + ")",
          assumed);
}

/// Fields 28-30: C angles, gamma angles and the intensities of the planes Isym stores.
void LdtParse::intensities() {
    const std::string& path = d.path;
    int cLine = in.tokenLine();
    RepeatedPlane repeat;
    std::vector<double> cAngles = cPlaneAngles(repeat);
    int gLine = in.tokenLine();
    d.vertical = in.numbers(size_t(ng), "gamma angles");
    checkAscending(d.vertical, 0.0, 180.0, false, path, gLine, "gamma angles");
    std::vector<double> given = storedPlanes(cAngles, cLine);

    // With Isym 0 the repeated plane's intensities follow the others when the file has them.
    size_t values = given.size() * size_t(ng);
    bool repeatedData = repeat.present && isym == 0 && in.remaining() >= values + size_t(ng);
    std::vector<double> cd = intensityValues(given, repeat, repeatedData);
    if (repeat.present) dropRepeatedPlane(cd, given, repeat, repeatedData);
    double scale = conversion * totalFlux / 1000.0;
    for (double& c : cd) c *= scale;
    if (size_t extra = in.remaining())
        allow(d, options, in.tokenLine(),
              std::to_string(extra) + " value" + (extra == 1 ? "" : "s") +
                  " after the intensities (from " + showToken(in.peek()) + ")",
              "ignored");
    d.goniometer = Goniometer::C;
    photometry_detail::unfold(d, given, cd);
}

void LdtParse::opening() {
    // Luminous area: the length runs along the luminaire's long axis, C90-C270, and the width
    // across it, along C0-C180 (EN 13032-1's C planes: "C0/C180 quer, C90/C270 längs", crosswise
    // and lengthwise, as DIAL's DIALux documentation and manufacturers' catalogues put it; Relux's
    // printed luminances of a linear luminaire with luminous sides fit this reading only). So the
    // file's length is the opening's extent along local y and its width the extent along local x
    // (LuminousOpening::length is along C0). Width 0 means round.
    const double mm = 1e-3;
    double fileLength = size[3] * mm, fileWidth = size[4] * mm;
    double height = std::max({size[5], size[6], size[7], size[8]}) * mm;
    d.opening.height = height;
    if (fileLength == 0.0 && fileWidth == 0.0) {
        d.opening.shape = LuminousOpening::Shape::Point;
        d.opening.height = 0.0;
    } else if (fileWidth == 0.0) {  // round: the length is its diameter
        d.opening.shape =
            height > 0.0 ? LuminousOpening::Shape::Cylinder : LuminousOpening::Shape::Ellipse;
        d.opening.length = d.opening.width = fileLength;
    } else {
        d.opening.shape = LuminousOpening::Shape::Rectangle;
        d.opening.length = fileWidth;  // along C0-C180
        d.opening.width = fileLength;  // along C90-C270
    }
}

}  // namespace

PhotometricData parseEulumdat(const std::string& text, const std::string& path,
                              const PhotometryOptions& options) {
    PhotometricData d;
    d.path = path;
    d.format = "EULUMDAT";
    LdtParse p{LdtReader(photometry_detail::readLines(text, d, options), path), d, options};
    p.header();
    p.lampSets();
    p.directRatios();
    p.intensities();
    p.opening();
    if (int line = p.in.decimalCommaLine())
        allow(d, options, line, "a decimal comma (not in EULUMDAT)", "read as a decimal point");
    return d;
}

}  // namespace candela
