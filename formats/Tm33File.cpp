// IES TM-33 luminaire optical data (XML): ANSI/IES TM-33-18 (root <IESTM33>, version 1.0, the
// same schema as ATLA S001 and UNI 11733:2019) and TM-33-23 (root <IESTM33-22>, version 1.1,
// which adds <Symm> and <Multiplier> to the intensity table).
//
// What is read (element names as in the standard's schema, Annex A):
//   Header            Manufacturer, CatalogNumber, Description (the name), Laboratory,
//                     ReportNumber, ReportDate, ... kept as keywords.
//   Luminaire         Dimensions (Length along C0-C180, Width along C90-C270, Height; metres):
//                     the opening when the emitter gives no emission areas, as LM-63's
//                     luminous dimensions are.
//   Equipment         Gonioradiometer/Type: CIE_C or IES_C (type C, the default when absent),
//                     CIE_B or IES_B (type B); type A and CUSTOM are refused.
//   Emitter           the one emitter with <LuminousData>: Quantity, RatedLumens (per emitter),
//                     InputWattage (W), TiltAngles, and
//     LuminousData/LuminousIntensity
//                     AbsolutePhotometry, Symm, Multiplier, NumberMeasured, NumberHorz,
//                     NumberVert and one <IntData h="H" v="V">cd</IntData> per direction, in any
//                     order; LuminousFlux (lm) beside it.
//     EmissionAreas   BottomFace (or TopFace) areas give the opening's length and width,
//                     Circular an ellipse; C0/C90/C180/C270 faces give it a height (a box, or a
//                     vertical cylinder under a circular bottom).
// Intensities are candela. Relative photometry (AbsolutePhotometry false) is candela for the
// emitters' rated lumens, as in LM-63, so the table is used as it stands and the rated flux
// (Quantity x RatedLumens) is the lamp flux. The horizontal angles' range gives the symmetry as in
// LM-63 (TM-33-18 has no symmetry field); a TM-33-23 <Symm> must agree with it. BallastFactor and
// PowerFactor are kept as keywords, not applied (TM-33 tables are the luminaire's output).
// Refused with a one-line message naming the file and line: malformed XML, another root, missing
// or non-numeric counts and values, a table with a direction missing or given twice, counts that
// disagree with the table, several emitters with luminous data (colour channels; Candela reads a
// luminaire's one distribution), and the same value defects as LM-63 files.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <pugixml.hpp>
#include <set>
#include <sstream>

#include "formats/Photometry.h"
#include "util/Error.h"
#include "util/TextEncoding.h"

namespace candela {

using photometry_detail::fail;
using photometry_detail::formatNumber;
using photometry_detail::kMaxCount;

namespace {

/// Two angles of a table closer than this (degrees) are the same angle.
constexpr double kAngleTolerance = 1e-9;

std::string trimmed(const char* s) {
    std::string t = s;
    size_t b = 0, e = t.size();
    while (b < e && std::isspace(static_cast<unsigned char>(t[b]))) ++b;
    while (e > b && std::isspace(static_cast<unsigned char>(t[e - 1]))) --e;
    return t.substr(b, e - b);
}

/// An enumeration value without spaces and in upper case: the published TM-33-23 schema's
/// values read "Symm_Quad" in the XSD and "Symm _ Quad" where its PDF was set in type.
std::string normalised(const std::string& s) {
    std::string out;
    for (char c : s)
        if (!std::isspace(static_cast<unsigned char>(c)))
            out.push_back(char(std::toupper(static_cast<unsigned char>(c))));
    return out;
}

/// A value as a message shows it: at most 40 bytes (then "..."), on one line in valid UTF-8
/// (util/TextEncoding.h's oneLine).
std::string printable(const std::string& value) {
    return oneLine(value.size() > 40 ? value.substr(0, 40) + "..." : value);
}

std::string inQuotes(const std::string& value) {
    std::string out = "\"";  // appended piecewise: GCC 12 warns wrongly about "\"" + temporary
    out += printable(value);
    out += '"';
    return out;
}

/// One document being read: the text (for line numbers) and the file's name.
struct Tm33Reader {
    std::string path;
    std::string text;  ///< UTF-8, as pugixml parsed it (offsets index it).
    PhotometricData& d;
    const PhotometryOptions& options;

    int line(const pugi::xml_node& node) const {
        ptrdiff_t offset = node.offset_debug();
        if (offset < 0) return 1;
        size_t end = std::min(size_t(offset), text.size());
        return 1 + int(std::count(text.begin(), text.begin() + ptrdiff_t(end), '\n'));
    }

    [[noreturn]] void failAt(const pugi::xml_node& node, const std::string& expected,
                             const std::string& found) const {
        fail(path, line(node), expected, found);
    }

    /// The child element `name` of `parent`, which must be there.
    pugi::xml_node child(const pugi::xml_node& parent, const char* name) const {
        pugi::xml_node c = parent.child(name);
        if (!c) failAt(parent, std::string("a <") + name + "> in <" + parent.name() + ">", "none");
        return c;
    }

    double number(const pugi::xml_node& node, const std::string& what) const {
        std::string t = trimmed(node.child_value());
        double v = 0.0;
        if (!photometry_detail::parseNumber(t, v)) failAt(node, what + " (a number)", inQuotes(t));
        return v;
    }

    /// An optional non-negative number; `fallback` when the element is absent.
    double optionalNumber(const pugi::xml_node& parent, const char* name, double fallback,
                          const std::string& what) const {
        pugi::xml_node c = parent.child(name);
        if (!c) return fallback;
        double v = number(c, what);
        if (v < 0.0) failAt(c, "a non-negative " + what, formatNumber(v));
        return v;
    }

    int count(const pugi::xml_node& parent, const char* name, int lo,
              const std::string& what) const {
        pugi::xml_node c = child(parent, name);
        double v = number(c, what);
        if (!(v >= lo && v <= kMaxCount) || v != std::floor(v))
            failAt(c,
                   what + " (a whole number from " + std::to_string(lo) + " to " +
                       std::to_string(kMaxCount) + ")",
                   formatNumber(v));
        return int(v);
    }

    bool boolean(const pugi::xml_node& node, const std::string& what) const {
        std::string t = trimmed(node.child_value());
        if (t == "true" || t == "1") return true;
        if (t == "false" || t == "0") return false;
        failAt(node, what + " (true or false)", inQuotes(t));
    }

    double attribute(const pugi::xml_node& node, const char* name) const {
        pugi::xml_attribute a = node.attribute(name);
        double v = 0.0;
        if (!a || !photometry_detail::parseNumber(trimmed(a.value()), v))
            failAt(node, std::string("an angle in attribute ") + name + " of <IntData>",
                   a ? inQuotes(a.value()) : std::string("none"));
        return v;
    }

    void keep(const pugi::xml_node& parent, const char* name, const std::string& key) {
        for (pugi::xml_node c : parent.children(name)) {
            std::string v = toValidUtf8(trimmed(c.child_value()));
            if (!v.empty()) d.keywords.emplace_back(key, v);
        }
    }
};

/// The angles (ascending, each once) that a table's directions use along one axis.
std::vector<double> distinctAngles(std::vector<double> all) {
    std::sort(all.begin(), all.end());
    std::vector<double> out;
    for (double a : all)
        if (out.empty() || a - out.back() > kAngleTolerance) out.push_back(a);
    return out;
}

size_t indexOf(const std::vector<double>& angles, double a) {
    auto it = std::lower_bound(angles.begin(), angles.end(), a - kAngleTolerance);
    return size_t(it - angles.begin());
}

const char* symmetryWord(PhotometricSymmetry s) {
    switch (s) {
        case PhotometricSymmetry::None:
            return "Symm_None";
        case PhotometricSymmetry::Axial:
            return "Symm_Full";
        case PhotometricSymmetry::Quadrant:
            return "Symm_Quad";
        case PhotometricSymmetry::PlaneC0C180:
            return "Symm_Bi_0";
        case PhotometricSymmetry::PlaneC90C270:
            return "Symm_Bi_90";
    }
    return "?";
}

void readHeader(Tm33Reader& r, const pugi::xml_node& root) {
    pugi::xml_node h = root.child("Header");
    if (!h) return;  // the photometry needs none of it
    r.keep(h, "Manufacturer", "Manufacturer");
    r.keep(h, "CatalogNumber", "CatalogNumber");
    r.keep(h, "Description", "Description");
    r.keep(h, "GTIN", "GTIN");
    r.keep(h, "Laboratory", "Laboratory");
    r.keep(h, "ReportNumber", "ReportNumber");
    r.keep(h, "ReportDate", "ReportDate");
    r.keep(h, "UniqueIdentifier", "UniqueIdentifier");
    r.keep(h, "Comment", "Comment");
    std::string description = toValidUtf8(trimmed(h.child_value("Description")));
    std::string catalog = toValidUtf8(trimmed(h.child_value("CatalogNumber")));
    r.d.name = !description.empty() ? description : catalog;
}

Goniometer readGoniometer(const Tm33Reader& r, const pugi::xml_node& root) {
    pugi::xml_node type = root.child("Equipment").child("Gonioradiometer").child("Type");
    if (!type) return Goniometer::C;
    std::string t = normalised(type.child_value());
    if (t == "CIE_C" || t == "IES_C") return Goniometer::C;
    if (t == "CIE_B" || t == "IES_B") return Goniometer::B;
    r.failAt(type, "gonioradiometer type CIE_C, IES_C, CIE_B or IES_B",
             inQuotes(trimmed(type.child_value())) +
                 (t == "CIE_A" || t == "IES_A" ? " (type A photometry is not supported)" : ""));
}

/// The one emitter that carries luminous data.
pugi::xml_node findEmitter(const Tm33Reader& r, const pugi::xml_node& root) {
    std::vector<pugi::xml_node> luminous;
    bool other = false;
    for (pugi::xml_node e : root.children("Emitter")) {
        if (e.child("LuminousData"))
            luminous.push_back(e);
        else if (e.child("RadiantData") || e.child("PhotonData"))
            other = true;
    }
    if (luminous.empty())
        r.failAt(root, "an <Emitter> with <LuminousData> (luminous intensities)",
                 other ? "only radiant or photon data" : "none");
    if (luminous.size() > 1)
        r.failAt(luminous[1],
                 "one <Emitter> with <LuminousData> (Candela reads a luminaire's one distribution)",
                 std::to_string(luminous.size()) + " (separately controlled channels)");
    return luminous.front();
}

void readTilt(Tm33Reader& r, const pugi::xml_node& emitter) {
    pugi::xml_node tilt = emitter.child("TiltAngles");
    if (!tilt) return;
    int n = r.count(tilt, "NumberAngles", 1, "number of tilt angles");
    std::vector<std::pair<double, double>> table;
    for (pugi::xml_node t : tilt.children("Tilt")) {
        double angle = r.attribute(t, "angle");
        double factor = r.number(t, "tilt multiplying factor");
        if (!(angle >= -360.0 && angle <= 360.0))
            r.failAt(t, "a tilt angle between -360 and 360 degrees", formatNumber(angle));
        if (factor < 0.0)
            r.failAt(t, "a non-negative tilt multiplying factor", formatNumber(factor));
        table.emplace_back(angle, factor);
    }
    if (int(table.size()) != n)
        r.failAt(tilt, std::to_string(n) + " <Tilt> elements (NumberAngles)",
                 std::to_string(table.size()));
    std::sort(table.begin(), table.end());
    for (size_t k = 1; k < table.size(); ++k)
        if (!(table[k].first > table[k - 1].first))
            r.failAt(tilt, "each tilt angle once", formatNumber(table[k].first) + " twice");
    r.d.tiltGeometry = 1;  // TM-33 names no lamp-to-luminaire geometry; kept for the record
    for (auto& [a, f] : table) {
        r.d.tiltAngles.push_back(a);
        r.d.tiltFactors.push_back(f);
    }
}

/// The table: angles, symmetry, candela (multiplier and tilt applied), unfolded. Returns whether
/// the photometry is relative.
bool readIntensities(Tm33Reader& r, const pugi::xml_node& intensity) {
    PhotometricData& d = r.d;
    bool absolute = true;
    if (pugi::xml_node a = intensity.child("AbsolutePhotometry"))
        absolute = r.boolean(a, "AbsolutePhotometry");
    if (!absolute) d.keywords.emplace_back("AbsolutePhotometry", "false");
    double multiplier = 1.0;
    if (pugi::xml_node m = intensity.child("Multiplier")) {
        multiplier = r.number(m, "intensity multiplier");
        if (!(multiplier > 0.0)) r.failAt(m, "a positive <Multiplier>", formatNumber(multiplier));
    }
    int measured = r.count(intensity, "NumberMeasured", 1, "number of measured intensities");
    int nh = r.count(intensity, "NumberHorz", 1, "number of horizontal angles");
    int nv = r.count(intensity, "NumberVert", 1, "number of vertical angles");
    if (int64_t(nh) * nv != measured)
        r.failAt(intensity.child("NumberMeasured"),
                 "NumberMeasured = NumberHorz x NumberVert = " + std::to_string(int64_t(nh) * nv),
                 std::to_string(measured));

    struct Entry {
        double h, v, cd;
        pugi::xml_node node;
    };
    std::vector<Entry> entries;
    for (pugi::xml_node e : intensity.children("IntData")) {
        if (entries.size() >= size_t(measured))
            r.failAt(e, std::to_string(measured) + " <IntData> elements (NumberMeasured)", "more");
        Entry x{r.attribute(e, "h"), r.attribute(e, "v"), r.number(e, "an intensity in cd"), e};
        if (x.cd < 0.0)
            r.failAt(e,
                     "a non-negative intensity (h " + formatNumber(x.h) + ", v " +
                         formatNumber(x.v) + ")",
                     formatNumber(x.cd));
        entries.push_back(x);
    }
    if (entries.size() != size_t(measured))
        r.failAt(intensity, std::to_string(measured) + " <IntData> elements (NumberMeasured)",
                 std::to_string(entries.size()));

    std::vector<double> hs, vs;
    for (const Entry& e : entries) hs.push_back(e.h), vs.push_back(e.v);
    std::vector<double> given = distinctAngles(hs);
    d.vertical = distinctAngles(vs);
    if (given.size() != size_t(nh))
        r.failAt(intensity.child("NumberHorz"),
                 std::to_string(nh) + " horizontal angles (NumberHorz)",
                 std::to_string(given.size()) + " in the <IntData> elements");
    if (d.vertical.size() != size_t(nv))
        r.failAt(intensity.child("NumberVert"),
                 std::to_string(nv) + " vertical angles (NumberVert)",
                 std::to_string(d.vertical.size()) + " in the <IntData> elements");

    bool typeC = d.goniometer == Goniometer::C;
    double vLo = typeC ? 0.0 : -90.0, vHi = typeC ? 180.0 : 90.0;
    double hLo = typeC ? 0.0 : -180.0, hHi = typeC ? 360.0 : 180.0;
    for (const Entry& e : entries) {
        if (!(e.v >= vLo && e.v <= vHi))
            r.failAt(e.node,
                     "a vertical angle v between " + formatNumber(vLo) + " and " +
                         formatNumber(vHi) + " degrees",
                     formatNumber(e.v));
        if (!(e.h >= hLo && e.h <= hHi))
            r.failAt(e.node,
                     "a horizontal angle h between " + formatNumber(hLo) + " and " +
                         formatNumber(hHi) + " degrees",
                     formatNumber(e.h));
    }
    d.symmetry = photometry_detail::symmetryOfRange(d.goniometer, given, r.path,
                                                    r.line(intensity.child("NumberHorz")));
    if (pugi::xml_node symm = intensity.child("Symm")) {
        std::string s = normalised(symm.child_value());
        if (s != "SYMM_ARBITRARY" && s != normalised(symmetryWord(d.symmetry)))
            r.failAt(symm,
                     std::string(symmetryWord(d.symmetry)) + " (what horizontal angles " +
                         formatNumber(given.front()) + ".." + formatNumber(given.back()) + " give)",
                     inQuotes(trimmed(symm.child_value())));
        d.keywords.emplace_back("Symm", toValidUtf8(trimmed(symm.child_value())));
    }

    double scale = multiplier * photometry_detail::tiltFactorAtZero(d);
    std::vector<double> cd(size_t(nh) * size_t(nv), -1.0);
    for (const Entry& e : entries) {
        size_t k = indexOf(given, e.h) * size_t(nv) + indexOf(d.vertical, e.v);
        if (cd[k] >= 0.0)
            r.failAt(e.node, "each direction once",
                     "h " + formatNumber(e.h) + ", v " + formatNumber(e.v) + " again");
        cd[k] = e.cd * scale;
        if (!(cd[k] <= kMaxCandela))  // the line is counted only for the message
            photometry_detail::checkCandela(r.path, r.line(e.node), cd[k],
                                            "intensities (after the multiplier)");
    }
    // With the counts checked, no direction can be missing; this keeps the message exact if a
    // duplicate slipped past the tolerance.
    for (size_t k = 0; k < cd.size(); ++k)
        if (cd[k] < 0.0)
            r.failAt(intensity, "an <IntData> for every pair of its angles",
                     "none for h " + formatNumber(given[k / size_t(nv)]) + ", v " +
                         formatNumber(d.vertical[k % size_t(nv)]));
    photometry_detail::unfold(d, given, cd);
    return !absolute;
}

/// One face's areas: their bounding rectangle in the face's two in-plane sizes.
struct FaceAreas {
    int count = 0;
    bool circular = false;
    bool offset = false;
    double a = 0.0, b = 0.0;  ///< Bounding sizes along the face's two axes, metres.
    pugi::xml_node first;
};

FaceAreas readFace(const Tm33Reader& r, const pugi::xml_node& face, const char* areaName,
                   const char* sizeA, const char* sizeB, const char* offsetA, const char* offsetB) {
    FaceAreas f;
    double loA = 0, hiA = 0, loB = 0, hiB = 0;
    for (pugi::xml_node area : face.children(areaName)) {
        double a = r.number(r.child(area, sizeA), std::string(sizeA) + " in metres");
        double b = r.number(r.child(area, sizeB), std::string(sizeB) + " in metres");
        double oa = 0.0, ob = 0.0;
        if (pugi::xml_node n = area.child(offsetA)) oa = r.number(n, offsetA);
        if (pugi::xml_node n = area.child(offsetB)) ob = r.number(n, offsetB);
        for (double s : {a, b})
            if (!(s >= 0.0 && s <= kMaxOpening))
                r.failAt(area, "emission area sizes from 0 to " + formatNumber(kMaxOpening) + " m",
                         formatNumber(s));
        for (double o : {oa, ob})
            if (!(std::abs(o) <= kMaxOpening))
                r.failAt(area,
                         "emission area offsets of at most " + formatNumber(kMaxOpening) + " m",
                         formatNumber(o));
        if (f.count == 0) {
            loA = oa - a / 2, hiA = oa + a / 2, loB = ob - b / 2, hiB = ob + b / 2;
            f.first = area;
        } else {
            loA = std::min(loA, oa - a / 2), hiA = std::max(hiA, oa + a / 2);
            loB = std::min(loB, ob - b / 2), hiB = std::max(hiB, ob + b / 2);
        }
        if (pugi::xml_node c = area.child("Circular")) f.circular = r.boolean(c, "Circular");
        f.offset = f.offset || oa != 0.0 || ob != 0.0;
        ++f.count;
    }
    f.a = hiA - loA;
    f.b = hiB - loB;
    return f;
}

/// The luminous opening: the emitter's emission areas, else the luminaire's dimensions.
void readOpening(Tm33Reader& r, const pugi::xml_node& root, const pugi::xml_node& emitter) {
    PhotometricData& d = r.d;
    LuminousOpening& o = d.opening;
    pugi::xml_node areas = emitter.child("EmissionAreas");
    if (!areas) {
        pugi::xml_node dims = root.child("Luminaire").child("Dimensions");
        if (!dims) return;  // a point source
        o.length = r.number(r.child(dims, "Length"), "Length in metres");
        o.width = r.number(r.child(dims, "Width"), "Width in metres");
        o.height = r.number(r.child(dims, "Height"), "Height in metres");
        for (double s : {o.length, o.width, o.height})
            if (!(s >= 0.0 && s <= kMaxOpening))
                r.failAt(dims, "luminaire dimensions from 0 to " + formatNumber(kMaxOpening) + " m",
                         formatNumber(s));
        bool point = o.length == 0.0 && o.width == 0.0 && o.height == 0.0;
        o.shape = point ? LuminousOpening::Shape::Point : LuminousOpening::Shape::Rectangle;
        return;
    }
    FaceAreas bottom = readFace(r, areas.child("BottomFace"), "BottomArea", "Length", "Width",
                                "LengthOffset", "WidthOffset");
    const char* horizontalFace = "bottom";
    if (bottom.count == 0) {
        bottom = readFace(r, areas.child("TopFace"), "TopArea", "Length", "Width", "LengthOffset",
                          "WidthOffset");
        horizontalFace = "top";
    }
    double height = 0.0;
    int sideCount = 0;
    bool sideOffset = false;
    struct Side {
        const char *face, *area, *size, *offset;
    };
    // The schema gives the C0 and C180 faces' areas a Length and the C90 and C270 faces' a
    // Width (and each a Height).
    for (Side s : {Side{"C0Face", "C0Area", "Length", "LengthOffset"},
                   Side{"C90Face", "C90Area", "Width", "WidthOffset"},
                   Side{"C180Face", "C180Area", "Length", "LengthOffset"},
                   Side{"C270Face", "C270Area", "Width", "WidthOffset"}}) {
        FaceAreas f =
            readFace(r, areas.child(s.face), s.area, s.size, "Height", s.offset, "HeightOffset");
        if (f.count == 0) continue;
        height = std::max(height, f.b);
        sideCount += f.count;
        sideOffset = sideOffset || f.offset;
        if (bottom.count == 0) {  // sides only: the box they bound
            if (s.size[0] == 'W')
                o.width = std::max(o.width, f.a);
            else
                o.length = std::max(o.length, f.a);
        }
    }
    if (bottom.count > 0) {
        o.length = bottom.a;
        o.width = bottom.b;
    }
    o.height = height;
    if (o.length == 0.0 && o.width == 0.0 && o.height == 0.0) return;  // a point source
    if (bottom.circular)
        o.shape = height > 0.0 ? LuminousOpening::Shape::Cylinder : LuminousOpening::Shape::Ellipse;
    else
        o.shape = LuminousOpening::Shape::Rectangle;  // a box when height > 0
    int line = r.line(areas);
    if (bottom.count > 1)
        photometry_detail::allow(
            d, r.options, line,
            std::to_string(bottom.count) + " " + horizontalFace + " emission areas",
            "the opening is the rectangle bounding them");
    else if (bottom.offset || sideOffset)
        photometry_detail::allow(d, r.options, line, "an emission area off the photometric centre",
                                 "the opening is centred on it");
    if (sideCount > 0 && bottom.count == 0 && o.length * o.width == 0.0)
        photometry_detail::allow(d, r.options, line, "side emission areas only",
                                 "the opening is the box they bound");
}

void readEmitter(Tm33Reader& r, const pugi::xml_node& root, const pugi::xml_node& emitter) {
    PhotometricData& d = r.d;
    int quantity = 1;
    if (emitter.child("Quantity")) quantity = r.count(emitter, "Quantity", 1, "emitter quantity");
    d.keywords.emplace_back("Quantity", std::to_string(quantity));
    r.keep(emitter, "Description", "Emitter");
    r.keep(emitter, "CatalogNumber", "EmitterCatalogNumber");
    r.keep(emitter, "BallastFactor", "BallastFactor");
    r.keep(emitter, "PowerFactor", "PowerFactor");
    r.keep(emitter.child("ColorTemperature"), "FixedCCT", "FixedCCT (K)");
    r.keep(emitter.child("ColorRendering").child("CIE_CRI"), "Ra", "Ra");
    double rated = r.optionalNumber(emitter, "RatedLumens", 0.0, "rated flux in lm");
    d.inputWatts = r.optionalNumber(emitter, "InputWattage", 0.0, "input power in W");
    readTilt(r, emitter);

    pugi::xml_node luminous = emitter.child("LuminousData");
    pugi::xml_node intensity = r.child(luminous, "LuminousIntensity");
    bool relative = readIntensities(r, intensity);
    double lampFlux = double(quantity) * rated;
    if (!(lampFlux <= kMaxLumens))
        r.failAt(
            emitter.child("RatedLumens"),
            "a rated flux (Quantity x RatedLumens) of at most " + formatNumber(kMaxLumens) + " lm",
            formatNumber(lampFlux) + " lm");
    d.lampFlux = relative && lampFlux > 0.0 ? lampFlux : -1.0;
    if (!relative && rated > 0.0) d.keywords.emplace_back("RatedLumens", formatNumber(rated));
    d.statedFlux = r.optionalNumber(luminous, "LuminousFlux", 0.0, "luminous flux in lm");
    if (!(d.statedFlux <= kMaxLumens))
        r.failAt(luminous.child("LuminousFlux"),
                 "a luminous flux of at most " + formatNumber(kMaxLumens) + " lm",
                 formatNumber(d.statedFlux));
    readOpening(r, root, emitter);
}

}  // namespace

PhotometricData parseTm33(const std::string& bytes, const std::string& path,
                          const PhotometryOptions& options) {
    PhotometricData d;
    d.path = path;
    DecodedText decoded = decodeText(bytes, path);
    Tm33Reader r{path, decoded.utf8, d, options};
    if (decoded.encoding == DecodedText::Encoding::Windows1252)
        photometry_detail::allow(d, options, decoded.firstLine,
                                 "text in Windows-1252, not UTF-8 or UTF-16",
                                 "transcoded to UTF-8");
    pugi::xml_document doc;
    pugi::xml_parse_result parsed =
        doc.load_buffer(r.text.data(), r.text.size(), pugi::parse_default, pugi::encoding_utf8);
    if (!parsed) {
        size_t end = std::min(size_t(std::max<ptrdiff_t>(parsed.offset, 0)), r.text.size());
        int line = 1 + int(std::count(r.text.begin(), r.text.begin() + ptrdiff_t(end), '\n'));
        fail(path, line, "well-formed XML", parsed.description());
    }
    pugi::xml_node root = doc.document_element();
    std::string rootName = root.name();
    if (rootName == "IESTM33")
        d.format = "IES TM-33-18";
    else if (rootName == "IESTM33-22")
        d.format = "IES TM-33-23";
    else
        r.failAt(root, "a TM-33 document (root element <IESTM33> or <IESTM33-22>)",
                 "<" + printable(rootName) + ">");
    if (pugi::xml_node version = root.child("Version"))
        d.keywords.emplace_back("Version", toValidUtf8(trimmed(version.child_value())));
    readHeader(r, root);
    d.goniometer = readGoniometer(r, root);
    readEmitter(r, root, findEmitter(r, root));
    return d;
}

// ---------------------------------------------------------------------------------------------
// Writing

namespace {

/// Text for an XML element's content: the five special characters escaped, and characters XML
/// 1.0 forbids (C0 controls other than tab and newline) dropped.
std::string escaped(const std::string& s) {
    std::string out;
    for (char c : toValidUtf8(s)) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&apos;";
                break;
            default:
                if (static_cast<unsigned char>(c) >= 0x20 || c == '\t' || c == '\n') out += c;
        }
    }
    return out;
}

/// The shortest of %.15g, %.16g and %.17g that reads back as the same double.
std::string num(double v) {
    char buf[32];
    for (int digits = 15; digits <= 17; ++digits) {
        std::snprintf(buf, sizeof buf, "%.*g", digits, v);
        if (std::strtod(buf, nullptr) == v) break;
    }
    return buf;
}

/// The horizontal angles of the unfolded table that the symmetry keeps (the range LM-63 and
/// TM-33-18 read it from).
bool keeps(const PhotometricData& d, double h) {
    using Sym = PhotometricSymmetry;
    const double e = 1e-9;
    if (d.goniometer == Goniometer::B) {
        if (d.symmetry == Sym::Axial) return h == d.horizontal.front();
        if (d.symmetry == Sym::PlaneC90C270) return h >= -e;
        return true;
    }
    switch (d.symmetry) {
        case Sym::Axial:
            return h == d.horizontal.front();
        case Sym::Quadrant:
            return h <= 90.0 + e;
        case Sym::PlaneC0C180:
            return h <= 180.0 + e;
        case Sym::PlaneC90C270:
            return h >= 90.0 - e && h <= 270.0 + e;
        case Sym::None:
            return true;
    }
    return true;
}

}  // namespace

std::string writeTm33(const PhotometricData& d, const std::string& date,
                      std::vector<std::string>& notes) {
    std::ostringstream x;
    auto element = [&](int indent, const std::string& name, const std::string& value) {
        x << std::string(size_t(indent) * 2, ' ') << "<" << name << ">" << escaped(value) << "</"
          << name << ">\n";
    };
    std::string source = d.path.substr(d.path.find_last_of("/\\") + 1);
    x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<IESTM33>\n";
    element(1, "Version", "1.0");
    x << "  <Header>\n";
    std::string manufacturer = d.keyword({"MANUFAC", "Manufacturer", "company"});
    if (!manufacturer.empty()) element(2, "Manufacturer", manufacturer);
    std::string catalog = d.keyword({"LUMCAT", "CatalogNumber", "luminaire number"});
    if (!catalog.empty()) element(2, "CatalogNumber", catalog);
    element(2, "Description", d.name.empty() ? source : d.name);
    std::string lab = d.keyword({"TESTLAB", "Laboratory"});
    element(2, "Laboratory", lab.empty() ? "not stated in " + source : lab);
    std::string report = d.keyword({"TEST", "ReportNumber", "measurement report"});
    element(2, "ReportNumber", report.empty() ? "not stated in " + source : report);
    std::string reportDate = d.keyword({"ReportDate"});
    bool dated = reportDate.size() == 10 && reportDate[4] == '-' && reportDate[7] == '-';
    element(2, "ReportDate", dated ? reportDate : date);
    element(2, "DocumentCreator", "Candela (candela convert)");
    element(2, "DocumentCreationDate", date);
    element(2, "Comment", "Converted from " + source + " (" + d.format + ").");
    if (!dated)
        element(2, "Comment",
                "ReportDate is the date of this conversion: " + source +
                    " states no report date in this form.");
    x << "  </Header>\n  <Luminaire>\n    <Dimensions>\n";
    element(3, "Length", num(d.opening.length));
    element(3, "Width", num(d.opening.width));
    element(3, "Height", num(d.opening.height));
    x << "    </Dimensions>\n";
    element(2, "NumEmitter", "1");
    x << "  </Luminaire>\n  <Equipment>\n    <Gonioradiometer>\n";
    element(3, "Type", d.goniometer == Goniometer::B ? "CIE_B" : "CIE_C");
    x << "    </Gonioradiometer>\n  </Equipment>\n  <Emitter>\n";
    element(2, "Quantity", "1");
    element(2, "Description", d.name.empty() ? source : d.name);
    bool relative = d.lampFlux > 0.0;
    if (relative) element(2, "RatedLumens", num(d.lampFlux));
    element(2, "InputWattage", num(d.inputWatts));
    x << "    <LuminousData>\n      <LuminousIntensity>\n";
    element(4, "AbsolutePhotometry", relative ? "false" : "true");
    std::vector<size_t> rows;
    for (size_t h = 0; h < d.horizontal.size(); ++h)
        if (keeps(d, d.horizontal[h])) rows.push_back(h);
    size_t nv = d.vertical.size();
    element(4, "NumberMeasured", std::to_string(rows.size() * nv));
    element(4, "NumberHorz", std::to_string(rows.size()));
    element(4, "NumberVert", std::to_string(nv));
    for (size_t h : rows)
        for (size_t v = 0; v < nv; ++v)
            x << "        <IntData h=\"" << num(d.horizontal[h]) << "\" v=\"" << num(d.vertical[v])
              << "\">" << num(d.candela[h * nv + v]) << "</IntData>\n";
    x << "      </LuminousIntensity>\n";
    // The luminaire flux the source states: EULUMDAT's lamps x LORL (an IES file states none;
    // the table's own flux is what a reader computes, not a statement to copy).
    if (double declared = d.declaredFlux(); d.declaresLightOutputRatio && declared > 0.0)
        element(3, "LuminousFlux", num(declared));
    else if (d.statedFlux > 0.0)
        element(3, "LuminousFlux", num(d.statedFlux));
    x << "    </LuminousData>\n";

    const LuminousOpening& o = d.opening;
    using Shape = LuminousOpening::Shape;
    // Without emission areas a reader takes the luminaire's dimensions (written above) as the
    // opening: enough for a point and for a flat opening without area.
    if (o.shape != Shape::Point && ((o.length > 0.0 && o.width > 0.0) || o.height > 0.0)) {
        double length = o.length, width = o.width, height = o.height;
        bool circular = o.shape == Shape::Ellipse ||
                        (o.shape == Shape::Cylinder && o.axis == LuminousOpening::Axis::Z);
        if (o.shape == Shape::Sphere) {
            circular = true;
            notes.push_back(
                "the spherical opening is written as the vertical cylinder around it "
                "(TM-33 gives emission areas on a box's faces)");
        } else if (o.shape == Shape::Cylinder && o.axis != LuminousOpening::Axis::Z) {
            circular = false;
            notes.push_back(
                "the lying cylindrical opening is written as the box around it "
                "(TM-33 gives emission areas on a box's faces)");
        }
        x << "    <EmissionAreas>\n";
        if (length > 0.0 && width > 0.0) {
            x << "      <BottomFace>\n";
            element(4, "NumberBottom", "1");
            x << "        <BottomArea>\n";
            element(5, "Length", num(length));
            element(5, "Width", num(width));
            element(5, "LengthOffset", "0");
            element(5, "WidthOffset", "0");
            if (circular) element(5, "Circular", "true");
            x << "        </BottomArea>\n      </BottomFace>\n";
        }
        if (height > 0.0) {
            struct Side {
                const char *face, *count, *area, *size, *offset;
                double extent;
            };
            for (Side s :
                 {Side{"C0Face", "NumberC0", "C0Area", "Length", "LengthOffset", length},
                  Side{"C90Face", "NumberC90", "C90Area", "Width", "WidthOffset", width},
                  Side{"C180Face", "NumberC180", "C180Area", "Length", "LengthOffset", length},
                  Side{"C270Face", "NumberC270", "C270Area", "Width", "WidthOffset", width}}) {
                x << "      <" << s.face << ">\n";
                element(4, s.count, "1");
                x << "        <" << s.area << ">\n";
                element(5, s.size, num(s.extent));
                element(5, "Height", num(height));
                element(5, s.offset, "0");
                element(5, "HeightOffset", "0");
                x << "        </" << s.area << ">\n      </" << s.face << ">\n";
            }
        }
        x << "    </EmissionAreas>\n";
    }
    x << "  </Emitter>\n</IESTM33>\n";
    return x.str();
}

}  // namespace candela
