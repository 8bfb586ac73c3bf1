// IES LM-63 photometric data files (.ies): the 1986 layout (no header line), IESNA91,
// IESNA:LM-63-1995, IESNA:LM-63-2002 and IES:LM-63-2019.
//
// Layout (ANSI/IES LM-63-2019 Sec. 5, and the 2002 and 1995 editions): a header line (absent in
// 1986 files), keyword lines "[KEY] value" with [MORE] continuing the previous keyword, the line
// TILT=NONE | INCLUDE | <file name>, the tilt data when INCLUDE, then free-format numbers:
//   number of lamps, lumens per lamp (-1: absolute photometry), candela multiplier,
//   number of vertical angles, number of horizontal angles, photometric type (1 C, 2 B, 3 A),
//   units type (1 feet, 2 metres), width, length, height of the luminous opening,
//   ballast factor, ballast-lamp photometric factor (2019: file generation type), input watts,
//   vertical angles, horizontal angles, candela values one horizontal angle after another.
// Numbers may be separated by any white space or commas; "//" starts a comment to the end of the
// line (not in the standard, found in annotated files); tokens after the candela values are
// ignored. Width and length follow LM-63: width along C90-C270 (local y), length along C0-C180
// (local x).

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "formats/Photometry.h"
#include "util/Error.h"
#include "util/FileInput.h"

namespace candela {

using photometry_detail::fail;
using photometry_detail::formatNumber;
using photometry_detail::kMaxCount;
using photometry_detail::parseNumber;
using photometry_detail::splitLines;
using photometry_detail::tiltFactorAtZero;

namespace {

constexpr double kFootInMetres = 0.3048;

struct Token {
    std::string text;
    int line = 0;
};

std::string trim(const std::string& s) {
    size_t b = 0, e = s.size();
    while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
    while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
    return s.substr(b, e - b);
}

std::string upper(std::string s) {
    for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
    return s;
}

std::string showToken(const std::string& s) {
    std::string shown = s.size() > 40 ? s.substr(0, 40) + "..." : s;
    for (char& c :
         shown)  // control characters as '?'; the text is UTF-8 (fail() repairs a cut sequence)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) c = '?';
    return "'" + shown + "'";
}

/// Free-format numbers after the TILT line: white space and commas separate, "//" comments out
/// the rest of the line. Numbers are converted only when asked for, so trailing junk after the
/// candela block is never looked at.
class TokenStream {
  public:
    TokenStream(std::string path, const std::vector<std::string>& lines, size_t firstLine)
        : mPath(std::move(path)) {
        for (size_t l = firstLine; l < lines.size(); ++l) {
            std::string s = lines[l];
            size_t comment = s.find("//");
            if (comment != std::string::npos) {
                s.resize(comment);
                if (mCommentLine == 0) mCommentLine = int(l) + 1;
            }
            std::replace(s.begin(), s.end(), ',', ' ');
            std::istringstream words(s);
            std::string w;
            while (words >> w) mTokens.push_back({w, int(l) + 1});
        }
        mLastLine = mTokens.empty() ? int(lines.size()) : mTokens.back().line;
        if (mLastLine < 1) mLastLine = 1;
    }

    const std::string& path() const { return mPath; }
    int line() const { return mPos < mTokens.size() ? mTokens[mPos].line : mLastLine; }

    /// Reads n numbers described by `what` ("vertical angles"). Truncation is reported with the
    /// line where the data ended and how many of the n values were there.
    std::vector<double> numbers(size_t n, const std::string& what) {
        size_t available = mTokens.size() - mPos;
        size_t take = std::min(n, available);
        std::vector<double> out;
        out.reserve(take);
        for (size_t k = 0; k < take; ++k) {
            const Token& t = mTokens[mPos++];
            double v;
            if (!parseNumber(t.text, v))
                fail(mPath, t.line,
                     "a finite number (" + what + ", value " + std::to_string(k + 1) + " of " +
                         std::to_string(n) + ")",
                     showToken(t.text));
            out.push_back(v);
        }
        if (take < n)
            fail(mPath, mLastLine, std::to_string(n) + " " + what,
                 "only " + std::to_string(take) + " before the data ended at line " +
                     std::to_string(mLastLine));
        return out;
    }
    int lineOfPrevious(size_t back) const {
        return mPos >= back && back > 0 ? mTokens[mPos - back].line : line();
    }
    /// Tokens not read yet.
    size_t remaining() const { return mTokens.size() - mPos; }
    /// The next token's text (call only when remaining() > 0).
    const std::string& peek() const { return mTokens[mPos].text; }
    /// First line holding a "//" comment, 0 when none does.
    int commentLine() const { return mCommentLine; }

  private:
    std::string mPath;
    std::vector<Token> mTokens;
    size_t mPos = 0;
    int mLastLine = 1;
    int mCommentLine = 0;
};

/// An integer count field in [lo, hi]; `line` for messages.
int countField(double v, int lo, int hi, const std::string& path, int line,
               const std::string& what) {
    if (!(std::abs(v - std::round(v)) < 1e-6) || v < lo || v > hi)
        fail(path, line,
             what + " (an integer from " + std::to_string(lo) + " to " + std::to_string(hi) + ")",
             formatNumber(v));
    return int(std::lround(v));
}

void checkAscending(const std::vector<double>& a, double lo, double hi, const std::string& path,
                    int line, const std::string& what) {
    for (size_t k = 0; k < a.size(); ++k) {
        if (a[k] < lo || a[k] > hi)
            fail(path, line,
                 what + " between " + formatNumber(lo) + " and " + formatNumber(hi) + " degrees",
                 formatNumber(a[k]));
        if (k > 0 && !(a[k] > a[k - 1]))
            fail(path, line, what + " in strictly ascending order",
                 formatNumber(a[k]) + " after " + formatNumber(a[k - 1]));
    }
}

/// TILT data (from the .ies itself or a TILT file): geometry, count, angles, factors.
void readTilt(TokenStream& in, PhotometricData& d) {
    int line = in.line();
    d.tiltGeometry = countField(in.numbers(1, "lamp-to-luminaire geometry")[0], 1, 3, in.path(),
                                line, "lamp-to-luminaire geometry");
    line = in.line();
    int n = countField(in.numbers(1, "number of tilt angles")[0], 1, kMaxCount, in.path(), line,
                       "number of tilt angles");
    line = in.line();
    d.tiltAngles = in.numbers(size_t(n), "tilt angles");
    checkAscending(d.tiltAngles, -360.0, 360.0, in.path(), line, "tilt angles");
    line = in.line();
    d.tiltFactors = in.numbers(size_t(n), "tilt multiplying factors");
    for (double f : d.tiltFactors)
        if (f < 0.0)
            fail(in.path(), line, "non-negative tilt multiplying factors", formatNumber(f));
}

/// LM-63-2002 Table 1 / LM-63-2019 Annex D luminous opening from signed width, length, height
/// (metres). Negative values mark curved shapes; a zero horizontal size next to a negative one
/// takes the other's magnitude (older files give a circle's diameter once).
LuminousOpening openingFrom(double width, double length, double height) {
    LuminousOpening o;
    double w = std::abs(width), l = std::abs(length), h = std::abs(height);
    o.length = l;
    o.width = w;
    o.height = h;
    bool curvedW = width < 0.0, curvedL = length < 0.0, curvedH = height < 0.0;
    if (w == 0.0 && l == 0.0 && h == 0.0) {
        o.shape = LuminousOpening::Shape::Point;
    } else if (!curvedW && !curvedL && !curvedH) {
        o.shape = LuminousOpening::Shape::Rectangle;  // a box when height > 0
    } else if (curvedH && (width > 0.0) != (length > 0.0)) {
        // Horizontal cylinder: its axis runs along the positive (or only non-zero) size, the
        // negative height is its diameter.
        o.shape = LuminousOpening::Shape::Cylinder;
        if (length > 0.0) {
            o.axis = LuminousOpening::Axis::X;
            o.width = h;
        } else {
            o.axis = LuminousOpening::Axis::Y;
            o.length = h;
        }
    } else {
        if (o.length == 0.0) o.length = o.width > 0.0 ? o.width : h;
        if (o.width == 0.0) o.width = o.length;
        if (curvedH) {
            o.shape = LuminousOpening::Shape::Sphere;  // ellipsoid when the sizes differ
        } else if (h > 0.0) {
            o.shape = LuminousOpening::Shape::Cylinder;  // vertical, circular or elliptical
        } else {
            o.shape = LuminousOpening::Shape::Ellipse;  // circle when length == width
        }
    }
    return o;
}

std::string formatFromHeader(const std::string& header) {
    std::string u = upper(header);
    u.erase(std::remove_if(u.begin(), u.end(),
                           [](char c) { return std::isspace(static_cast<unsigned char>(c)); }),
            u.end());
    if (u.find("LM-63-2019") != std::string::npos) return "IES LM-63-2019";
    if (u.find("LM-63-2002") != std::string::npos) return "IES LM-63-2002";
    if (u.find("LM-63-1995") != std::string::npos) return "IES LM-63-1995";
    if (u.rfind("IESNA91", 0) == 0) return "IES LM-63-1991";
    return "IES LM-63-1995";  // an IESNA header with an unknown year: read as the 1995 layout
}

/// Header line and keywords, up to the TILT line; returns the TILT line's index.
size_t readHeaderAndKeywords(const std::vector<std::string>& lines, PhotometricData& d,
                             const std::string& path) {
    size_t l = 0;
    std::string first = lines.empty() ? "" : upper(trim(lines[0]));
    if (first.rfind("IESNA", 0) == 0 || first.rfind("IES:", 0) == 0) {
        d.format = formatFromHeader(first);
        l = 1;
    } else {
        d.format = "IES LM-63-1986";
    }
    size_t tiltLine = lines.size();
    for (; l < lines.size(); ++l) {
        std::string s = trim(lines[l]);
        if (upper(s).rfind("TILT", 0) == 0 && s.find('=') != std::string::npos) {
            tiltLine = l;
            break;
        }
        if (s.empty()) continue;
        size_t close = s.find(']');
        if (s[0] == '[' && close != std::string::npos) {
            std::string key = upper(trim(s.substr(1, close - 1)));
            std::string value = trim(s.substr(close + 1));
            if (key == "MORE" && !d.keywords.empty())
                d.keywords.back().second += "\n" + value;
            else
                d.keywords.emplace_back(key, value);
        } else {
            d.keywords.emplace_back("LABEL", s);  // 1986 free text, or a stray label line
        }
    }
    if (tiltLine == lines.size())
        fail(path, std::max<int>(1, int(lines.size())),
             "a TILT= line (TILT=NONE, TILT=INCLUDE or TILT=<file>) before the photometric data",
             "none in the file's " + std::to_string(lines.size()) + " line(s)");
    for (const auto& [key, value] : d.keywords)
        if (key == "LUMINAIRE") {
            d.name = value;
            break;
        }
    return tiltLine;
}

/// The TILT= line's tilt data: none, INCLUDE (read from `in`) or a TILT file next to `path`.
void readTiltSection(const std::string& tiltLineText, size_t tiltLine, TokenStream& in,
                     PhotometricData& d, const std::string& path) {
    std::string tilt = trim(tiltLineText.substr(tiltLineText.find('=') + 1));
    if (upper(tilt) == "INCLUDE") {
        readTilt(in, d);
    } else if (upper(tilt) != "NONE") {
        if (tilt.empty())
            fail(path, int(tiltLine) + 1, "NONE, INCLUDE or a file name after TILT=", "nothing");
        std::filesystem::path tiltPath = std::filesystem::path(path).parent_path() / tilt;
        std::string tiltText;
        try {
            tiltText = readInputFile(tiltPath.string(), "TILT", kMaxPhotometryBytes);
        } catch (const InputError& e) {
            fail(path, int(tiltLine) + 1,
                 "the TILT file " + showToken(tilt) + " next to the photometry file", e.what());
        }
        TokenStream tiltIn(tiltPath.string(), splitLines(tiltText), 0);
        readTilt(tiltIn, d);
        d.tiltPath = tiltPath.string();
    }
}

/// The lamp line's values that later sections need.
struct LampLine {
    int line = 0;  ///< Where it starts, for messages.
    int lamps = 0;
    double lumens = 0.0;  ///< Per lamp, lm; -1: absolute photometry.
    double multiplier = 1.0;
    int nv = 0, nh = 0;  ///< Vertical and horizontal angle counts.
};

/// The lamp and photometry line: counts, photometric type, units and the luminous opening.
LampLine readLampLine(TokenStream& in, PhotometricData& d, const std::string& path) {
    LampLine lamp;
    int headerLine = in.line();
    lamp.line = headerLine;
    std::vector<double> h = in.numbers(10,
                                       "values on the lamp line (number of lamps, lumens per lamp, "
                                       "candela multiplier, vertical and horizontal angle counts, "
                                       "photometric type, units type, width, length, height)");
    lamp.lamps = countField(h[0], 1, kMaxCount, path, headerLine, "number of lamps");
    double lumens = h[1], multiplier = h[2];
    if (!(lumens > 0.0) && lumens != -1.0)
        fail(path, headerLine, "lumens per lamp > 0, or -1 for absolute photometry",
             formatNumber(lumens));
    if (!(multiplier > 0.0))
        fail(path, headerLine, "a positive candela multiplier", formatNumber(multiplier));
    lamp.lumens = lumens;
    lamp.multiplier = multiplier;
    lamp.nv = countField(h[3], 1, kMaxCount, path, headerLine, "number of vertical angles");
    lamp.nh = countField(h[4], 1, kMaxCount, path, headerLine, "number of horizontal angles");
    int type = countField(h[5], 1, 3, path, headerLine, "photometric type 1 (C), 2 (B) or 3 (A)");
    if (type == 3)
        fail(path, headerLine, "photometric type 1 (C) or 2 (B)",
             "3: type A (automotive) photometry is not supported");
    d.goniometer = type == 1 ? Goniometer::C : Goniometer::B;
    int units = countField(h[6], 1, 2, path, headerLine, "units type 1 (feet) or 2 (metres)");
    double toMetres = units == 1 ? kFootInMetres : 1.0;
    const char* sizeNames[] = {"width", "length", "height"};
    for (int k = 0; k < 3; ++k)
        if (!(std::abs(h[7 + k]) * toMetres <= kMaxOpening))
            fail(path, headerLine,
                 std::string("a luminous opening ") + sizeNames[k] + " of at most " +
                     formatNumber(kMaxOpening) + " m",
                 formatNumber(h[7 + k]) + (units == 1 ? " ft" : " m"));
    d.opening = openingFrom(h[7] * toMetres, h[8] * toMetres, h[9] * toMetres);
    return lamp;
}

/// The ballast line, and the lamp flux; returns the factor the candela values are scaled by.
double readBallastLine(TokenStream& in, PhotometricData& d, const std::string& path,
                       const LampLine& lamp) {
    int headerLine = lamp.line;
    int ballastLine = in.line();
    std::vector<double> b = in.numbers(3,
                                       "values on the ballast line (ballast factor, ballast-lamp "
                                       "photometric factor or file generation type, input watts)");
    if (!(b[0] > 0.0)) fail(path, ballastLine, "a positive ballast factor", formatNumber(b[0]));
    // LM-63-2019 replaced the ballast-lamp photometric factor by the file generation type
    // (Sec. 5.12), which is a code, not a multiplier.
    bool is2019 = d.format == "IES LM-63-2019";
    if (is2019)
        d.keywords.emplace_back("FILEGENTYPE", formatNumber(b[1]));
    else if (!(b[1] > 0.0))
        fail(path, ballastLine, "a positive ballast-lamp photometric factor", formatNumber(b[1]));
    double scale = lamp.multiplier * b[0] * (is2019 ? 1.0 : b[1]);
    d.inputWatts = b[2];
    d.lampFlux = lamp.lumens > 0.0 ? double(lamp.lamps) * lamp.lumens : -1.0;
    if (!(d.lampFlux <= kMaxLumens))
        fail(path, headerLine,
             "a lamp flux (lamps x lumens per lamp) of at most " + formatNumber(kMaxLumens) + " lm",
             std::isfinite(d.lampFlux) ? formatNumber(d.lampFlux) + " lm"
                                       : std::string("an overflow"));
    return scale;
}

/// The vertical angles, in the goniometer type's range.
void readVerticalAngles(TokenStream& in, PhotometricData& d, const std::string& path, int nv) {
    int vLine = in.line();
    d.vertical = in.numbers(size_t(nv), "vertical angles");
    if (d.goniometer == Goniometer::C)
        checkAscending(d.vertical, 0.0, 180.0, path, vLine, "vertical angles");
    else
        checkAscending(d.vertical, -90.0, 90.0, path, vLine, "vertical angles");
}

/// The horizontal angles as given, and the symmetry their range implies.
std::vector<double> readHorizontalAngles(TokenStream& in, PhotometricData& d,
                                         const std::string& path, int nh) {
    int hLine = in.line();
    std::vector<double> given = in.numbers(size_t(nh), "horizontal angles");
    if (d.goniometer == Goniometer::C)
        checkAscending(given, 0.0, 360.0, path, hLine, "horizontal angles");
    else
        checkAscending(given, -180.0, 180.0, path, hLine, "horizontal angles");
    d.symmetry = photometry_detail::symmetryOfRange(d.goniometer, given, path, hLine);
    return given;
}

/// The candela values, one horizontal angle after another, scaled by the multipliers and the
/// tilt factor at 0.
std::vector<double> readCandelaTable(TokenStream& in, const PhotometricData& d,
                                     const std::string& path, const std::vector<double>& given,
                                     double scale) {
    size_t nv = d.vertical.size(), nh = given.size();
    std::vector<double> cd =
        in.numbers(nv * nh, "candela values (" + std::to_string(nh) + " horizontal x " +
                                std::to_string(nv) + " vertical angles)");
    double tiltScale = tiltFactorAtZero(d);
    for (size_t k = 0; k < cd.size(); ++k) {
        if (cd[k] < 0.0)
            fail(path, in.lineOfPrevious(cd.size() - k),
                 "non-negative candela values (horizontal angle " + formatNumber(given[k / nv]) +
                     ", vertical angle " + formatNumber(d.vertical[k % nv]) + ")",
                 formatNumber(cd[k]));
        cd[k] *= scale * tiltScale;
        photometry_detail::checkCandela(path, in.lineOfPrevious(cd.size() - k), cd[k],
                                        "candela values (after the multipliers)");
    }
    return cd;
}

/// Warnings (or, strict, errors) for "//" comments and values after the candela table.
void allowCommentsAndTrailingValues(const TokenStream& in, PhotometricData& d,
                                    const PhotometryOptions& options) {
    if (in.commentLine() > 0)
        photometry_detail::allow(d, options, in.commentLine(),
                                 "a '//' comment in the numeric data (not in LM-63)",
                                 "ignored to the end of each line");
    if (size_t extra = in.remaining())
        photometry_detail::allow(d, options, in.line(),
                                 std::to_string(extra) + " value" + (extra == 1 ? "" : "s") +
                                     " after the candela table (from " + showToken(in.peek()) + ")",
                                 "ignored");
}

}  // namespace

PhotometricData parseIes(const std::string& text, const std::string& path,
                         const PhotometryOptions& options) {
    PhotometricData d;
    d.path = path;
    std::vector<std::string> lines = photometry_detail::readLines(text, d, options);
    size_t tiltLine = readHeaderAndKeywords(lines, d, path);
    TokenStream in(path, lines, tiltLine + 1);
    readTiltSection(trim(lines[tiltLine]), tiltLine, in, d, path);
    LampLine lamp = readLampLine(in, d, path);
    double scale = readBallastLine(in, d, path, lamp);
    readVerticalAngles(in, d, path, lamp.nv);
    std::vector<double> given = readHorizontalAngles(in, d, path, lamp.nh);
    std::vector<double> cd = readCandelaTable(in, d, path, given, scale);
    allowCommentsAndTrailingValues(in, d, options);
    photometry_detail::unfold(d, given, cd);
    return d;
}

}  // namespace candela
